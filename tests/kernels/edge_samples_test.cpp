// kernels/shared/edge_samples.h: the positions of a pixel's edge samples. Sample 0 is the
// base pass's jitter, every sample is uniform over the pixel (chi-square), and a pixel's
// first 16 samples stratify it (one per sixteenth of its width). Many samples narrow each
// one's texture footprint, on both backends.
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include <cmath>

#include "backend/embree_tracer.h"
#include "device/frame.h"
#include "support/chi_square.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"
#include "kernels/shared/srgb_table.h"

// After the tracer (embree_tracer.h): the shared code calls it.
#include "kernels/shared/edge_samples.h"

namespace tessera {
namespace {

TsFrame frame(uint32_t width, uint32_t height, uint32_t seed, uint32_t pass) {
    TsFrame f{};
    f.width = width;
    f.height = height;
    f.seed = seed;
    f.pass = pass;
    return f;
}

TEST(EdgeSamples, SampleZeroIsTheBasePassJitter) {
    const TsFrame f = frame(16, 8, 7, 3);
    for (uint32_t py = 0; py < 8; ++py)
        for (uint32_t px = 0; px < 16; ++px) {
            ts::TsRng rng = ts::ts_rng_seed(f.seed, py * f.width + px, f.pass);  // ts_igi_view_ray's stream
            const float ux = ts::ts_rng_next(&rng), uy = ts::ts_rng_next(&rng);
            float jx, jy;
            ts::ts_edge_sample_jitter(&f, px, py, 0, &jx, &jy);
            ASSERT_EQ(jx, ux);
            ASSERT_EQ(jy, uy);
        }
}

TEST(EdgeSamples, SixteenSamplesStratifyThePixel) {
    const TsFrame f = frame(32, 32, 1, 0);
    for (uint32_t p = 0; p < 32 * 32; ++p) {
        std::set<int> columns;
        for (uint32_t j = 0; j < 16; ++j) {
            float jx, jy;
            ts::ts_edge_sample_jitter(&f, p % 32, p / 32, j, &jx, &jy);
            ASSERT_GE(jx, 0.0f);
            ASSERT_LT(jx, 1.0f);
            ASSERT_GE(jy, 0.0f);
            ASSERT_LT(jy, 1.0f);
            // A rotation by u keeps the base-2 points 1/16 apart: one in each of the 16
            // intervals [u mod 1/16 + k/16, ...), i.e. distinct values of ⌊16 (x − u mod 1/16)⌋.
            float u0, u1;
            ts::ts_edge_sample_jitter(&f, p % 32, p / 32, 0, &u0, &u1);
            const float shift = u0 - std::floor(16.0f * u0) / 16.0f;
            columns.insert(static_cast<int>(std::floor(16.0f * (jx - shift) + 1e-3f)));
        }
        ASSERT_EQ(columns.size(), 16u) << "pixel " << p;
    }
}

TEST(EdgeSamples, EachSampleIsUniformOverThePixel) {
    // 64×64 pixels × 4 passes of sample j, binned 8×8 over the pixel: a χ² test per j.
    for (uint32_t j : {1u, 2u, 5u, 15u}) {
        std::vector<double> observed(64, 0.0), expected(64, 64.0 * 64.0 * 4.0 / 64.0);
        for (uint32_t pass = 0; pass < 4; ++pass) {
            const TsFrame f = frame(64, 64, 11, pass);
            for (uint32_t p = 0; p < 64 * 64; ++p) {
                float jx, jy;
                ts::ts_edge_sample_jitter(&f, p % 64, p / 64, j, &jx, &jy);
                observed[static_cast<int>(8.0f * jy) * 8 + static_cast<int>(8.0f * jx)] += 1.0;
            }
        }
        const test::ChiSquareResult r = test::chi_square(observed, expected);
        EXPECT_FALSE(r.reject) << "sample " << j << ": chi² " << r.statistic << " on " << r.dof << " dof";
    }
}

TEST(EdgeSamples, ManySamplesNarrowTheTextureFootprint) {
    // The one-texel checker seen from 80 units spans 7.4 texels a pixel (test::checker_floor):
    // with 1 edge sample the cone narrows by √2 to 5.2 texels, mip level 2.4, where the
    // checker is flat grey; with 15 by 4 to 1.9 texels, level 0.9, where level 0's black and
    // white show through (weighted little by the trilinear blend), so the albedos spread.
    // Their mean stays the checker's.
    const Scene scene = test::checker_floor();
    SceneBuffers b = make_scene_buffers(scene);
    const double grey = ts::ts_srgb_table[188];  // levels 1 and coarser (texture_mips_test)
    for (BackendKind kind : {BackendKind::Embree, BackendKind::OpenCL}) {
        auto be = make_backend({kind, ""}, b, plan_effects(scene));
        const TsFrame f = make_frame(scene.camera, 32, 32, 1, 1, b.light_count);
        for (uint32_t n : {1u, 15u}) {
            std::vector<uint32_t> items;
            for (uint32_t p = 0; p < 32 * 32; ++p) items.insert(items.end(), {p, 1u, n});
            std::vector<float> out;
            be->launch_items(KernelId::EdgeSample, f, items, out);
            double sum = 0.0, sum2 = 0.0, max_dev = 0.0;
            for (uint32_t p = 0; p < 32 * 32; ++p) {
                const double a = out[p * TS_EDGE_SAMPLE_FLOATS + TS_EDGE_SAMPLE_ALBEDO];
                sum += a, sum2 += a * a;
                max_dev = std::max(max_dev, std::fabs(a - grey));
            }
            const double mean = sum / 1024.0, sd = std::sqrt(std::max(0.0, sum2 / 1024.0 - mean * mean));
            SCOPED_TRACE(testing::Message() << (kind == BackendKind::Embree ? "embree" : "opencl") << ", n " << n);
            if (n == 1) {
                EXPECT_LT(max_dev, 1e-5);
            } else {
                EXPECT_GT(sd, 0.002);  // measured 0.0054 on both backends; float rounding gives < 1e-5
                EXPECT_NEAR(mean, 0.5, 0.05);
            }
        }
    }
}

}  // namespace
}  // namespace tessera
