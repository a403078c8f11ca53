#include "scene/obj_scan.h"

#include <climits>
#include <cmath>
#include <set>

#include "scene/obj_text.h"

namespace tessera::scene_detail {

namespace fs = std::filesystem;

namespace {

std::string in_quotes(std::string_view s) { return "'" + std::string(s) + "'"; }

// Element counts: total in the file, and defined so far while scanning.
struct Counts {
    size_t v = 0, vt = 0, vn = 0;
};

// `count` numbers after the keyword, each in tinyobjloader's grammar; the first
// `finite` of them must be finite as floats (the ones the loader uses).
void check_reals(const fs::path& obj, const TextLine& l, size_t min, size_t max, size_t finite,
                 const char* what) {
    const auto values = value_tokens(l);
    if (values.size() < min || values.size() > max)
        line_error(obj, l.number, std::string(what) + " needs " +
                                      (min == max ? std::to_string(min) : std::to_string(min) + " to " + std::to_string(max)) +
                                      " numbers, got " + std::to_string(values.size()) + ": " + in_quotes(l.text));
    for (size_t i = 0; i < values.size(); ++i) {
        double d = 0;
        if (!parse_real(values[i], d))
            line_error(obj, l.number, std::string(what) + " value " + in_quotes(values[i]) + " is not a number");
        if (i < finite && !(std::isfinite(d) && std::isfinite(static_cast<float>(d))))
            line_error(obj, l.number, std::string(what) + " value " + in_quotes(values[i]) +
                                          " is not finite (or overflows a float)");
    }
}

// vw <vertex> <joint> <weight> [<joint> <weight> ...], tinyobjloader's skin-weight
// extension (not used here). Its parser converts the vertex with atoi and each joint id,
// read as a float, to int: an id that is not finite or outside [0, 2^31) as a float would
// be undefined behaviour inside it (found by scripts/fuzz), so every value must be a
// number and those two in range.
void check_skin_weight(const fs::path& obj, const TextLine& l) {
    const auto values = value_tokens(l);
    long long vertex = 0;
    bool overflow = false;
    if (values.empty() || !parse_index(values[0], vertex, overflow) || overflow || vertex < INT_MIN ||
        vertex > INT_MAX)
        line_error(obj, l.number, "skin weight (vw) needs a vertex index that fits an int first: " + in_quotes(l.text));
    for (size_t i = 1; i < values.size(); ++i) {
        double d = 0;
        if (!parse_real(values[i], d))
            line_error(obj, l.number, "skin weight (vw) value " + in_quotes(values[i]) + " is not a number");
        const bool joint = i % 2 == 1;
        if (joint && !(d >= 0.0 && static_cast<float>(d) < 2147483648.0f))
            line_error(obj, l.number, "skin weight (vw) joint id " + in_quotes(values[i]) +
                                          " is not a float in [0, 2^31)");
    }
}

// One index of a corner: `kind` is "vertex", "texcoord" or "normal".
void check_index(const fs::path& obj, const TextLine& l, std::string_view corner, std::string_view text,
                 const char* kind, size_t total, size_t so_far) {
    long long idx = 0;
    bool overflow = false;
    if (!parse_index(text, idx, overflow))
        line_error(obj, l.number, "corner " + in_quotes(corner) + ": " + kind + " index " + in_quotes(text) +
                                      " is not an integer");
    if (!overflow && idx == 0)
        line_error(obj, l.number, "corner " + in_quotes(corner) + ": " + kind +
                                      " index 0 is invalid (OBJ indices start at 1; negative ones count back "
                                      "from the last element defined)");
    const bool in_range = !overflow && (idx > 0 ? static_cast<unsigned long long>(idx) <= total
                                                : static_cast<unsigned long long>(-idx) <= so_far);
    if (!in_range)
        line_error(obj, l.number, "corner " + in_quotes(corner) + ": " + kind + " index " + in_quotes(text) +
                                      " is out of range (" +
                                      (idx > 0 || overflow ? "the file has " + std::to_string(total)
                                                           : std::to_string(so_far) + " defined before this line") +
                                      ")");
}

// One corner of f/l/p: v, v/vt, v//vn or v/vt/vn.
void check_corner(const fs::path& obj, const TextLine& l, std::string_view corner, const Counts& total,
                  const Counts& so_far) {
    std::vector<std::string_view> parts;
    for (size_t start = 0;;) {
        const size_t slash = corner.find('/', start);
        parts.push_back(corner.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start));
        if (slash == std::string_view::npos) break;
        start = slash + 1;
    }
    const bool shape_ok = parts.size() <= 3 && !parts[0].empty() &&
                          (parts.size() < 2 || !parts[1].empty() || parts.size() == 3) &&
                          (parts.size() < 3 || !parts[2].empty());
    if (!shape_ok)
        line_error(obj, l.number, "corner " + in_quotes(corner) + " is not v, v/vt, v//vn or v/vt/vn");
    check_index(obj, l, corner, parts[0], "vertex", total.v, so_far.v);
    if (parts.size() >= 2 && !parts[1].empty()) check_index(obj, l, corner, parts[1], "texcoord", total.vt, so_far.vt);
    if (parts.size() == 3) check_index(obj, l, corner, parts[2], "normal", total.vn, so_far.vn);
}

// mtllib names one file, relative to the OBJ's folder and inside it. tinyobjloader splits
// the names at spaces (a backslash escapes one) and reads only the first that exists.
MtlLibLine check_mtllib(const fs::path& obj, const TextLine& l) {
    std::string rest(l.text.substr(l.tokens[0].size()));
    rest.erase(0, rest.find_first_not_of(" \t"));
    std::vector<std::string> names(1);
    for (size_t i = 0; i < rest.size(); ++i) {
        if (rest[i] == '\\' && i + 1 < rest.size() && rest[i + 1] == ' ') names.back() += rest[++i];
        else if (rest[i] == ' ') { if (!names.back().empty()) names.emplace_back(); }
        else names.back() += rest[i];
    }
    if (names.back().empty()) names.pop_back();
    if (names.empty()) line_error(obj, l.number, "mtllib names no file");
    if (names.size() > 1)
        line_error(obj, l.number, "mtllib names " + std::to_string(names.size()) +
                                      " files; write one mtllib line per MTL file");
    // Beside the OBJ, so that map_Kd paths (relative to the MTL) are relative to the OBJ's
    // folder too, and a mesh cannot make the loader read files elsewhere.
    const fs::path norm = fs::path(names[0]).lexically_normal();
    if (norm.is_absolute() || norm.has_parent_path() || norm == ".." || norm == "." || norm.empty())
        line_error(obj, l.number, "mtllib " + in_quotes(names[0]) + " is not a file name beside the OBJ (in " +
                                      obj.parent_path().string() + "); MTL files are looked up only there");
    return {l.number, names[0], obj.parent_path() / norm};
}

Counts count_elements(const std::vector<TextLine>& lines) {
    Counts c;
    for (const TextLine& l : lines) {
        const auto k = l.tokens[0];
        if (k == "v") ++c.v;
        else if (k == "vt") ++c.vt;
        else if (k == "vn") ++c.vn;
    }
    return c;
}

}  // namespace

