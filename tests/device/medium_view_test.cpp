// Whether a frame's camera can see the medium (device/medium_view.h): never "no" where
// some camera ray the kernels trace meets the box, and "no" for boxes out of view.
#include "device/medium_view.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "device/frame.h"
#include "kernels/shared/geometry.h"

namespace tessera {
namespace {

ts::TsMedium box_medium(glm::vec3 lo, glm::vec3 hi) {
    ts::TsMedium m{};
    m.present = 1;
    m.bounded = 1;
    m.box_min = ts::make_float3(lo.x, lo.y, lo.z);
    m.box_max = ts::make_float3(hi.x, hi.y, hi.z);
    return m;
}

TsFrame frame_at(glm::vec3 pos, glm::vec3 look_at, float vfov, int width, int height) {
    Camera c;
    c.position = pos;
    c.look_at = look_at;
    c.up = glm::vec3(0, 1, 0);
    c.vfov_deg = vfov;
    return make_frame(c, width, height, 1, 1, 0);
}

// Whether any of the kernels' camera rays (ts_camera_ray, float) through the image's
// border pixels at extreme jitters, or a few thousand random ones, meets the box.
bool some_ray_meets(const TsFrame& f, const ts::TsMedium& m, std::mt19937& rng) {
    const float jitters[] = {0.0f, 0.5f, std::nextafter(1.0f, 0.0f)};
    auto meets = [&](uint32_t x, uint32_t y, float jx, float jy) {
        const ts::TsRay r = ts::ts_camera_ray(&f, x, y, jx, jy);
        float t0 = 0.0f, t1 = ts::TS_INF;
        return ts::ts_medium_clip(&m, r.org, r.dir, &t0, &t1) != 0;
    };
    for (uint32_t x = 0; x < f.width; ++x)
        for (uint32_t y = 0; y < f.height; ++y) {
            if (x != 0 && y != 0 && x + 1 != f.width && y + 1 != f.height) continue;
            for (float jx : jitters)
                for (float jy : jitters)
                    if (meets(x, y, jx, jy)) return true;
        }
    // Rays aimed at the box's corners and centre (clamped into the image), nudged by a
    // few ulps of the jitter: where the box grazes the view's edge, only these come near.
    const float lo[3] = {m.box_min.x, m.box_min.y, m.box_min.z}, hi[3] = {m.box_max.x, m.box_max.y, m.box_max.z};
    const glm::dvec3 o(f.cam_pos[0], f.cam_pos[1], f.cam_pos[2]), fw(f.cam_forward[0], f.cam_forward[1], f.cam_forward[2]),
        rt(f.cam_right[0], f.cam_right[1], f.cam_right[2]), up(f.cam_up[0], f.cam_up[1], f.cam_up[2]);
    for (int corner = 0; corner < 9; ++corner) {
        glm::dvec3 p;
        for (int a = 0; a < 3; ++a) p[a] = corner == 8 ? 0.5 * (double(lo[a]) + hi[a]) : (corner >> a & 1 ? hi[a] : lo[a]);
        const glm::dvec3 d = p - o;
        const double z = glm::dot(d, fw);
        if (!(z > 0.0)) continue;
        const double sx = glm::dot(d, rt) / (glm::dot(rt, rt) * z), sy = glm::dot(d, up) / (glm::dot(up, up) * z);
        const double ix = std::clamp((sx + 1.0) * 0.5 * f.width, 0.0, double(f.width));
        const double iy = std::clamp((1.0 - sy) * 0.5 * f.height, 0.0, double(f.height));
        const uint32_t x = std::min(uint32_t(ix), f.width - 1), y = std::min(uint32_t(iy), f.height - 1);
        for (int kx = -4; kx <= 4; ++kx)
            for (int ky = -4; ky <= 4; ++ky) {
                const float jx = std::clamp(float(ix - x) + 3e-8f * kx, 0.0f, jitters[2]);
                const float jy = std::clamp(float(iy - y) + 3e-8f * ky, 0.0f, jitters[2]);
                if (meets(x, y, jx, jy)) return true;
            }
    }
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 4000; ++i) {
        const uint32_t x = std::min(f.width - 1, uint32_t(u(rng) * f.width));
        const uint32_t y = std::min(f.height - 1, uint32_t(u(rng) * f.height));
        if (meets(x, y, std::min(u(rng), jitters[2]), std::min(u(rng), jitters[2]))) return true;
    }
    return false;
}

TEST(MediumView, BoxesInFrontMeetAndBoxesBehindOrBesideDoNot) {
    // Camera at the origin looking down +z, 90° square view: the cone |x|, |y| <= z.
    const TsFrame f = frame_at({0, 0, 0}, {0, 0, 1}, 90.0f, 64, 64);
    EXPECT_TRUE(camera_may_meet_medium(f, box_medium({-1, -1, 4}, {1, 1, 5})));
    EXPECT_TRUE(camera_may_meet_medium(f, box_medium({-1, -1, -1}, {1, 1, 1}))) << "the camera inside";
    EXPECT_FALSE(camera_may_meet_medium(f, box_medium({-1, -1, -5}, {1, 1, -4}))) << "behind";
    EXPECT_FALSE(camera_may_meet_medium(f, box_medium({3.1f, -1, 2}, {4, 1, 3}))) << "right of the view";
    EXPECT_TRUE(camera_may_meet_medium(f, box_medium({2.9f, -1, 2}, {4, 1, 3}))) << "its corner in view";
    EXPECT_FALSE(camera_may_meet_medium(f, box_medium({-1, 5.1f, 2}, {1, 6, 5}))) << "above the view";
    // Beside a turned view's corner edge, where no face plane of the view or the box
    // separates them: only a box edge crossed with a cone edge does.
    const TsFrame turned = frame_at({0, 0, 0}, {1, 0.6f, 1.3f}, 60.0f, 64, 64);
    const glm::vec3 c(1.828f, 2.081f, -0.079f), h(0.422f);
    EXPECT_FALSE(camera_may_meet_medium(turned, box_medium(c - h, c + h)));
    std::mt19937 rng(1);
    EXPECT_FALSE(some_ray_meets(turned, box_medium(c - h, c + h), rng));
    EXPECT_TRUE(camera_may_meet_medium(turned, box_medium(c - 2.5f * h, c + 2.5f * h)));
    EXPECT_TRUE(some_ray_meets(turned, box_medium(c - 2.5f * h, c + 2.5f * h), rng));
    // Degenerate boxes: a point, one touching the camera, one given max before min (the
    // slab test reads it swapped).
    EXPECT_TRUE(camera_may_meet_medium(f, box_medium({0, 0, 3}, {0, 0, 3})));
    EXPECT_FALSE(camera_may_meet_medium(f, box_medium({0, 0, -3}, {0, 0, -3})));
    EXPECT_TRUE(camera_may_meet_medium(f, box_medium({-1, -1, -1}, {1, 1, 0}))) << "its face through the camera";
    EXPECT_TRUE(camera_may_meet_medium(f, box_medium({1, 1, 5}, {-1, -1, 4})));
    EXPECT_FALSE(camera_may_meet_medium(f, box_medium({1, 1, -4}, {-1, -1, -5})));
    // Far from the origin, 1e6: the box's margin is 100 units there.
    const glm::vec3 far(1e6f, -1e6f, 1e6f);
    const TsFrame g = frame_at(far, far + glm::vec3(0, 0, 1), 90.0f, 64, 64);
    EXPECT_TRUE(camera_may_meet_medium(g, box_medium(far + glm::vec3(-1, -1, 4), far + glm::vec3(1, 1, 5))));
    EXPECT_FALSE(camera_may_meet_medium(g, box_medium(far + glm::vec3(-1, -1, -500), far + glm::vec3(1, 1, -400))));
    EXPECT_FALSE(camera_may_meet_medium(g, box_medium(far + glm::vec3(600, -1, 200), far + glm::vec3(700, 1, 300))));
    // A view near 180°: any box may meet it.
    EXPECT_TRUE(camera_may_meet_medium(frame_at({0, 0, 0}, {0, 0, 1}, 179.5f, 64, 64), box_medium({-1, -1, -5}, {1, 1, -4})));
    ts::TsMedium none{};
    EXPECT_FALSE(camera_may_meet_medium(f, none)) << "no medium";
    ts::TsMedium space = box_medium({-1, -1, -5}, {1, 1, -4});
    space.bounded = 0;
    EXPECT_TRUE(camera_may_meet_medium(f, space)) << "a medium filling space";
    ts::TsMedium nan = box_medium({-1, -1, -5}, {1, 1, -4});
    nan.box_min.x = NAN;
    EXPECT_TRUE(camera_may_meet_medium(f, nan));
    nan = box_medium({-1, -1, -5}, {1, 1, -4});
    nan.box_max.z = NAN;
    EXPECT_TRUE(camera_may_meet_medium(f, nan)) << "a NaN in either corner";
}

TEST(MediumView, NoKernelCameraRayMeetsABoxItCallsOutOfView) {
    // Random cameras and boxes, many of them grazing the view's edges at 1e-9..1e-1 of the
    // scene's scale (the float rays' rounding is ~1e-7 of it): wherever some camera ray
    // the kernels would trace meets the box, the predicate must say it may. Both answers
    // must come up often, or the test would check nothing.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int out_of_view = 0, in_view = 0, grazing_out = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const float scale = std::pow(10.0f, -2.0f + 5.0f * u(rng));  // 1e-2 .. 1e3
        // Every fifth trial far from the origin (1e4 of the scale): the rays' rounding and
        // the margins grow with the coordinates.
        const glm::vec3 shift = trial % 5 == 0 ? 1e4f * scale * glm::vec3(u(rng), u(rng) - 0.5f, -u(rng)) : glm::vec3(0.0f);
        auto point = [&] { return shift + scale * glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f) * 4.0f; };
        const glm::vec3 pos = point(), look = point();
        if (glm::length(look - pos) < 1e-3f * scale || std::fabs(glm::normalize(look - pos).y) > 0.99f) continue;
        const int width = trial % 7 == 0 ? 1 : 1 + int(u(rng) * 96), height = trial % 11 == 0 ? 1 : 1 + int(u(rng) * 96);
        const TsFrame f = frame_at(pos, look, 5.0f + 170.0f * u(rng), width, height);
        glm::vec3 lo, hi;
        if (trial % 2 == 0) {  // anywhere
            const glm::vec3 a = point(), b = point();
            lo = glm::min(a, b), hi = glm::max(a, b);
        } else {  // a small box touching the view's side plane through a random edge point
            const glm::vec3 fw(f.cam_forward[0], f.cam_forward[1], f.cam_forward[2]),
                rt(f.cam_right[0], f.cam_right[1], f.cam_right[2]), up(f.cam_up[0], f.cam_up[1], f.cam_up[2]);
            // The left, right, top or bottom face.
            const float sign = u(rng) < 0.5f ? -1.0f : 1.0f;
            const float sx = trial % 4 == 1 ? sign : 2.0f * u(rng) - 1.0f, sy = trial % 4 == 1 ? 2.0f * u(rng) - 1.0f : sign;
            const glm::vec3 edge = fw + sx * rt + sy * up;
            const glm::vec3 side = sign * (trial % 4 == 1 ? rt : up);  // the face's outward image direction
            glm::vec3 outward = glm::normalize(glm::cross(trial % 4 == 1 ? up : rt, edge));
            if (glm::dot(outward, side) < 0.0f) outward = -outward;
            const float t = scale * (0.1f + 3.0f * u(rng)), h = scale * 1e-3f * u(rng);
            const float gap = scale * std::pow(10.0f, -9.0f + 8.0f * u(rng)) * (u(rng) < 0.5f ? -1.0f : 1.0f);
            // The box's nearest corner lies `gap` outside the face's plane.
            const float reach = h * (std::fabs(outward.x) + std::fabs(outward.y) + std::fabs(outward.z));
            const glm::vec3 c = pos + t * glm::normalize(edge) + outward * (gap + reach);
            lo = c - glm::vec3(h), hi = c + glm::vec3(h);
        }
        const ts::TsMedium m = box_medium(lo, hi);
        const bool may = camera_may_meet_medium(f, m);
        if (!may) {
            ASSERT_FALSE(some_ray_meets(f, m, rng)) << "trial " << trial << ": a camera ray meets the box";
        }
        (may ? in_view : out_of_view) += 1;
        if (!may && trial % 2 == 1) ++grazing_out;
    }
    std::printf("  %d boxes out of view (%d grazing the view's edge), %d may be seen\n", out_of_view, grazing_out,
                in_view);
    EXPECT_GT(out_of_view, 400);
    EXPECT_GT(in_view, 300);
    EXPECT_GT(grazing_out, 100);
}

}  // namespace
}  // namespace tessera
