#include "device/coincident_emitters.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tessera {
namespace {

using Tri = std::array<glm::vec3, 3>;

constexpr double kUlp = 0x1p-23;  // float epsilon: one ulp of a coordinate in [1, 2)

Tri triangle(const std::vector<glm::vec3>& p, size_t i) { return {p[3 * i], p[3 * i + 1], p[3 * i + 2]}; }

double max_abs(const Tri& t) {
    float m = 0.0f;
    for (const glm::vec3& v : t) m = std::max({m, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return m;
}

// The unit normal cross(p1 - p0, p2 - p0) in double (a float one of a thin triangle is
// off by more than the tolerance); zero for a degenerate triangle.
glm::dvec3 unit_normal(const Tri& t) {
    const glm::dvec3 p0(t[0]);
    const glm::dvec3 c = glm::cross(glm::dvec3(t[1]) - p0, glm::dvec3(t[2]) - p0);
    const double len = glm::length(c);
    return len > 0.0 ? c / len : glm::dvec3(0.0);
}

struct Box {
    glm::vec3 lo, hi;
};
// The triangle's bounds, widened by its coplanarity tolerance: two triangles within the
// tolerance of one plane have overlapping boxes.
Box box_of(const Tri& t) {
    const float pad = float(kCoplanarEmitterUlps * kUlp * max_abs(t));
    return {glm::min(glm::min(t[0], t[1]), t[2]) - pad, glm::max(glm::max(t[0], t[1]), t[2]) + pad};
}
bool boxes_overlap(const Box& a, const Box& b) {
    return glm::all(glm::lessThanEqual(a.lo, b.hi)) && glm::all(glm::lessThanEqual(b.lo, a.hi));
}

// The interval of the 2D triangle's vertices along `axis`.
void project(const std::array<glm::dvec2, 3>& t, glm::dvec2 axis, double& lo, double& hi) {
    lo = hi = glm::dot(t[0], axis);
    for (int i = 1; i < 3; ++i) {
        const double d = glm::dot(t[i], axis);
        lo = std::min(lo, d), hi = std::max(hi, d);
    }
}

// Whether two triangles of one plane (unit normal n) share interior area, by the
// separating axis theorem in the plane: a gap or mere contact (overlap ≤ tol) on any
// edge normal separates them.
bool interiors_overlap(const Tri& a, const Tri& b, const glm::dvec3& n, double tol) {
    // Drop the normal's dominant axis: the projection keeps areas nonzero.
    const glm::dvec3 an = glm::abs(n);
    const int drop = an.x > an.y ? (an.x > an.z ? 0 : 2) : (an.y > an.z ? 1 : 2);
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    std::array<glm::dvec2, 3> a2, b2;
    for (int i = 0; i < 3; ++i) a2[i] = {a[i][u], a[i][v]}, b2[i] = {b[i][u], b[i][v]};
    for (const auto* t : {&a2, &b2})
        for (int i = 0; i < 3; ++i) {
            const glm::dvec2 e = (*t)[(i + 1) % 3] - (*t)[i];
            const double len = glm::length(e);
            if (!(len > 0.0)) return false;  // degenerate: no interior
            const glm::dvec2 axis(-e.y / len, e.x / len);
            double alo, ahi, blo, bhi;
            project(a2, axis, alo, ahi);
            project(b2, axis, blo, bhi);
            if (std::min(ahi, bhi) - std::max(alo, blo) <= tol) return false;
        }
    return true;
}

// Where emitter e lies in w's plane (unit normals ne, nw), within `tol` (scene units),
// their interiors overlapping: the least distance of e's vertices in front of w's plane
// along ne (negative: behind it). NaN where they do not coincide.
double coincident_gap(const Tri& e, const glm::dvec3& ne, const Tri& w, const glm::dvec3& nw, double tol) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double facing = glm::dot(ne, nw);
    if (std::abs(facing) < 1.0 - 1e-6) return nan;  // not parallel
    const glm::dvec3 w0(w[0]);
    double gap = INFINITY;
    for (const glm::vec3& p : e) {
        const double d = glm::dot(glm::dvec3(p) - w0, nw);
        if (std::abs(d) > tol) return nan;
        gap = std::min(gap, facing > 0.0 ? d : -d);
    }
    return interiors_overlap(e, w, nw, tol) ? gap : nan;
}

// A uniform grid over the emitters' joint box, each cell listing the emitters whose box
// meets it: a triangle is tested against the emitters of the cells its box meets, so the
// cost follows the pairs that are near each other, not emitters × triangles.
class EmitterGrid {
public:
    EmitterGrid(const std::vector<Box>& boxes) {
        all_ = {glm::vec3(INFINITY), glm::vec3(-INFINITY)};
        for (const Box& b : boxes) all_ = {glm::min(all_.lo, b.lo), glm::max(all_.hi, b.hi)};
        // About 8 cells per emitter, at most 64 per axis (262,144 cells).
        res_ = std::clamp(int(2.0 * std::cbrt(double(boxes.size()))), 1, 64);
        // A flat grid keeps a finite 1/cell (64/1e-30): ±inf, never NaN, in cell_of.
        const glm::vec3 extent = glm::max(all_.hi - all_.lo, glm::vec3(1e-30f));
        inv_cell_ = float(res_) / extent;
        cells_.resize(size_t(res_) * res_ * res_);
        for (uint32_t i = 0; i < boxes.size(); ++i) visit(boxes[i], [&](std::vector<uint32_t>& c) { c.push_back(i); });
    }
    const Box& bounds() const { return all_; }
    // Calls f(cell) for every cell `b` meets (b must meet bounds()).
    template <class F> void visit(const Box& b, F&& f) {
        const glm::ivec3 lo = cell_of(b.lo), hi = cell_of(b.hi);
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) f(cells_[(size_t(z) * res_ + y) * res_ + x]);
    }

private:
    glm::ivec3 cell_of(const glm::vec3& p) const {
        // Clamped before the conversion: a box far outside a flat grid gives ±inf here.
        const glm::vec3 c = glm::clamp(glm::floor((p - all_.lo) * inv_cell_), glm::vec3(0.0f), glm::vec3(float(res_ - 1)));
        return glm::ivec3(c);
    }
    Box all_;
    int res_ = 1;
    glm::vec3 inv_cell_{1.0f};
    std::vector<std::vector<uint32_t>> cells_;
};

}  // namespace

