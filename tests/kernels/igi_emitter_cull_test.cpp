// kernels/shared/igi.h ts_igi_may_meet_emitter: the box test that lets the ray march skip
// tracing phase-sampled rays that cannot reach a light. It must be conservative (every
// ray whose closest hit is an emitter passes it, so images do not change) and it must
// cull (most directions from inside the Cornell box miss its small ceiling light).
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "backend/embree_tracer.h"
#include "bvh/embree_scene.h"
#include "device/scene_view.h"
#include "support/render_helpers.h"

// After the tracer (embree_tracer.h): the shared code calls it.
#include "kernels/shared/igi.h"

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

}  // namespace
}  // namespace tessera
