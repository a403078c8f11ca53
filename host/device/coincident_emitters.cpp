#include "device/coincident_emitters.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tessera {
namespace {

using Tri = std::array<glm::vec3, 3>;

constexpr float kUlp = 0x1p-23f;  // float epsilon: one ulp of a coordinate in [1, 2)
// In the plane: the computed distance of a vertex from the other's plane is within about
// an ulp of the coordinates when the two were placed in one plane. No more: a light
// deliberately 2 ulps off its ceiling (Scale.*: 1e-3 of the box's size at 1e4 from the
// origin) already renders the same on both backends and must stay put.
constexpr float kCoplanarUlps = 1.0f;

Tri triangle(const std::vector<glm::vec3>& p, size_t i) { return {p[3 * i], p[3 * i + 1], p[3 * i + 2]}; }

bool emits(const Material& m) {
    const glm::vec3 e = glm::max(m.emission, m.emission_max);  // as add_lights picks lights
    return e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
}

float max_abs(const Tri& t) {
    float m = 0.0f;
    for (const glm::vec3& v : t) m = std::max({m, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return m;
}

struct Box {
    glm::vec3 lo, hi;
};
// The triangle's bounds, widened by the coplanarity tolerance of its coordinates: two
// triangles within the tolerance of a plane have overlapping boxes.
Box box_of(const Tri& t) {
    const float pad = kCoplanarUlps * kUlp * max_abs(t);
    return {glm::min(glm::min(t[0], t[1]), t[2]) - pad, glm::max(glm::max(t[0], t[1]), t[2]) + pad};
}
bool boxes_overlap(const Box& a, const Box& b) {
    return glm::all(glm::lessThanEqual(a.lo, b.hi)) && glm::all(glm::lessThanEqual(b.lo, a.hi));
}

// The interval of the 2D triangle's vertices along `axis`.
void project(const std::array<glm::vec2, 3>& t, glm::vec2 axis, float& lo, float& hi) {
    lo = hi = glm::dot(t[0], axis);
    for (int i = 1; i < 3; ++i) {
        const float d = glm::dot(t[i], axis);
        lo = std::min(lo, d), hi = std::max(hi, d);
    }
}

// Whether two triangles of one plane (normal n) share interior area, by the separating
// axis theorem in the plane: a gap or mere contact (overlap ≤ tol) on any edge normal
// separates them.
bool interiors_overlap(const Tri& a, const Tri& b, const glm::vec3& n, float tol) {
    // Drop the normal's dominant axis: the projection keeps areas nonzero.
    const glm::vec3 an = glm::abs(n);
    const int drop = an.x > an.y ? (an.x > an.z ? 0 : 2) : (an.y > an.z ? 1 : 2);
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    std::array<glm::vec2, 3> a2, b2;
    for (int i = 0; i < 3; ++i) a2[i] = {a[i][u], a[i][v]}, b2[i] = {b[i][u], b[i][v]};
    for (const auto* t : {&a2, &b2})
        for (int i = 0; i < 3; ++i) {
            const glm::vec2 e = (*t)[(i + 1) % 3] - (*t)[i];
            const float len = glm::length(e);
            if (!(len > 0.0f)) return false;  // degenerate: no interior
            const glm::vec2 axis(-e.y / len, e.x / len);
            float alo, ahi, blo, bhi;
            project(a2, axis, alo, ahi);
            project(b2, axis, blo, bhi);
            if (std::min(ahi, bhi) - std::max(alo, blo) <= tol) return false;
        }
    return true;
}

// Whether emitter e (unit normal n) lies in w's plane with their interiors overlapping;
// tol is the coplanarity distance.
bool coincide(const Tri& e, const glm::vec3& n, const Tri& w, float tol) {
    const glm::vec3 c = glm::cross(w[1] - w[0], w[2] - w[0]);
    const float len = glm::length(c);
    if (!(len > 0.0f)) return false;
    const glm::vec3 nw = c / len;
    if (std::abs(glm::dot(n, nw)) < 1.0f - 1e-6f) return false;
    for (const glm::vec3& p : e)
        if (std::abs(glm::dot(p - w[0], nw)) > tol) return false;
    return interiors_overlap(e, w, nw, tol);
}

}  // namespace

size_t separate_coincident_emitters(const Scene& scene, std::vector<glm::vec3>& positions) {
    const size_t n = positions.size() / 3;
    std::vector<size_t> walls;
    std::vector<size_t> emitters;
    for (size_t i = 0; i < n; ++i) (emits(scene.materials[scene.material[i]]) ? emitters : walls).push_back(i);
    if (emitters.empty() || walls.empty()) return 0;
    // Only surfaces within the emitters' joint box can meet one: an emissive mesh of many
    // triangles in a small part of a large scene then tests few pairs.
    Box all{glm::vec3(INFINITY), glm::vec3(-INFINITY)};
    for (size_t ei : emitters) {
        const Box b = box_of(triangle(positions, ei));
        all = {glm::min(all.lo, b.lo), glm::max(all.hi, b.hi)};
    }
    std::erase_if(walls, [&](size_t wi) { return !boxes_overlap(all, box_of(triangle(positions, wi))); });
    size_t moved = 0;
    for (size_t ei : emitters) {
        const Tri e = triangle(positions, ei);
        const glm::vec3 c = glm::cross(e[1] - e[0], e[2] - e[0]);
        const float len = glm::length(c);
        if (!(len > 0.0f)) continue;  // zero area: not a light
        const glm::vec3 normal = c / len;
        const Box eb = box_of(e);
        for (size_t wi : walls) {
            const Tri w = triangle(positions, wi);
            if (!boxes_overlap(eb, box_of(w))) continue;
            const float scale = std::max({max_abs(e), max_abs(w), 1e-30f});
            if (!coincide(e, normal, w, kCoplanarUlps * kUlp * scale)) continue;
            const glm::vec3 shift = normal * (kCoincidentEmitterUlps * kUlp * scale);
            for (int k = 0; k < 3; ++k) positions[3 * ei + k] += shift;
            ++moved;
            break;
        }
    }
    return moved;
}

}  // namespace tessera
