#include "scene/transform.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace tessera::scene_detail {

Transform make_transform(glm::vec3 scale, const std::vector<Rotation>& rotations,
                         glm::vec3 translate) {
    // Built right to left: the last matrix multiplied in is applied first.
    glm::mat4 rot(1.0f);
    for (const auto& r : rotations)
        rot = glm::rotate(glm::mat4(1.0f), glm::radians(r.degrees), glm::normalize(r.axis)) * rot;
    Transform t;
    t.matrix = glm::translate(glm::mat4(1.0f), translate) * rot * glm::scale(glm::mat4(1.0f), scale);
    const glm::mat3 linear(t.matrix);
    t.normal_matrix = glm::transpose(glm::inverse(linear));
    t.flips_winding = glm::determinant(linear) < 0.0f;
    return t;
}

namespace {

bool usable(glm::vec3 n) {
    const float len2 = glm::dot(n, n);
    return std::isfinite(len2) && len2 > 0.0f;
}

glm::vec3 geometric_normal(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2) {
    const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
    return usable(n) ? glm::normalize(n) : glm::vec3(0.0f, 1.0f, 0.0f);
}

}  // namespace

void append_mesh(Scene& scene, const ObjMesh& mesh, const Transform& t, const std::vector<uint32_t>& material_index) {
    const size_t tris = mesh.material.size();
    scene.positions.reserve(scene.positions.size() + 3 * tris);
    scene.normals.reserve(scene.normals.size() + 3 * tris);
    scene.uvs.reserve(scene.uvs.size() + 3 * tris);
    // Corner order; a mirror swaps corners 1 and 2 to restore the front side.
    const size_t order[2][3] = {{0, 1, 2}, {0, 2, 1}};
    const size_t* o = order[t.flips_winding ? 1 : 0];
    for (size_t i = 0; i < tris; ++i) {
        glm::vec3 p[3], n[3];
        for (size_t k = 0; k < 3; ++k) {
            const size_t src = 3 * i + o[k];
            p[k] = glm::vec3(t.matrix * glm::vec4(mesh.positions[src], 1.0f));
            n[k] = t.normal_matrix * mesh.normals[src];
        }
        const glm::vec3 ng = geometric_normal(p[0], p[1], p[2]);
        for (size_t k = 0; k < 3; ++k) {
            scene.positions.push_back(p[k]);
            scene.normals.push_back(usable(n[k]) ? glm::normalize(n[k]) : ng);
            scene.uvs.push_back(mesh.uvs[3 * i + o[k]]);
        }
        scene.material.push_back(material_index[mesh.material[i]]);
    }
}

void append_quad_light(Scene& scene, glm::vec3 corner, glm::vec3 edge1, glm::vec3 edge2,
                       glm::vec3 radiance, const std::string& name) {
    Material m;
    m.name = name;
    m.albedo = glm::vec3(0.0f);
    m.emission = radiance;
    const auto mat = static_cast<uint32_t>(scene.materials.size());
    scene.materials.push_back(m);
    const glm::vec3 n = glm::normalize(glm::cross(edge1, edge2));
    // Both triangles have cross(p1 - p0, p2 - p0) parallel to cross(edge1, edge2).
    const glm::vec3 p[4] = {corner, corner + edge1, corner + edge1 + edge2, corner + edge2};
    const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const int k : {0, 1, 2, 0, 2, 3}) {
        scene.positions.push_back(p[k]);
        scene.normals.push_back(n);
        scene.uvs.push_back(uv[k]);
    }
    scene.material.push_back(mat);
    scene.material.push_back(mat);
}

}  // namespace tessera::scene_detail
