#include "scene/json_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "scene/camera_view.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {

JsonField::JsonField(const nlohmann::json& value, const std::filesystem::path& file,
                     std::string key)
    : value_(&value), file_(&file), key_(std::move(key)) {}

namespace {

// The value as JSON text, for messages; long objects and arrays are cut short.
std::string shown(const nlohmann::json& v) {
    std::string text = v.dump();
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    return text;
}

}  // namespace

void JsonField::fail(const std::string& what) const {
    const std::string where = key_.empty() ? "top level" : "key '" + key_ + "' = " + shown(*value_);
    throw InputError(file_->string() + ": " + where + ": " + what);
}

bool is_comment_key(std::string_view key) { return key == "comment" || (!key.empty() && key.front() == '_'); }

std::string closest_match(std::string_view word, std::initializer_list<std::string_view> candidates) {
    return closest_match(word, std::vector<std::string_view>(candidates));
}

std::string closest_match(std::string_view word, const std::vector<std::string_view>& candidates,
                          size_t max_edits) {
    // Optimal string alignment distance (Damerau-Levenshtein without repeated edits of
    // one substring): "materails" is one swap from "materials".
    const auto distance = [](std::string_view a, std::string_view b) {
        std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
        for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
        for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
        for (size_t i = 1; i <= a.size(); ++i)
            for (size_t j = 1; j <= b.size(); ++j) {
                d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
                if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                    d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
            }
        return d[a.size()][b.size()];
    };
    // Keys are short; a long one cannot be a typo of them (and must not cost much).
    if (word.size() > 64) return "";
    std::string best;
    size_t best_d = std::numeric_limits<size_t>::max();
    for (const auto c : candidates) {
        // Up to half the longer word may differ ("rotation" for "rotate" is 3 edits),
        // at least 2 ("fov" for "vfov").
        const size_t limit = std::min(max_edits, std::max<size_t>(2, std::max(word.size(), c.size()) / 2));
        if (const size_t d = distance(word, c); d <= limit && d < best_d) {
            best_d = d;
            best = std::string(c);
        }
    }
    return best;
}

void JsonField::require_known_keys(std::initializer_list<std::string_view> known) const {
    require_object();
    for (const auto& [name, value] : value_->items()) {
        if (is_comment_key(name)) continue;
        bool ok = false;
        for (const auto k : known) ok = ok || k == name;
        if (ok) continue;
        const std::string path = key_.empty() ? name : key_ + "." + name;
        const std::string suggestion = closest_match(name, known);
        std::string list;
        for (const auto k : known) list += (list.empty() ? "" : ", ") + std::string(k);
        throw InputError(file_->string() + ": unknown key '" + path + "' = " + shown(value) + " (" +
                         (suggestion.empty() ? "" : "did you mean '" + suggestion + "'? ") + "known keys here: " +
                         list + "; \"comment\" and keys starting with '_' are ignored)");
    }
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
    if (!std::isfinite(d) || !std::isfinite(f)) fail("number is not finite (or overflows a float, |x| > 3.4e38)");
    if (limits::below_normal_float(d)) fail(std::string("number ") + limits::kBelowNormalFloat);
    return f;
}

int JsonField::integer() const {
    if (!value_->is_number_integer()) fail(std::string("expected an integer, got ") + value_->type_name());
    // A literal above INT64_MAX is stored unsigned; get<long long> would wrap it.
    const bool too_big = value_->is_number_unsigned() &&
                         value_->get<unsigned long long>() > static_cast<unsigned long long>(std::numeric_limits<int>::max());
    const auto v = too_big ? 0 : value_->get<long long>();
    if (too_big || v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
        fail("integer out of range (it must fit a 32-bit int)");
    return static_cast<int>(v);
}

std::string JsonField::string() const {
    if (!value_->is_string()) fail(std::string("expected a string, got ") + value_->type_name());
    std::string text = value_->get<std::string>();
    // JSON may spell a NUL ("\u0000"); a path or name holding one would be cut short by
    // the operating system and by every message that quotes it.
    if (text.find('\0') != std::string::npos) fail("must not contain a NUL character (\\u0000)");
    return text;
}

glm::vec3 JsonField::vec3() const {
    if (size() != 3) fail("expected an array of 3 numbers, got " + std::to_string(size()) + " elements");
    return {at(0).number(), at(1).number(), at(2).number()};
}

glm::vec3 read_colour(const JsonField& j, Colour kind) {
    const glm::vec3 c = j.vec3();
    for (int i = 0; i < 3; ++i) {
        if (c[i] < 0.0f) j.fail("colour components must be >= 0");
        if (kind == Colour::Albedo && c[i] > 1.0f) j.fail("albedo components must be <= 1 (in [0, 1])");
        if (kind == Colour::Radiance && c[i] > limits::kMaxRadiance)
            j.fail("radiance components must be <= " + limits::shown_radiance_limit());
    }
    return c;
}

void check_camera_view(const JsonField& where, glm::vec3 position, glm::vec3 look_at, glm::vec3 up,
                       const std::string& when) {
    if (const char* problem = camera_view_problem(position, look_at, up)) where.fail(when + problem);
}

}  // namespace tessera::scene_detail
