#include "scene/obj_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include <tiny_obj_loader.h>

#include "scene/input_file.h"
#include "scene/mtl_scan.h"
#include "scene/obj_scan.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void obj_error(const fs::path& obj, const std::string& what) {
    throw InputError(obj.string() + ": " + what);
}

[[noreturn]] void obj_line_error(const fs::path& obj, size_t line, const std::string& what) {
    throw InputError(obj.string() + ":" + std::to_string(line) + ": " + what);
}

// Turns tinyobjloader warnings that mean bad input into errors. scan_obj, scan_mtl and
// check_usemtl catch these cases first, with the line; this is the backstop should the
// parser find one they do not. The strings matched are tinyobjloader 2.0rc10's (LoadObj,
// MaterialFileReader, exportGroupsToShape).
void check_warnings(const fs::path& obj, const std::string& warn) {
    std::istringstream lines(warn);
    std::string line;
    while (std::getline(lines, line)) {
        for (const char* bad : {"Material file [", "not found in .mtl", "invalid vertex index", "Degenerated face"})
            if (line.find(bad) != std::string::npos) obj_error(obj, "OBJ rejected by the parser: " + line);
    }
}

// The line of the mtllib statement that read `mtl`.
size_t mtllib_line(const ObjScan& scan, const fs::path& mtl) {
    for (const auto& lib : scan.mtllibs)
        if (lib.file == mtl) return lib.line;
    return 0;
}

// Each usemtl must name a material of an MTL file read by an earlier mtllib line (as
// tinyobjloader looks them up); otherwise its faces would silently get no material.
void check_usemtl(const fs::path& obj, const ObjScan& scan, const std::map<std::string, MtlDefinition>& defined) {
    for (const UseMtlLine& use : scan.usemtls) {
        const auto it = defined.find(use.name);
        if (it != defined.end() && mtllib_line(scan, it->second.file) < use.line) continue;
        std::string files, names;
        for (const auto& lib : scan.mtllibs)
            if (lib.line < use.line) files += (files.empty() ? "" : ", ") + lib.file.string();
        for (const auto& [name, def] : defined)
            if (mtllib_line(scan, def.file) < use.line) names += (names.empty() ? "" : ", ") + name;
        if (names.size() > 200) names = names.substr(0, 200) + "...";
        obj_line_error(obj, use.line,
                       "usemtl '" + use.name + "' names no material of " +
                           (files.empty() ? std::string("an MTL file: no mtllib line comes before it")
                                          : "the MTL file(s) read before it: " + files + " (defining " +
                                                (names.empty() ? std::string("no material") : names) + ")"));
    }
}

// Polygons of more than 4 corners go through tinyobjloader's ear clipping, which drops
// the triangles of a polygon it cannot clip (self-intersecting, or not planar enough).
void check_triangle_count(const fs::path& obj, const ObjScan& scan, const tinyobj::ObjReader& reader) {
    size_t triangles = 0;
    for (const auto& shape : reader.GetShapes()) triangles += shape.mesh.num_face_vertices.size();
    if (triangles != scan.triangles)
        obj_line_error(obj, scan.first_polygon_line,
                       "a polygon of more than 4 corners (the first is on this line) could not be "
                       "triangulated: the faces give " + std::to_string(scan.triangles) +
                           " triangles, the parser made " + std::to_string(triangles) +
                           "; split non-planar or self-intersecting polygons into triangles");
}

Material convert_material(const tinyobj::material_t& m, const fs::path& obj,
                          const std::map<std::string, MtlDefinition>& defined,
                          std::map<fs::path, int>& texture_index, std::vector<fs::path>& texture_files,
                          std::vector<std::string>& texture_roles, std::vector<std::string>& notes) {
    const auto def = defined.find(m.name);
    const std::string where =
        (def == defined.end() ? obj.string() : def->second.file.string() + ":" + std::to_string(def->second.line)) +
        ": material '" + m.name + "'";
    Material out;
    out.name = m.name;
    // scan_mtl has rejected negative and non-finite values with their line; this check of
    // what the parser produced is the backstop. Kd above 1 would make the surface create
    // energy: it is clamped (documented in scenes/README.md), and Ks likewise.
    for (int c = 0; c < 3; ++c) {
        for (const float v : {m.diffuse[c], m.specular[c], m.emission[c]})
            if (!(std::isfinite(v) && v >= 0.0f)) throw InputError(where + ": Kd, Ks and Ke must be finite and >= 0");
        out.albedo[c] = std::min(static_cast<float>(m.diffuse[c]), 1.0f);
        out.emission[c] = static_cast<float>(m.emission[c]);
        out.specular[c] = std::min(static_cast<float>(m.specular[c]), 1.0f);
    }
    auto note_clamped = [&](const char* statement, const tinyobj::real_t* v) {
        if (v[0] <= 1 && v[1] <= 1 && v[2] <= 1) return;
        char text[96];
        std::snprintf(text, sizeof text, "%s %g %g %g clamped to 1 per channel", statement, double(v[0]),
                      double(v[1]), double(v[2]));
        notes.push_back(where + ": " + text + " (above 1 the surface would reflect more light than it receives)");
    };
    note_clamped("Kd", m.diffuse);
    note_clamped("Ks", m.specular);
    out.illum = m.illum;
    out.ior = static_cast<float>(m.ior);
    if (!(std::isfinite(out.ior) && out.ior >= 0.0f) || (out.illum == 7 && out.ior == 0.0f))
        throw InputError(where + ": Ni must be finite and >= 0 (> 0 for illum 7)");
    if (!m.diffuse_texname.empty()) {
        // map_Kd is relative to the MTL, which is beside the OBJ (scan_obj).
        const fs::path file = (obj.parent_path() / m.diffuse_texname).lexically_normal();
        const std::string role =
            "map_Kd of " + (def == defined.end() || def->second.map_kd_line == 0
                                ? where
                                : def->second.file.string() + ":" + std::to_string(def->second.map_kd_line) +
                                      ": material '" + m.name + "'");
        require_regular_file(file, "texture (" + role + ")");
        auto [it, added] = texture_index.try_emplace(file, static_cast<int>(texture_files.size()));
        if (added) texture_files.push_back(file), texture_roles.push_back(role);
        out.texture = it->second;
    }
    return out;
}

