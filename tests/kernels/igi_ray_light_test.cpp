// kernels/shared/igi_ray_lights.h ts_igi_march_vrl_link: a virtual ray light's link from the ray
// march (docs/igi.md §6). Summed over a march's steps and the link's two numbers, it must
// give the double integral of the light the ray light scatters toward the camera segment
// (quadrature), in both march modes; and its terms must stay bounded as the ray light
// passes closer to the camera ray, where a point light's 1/d² would not.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

// The tracer first (embree_tracer.h): the shared code calls it.
#include "backend/embree_tracer.h"
#include "kernels/shared/igi_media.h"

namespace tessera {
namespace {

using ts::float3;
using ts::make_float3;

constexpr float kSigmaS = 0.5f, kSigmaA = 0.1f, kG = 0.3f;

ts::TsMedium fog() {
    // Fills space (not bounded): the segments below are all inside it.
    float buf[TS_MEDIUM_FLOATS] = {kSigmaA, kSigmaA, kSigmaA, kSigmaS, kSigmaS, kSigmaS, kG, 0.0f,
                                   0.0f,    0.0f,    0.0f,    0.0f,    0.0f,    0.0f,    1.0f, 0.0f};
    return ts::ts_medium_load(buf);
}

// The camera segment [0.5, 4.5] along +z from the origin, in 8 steps.
ts::TsIgiMarch march(bool equiangular) {
    ts::TsIgiMarch m{};
    m.ray.org = make_float3(0, 0, 0);
    m.ray.dir = make_float3(0, 0, 1);
    m.ray.tmin = 0.0f;
    m.ray.tmax = ts::TS_INF;
    m.t0 = 0.5f;
    m.t1 = 4.5f;
    m.step = 0.5f;
    m.active = 1;
    m.equiangular = equiangular;
    return m;
}

struct RayLight {
    float v[TS_VRL_FLOATS];
};

RayLight ray_light(float3 start, float3 dir, float length) {
    RayLight r{};
    ts::ts_f3_store(r.v + TS_VRL_START, start);
    ts::ts_f3_store(r.v + TS_VRL_DIR, ts::normalize(dir));
    ts::ts_f3_store(r.v + TS_VRL_FLUX, make_float3(1, 1, 1));
    r.v[TS_VRL_LENGTH] = length;
    return r;
}

// Φ ∫∫ σs T(t0, t) · σs T(τ) · f_p(ω, y→x) f_p(dir, x→y) · T(x, y) / |x − y|² dτ dt by the
// midpoint rule in double, Φ = 1.
double quadrature(const ts::TsIgiMarch& m, const RayLight& r) {
    const int nt = 2000, ns = 2000;
    const float3 s = ts::ts_f3_load(r.v + TS_VRL_START), w = ts::ts_f3_load(r.v + TS_VRL_DIR);
    const double len = r.v[TS_VRL_LENGTH], sigma_t = kSigmaS + kSigmaA;
    const double dt = (m.t1 - m.t0) / nt, ds = len / ns;
    double sum = 0.0;
    for (int i = 0; i < nt; ++i) {
        const double t = m.t0 + (i + 0.5) * dt;
        const float3 x = m.ray.org + m.ray.dir * float(t);
        for (int j = 0; j < ns; ++j) {
            const double tau = (j + 0.5) * ds;
            const float3 y = s + w * float(tau);
            const float3 d = y - x;
            const double d2 = ts::dot(d, d), dist = std::sqrt(d2);
            const float3 wi = d * float(1.0 / dist);
            const double phases = ts::ts_hg_phase(ts::dot(w, -wi), kG) * ts::ts_hg_phase(ts::dot(m.ray.dir, wi), kG);
            sum += kSigmaS * std::exp(-sigma_t * (t - m.t0)) * kSigmaS * std::exp(-sigma_t * tau) * phases *
                   std::exp(-sigma_t * dist) / d2;
        }
    }
    return sum * dt * ds;
}

// The links of a march with one ray light gathered at every step (stride 1): each step's
// point from a midpoint grid over its stratum, the ray light's number from another. With
// !equiangular the step's end multiplies by σs T(t0, t) · step, as ts_igi_march_step_end.
// Also the largest single term.
double links(const ts::TsIgiMarch& m, const RayLight& r, double* largest) {
    const ts::TsMedium med = fog();
    const int nx = 128, nu = 128;
    const double sigma_t = kSigmaS + kSigmaA;
    double sum = 0.0;
    *largest = 0.0;
    for (int i = 0; i < 8; ++i)
        for (int a = 0; a < nx; ++a) {
            const float t = m.t0 + (float(i) + (a + 0.5f) / nx) * m.step;
            ts::TsIgiMarch at = m;  // the march at the step of distance t, as the march keeps it
            ts::ts_igi_march_step_begin(&at, &med, t);
            for (int b = 0; b < nu; ++b) {
                ts::TsRay shadow;
                float w;
                float3 tint;
                if (!ts::ts_igi_march_vrl_link(&med, &at, t, (b + 0.5f) / nu, 1.0f, r.v, &shadow, &w, &tint)) continue;
                double term = double(w) * tint.y * ts::ts_shadow_transmittance(&med, shadow).y;
                if (!m.equiangular) term *= kSigmaS * std::exp(-sigma_t * (t - m.t0)) * m.step;
                sum += term;
                *largest = std::max(*largest, term);
            }
        }
    return sum / (double(nx) * nu);
}

TEST(IgiRayLight, LinksOverAMarchMatchQuadrature) {
    // A ray light passing 0.3 from the camera ray (within two steps: its links draw their
    // camera distance toward it) and one 3 away (the step's own point). Both march modes
    // estimate the same integral; measured within 0.3%.
    const RayLight near = ray_light(make_float3(0.3f, -1.5f, 2.0f), make_float3(0, 1, 0.3f), 3.0f),
                   far = ray_light(make_float3(3.0f, -2.0f, 1.0f), make_float3(0, 1, 0), 4.0f);
    for (const RayLight* r : {&near, &far}) {
        const double expect = quadrature(march(true), *r);
        for (bool equiangular : {true, false}) {
            double largest;
            const double got = links(march(equiangular), *r, &largest);
            std::printf("  %s ray light, %s march: links %.6g, quadrature %.6g (%.3f%%)\n", r == &near ? "near" : "far",
                        equiangular ? "equiangular" : "uniform", got, expect, 100.0 * (got / expect - 1.0));
            EXPECT_NEAR(got, expect, 0.01 * expect);
        }
    }
}

TEST(IgiRayLight, TermsStayBoundedAsTheRayLightPassesCloser) {
    // The same ray light at 0.3, 0.03 and 0.003 from the camera ray. A point light's term
    // at the closest point would grow with 1/h², 10,000-fold, far beyond the integral,
    // which grows only like log(1/h) here. The ray light's largest single term stays
    // below the whole march's estimate (the mean of its sums over the steps), and its
    // share of it does not grow: measured 0.45, 0.35, 0.32.
    double previous = 0.0;
    for (float h : {0.3f, 0.03f, 0.003f}) {
        const RayLight r = ray_light(make_float3(h, -1.5f, 2.0f), make_float3(0, 1, 0.3f), 3.0f);
        double largest;
        const double mean = links(march(true), r, &largest);
        std::printf("  h %.3g: mean %.6g, largest term %.6g (%.3f of the mean)\n", h, mean, largest, largest / mean);
        ASSERT_TRUE(std::isfinite(largest));
        EXPECT_LT(largest, mean) << "h " << h;
        if (previous > 0.0) {
            EXPECT_LT(largest / mean, 1.1 * previous) << "h " << h;
        }
        previous = largest / mean;
    }
}

}  // namespace
}  // namespace tessera
