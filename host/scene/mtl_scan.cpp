#include "scene/mtl_scan.h"

#include <cmath>
#include <optional>
#include <vector>

#include "scene/obj_text.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {

namespace fs = std::filesystem;

namespace {

std::string in_quotes(std::string_view s) { return "'" + std::string(s) + "'"; }

// The statements of one material that need checking together.
struct Current {
    std::string name;
    size_t line = 0;
    std::optional<double> ni;
    std::string ni_text;
    size_t ni_line = 0;
    long illum = 2;
};

class MtlScanner {
public:
    MtlScanner(const fs::path& mtl, std::map<std::string, MtlDefinition>& defined)
        : mtl_(mtl), defined_(defined) {}

    void statement(const TextLine& l) {
        const std::string_view k = l.tokens[0];
        if (k == "newmtl") return begin(l);
        const bool read = k == "Kd" || k == "Ks" || k == "Ke" || k == "Ni" || k == "illum" || k == "map_Kd";
        if (read && cur_.name.empty())
            fail(l.number, std::string(k) + " belongs to no material (the loader would drop it)");
        if (k == "Kd" || k == "Ks" || k == "Ke") colour(l, k);
        else if (k == "Ni") ior(l);
        else if (k == "illum") illum(l);
        else if (k == "map_Kd") map_kd(l);
    }

    // A dielectric's Ni is only known to be bad once its illum is known, which may come
    // later: checked when the material ends.
    void end() {
        if (cur_.illum == 7 && cur_.ni && !(*cur_.ni > 0.0))
            fail(cur_.ni_line, "Ni " + in_quotes(cur_.ni_text) +
                                   " in a dielectric (illum 7): the index of refraction must be > 0");
    }

private:
    [[noreturn]] void fail(size_t line, const std::string& what) const {
        line_error(mtl_, line, (cur_.name.empty() ? std::string("before any newmtl") : "material " + in_quotes(cur_.name)) +
                                   ": " + what);
    }

    void begin(const TextLine& l) {
        end();
        if (l.tokens.size() < 2) line_error(mtl_, l.number, "newmtl needs a material name");
        // tinyobjloader: the name is the rest of the line after "newmtl" and one blank.
        cur_ = Current{};
        cur_.name = std::string(l.text.substr(7));
        cur_.line = l.number;
        auto [it, added] = defined_.try_emplace(cur_.name, MtlDefinition{mtl_, l.number});
        if (!added)
            fail(l.number, "defined twice (first at " + it->second.file.string() + ":" +
                               std::to_string(it->second.line) + ")");
    }

    double number(const TextLine& l, std::string_view key, std::string_view token) const {
        double d = 0;
        if (!parse_real(token, d))
            fail(l.number, std::string(key) + " value " + in_quotes(token) + " is not a number");
        if (!std::isfinite(d) || !std::isfinite(static_cast<float>(d)))
            fail(l.number, std::string(key) + " value " + in_quotes(token) + " is not finite (or overflows a float)");
        if (limits::below_normal_float(d))
            fail(l.number, std::string(key) + " value " + in_quotes(token) + " " + limits::kBelowNormalFloat);
        return d;
    }

    void colour(const TextLine& l, std::string_view key) const {
        const auto values = value_tokens(l);
        if (values.size() != 3)
            fail(l.number, std::string(key) + " needs 3 numbers (r g b), got " + in_quotes(l.text) +
                               " (spectral and xyz forms are not supported)");
        for (const auto v : values) {
            const double d = number(l, key, v);
            if (d < 0.0) fail(l.number, std::string(key) + " value " + in_quotes(v) + " is negative (must be >= 0)");
            if (key == "Ke" && static_cast<float>(d) > limits::kMaxRadiance)
                fail(l.number, "Ke value " + in_quotes(v) + " exceeds the limit of " + limits::shown_radiance_limit());
        }
    }

    void ior(const TextLine& l) {
        const auto values = value_tokens(l);
        if (values.size() != 1) fail(l.number, "Ni needs 1 number, got " + in_quotes(l.text));
        const double d = number(l, "Ni", values[0]);
        if (d < 0.0) fail(l.number, "Ni value " + in_quotes(values[0]) + " is negative (must be >= 0)");
        cur_.ni = d;
        cur_.ni_text = std::string(values[0]);
        cur_.ni_line = l.number;
    }

    // A map_Kd with no token after it names no texture (tinyobjloader took it as none); the
    // line is kept so that the texture's own errors can name it (scene/obj_mesh.cpp).
    void map_kd(const TextLine& l) {
        if (value_tokens(l).empty()) fail(l.number, "map_Kd needs a texture file name");
        defined_[cur_.name].map_kd_line = l.number;
    }

    void illum(const TextLine& l) {
        const auto values = value_tokens(l);
        long long v = 0;
        bool overflow = false;
        if (values.size() != 1 || !parse_index(values[0], v, overflow))
            fail(l.number, "illum needs 1 integer, got " + in_quotes(l.text));
        if (overflow || v < 0 || v > 10)
            fail(l.number, "illum " + in_quotes(values[0]) + " is not an MTL illumination model (0..10)");
        cur_.illum = static_cast<long>(v);
    }

    const fs::path& mtl_;
    std::map<std::string, MtlDefinition>& defined_;
    Current cur_;
};

}  // namespace

void scan_mtl(const fs::path& mtl, std::string_view text, std::map<std::string, MtlDefinition>& defined) {
    MtlScanner scanner(mtl, defined);
    for (const TextLine& l : text_lines(mtl, text)) scanner.statement(l);
    scanner.end();
}

}  // namespace tessera::scene_detail
