// Typed, validated access to one value of a parsed scene file. Every failure throws
// InputError naming the scene file and the key path (e.g. "objects[2].transform.scale"),
// so the loader itself never has to format an error message about JSON types.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <initializer_list>
#include <string>
#include <vector>
#include <string_view>

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
    std::string string() const;  ///< a string; one holding a NUL character fails
    glm::vec3 vec3() const;      ///< an array of exactly 3 finite numbers
    void require_object() const; ///< throws unless this is a JSON object

    /// Throws unless every member of this object is one of `known` or a comment key
    /// (is_comment_key). The message names the key's path and value and suggests the
    /// closest known key (scenes/README.md: a misspelt key must not be ignored).
    void require_known_keys(std::initializer_list<std::string_view> known) const;

    const nlohmann::json& raw() const { return *value_; }
    const std::string& key() const { return key_; }
    const std::filesystem::path& file() const { return *file_; }

    /// Throws InputError "<file>: key '<key>' = <value>: <what>" (the value shortened to
    /// 60 characters; "<file>: top level: <what>" for the root).
    [[noreturn]] void fail(const std::string& what) const;

private:
    const nlohmann::json* value_;
    const std::filesystem::path* file_;
    std::string key_;
};

}  // namespace tessera::scene_detail

namespace tessera::scene_detail {

/// Keys any object may hold and the loader ignores: "comment" and those starting with
/// '_' (in objects keyed by names, such as "materials", they are skipped too).
bool is_comment_key(std::string_view key);

/// The entry of `candidates` closest to `word` by edit distance (insertions, deletions,
/// substitutions and swaps of neighbours each count 1), or "" when none is within
/// max(2, half the longer word) edits, i.e. close enough to be a likely typo.
std::string closest_match(std::string_view word, std::initializer_list<std::string_view> candidates);
/// The same over a list built at run time (the command line's option names), within
/// `max_edits` edits when given (short option names need a stricter bound than keys).
std::string closest_match(std::string_view word, const std::vector<std::string_view>& candidates,
                          size_t max_edits = SIZE_MAX);

/// What an [r, g, b] triple holds, which sets its upper bound.
enum class Colour {
    Albedo,       ///< reflectance, in [0, 1]
    Radiance,     ///< emitted radiance, W/(sr·m²), <= limits::kMaxRadiance
    Coefficient,  ///< a medium's σ per scene unit; bounded with the scene (read_medium)
};

/// An [r, g, b] triple with every channel >= 0 and within `kind`'s bound. Throws
/// InputError naming the key and the value otherwise.
glm::vec3 read_colour(const JsonField& j, Colour kind);

/// Checks a pinhole view (the `camera` block or an animation key, named by `where`) with
/// camera_view_problem (scene/camera_view.h), make_frame's own test: look_at − position
/// non-zero and finite, up of finite length and more than ~1e-6 rad from the view
/// direction. Throws InputError naming `where`, `when` and the problem otherwise.
void check_camera_view(const JsonField& where, glm::vec3 position, glm::vec3 look_at, glm::vec3 up,
                       const std::string& when = "");

/// Reads and parses a JSON file; `what` names its role in messages ("scene file", "camera
/// path"). Throws InputError naming the file if it is missing, a directory, unreadable or
/// larger than limits::kJsonFileBytes; "<file>:<line>:<column>: malformed JSON: <reason>"
/// for a syntax error; and naming the key path for a duplicate key, a number literal that
/// overflows a double (1e999) or nesting deeper than limits::kJsonDepth. Memory and time
/// are linear in the file's size (util/input_limits.h).
nlohmann::json parse_json_file(const std::filesystem::path& file, const std::string& what = "scene file");

}  // namespace tessera::scene_detail
