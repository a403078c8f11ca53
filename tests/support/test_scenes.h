// Scenes built in code for tests, so the tests state their geometry exactly.
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace tessera::test {

/// Adds a material and returns its index.
inline uint32_t add_material(Scene& s, glm::vec3 albedo, glm::vec3 emission = glm::vec3(0.0f)) {
    Material m;
    m.name = "m" + std::to_string(s.materials.size());
    m.albedo = albedo;
    m.emission = emission;
    s.materials.push_back(m);
    return static_cast<uint32_t>(s.materials.size() - 1);
}

/// Adds the parallelogram corner + [0,1] e1 + [0,1] e2 as two triangles whose front
/// face (geometric normal) is cross(e1, e2).
inline void add_quad(Scene& s, glm::vec3 corner, glm::vec3 e1, glm::vec3 e2, uint32_t material) {
    const glm::vec3 n = glm::normalize(glm::cross(e1, e2));
    const glm::vec3 v[4] = {corner, corner + e1, corner + e1 + e2, corner + e2};
    const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int tri : {0, 1}) {
        const int idx[3] = {0, tri == 0 ? 1 : 2, tri == 0 ? 2 : 3};
        for (int k : idx) {
            s.positions.push_back(v[k]);
            s.normals.push_back(n);
            s.uvs.push_back(uv[k]);
        }
        s.material.push_back(material);
    }
}

/// A closed box [lo, hi] with inward-facing walls of the given albedo and a square
/// light of half-size `light_half` just below the ceiling, facing down.
inline Scene closed_box(glm::vec3 lo, glm::vec3 hi, glm::vec3 albedo, glm::vec3 le, float light_half) {
    Scene s;
    s.name = "test-box";
    const uint32_t wall = add_material(s, albedo);
    const uint32_t light = add_material(s, glm::vec3(0.0f), le);
    const glm::vec3 d = hi - lo;
    add_quad(s, lo, {0, 0, d.z}, {d.x, 0, 0}, wall);                         // floor, +y
    add_quad(s, {lo.x, hi.y, lo.z}, {d.x, 0, 0}, {0, 0, d.z}, wall);         // ceiling, -y
    add_quad(s, lo, {d.x, 0, 0}, {0, d.y, 0}, wall);                         // back z=lo, +z
    add_quad(s, {lo.x, lo.y, hi.z}, {0, d.y, 0}, {d.x, 0, 0}, wall);         // front z=hi, -z
    add_quad(s, lo, {0, d.y, 0}, {0, 0, d.z}, wall);                         // left x=lo, +x
    add_quad(s, {hi.x, lo.y, lo.z}, {0, 0, d.z}, {0, d.y, 0}, wall);         // right x=hi, -x
    const glm::vec3 c = 0.5f * (lo + hi);
    const float y = hi.y - 1e-3f * d.y;
    add_quad(s, {c.x - light_half, y, c.z - light_half}, {2 * light_half, 0, 0}, {0, 0, 2 * light_half},
             light);                                                         // faces -y
    s.camera.position = {c.x, c.y, hi.z - 0.01f * d.z};
    s.camera.look_at = {c.x, c.y, lo.z};
    s.camera.up = {0, 1, 0};
    s.camera.vfov_deg = 80.0f;
    s.camera.width = s.camera.height = 32;
    return s;
}

/// closed_box without its back wall (z = lo.z, the wall the camera faces): camera rays
/// and light paths leave through the opening.
inline Scene open_box(glm::vec3 lo, glm::vec3 hi, glm::vec3 albedo, glm::vec3 le, float light_half) {
    Scene s = closed_box(lo, hi, albedo, le, light_half);
    s.positions.erase(s.positions.begin() + 12, s.positions.begin() + 18);  // the back wall's two triangles
    s.normals.erase(s.normals.begin() + 12, s.normals.begin() + 18);
    s.uvs.erase(s.uvs.begin() + 12, s.uvs.begin() + 18);
    s.material.erase(s.material.begin() + 4, s.material.begin() + 6);
    return s;
}

// A 100 × 100 floor with a 256 × 256 one-texel black/white checker, seen straight down
// from 80 units with a 60° field of view at 32 × 32 pixels (the view, 92 units wide,
// lies inside the floor): one pixel spans 2·80·tan 30° / 32 = 2.9 units = 7.4 texels, so
// the cone picks mip level 2.9 or coarser, where the checker is flat grey (every level
// from 1 on is linear 0.5, 8-bit code 188).
inline Scene checker_floor() {
    Scene s;
    s.name = "checker-floor";
    Texture t;
    t.path = "checker";
    t.width = t.height = 256;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) t.rgba8.push_back((x + y) % 2 ? 0xffffffffu : 0xff000000u);
    s.textures.push_back(t);
    const uint32_t floor = add_material(s, glm::vec3(1.0f));
    s.materials[floor].texture = 0;
    add_quad(s, {-50, 0, -50}, {0, 0, 100}, {100, 0, 0}, floor);  // faces +y
    const uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(1.0f));
    add_quad(s, {-200, 300, -200}, {400, 0, 0}, {0, 0, 400}, light);  // faces -y
    s.camera.position = {0, 80, 0};
    s.camera.look_at = {0, 0, 0};
    s.camera.up = {0, 0, -1};
    s.camera.vfov_deg = 60.0f;
    s.camera.width = s.camera.height = 32;
    return s;
}

}  // namespace tessera::test
