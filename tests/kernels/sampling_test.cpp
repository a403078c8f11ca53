// Chi-square tests of the sample warps in kernels/shared/sampling.h (compiled as C++,
// the same source the OpenCL kernels use): each warp's samples must follow the pdf the
// estimators divide by.
#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "kernels/shared/sampling.h"
#include "support/chi_square.h"

namespace tessera {
namespace {

using ts::float3;
constexpr int kThetaBins = 20, kPhiBins = 40;
constexpr int kSamples = 400000;

// Histogram of unit directions over (cosθ, φ) about +z, and the expected counts from
// `pdf` (per steradian) integrated over each cell by a 64×4 midpoint rule in (cosθ, φ),
// dω = dcosθ dφ; fine in cosθ because HG with g = 0.9 peaks sharply there.
test::ChiSquareResult direction_chi2(const std::function<float3(float, float)>& sample,
                                     const std::function<double(float3)>& pdf, uint32_t seed) {
    std::vector<double> observed(kThetaBins * kPhiBins, 0.0), expected(observed.size(), 0.0);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto cell = [](double c, double phi) {
        int i = std::min(kThetaBins - 1, static_cast<int>((c + 1.0) / 2.0 * kThetaBins));
        int j = std::min(kPhiBins - 1, static_cast<int>(phi / (2 * M_PI) * kPhiBins));
        return i * kPhiBins + j;
    };
    for (int n = 0; n < kSamples; ++n) {
        float3 d = sample(u(rng), u(rng));
        double phi = std::atan2(d.y, d.x);
        if (phi < 0) phi += 2 * M_PI;
        observed[cell(d.z, phi)] += 1.0;
    }
    const double dc = 2.0 / kThetaBins, dp = 2 * M_PI / kPhiBins;
    for (int i = 0; i < kThetaBins; ++i)
        for (int j = 0; j < kPhiBins; ++j) {
            double sum = 0.0;
            for (int a = 0; a < 64; ++a)
                for (int b = 0; b < 4; ++b) {
                    double c = -1.0 + (i + (a + 0.5) / 64) * dc, phi = (j + (b + 0.5) / 4) * dp;
                    double s = std::sqrt(std::max(0.0, 1 - c * c));
                    sum += pdf(ts::make_float3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c)));
                }
            expected[i * kPhiBins + j] = kSamples * sum / 256.0 * dc * dp;
        }
    return test::chi_square(observed, expected);
}

TEST(Sampling, CosineHemisphereMatchesItsPdf) {
    auto r = direction_chi2([](float u, float v) { return ts::ts_sample_cosine_hemisphere(u, v); },
                            [](float3 d) { return d.z > 0 ? d.z / M_PI : 0.0; }, 1);
    EXPECT_FALSE(r.reject) << "chi2 " << r.statistic << " dof " << r.dof << " z " << r.z;
}

TEST(Sampling, UniformHemisphereMatchesItsPdf) {
    auto r = direction_chi2([](float u, float v) { return ts::ts_sample_uniform_hemisphere(u, v); },
                            [](float3 d) { return d.z > 0 ? 1.0 / (2 * M_PI) : 0.0; }, 3);
    EXPECT_FALSE(r.reject) << "chi2 " << r.statistic << " dof " << r.dof << " z " << r.z;
}

TEST(Sampling, CosineHemisphereAboutATiltedNormalStaysAbove) {
    const float3 n = ts::normalize(ts::make_float3(0.3f, -0.8f, 0.5f));
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 10000; ++i) {
        float3 d = ts::ts_from_local(n, ts::ts_sample_cosine_hemisphere(u(rng), u(rng)));
        ASSERT_GE(ts::dot(d, n), 0.0f);
        ASSERT_NEAR(ts::length(d), 1.0f, 1e-5f);
    }
}

class HenyeyGreenstein : public ::testing::TestWithParam<float> {};