CoincidentEmitters separate_coincident_emitters(const Scene& scene, std::vector<glm::vec3>& positions) {
    const size_t n = positions.size() / 3;
    std::vector<uint32_t> emitters;  // triangle indices
    std::vector<Box> boxes;
    std::vector<glm::dvec3> normals;
    for (size_t i = 0; i < n; ++i) {
        if (!scene.materials[scene.material[i]].may_emit()) continue;
        const Tri e = triangle(positions, i);
        const glm::dvec3 ne = unit_normal(e);
        if (ne == glm::dvec3(0.0)) continue;  // zero area: not a light
        emitters.push_back(uint32_t(i));
        boxes.push_back(box_of(e));
        normals.push_back(ne);
    }
    if (emitters.empty()) return {};
    EmitterGrid grid(boxes);
    // Every test reads the positions as given, so the result does not depend on order: of
    // two lights back to back in one plane (a two-sided light), both move, apart.
    std::vector<double> shift(emitters.size(), 0.0);  // scene units along the normal; 0: stays
    std::vector<uint32_t> tested_with(emitters.size(), UINT32_MAX);
    std::vector<bool> stacked(emitters.size(), false);  // on a light facing the same way
    for (uint32_t wi = 0; wi < n; ++wi) {
        const Tri w = triangle(positions, wi);
        const Box wb = box_of(w);
        if (!boxes_overlap(wb, grid.bounds())) continue;
        const bool w_emits = scene.materials[scene.material[wi]].may_emit();
        glm::dvec3 nw(0.0);  // computed once, on the first candidate
        grid.visit(wb, [&](const std::vector<uint32_t>& cell) {
            for (uint32_t k : cell) {
                if (emitters[k] == wi || tested_with[k] == wi) continue;
                // Nothing left to learn: moved already, and w can only move it or stack it.
                if (shift[k] > 0.0 && (!w_emits || stacked[k])) continue;
                tested_with[k] = wi;
                if (!boxes_overlap(boxes[k], wb)) continue;
                if (nw == glm::dvec3(0.0)) nw = unit_normal(w);
                if (nw == glm::dvec3(0.0)) continue;
                // Another light facing the same way would move as far: no separation, but
                // the pair is counted for the caller to report.
                const bool same_way = w_emits && glm::dot(normals[k], nw) > 0.0;
                if (same_way ? bool(stacked[k]) : shift[k] > 0.0) continue;
                const Tri e = triangle(positions, emitters[k]);
                const double scale = std::max(max_abs(e), max_abs(w));
                const double gap = coincident_gap(e, normals[k], w, nw, kCoplanarEmitterUlps * kUlp * scale);
                if (gap != gap) continue;
                if (same_way) stacked[k] = true;
                // To kCoincidentEmitterUlps in front: a light already part of the way
                // there moves less (one 2e-3 under a ceiling 1e4 from the origin, 1.7
                // ulps, moves 4.3).
                else shift[k] = std::max(kCoincidentEmitterUlps * kUlp * scale - gap, 1e-300);
            }
        });
    }
    CoincidentEmitters result;
    result.stacked = size_t(std::count(stacked.begin(), stacked.end(), true));
    for (size_t k = 0; k < emitters.size(); ++k) {
        if (!(shift[k] > 0.0)) continue;
        for (int v = 0; v < 3; ++v) {
            glm::vec3& p = positions[3 * size_t(emitters[k]) + v];
            p = glm::vec3(glm::dvec3(p) + normals[k] * shift[k]);
        }
        ++result.moved;
    }
    return result;
}

std::string stacked_emitters_text(size_t stacked) {
    return std::to_string(stacked) + " emissive triangles lie on another light facing the same way (a light listed "
           "twice?): both are sampled, so where they overlap their light counts twice";
}

}  // namespace tessera
