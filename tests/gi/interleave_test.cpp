// Interleaved sampling (kernels/shared/igi.h, geometry.h): the sets partition the
// pixels and the samples, and their union is the full sample set.
#include <limits>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "kernels/shared/geometry.h"

#include "support/null_tracer.h"

#include "kernels/shared/igi.h"

namespace tessera {
namespace {

TEST(Interleave, WorkItemsVisitEveryPixelOnceGroupedBySet) {
    for (uint32_t n = 1; n <= 8; ++n)
        for (auto [w, h] : {std::pair<uint32_t, uint32_t>{13, 7}, {16, 16}, {5, 11}}) {
            TsFrame f{};
            f.width = w;
            f.height = h;
            f.igi_tile = n;
            std::vector<int> seen(w * h, 0);
            uint32_t prev_set = 0;
            for (uint32_t i = 0; i < w * h; ++i) {
                uint32_t x, y;
                ts::ts_pixel_of_work_item(&f, i, &x, &y);
                ASSERT_LT(x, w);
                ASSERT_LT(y, h);
                ++seen[y * w + x];
                const uint32_t k = ts::ts_igi_set(x, y, n);
                if (n > 1) {
                    ASSERT_GE(k, prev_set) << "work-items must run set by set";
                }
                prev_set = k;
            }
            for (int c : seen) ASSERT_EQ(c, 1) << "n " << n << " size " << w << "x" << h;
        }
}

TEST(Interleave, SetsUnionToTheFullLightSampleSet) {
    // Set k holds light samples k·m .. k·m+m-1 of the N·m-point set; together their
    // stratified coordinate (j + ½)/(N·m), shifted by the frame rotation, takes every
    // one of the N·m strata exactly once.
    TsFrame f{};
    f.igi_tile = 3;
    f.shadow_samples = 4;
    f.igi_rotation[1] = 0.37f;
    const uint32_t N = 9, m = 4;
    std::vector<int> strata(N * m, 0);
    for (uint32_t k = 0; k < N; ++k)
        for (uint32_t j = 0; j < m; ++j) {
            ts::float3 q = ts::ts_igi_light_point(&f, k * m + j);
            ++strata[static_cast<uint32_t>(q.y * N * m)];
        }
    for (int c : strata) EXPECT_EQ(c, 1);
}

TEST(VplGeometry, ClampBoundsEveryContribution) {
    // A receiving plane z = 0 facing +z; VPLs on it, just above it and far away.
    float vpl[TS_VPL_FLOATS] = {};
    auto put = [&](float px, float py, float pz, float nx, float ny, float nz) {
        float* p = vpl + TS_VPL_POSITION;
        float* n = vpl + TS_VPL_NORMAL;
        p[0] = px, p[1] = py, p[2] = pz, n[0] = nx, n[1] = ny, n[2] = nz;
    };
    ts::TsSurface s{};
    s.position = s.origin = ts::make_float3(0, 0, 0);
    s.shading_normal = s.geo_normal = ts::make_float3(0, 0, 1);
    s.pos_scale = 1.0f;
    vpl[TS_VPL_POS_SCALE] = 1.0f;
    const float b = 100.0f;
    ts::TsRay shadow;
    put(0, 0, 1e-4f, 0, 0, -1);  // facing the receiver from 0.1 mm: G = 1e8, clamped
    EXPECT_EQ(ts::ts_vpl_geometry(&s, vpl, b, 0.0f, &shadow), b);
    put(0, 0, 2.0f, 0, 0, -1);  // G = 1/4, below the clamp: unchanged
    EXPECT_FLOAT_EQ(ts::ts_vpl_geometry(&s, vpl, b, 0.0f, &shadow), 0.25f);
    put(1e-3f, 0, 0, 0, 0, 1);  // on the receiving plane: cosines 0, no NaN
    EXPECT_EQ(ts::ts_vpl_geometry(&s, vpl, b, 0.0f, &shadow), 0.0f);
    put(0, 0, 0, 0, 0, 1);  // at the very point: d = 0
    EXPECT_EQ(ts::ts_vpl_geometry(&s, vpl, b, 0.0f, &shadow), 0.0f);
    put(0, 0, 1, 0, 0, 1);  // facing away from the receiver
    EXPECT_EQ(ts::ts_vpl_geometry(&s, vpl, b, 0.0f, &shadow), 0.0f);
    const float inf = std::numeric_limits<float>::infinity();
    put(0, 0, 1e-4f, 0, 0, -1);  // clamping disabled: the raw 1/d², finite
    EXPECT_FLOAT_EQ(ts::ts_vpl_geometry(&s, vpl, inf, 0.0f, &shadow), 1e8f);

    // A medium VPL 2 above the receiver, reached by light travelling toward it (-z):
    // min(cos θx · phase / d², b), the phase at cos 1 between that direction and the one
    // to the receiver. Isotropic: 1/(4π) · 1/4; g = 0.5: (1 - g²)/(4π(1 - g)³) · 1/4.
    vpl[TS_VPL_POS_SCALE] = -1.0f;
    put(0, 0, 2.0f, 0, 0, -1);
    const float pi = 3.14159265f;
    EXPECT_FLOAT_EQ(ts::ts_vpl_geometry(&s, vpl, b, 0.0f, &shadow), 1.0f / (16.0f * pi));
    EXPECT_FLOAT_EQ(ts::ts_vpl_geometry(&s, vpl, b, 0.5f, &shadow), 0.75f / (4.0f * pi * 0.125f) / 4.0f);
    // The shadow ray ends at the point itself (no surface to offset from).
    EXPECT_FLOAT_EQ(shadow.org.z + shadow.dir.z, 2.0f);
    // Close: clamped to b/4, a radius twice a surface VPL's (TS_VPL_MEDIUM_CLAMP_SCALE:
    // no cosine at the VPL keeps a medium VPL's 1/d² spike from fading near surfaces).
    put(0, 0, 1e-4f, 0, 0, -1);
    EXPECT_EQ(TS_VPL_MEDIUM_CLAMP_SCALE, 0.25f);
    EXPECT_EQ(ts::ts_vpl_geometry(&s, vpl, b, 0.0f, &shadow), b * 0.25f);
    put(0, 0, 2.0f, 0, 0, -1);  // a peaked phase function (g = 0.999: 1.6e5 at cos 1): b/4
    EXPECT_EQ(ts::ts_vpl_geometry(&s, vpl, b, 0.999f, &shadow), b * 0.25f);
}

}  // namespace
}  // namespace tessera
