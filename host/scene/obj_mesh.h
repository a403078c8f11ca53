// Reading one OBJ file (and its MTL) into object-space triangles, with validation.
#pragma once
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace tessera::scene_detail {

/// One OBJ file flattened to triangles, in the file's own (object) space.
/// Triangle i has corners positions/normals/uvs[3i..3i+2] and material[i], an index
/// into `materials` (always valid: faces without `usemtl` get an appended default
/// grey material). A normal is the zero vector where the file gives none; the caller
/// replaces it with the geometric normal after transforming. Material::texture
/// indexes `texture_files`, the resolved map_Kd paths (deduplicated).
struct ObjMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<uint32_t> material;
    std::vector<Material> materials;
    std::vector<std::filesystem::path> texture_files;
    std::vector<std::filesystem::path> mtl_files;  ///< the MTL files it read (mtllib), in order
    /// Where each of texture_files is named: "map_Kd of <mtl>:<line>: material '<name>'"
    /// (the first material that names it), for a message about the texture's content.
    std::vector<std::string> texture_roles;
    /// What loading changed without an error (Scene::notes): a Kd or Ks above 1 clamped.
    std::vector<std::string> notes;
};

/// Loads `obj_file` with tinyobjloader (quads split along the shorter diagonal, larger
/// polygons by ear clipping), after scan_obj (scene/obj_scan.h) and scan_mtl
/// (scene/mtl_scan.h) have checked the text of the OBJ and of each MTL it names. Throws
/// InputError naming the OBJ, MTL or texture file (with the line where there is one) for
/// everything those list, and for: a missing, directory or unreadable file; a `usemtl`
/// naming no material of the MTL files read before it (the message lists them); a
/// polygon the parser cannot triangulate; a missing map_Kd file; no faces. Kd and Ks
/// are clamped to at most 1 per channel.
ObjMesh load_obj_mesh(const std::filesystem::path& obj_file);

}  // namespace tessera::scene_detail
