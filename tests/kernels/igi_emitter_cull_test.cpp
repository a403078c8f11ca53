// kernels/shared/igi_emitters.h ts_igi_may_meet_emitter: the box test that lets the ray march skip
// tracing phase-sampled rays that cannot reach a light. It must be conservative (every
// ray whose closest hit is an emitter passes it, so images do not change) and it must
// cull (most directions from inside the Cornell box miss its small ceiling light). Its
// 16-lane form (kernels/shared/igi_march16.h ts_igi_may_meet_emitter_lanes) must pass
// every ray the one-ray test passes, and for rays of numbers exactly those.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "backend/embree_tracer.h"
#include "bvh/embree_scene.h"
#include "device/scene_view.h"
#include "support/render_helpers.h"

// After the tracer (embree_tracer.h): the shared code calls it.
#include "kernels/shared/igi_emitters.h"
#include "kernels/shared/igi_march16.h"

namespace tessera {
namespace {

ts::float3 unit(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    return ts::normalize(ts::make_float3(n(rng), n(rng), n(rng)));
}

TEST(IgiEmitterCull, EveryRayThatHitsALightPassesAndMostOthersAreCulled) {
    const Scene scene = test::cornell_box();
    const SceneBuffers b = make_scene_buffers(scene);
    ASSERT_GT(b.light_count, 0u);
    ASSERT_LE(b.light_count, TS_IGI_EMITTER_BOXES_MAX);
    RTCScene rtc = build_embree_scene(b);
    const ts::TsTracer tracer{rtc};
    const ts::TsSceneView sv = make_scene_view(b);
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& p : scene.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.02f, 0.98f);
    // Random directions, and the six axis directions (zero components: infinite inverses).
    const ts::float3 axes[6] = {ts::make_float3(1, 0, 0),  ts::make_float3(-1, 0, 0), ts::make_float3(0, 1, 0),
                                ts::make_float3(0, -1, 0), ts::make_float3(0, 0, 1),  ts::make_float3(0, 0, -1)};
    int emitter_hits = 0, axis_emitter_hits = 0, culled = 0, missed_emitters = 0;
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
        const glm::vec3 q = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
        const ts::float3 x = ts::make_float3(q.x, q.y, q.z);
        const bool axis = i % 8 == 0;
        const ts::float3 wi = axis ? axes[(i / 8) % 6] : unit(rng);
        ts::TsRay r;
        r.org = x;
        r.dir = wi;
        r.tmin = 0.0f;
        r.tmax = ts::TS_INF;
        const ts::TsHit h = ts::ts_trace_closest(&tracer, r);
        const glm::vec3 le = h.prim != TS_NO_HIT ? scene.materials[scene.material[h.prim]].emission : glm::vec3(0.0f);
        const bool emitter = le.x > 0.0f || le.y > 0.0f || le.z > 0.0f;
        const bool may = ts::ts_igi_may_meet_emitter(&sv, x, wi) != 0;
        emitter_hits += emitter;
        axis_emitter_hits += emitter && axis;
        missed_emitters += emitter && !may;
        culled += !may;
    }
    rtcReleaseScene(rtc);
    EXPECT_EQ(missed_emitters, 0) << "of " << emitter_hits << " rays that hit a light";
    EXPECT_GT(emitter_hits, 200);      // the check above saw many light hits
    EXPECT_GT(axis_emitter_hits, 20);  // straight up from below the light
    EXPECT_GT(culled, n * 3 / 4);      // the light is small: most rays are culled
}

// A light of one triangle far off along +x: a ray heading -x misses its box; with more
// emitters than TS_IGI_EMITTER_BOXES_MAX no ray is culled.
TEST(IgiEmitterCull, CullsUpToTheBoxLimitOnly) {
    std::vector<float> light(TS_LIGHT_FLOATS, 0.0f);
    const float p0[3] = {10.0f, 0.0f, 0.0f}, e1[3] = {0.0f, 1.0f, 0.0f}, e2[3] = {0.0f, 0.0f, 1.0f};
    std::copy(p0, p0 + 3, light.begin() + TS_LIGHT_P0);
    std::copy(e1, e1 + 3, light.begin() + TS_LIGHT_E1);
    std::copy(e2, e2 + 3, light.begin() + TS_LIGHT_E2);
    std::vector<float> lights;
    for (uint32_t i = 0; i <= TS_IGI_EMITTER_BOXES_MAX; ++i) lights.insert(lights.end(), light.begin(), light.end());
    ts::TsSceneView sv{};
    sv.lights = lights.data();
    const ts::float3 x = ts::make_float3(0.0f, 0.25f, 0.25f);
    sv.light_count = 1;
    EXPECT_EQ(ts::ts_igi_may_meet_emitter(&sv, x, ts::make_float3(1.0f, 0.0f, 0.0f)), 1);
    EXPECT_EQ(ts::ts_igi_may_meet_emitter(&sv, x, ts::make_float3(-1.0f, 0.0f, 0.0f)), 0);
    EXPECT_EQ(ts::ts_igi_may_meet_emitter(&sv, x, ts::normalize(ts::make_float3(1.0f, 1.0f, 0.0f))), 0);
    sv.light_count = TS_IGI_EMITTER_BOXES_MAX;
    EXPECT_EQ(ts::ts_igi_may_meet_emitter(&sv, x, ts::make_float3(-1.0f, 0.0f, 0.0f)), 0);
    sv.light_count = TS_IGI_EMITTER_BOXES_MAX + 1;
    EXPECT_EQ(ts::ts_igi_may_meet_emitter(&sv, x, ts::make_float3(-1.0f, 0.0f, 0.0f)), 1);
}

