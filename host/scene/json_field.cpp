#include "scene/json_field.h"

#include <cmath>
#include <limits>

#include "util/error.h"

namespace tessera::scene_detail {

JsonField::JsonField(const nlohmann::json& value, const std::filesystem::path& file,
                     std::string key)
    : value_(&value), file_(&file), key_(std::move(key)) {}

void JsonField::fail(const std::string& what) const {
    const std::string where = key_.empty() ? "top level" : "key '" + key_ + "'";
    throw InputError(file_->string() + ": " + where + ": " + what);
}

void JsonField::require_object() const {
    if (!value_->is_object()) fail(std::string("expected an object, got ") + value_->type_name());
}

std::optional<JsonField> JsonField::find(const char* name) const {
    require_object();
    const auto it = value_->find(name);
    if (it == value_->end()) return std::nullopt;
    return JsonField(*it, *file_, key_.empty() ? name : key_ + "." + name);
}

JsonField JsonField::operator[](const char* name) const {
    if (auto f = find(name)) return *f;
    const std::string full = key_.empty() ? name : key_ + "." + name;
    throw InputError(file_->string() + ": missing required key '" + full + "'");
}

size_t JsonField::size() const {
    if (!value_->is_array()) fail(std::string("expected an array, got ") + value_->type_name());
    return value_->size();
}

JsonField JsonField::at(size_t i) const {
    return JsonField((*value_)[i], *file_, key_ + "[" + std::to_string(i) + "]");
}

float JsonField::number() const {
    if (!value_->is_number()) fail(std::string("expected a number, got ") + value_->type_name());
    // nlohmann accepts literals such as 1e999 and stores them as infinity; a float
    // overflow does the same. Neither is a usable scene value.
    const double d = value_->get<double>();
    const float f = static_cast<float>(d);
    if (!std::isfinite(d) || !std::isfinite(f)) fail("number is not finite (or overflows a float)");
    return f;
}

int JsonField::integer() const {
    if (!value_->is_number_integer()) fail(std::string("expected an integer, got ") + value_->dump());
    const auto v = value_->get<long long>();
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
        fail("integer out of range");
    return static_cast<int>(v);
}

std::string JsonField::string() const {
    if (!value_->is_string()) fail(std::string("expected a string, got ") + value_->type_name());
    return value_->get<std::string>();
}

glm::vec3 JsonField::vec3() const {
    if (size() != 3) fail("expected an array of 3 numbers, got " + std::to_string(size()) + " elements");
    return {at(0).number(), at(1).number(), at(2).number()};
}

glm::vec3 read_colour(const JsonField& j, bool at_most_one) {
    const glm::vec3 c = j.vec3();
    for (int i = 0; i < 3; ++i) {
        if (c[i] < 0.0f) j.fail("colour components must be >= 0");
        if (at_most_one && c[i] > 1.0f) j.fail("albedo components must be <= 1");
    }
    return c;
}

}  // namespace tessera::scene_detail