ObjScan scan_obj(const fs::path& obj, std::string_view text) {
    const std::vector<TextLine> lines = text_lines(obj, text);
    const Counts total = count_elements(lines);
    Counts so_far;
    ObjScan scan;
    std::set<fs::path> mtl_seen;
    for (const TextLine& l : lines) {
        const std::string_view k = l.tokens[0];
        if (k == "v") {
            // x y z, then tinyobjloader's optional w or r g b (not used here).
            check_reals(obj, l, 3, 6, 3, "vertex (v)");
            ++so_far.v;
        } else if (k == "vt") {
            check_reals(obj, l, 1, 3, 2, "texture coordinate (vt)");
            ++so_far.vt;
        } else if (k == "vn") {
            check_reals(obj, l, 3, 3, 3, "normal (vn)");
            ++so_far.vn;
        } else if (k == "vw") {
            check_skin_weight(obj, l);
        } else if (k == "f" || k == "l" || k == "p") {
            const size_t corners = l.tokens.size() - 1;
            const size_t needed = k == "f" ? 3 : k == "l" ? 2 : 1;
            if (corners < needed)
                line_error(obj, l.number, std::string(k == "f" ? "face" : k == "l" ? "line" : "point") +
                                              " has " + std::to_string(corners) + " corner" +
                                              (corners == 1 ? "" : "s") + " (needs at least " +
                                              std::to_string(needed) + "): " + in_quotes(l.text));
            for (size_t i = 1; i < l.tokens.size(); ++i) check_corner(obj, l, l.tokens[i], total, so_far);
            if (k == "f") {
                scan.triangles += corners - 2;
                if (corners > 4 && scan.first_polygon_line == 0) scan.first_polygon_line = l.number;
            }
        } else if (k == "mtllib") {
            MtlLibLine m = check_mtllib(obj, l);
            if (mtl_seen.insert(m.file).second) scan.mtllibs.push_back(std::move(m));
        } else if (k.substr(0, 6) == "usemtl") {
            // tinyobjloader matches the prefix and takes the next token as the name.
            const std::string_view name = k.size() > 6 ? k.substr(6) : l.tokens.size() > 1 ? l.tokens[1] : "";
            scan.usemtls.push_back({l.number, std::string(name)});
        }
    }
    return scan;
}

}  // namespace tessera::scene_detail
