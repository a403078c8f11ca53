// Light samples drawn in solid angle (kernels/shared/spherical_triangle.h, compiled as
// C++, the source the OpenCL kernels use): the spherical triangle's area, the warp's
// uniformity (chi-square), and near a light the estimator's mean against Lambert's
// closed form for a polygon's irradiance, with a bound on each sample that area sampling
// lacks there.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backend/embree_tracer.h"
#include "support/chi_square.h"

// After the tracer.
#include "kernels/shared/direct.h"
#include "kernels/shared/spherical_triangle.h"

namespace tessera {
namespace {

using ts::float3;

TEST(SphericalTriangle, AreaOfAnOctantIsPiOverTwo) {
    const float3 x = ts::make_float3(1, 0, 0), y = ts::make_float3(0, 1, 0), z = ts::make_float3(0, 0, 1);
    EXPECT_NEAR(ts::ts_spherical_triangle_area(x, y, z), M_PI / 2, 1e-6);
    EXPECT_NEAR(ts::ts_spherical_triangle_area(z, y, x), M_PI / 2, 1e-6) << "either winding";
}

// Samples over the octant x, y, z > 0 in 20 × 40 cells of (cosθ, φ) about +z: the
// octant's cells are whole (cosθ ∈ (0, 1), φ ∈ (0, π/2) fall on cell edges), so each
// expects n · cell solid angle / (π/2) exactly, the rest none.
TEST(SphericalTriangle, SamplesAreUniformInSolidAngle) {
    constexpr int kTheta = 20, kPhi = 40, kSamples = 400000;
    const float3 a = ts::make_float3(1, 0, 0), b = ts::make_float3(0, 1, 0), c = ts::make_float3(0, 0, 1);
    std::vector<double> observed(kTheta * kPhi, 0.0), expected(observed.size(), 0.0);
    int outside = 0;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int i = 0; i < kSamples; ++i) {
        const float u = uniform(rng), v = uniform(rng);
        const float3 w = ts::ts_sample_spherical_triangle(a, b, c, static_cast<float>(M_PI / 2), u, v);
        ASSERT_NEAR(ts::length(w), 1.0f, 1e-5f) << "sample " << i;
        outside += !(w.x >= -1e-6f && w.y >= -1e-6f && w.z >= -1e-6f);
        double phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * M_PI;
        const int ci = std::min(kTheta - 1, static_cast<int>((w.z + 1.0) / 2.0 * kTheta));
        const int cj = std::min(kPhi - 1, static_cast<int>(phi / (2 * M_PI) * kPhi));
        observed[ci * kPhi + cj] += 1.0;
    }
    EXPECT_EQ(outside, 0);
    const double cell = (2.0 / kTheta) * (2 * M_PI / kPhi);
    for (int i = kTheta / 2; i < kTheta; ++i)
        for (int j = 0; j < kPhi / 4; ++j) expected[i * kPhi + j] = kSamples * cell / (M_PI / 2);
    const auto r = test::chi_square(observed, expected);
    EXPECT_FALSE(r.reject) << "chi2 " << r.statistic << " dof " << r.dof << " z " << r.z;
}

// One light triangle with corners (0, 0.5, 0), (1, 0.5, 0), (0, 0.5, 1), facing −y, of
// radiance 1 (selection probability 1).
struct Light {
    std::array<float, TS_LIGHT_FLOATS> buf{};
    std::array<float, 1> cdf{1.0f};
    Light() {
        const float p0[3] = {0, 0.5f, 0}, e1[3] = {1, 0, 0}, e2[3] = {0, 0, 1}, le[3] = {1, 1, 1};
        std::copy(p0, p0 + 3, buf.begin() + TS_LIGHT_P0);
        std::copy(e1, e1 + 3, buf.begin() + TS_LIGHT_E1);
        std::copy(e2, e2 + 3, buf.begin() + TS_LIGHT_E2);
        std::copy(le, le + 3, buf.begin() + TS_LIGHT_RADIANCE);
        buf[TS_LIGHT_AREA] = 0.5f;
    }
    ts::TsLightSample sample(float u, float v) const { return ts::ts_sample_light(buf.data(), cdf.data(), 1u, 0.5f, u, v); }
};

ts::TsSurface surface(float3 p, float3 n) {
    ts::TsSurface s{};
    s.position = s.origin = p;
    s.geo_normal = s.shading_normal = n;
    s.pos_scale = 1.0f;
    return s;
}

// Lambert (1760): the irradiance at p (normal n) from a polygon of unit radiance wholly
// above its horizon, ½ Σ Θ_i n·(v_i × v_i+1)/|v_i × v_i+1| over the edges of unit
// vectors v_i from p (Θ_i the angle between them), in double throughout.
double lambert_irradiance(float3 p, float3 n, const std::array<float3, 3>& corners) {
    using D3 = std::array<double, 3>;
    const auto unit = [&p](float3 q) {
        const D3 d = {double(q.x) - p.x, double(q.y) - p.y, double(q.z) - p.z};
        const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        return D3{d[0] / l, d[1] / l, d[2] / l};
    };
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
        const D3 a = unit(corners[i]), b = unit(corners[(i + 1) % 3]);
        const D3 g = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        const double gl = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        const double angle = std::atan2(gl, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
        sum += 0.5 * angle * (n.x * g[0] + n.y * g[1] + n.z * g[2]) / gl;
    }
    return std::fabs(sum);
}

struct NearCase {
    float3 p, n;
    const char* what;
};

// Near the light, the mean contribution over 128² stratified (u, v) equals Lambert's
// irradiance within 0.5%, and no sample exceeds Le Ω (≤ 2π) (or 2π where the hemisphere
// is sampled), while area sampling's largest is over 10 times that at the wall:
// - a wall beside the light's corner, 2 cm below it;
// - a floor 5 cm below the light's middle;
// - a floor 1 mm below it, where the light covers more than TS_SPHERICAL_SAMPLE_MAX
//   (hemisphere sampling);
// - a floor 1e-4 below the light's edge from (0, 0.5, 0) to (1, 0.5, 0), and 1e-4 in
//   front of it, where two corners are nearly opposite.
TEST(LightSampleFrom, NearALightMatchesLambertAndEachSampleIsBounded) {
    const Light light;
    const std::array<float3, 3> corners = {ts::make_float3(0, 0.5f, 0), ts::make_float3(1, 0.5f, 0),
                                           ts::make_float3(0, 0.5f, 1)};
    const NearCase cases[] = {{ts::make_float3(1.01f, 0.48f, 0.02f), ts::make_float3(-1, 0, 0), "wall"},
                              {ts::make_float3(0.3f, 0.45f, 0.3f), ts::make_float3(0, 1, 0), "floor"},
                              {ts::make_float3(0.3f, 0.499f, 0.3f), ts::make_float3(0, 1, 0), "floor at 1 mm"},
                              {ts::make_float3(0.4f, 0.4999f, -1e-4f), ts::make_float3(0, 1, 0), "below an edge"}};
    for (const NearCase& k : cases) {
        const ts::TsSurface s = surface(k.p, k.n);
        const float3 a = ts::normalize(corners[0] - k.p), b = ts::normalize(corners[1] - k.p),
                     c = ts::normalize(corners[2] - k.p);
        const double omega = ts::ts_spherical_triangle_area(a, b, c);
        const double bound = (omega > TS_SPHERICAL_SAMPLE_MAX ? 2 * M_PI : omega) * (1 + 1e-5);
        if (std::string(k.what) == "floor at 1 mm") {
            EXPECT_GT(omega, TS_SPHERICAL_SAMPLE_MAX) << "the case meant for hemisphere sampling";
        }
        constexpr int kGrid = 128;
        double sum = 0.0, largest = 0.0, largest_area = 0.0;
        int drawn = 0;
        for (int i = 0; i < kGrid; ++i)
            for (int j = 0; j < kGrid; ++j) {
                const ts::TsLightSample q = light.sample((i + 0.5f) / kGrid, (j + 0.5f) / kGrid);
                ts::TsRay shadow;
                const float3 e = ts::ts_light_contribution_from(light.buf.data(), &s, q, &shadow);
                ASSERT_TRUE(std::isfinite(e.x)) << k.what;
                drawn += ts::ts_light_sample_from(light.buf.data(), q, k.p).inv_pdf_solid_angle > 0.0f;
                sum += e.x;
                largest = std::max(largest, static_cast<double>(e.x));
                largest_area = std::max(largest_area, static_cast<double>(ts::ts_light_contribution(&s, q, &shadow).x));
            }
        const double want = lambert_irradiance(k.p, k.n, corners);
        EXPECT_EQ(drawn, kGrid * kGrid) << k.what;
        EXPECT_NEAR(sum / (kGrid * kGrid), want, 5e-3 * want) << k.what;
        EXPECT_LE(largest, bound) << k.what;
        if (k.n.x != 0.0f) {
            EXPECT_GT(largest_area, 10 * bound) << k.what << ": area sampling there has no bound";
        }
    }
}

// Far from the light (beyond 1.25 times its radius about its centroid) or behind it, the
// sample is the area sample itself, bit for bit; so are the degenerate cases: a point on
// a vertex, and one in the light's plane, which sees no solid angle.
TEST(LightSampleFrom, FarOrDegenerateKeepsTheAreaSample) {
    const Light light;
    const ts::TsLightSample q = light.sample(0.3f, 0.7f);
    for (float3 p : {ts::make_float3(0.3f, -1.5f, 0.3f), ts::make_float3(1, 0.5f, 0), ts::make_float3(0.2f, 0.5f, 0.2f),
                     ts::make_float3(1.5f, 0.5f, 0.5f), ts::make_float3(0.3f, 0.55f, 0.3f)}) {
        const ts::TsLightSample r = ts::ts_light_sample_from(light.buf.data(), q, p);
        EXPECT_EQ(r.inv_pdf_solid_angle, 0.0f) << p.x << ", " << p.y << ", " << p.z;
        EXPECT_EQ(std::memcmp(&r.position, &q.position, sizeof q.position), 0);
    }
}

}  // namespace
}  // namespace tessera