TEST_P(HenyeyGreenstein, SamplesMatchThePhaseFunction) {
    const float g = GetParam();
    const float3 d_in = ts::make_float3(0.0f, 0.0f, 1.0f);
    auto r = direction_chi2([&](float u, float v) { return ts::ts_sample_hg(d_in, g, u, v); },
                            [&](float3 d) { return ts::ts_hg_phase(ts::dot(d_in, d), g); }, 3);
    EXPECT_FALSE(r.reject) << "g " << g << ": chi2 " << r.statistic << " dof " << r.dof << " z " << r.z;
}

TEST_P(HenyeyGreenstein, PhaseIntegratesToOne) {
    const float g = GetParam();
    double sum = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) sum += ts::ts_hg_phase(-1.0f + 2.0f * (i + 0.5f) / n, g);
    EXPECT_NEAR(sum * 2.0 / n * 2 * M_PI, 1.0, 2e-3);
}

INSTANTIATE_TEST_SUITE_P(G, HenyeyGreenstein, ::testing::Values(-0.7f, 0.0f, 0.0005f, 0.3f, 0.9f));

TEST(Sampling, TriangleBarycentricsAreUniformInArea) {
    // Points of the unit right triangle binned on a 20x20 grid of its bounding square;
    // a cell's expected count is proportional to its area inside the triangle.
    const int g = 20;
    std::vector<double> observed(g * g, 0.0), expected(g * g, 0.0);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int n = 0; n < kSamples; ++n) {
        ts::float2 b = ts::ts_triangle_barycentrics(u(rng), u(rng));
        ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
        int i = std::min(g - 1, int(b.x * g)), j = std::min(g - 1, int(b.y * g));
        observed[i * g + j] += 1.0;
    }
    for (int i = 0; i < g; ++i)
        for (int j = 0; j < g; ++j) {
            // The diagonal b1 + b2 = 1 runs through cell corners: cells are wholly
            // inside, wholly outside, or cut exactly in half.
            const double inside = i + j + 2 <= g ? 1.0 : (i + j + 1 == g ? 0.5 : 0.0);
            expected[i * g + j] = kSamples * inside / (g * g) / 0.5;
        }
    auto r = test::chi_square(observed, expected);
    EXPECT_FALSE(r.reject) << "chi2 " << r.statistic << " dof " << r.dof << " z " << r.z;
}

TEST(Sampling, LightSelectionFollowsPower) {
    // Three lights of power 1 : 2 : 5 (luminance × area) are picked 1/8, 2/8, 5/8 of the time.
    const float cdf[3] = {1.0f / 8, 3.0f / 8, 1.0f};
    float lights[3 * TS_LIGHT_FLOATS] = {};
    for (int l = 0; l < 3; ++l) {
        float* L = lights + l * TS_LIGHT_FLOATS;
        L[TS_LIGHT_E1 + 0] = 1;  // e1 = x
        L[TS_LIGHT_E2 + 1] = 1;  // e2 = y
        for (int c = 0; c < 3; ++c) L[TS_LIGHT_RADIANCE + c] = float(l + 1);  // radiance tags the light
        L[TS_LIGHT_AREA] = 0.5f;
    }
    std::vector<double> observed(3, 0.0), expected = {kSamples / 8.0, 2 * kSamples / 8.0, 5 * kSamples / 8.0};
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int n = 0; n < kSamples; ++n) {
        ts::TsLightSample s = ts::ts_sample_light(lights, cdf, 3, u(rng), u(rng), u(rng));
        int l = int(s.radiance.x) - 1;
        observed[l] += 1.0;
        const double p_select = l == 0 ? 1.0 / 8 : (l == 1 ? 2.0 / 8 : 5.0 / 8);
        ASSERT_NEAR(s.pdf_area, p_select / 0.5, 1e-5);
    }
    for (int l = 0; l < 3; ++l) EXPECT_NEAR(observed[l] / kSamples, expected[l] / kSamples, 0.003);
}

}  // namespace
}  // namespace tessera
