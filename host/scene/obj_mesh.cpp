#include "scene/obj_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <tiny_obj_loader.h>

#include "util/error.h"

namespace tessera::scene_detail {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void obj_error(const fs::path& obj, const std::string& what) {
    throw InputError(obj.string() + ": " + what);
}

// tinyobjloader 2.0rc10 reads a coordinate it cannot parse ("nan", "inf") as 0
// without a warning, so a corrupt vertex would silently move to the origin. This scan
// re-reads only the coordinates of `v` lines, with strtod, to catch those; all other
// parsing stays with tinyobjloader.
void check_vertex_text(const fs::path& obj) {
    std::ifstream in(obj);
    std::string line;
    for (size_t line_no = 1; std::getline(in, line); ++line_no) {
        if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
        std::istringstream tokens(line.substr(2));
        std::string tok;
        for (int i = 0; i < 3 && tokens >> tok; ++i) {
            const double d = std::strtod(tok.c_str(), nullptr);
            if (!std::isfinite(d) || !std::isfinite(static_cast<float>(d)))
                obj_error(obj, "line " + std::to_string(line_no) + ": vertex coordinate '" + tok +
                                   "' is not a finite number");
        }
    }
}

// Turns tinyobjloader warnings that mean bad input into errors. The strings matched
// are the ones tinyobjloader 2.0rc10 emits (see LoadObj / MaterialFileReader).
void check_warnings(const fs::path& obj, const std::string& warn) {
    std::istringstream lines(warn);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.find("Material file [") != std::string::npos) {
            const auto a = line.find('[') + 1, b = line.find(']');
            std::string mtl = line.substr(a, b - a);
            while (!mtl.empty() && mtl.front() == ' ') mtl.erase(mtl.begin());
            while (!mtl.empty() && mtl.back() == ' ') mtl.pop_back();
            obj_error(obj, "MTL file '" + mtl + "' (named by mtllib) not found in " +
                               obj.parent_path().string());
        }
        if (line.find("not found in .mtl") != std::string::npos)
            obj_error(obj, "usemtl names a material the MTL does not define: " + line);
    }
}

Material convert_material(const tinyobj::material_t& m, const fs::path& obj,
                          std::map<fs::path, int>& texture_index,
                          std::vector<fs::path>& texture_files) {
    Material out;
    out.name = m.name;
    // Kd above 1 would make the surface create energy; clamping is documented in
    // scenes/README.md.
    for (int c = 0; c < 3; ++c) {
        out.albedo[c] = std::clamp(static_cast<float>(m.diffuse[c]), 0.0f, 1.0f);
        out.emission[c] = static_cast<float>(m.emission[c]);
        out.specular[c] = std::clamp(static_cast<float>(m.specular[c]), 0.0f, 1.0f);
        if (!std::isfinite(out.albedo[c]) || !std::isfinite(out.emission[c]) || out.emission[c] < 0)
            obj_error(obj, "material '" + m.name + "': Kd/Ke must be finite, Ke non-negative");
    }
    out.illum = m.illum;
    out.ior = static_cast<float>(m.ior);
    if (!m.diffuse_texname.empty()) {
        // map_Kd is relative to the MTL, which tinyobjloader looks up beside the OBJ.
        const fs::path file = (obj.parent_path() / m.diffuse_texname).lexically_normal();
        std::error_code ec;
        if (!fs::is_regular_file(file, ec))
            obj_error(obj, "material '" + m.name + "': map_Kd texture '" + file.string() +
                               "' not found");
        auto [it, added] = texture_index.try_emplace(file, static_cast<int>(texture_files.size()));
        if (added) texture_files.push_back(file);
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
    std::error_code ec;
    if (!fs::is_regular_file(obj_file, ec)) obj_error(obj_file, "OBJ file not found");
    check_vertex_text(obj_file);

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    const bool ok = reader.ParseFromFile(obj_file.string(), config);
    if (!ok || !reader.Error().empty())
        obj_error(obj_file, "OBJ parse error: " + reader.Error());
    check_warnings(obj_file, reader.Warning());

    const auto& attrib = reader.GetAttrib();
    for (const float v : attrib.vertices)
        if (!std::isfinite(v)) obj_error(obj_file, "a vertex position is not finite");
    // Texture lookups index texels with them: a non-finite one has no texel.
    for (const float t : attrib.texcoords)
        if (!std::isfinite(t)) obj_error(obj_file, "a texture coordinate (vt) is not finite");

    ObjMesh mesh;
    std::map<fs::path, int> texture_index;
    for (const auto& m : reader.GetMaterials())
        mesh.materials.push_back(convert_material(m, obj_file, texture_index, mesh.texture_files));
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
    if (mesh.material.empty()) obj_error(obj_file, "OBJ has no faces");
    return mesh;
}

}  // namespace tessera::scene_detail