void check_index(const fs::path& obj, const std::string& shape, size_t face, const char* kind,
                 int idx, size_t count, bool optional) {
    if (optional && idx == -1) return;  // -1: not given
    if (idx >= 0 && static_cast<size_t>(idx) < count) return;
    // tinyobjloader has already made the index 0-based (a relative one absolute), so a
    // non-negative index is reported 1-based as written in a plain OBJ.
    const std::string name = shape.empty() ? "(unnamed)" : shape;
    obj_error(obj, "shape '" + name + "' face " + std::to_string(face + 1) + ": " + kind +
                       " index " + std::to_string(idx >= 0 ? idx + 1 : idx) +
                       " out of range (the file has " + std::to_string(count) + ")");
}

}  // namespace

ObjMesh load_obj_mesh(const fs::path& obj_file) {
    const ObjScan scan = scan_obj(obj_file, read_input_file(obj_file, "OBJ file", limits::kMeshFileBytes));
    std::map<std::string, MtlDefinition> defined;
    for (const MtlLibLine& lib : scan.mtllibs) {
        const std::string why = "MTL file (mtllib at " + obj_file.string() + ":" + std::to_string(lib.line) + ")";
        scan_mtl(lib.file, read_input_file(lib.file, why, limits::kMeshFileBytes), defined);
    }
    check_usemtl(obj_file, scan, defined);

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    const bool ok = reader.ParseFromFile(obj_file.string(), config);
    if (!ok || !reader.Error().empty())
        obj_error(obj_file, "OBJ rejected by the parser: " + reader.Error());
    check_warnings(obj_file, reader.Warning());
    check_triangle_count(obj_file, scan, reader);

    const auto& attrib = reader.GetAttrib();
    for (const float v : attrib.vertices)
        if (!std::isfinite(v)) obj_error(obj_file, "a vertex position is not finite");
    // Texture lookups index texels with them: a non-finite one has no texel.
    for (const float t : attrib.texcoords)
        if (!std::isfinite(t)) obj_error(obj_file, "a texture coordinate (vt) is not finite");

    ObjMesh mesh;
    for (const MtlLibLine& lib : scan.mtllibs) mesh.mtl_files.push_back(lib.file);
    std::map<fs::path, int> texture_index;
    for (const auto& m : reader.GetMaterials())
        mesh.materials.push_back(
            convert_material(m, obj_file, defined, texture_index, mesh.texture_files, mesh.texture_roles,
                             mesh.notes));
    const auto default_material = static_cast<uint32_t>(mesh.materials.size());
    bool uses_default = false;

    const size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3,
                 nt = attrib.texcoords.size() / 2;
    for (const auto& shape : reader.GetShapes()) {
        const auto& idx = shape.mesh.indices;
        const auto& fv = shape.mesh.num_face_vertices;
        for (size_t f = 0; f < fv.size(); ++f) {
            if (fv[f] != 3)
                obj_error(obj_file, "shape '" + shape.name + "' face " + std::to_string(f + 1) +
                                        " has " + std::to_string(fv[f]) + " vertices after triangulation");
            for (size_t k = 0; k < 3; ++k) {
                const auto& i = idx[3 * f + k];
                check_index(obj_file, shape.name, f, "vertex", i.vertex_index, nv, false);
                check_index(obj_file, shape.name, f, "normal", i.normal_index, nn, true);
                check_index(obj_file, shape.name, f, "texcoord", i.texcoord_index, nt, true);
                const float* p = &attrib.vertices[3 * size_t(i.vertex_index)];
                mesh.positions.emplace_back(p[0], p[1], p[2]);
                if (i.normal_index >= 0) {
                    const float* n = &attrib.normals[3 * size_t(i.normal_index)];
                    mesh.normals.emplace_back(n[0], n[1], n[2]);
                } else {
                    mesh.normals.emplace_back(0.0f);
                }
                if (i.texcoord_index >= 0) {
                    const float* t = &attrib.texcoords[2 * size_t(i.texcoord_index)];
                    mesh.uvs.emplace_back(t[0], t[1]);
                } else {
                    mesh.uvs.emplace_back(0.0f);
                }
            }
            const int mid = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            if (mid >= static_cast<int>(mesh.materials.size()))
                obj_error(obj_file, "shape '" + shape.name + "': material id out of range");
            uses_default |= mid < 0;
            mesh.material.push_back(mid < 0 ? default_material : static_cast<uint32_t>(mid));
        }
    }
    if (uses_default) {
        Material grey;
        grey.name = "(default)";
        grey.albedo = glm::vec3(0.5f);
        mesh.materials.push_back(grey);
    }
    if (mesh.material.empty()) obj_error(obj_file, "OBJ has no faces (no f lines)");
    return mesh;
}

}  // namespace tessera::scene_detail
