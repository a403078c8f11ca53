// Typed, validated access to one value of a parsed scene file. Every failure throws
// InputError naming the scene file and the key path (e.g. "objects[2].transform.scale"),
// so the loader itself never has to format an error message about JSON types.
#pragma once
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace tessera::scene_detail {

class JsonField {
public:
    /// `key` is the path of `value` inside the file ("" for the document root).
    JsonField(const nlohmann::json& value, const std::filesystem::path& file, std::string key);

    /// The member `name` of this object; throws if this is not an object or lacks it.
    JsonField operator[](const char* name) const;
    /// The member `name`, or nothing when absent; throws if this is not an object.
    std::optional<JsonField> find(const char* name) const;
    /// Element i of this array (i < size()).
    JsonField at(size_t i) const;
    /// Number of elements; throws if this is not an array.
    size_t size() const;

    float number() const;        ///< a finite number
    int integer() const;         ///< an integer that fits an int
    std::string string() const;  ///< a string
    glm::vec3 vec3() const;      ///< an array of exactly 3 finite numbers
    void require_object() const; ///< throws unless this is a JSON object

    const nlohmann::json& raw() const { return *value_; }
    const std::string& key() const { return key_; }
    const std::filesystem::path& file() const { return *file_; }

    /// Throws InputError "<file>: key '<key>': <what>".
    [[noreturn]] void fail(const std::string& what) const;

private:
    const nlohmann::json* value_;
    const std::filesystem::path* file_;
    std::string key_;
};

}  // namespace tessera::scene_detail

namespace tessera::scene_detail {

/// An [r, g, b] colour with every channel >= 0, and also <= 1 when `at_most_one` (an
/// albedo). Throws InputError naming the key otherwise.
glm::vec3 read_colour(const JsonField& j, bool at_most_one);

/// Reads and parses a JSON file. Throws InputError naming the file if it is missing
/// or unreadable, and "<file>:<line>:<column>" (byte offset too) when malformed.
nlohmann::json parse_json_file(const std::filesystem::path& file);

}  // namespace tessera::scene_detail
