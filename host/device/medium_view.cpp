#include "device/medium_view.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/glm.hpp>

namespace tessera {
namespace {

using V3 = glm::dvec3;
V3 load(const float* v) { return {v[0], v[1], v[2]}; }
V3 load(ts::float3 v) { return {v.x, v.y, v.z}; }

// Whether `axis` separates the cone (apex o, edge directions d) from the box [lo, hi]:
// the cone projects to a half-line from o·axis (or the whole line where its edges point
// both ways), the box to [min, max] over its corners.
// An edge within 1e-9 of its length of the axis's plane counts as in it: a crossed axis
// holds its own edge at 0 up to double rounding (1e-16), which would otherwise pick the
// side at random. Safe: an edge that dips 1e-9 below the plane reaches the box, at most
// 2√3 of the scale from the camera, at most 3.5e-9 of the scale below the apex; a ray
// between the edges dips at most ~150× that in a view under 179° (the guard in
// camera_may_meet_medium), still far below the box's 1e-4 margin.
bool separates(V3 axis, V3 o, const std::array<V3, 4>& d, V3 lo, V3 hi) {
    bool up = true, down = true;
    const double axis_length = glm::length(axis);
    if (!(axis_length > 0.0)) return false;
    for (const V3& e : d) {
        const double s = glm::dot(e, axis), zero = 1e-9 * glm::length(e) * axis_length;
        up = up && s >= -zero;
        down = down && s <= zero;
    }
    if (!up && !down) return false;
    const V3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    const double centre = glm::dot(c, axis), radius = glm::dot(h, glm::abs(axis)), apex = glm::dot(o, axis);
    return (up && centre + radius < apex) || (down && centre - radius > apex);
}

}  // namespace

bool camera_may_meet_medium(const TsFrame& f, const ts::TsMedium& m) {
    if (!m.present) return false;
    if (!m.bounded) return true;
    const V3 o = load(f.cam_pos), fw = load(f.cam_forward), rt = load(f.cam_right), up = load(f.cam_up);
    // The slab test reads a box given max before min as the swapped one.
    const V3 a0 = load(m.box_min), a1 = load(m.box_max);
    const double coords[] = {a0.x, a0.y, a0.z, a1.x, a1.y, a1.z, o.x, o.y, o.z};
    double scale = 0.0;
    for (double c : coords) {
        if (!std::isfinite(c)) return true;
        scale = std::max(scale, std::fabs(c));
    }
    const double lr = glm::length(rt), lu = glm::length(up), lf = glm::length(fw);
    if (!(std::isfinite(lr + lu + lf) && lr > 0.0 && lu > 0.0 && lf > 0.0)) return true;
    const double e = 1e-4 * scale;
    const V3 lo = glm::min(a0, a1) - e, hi = glm::max(a0, a1) + e;  // inputs finite: min/max keep them all
    // A float ray's direction may lie off the image's cone by a few ulps of its summands'
    // lengths, in any direction: widen the cone's image coordinates by ten times that.
    const double slack = 1e-5 * (lf + lr + lu), a = 1.0 + slack / lr, b = 1.0 + slack / lu;
    // A view wider than ~179° (an image coordinate's vector 100× forward's): its cone is
    // near a half-space, where the edge tolerance of `separates` would no longer be small
    // beside the box's margin; every box may meet it.
    if (!(lr < 100.0 * lf && lu < 100.0 * lf)) return true;
    const V3 f0 = (1.0 - slack / lf) * fw;
    const std::array<V3, 4> d = {f0 + a * rt + b * up, f0 - a * rt + b * up, f0 - a * rt - b * up, f0 + a * rt - b * up};
    const std::array<V3, 3> box_axes = {V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1)};
    for (const V3& n : box_axes)
        if (separates(n, o, d, lo, hi)) return false;
    for (int i = 0; i < 4; ++i) {
        if (separates(glm::cross(d[i], d[(i + 1) % 4]), o, d, lo, hi)) return false;
        for (const V3& n : box_axes)
            if (separates(glm::cross(n, d[i]), o, d, lo, hi)) return false;
    }
    return true;
}

}  // namespace tessera
