// Object-to-world transforms and appending transformed triangles to a Scene.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "scene/obj_mesh.h"
#include "scene/scene.h"

namespace tessera::scene_detail {

struct Rotation {
    glm::vec3 axis;  ///< any non-zero length; normalised when used
    float degrees;   ///< counter-clockwise looking down the axis (right-handed)
};

/// An affine object-to-world transform.
struct Transform {
    glm::mat4 matrix{1.0f};         ///< points: world = matrix * (p, 1)
    glm::mat3 normal_matrix{1.0f};  ///< normals: inverse-transpose of the linear part
    bool flips_winding = false;     ///< determinant < 0 (a mirror): swap two corners
};

/// Scale first, then the rotations in list order, then the translation.
/// The caller must ensure the scale has no zero component (determinant 0).
Transform make_transform(glm::vec3 scale, const std::vector<Rotation>& rotations,
                         glm::vec3 translate);

/// Appends `mesh` transformed by `t` to `scene`; a triangle of mesh material k gets
/// scene material `material_index[k]` (one per mesh.materials entry). A mirroring
/// transform gets corners 1 and 2 swapped so cross(p1 - p0, p2 - p0) keeps facing the
/// same side of the surface. Missing, zero or non-finite normals become the geometric
/// normal (or +y for a degenerate triangle, whose normal is undefined).
void append_mesh(Scene& scene, const ObjMesh& mesh, const Transform& t, const std::vector<uint32_t>& material_index);

/// Appends the parallelogram light corner + [0,1]·edge1 + [0,1]·edge2 as two triangles
/// with a new material (albedo 0, emission `radiance`). It emits from the side of
/// cross(edge1, edge2) only.
void append_quad_light(Scene& scene, glm::vec3 corner, glm::vec3 edge1, glm::vec3 edge2,
                       glm::vec3 radiance, const std::string& name);

}  // namespace tessera::scene_detail