// The lanes against the one-ray test, over the Cornell box's lights: random points and
// directions, the axis directions (infinite inverses), points on a grown box's face with a
// direction parallel to it (0·∞ in the slab test), NaN and infinite inputs, and lanes left
// out of `in` holding NaNs (which must not leak into the other lanes' answers).
TEST(IgiEmitterCull, TheLanesPassWhatTheOneRayTestPasses) {
    const Scene scene = test::cornell_box();
    const SceneBuffers b = make_scene_buffers(scene);
    const ts::TsSceneView sv = make_scene_view(b);
    ASSERT_GT(sv.light_count, 0u);
    const ts::TsEmitterBox box = ts::ts_igi_emitter_box(&sv, 0);
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& p : scene.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float nan = std::nanf(""), inf = INFINITY;
    int passed = 0, culled = 0, special = 0, zero_inf = 0;
    for (int round = 0; round < 4000; ++round) {
        ts::float3 x[TS_PACKET_LANES], wi[TS_PACKET_LANES];
        bool exact[TS_PACKET_LANES];
        const uint32_t in = round % 5 == 4 ? uint32_t(rng()) & 0xffffu : 0xffffu;
        for (int l = 0; l < TS_PACKET_LANES; ++l) {
            const glm::vec3 q = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
            x[l] = ts::make_float3(q.x, q.y, q.z);
            wi[l] = unit(rng);
            exact[l] = true;
            switch (rng() % 8) {
            case 0:  // an axis direction
                wi[l] = ts::make_float3(0.0f, 0.0f, 0.0f);
                (rng() % 2 ? wi[l].y : wi[l].x) = rng() % 2 ? 1.0f : -1.0f;
                break;
            case 1: {  // on the light box's grown low y face, moving in x: (lo - pad - y)·∞ = 0·∞
                x[l].x = hi.x * 4.0f;  // the largest coordinate, so that it sets the pad
                const float pad = ts::ts_igi_emitter_pad(box.mag, ts::ts_max_abs3(x[l]));
                x[l].y = box.lo.y - pad;
                exact[l] = box.lo.y - pad - x[l].y != 0.0f;  // the slab distance is NaN where this is 0
                wi[l] = ts::make_float3(rng() % 2 ? 1.0f : -1.0f, 0.0f, 0.0f);
                zero_inf += !exact[l];
                break;
            }
            case 2:  // not numbers
                (rng() % 2 ? x[l].z : wi[l].x) = rng() % 2 ? nan : inf;
                exact[l] = false;
                break;
            default:
                break;
            }
            if (!(in >> l & 1u)) x[l].x = wi[l].y = nan;  // must not leak into the other lanes
        }
        const uint32_t lanes = ts::ts_igi_may_meet_emitter_lanes(&sv, x, wi, in);
        EXPECT_EQ(lanes & ~in, 0u);
        for (int l = 0; l < TS_PACKET_LANES; ++l) {
            if (!(in >> l & 1u)) continue;
            const bool one = ts::ts_igi_may_meet_emitter(&sv, x[l], wi[l]) != 0, lane = (lanes >> l & 1u) != 0;
            if (exact[l]) EXPECT_EQ(lane, one) << "round " << round << " lane " << l;
            else EXPECT_TRUE(lane || !one) << "round " << round << " lane " << l;
            passed += lane;
            culled += !lane;
            special += !exact[l];
        }
    }
    EXPECT_GT(passed, 1000);  // both answers were seen many times
    EXPECT_GT(culled, 10000);
    EXPECT_GT(special, 5000);
    EXPECT_GT(zero_inf, 3000);  // the 0·∞ case came about
}

}  // namespace
}  // namespace tessera
