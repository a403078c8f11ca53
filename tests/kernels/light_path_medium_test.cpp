// kernels/shared/light_path.h's medium events compiled as C++ (ts_light_path_medium): a
// light path's chain of scattering events in a strongly chromatic medium leaves medium VPLs
// whose flux is unbiased and bounded, with its Russian roulette.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "kernels/shared/light_path.h"

namespace tessera {
namespace {

using ts::make_float3;

// A medium filling space (no box): every free-flight distance is a scattering event.
ts::TsMedium unbounded(ts::float3 sigma_a, ts::float3 sigma_s) {
    float buf[TS_MEDIUM_FLOATS] = {sigma_a.x, sigma_a.y, sigma_a.z, sigma_s.x, sigma_s.y, sigma_s.z, 0.0f, 0.0f,
                                   0.0f,      0.0f,      0.0f,      0.0f,      0.0f,      0.0f,      1.0f, 0.0f};
    return ts::ts_medium_load(buf);
}

// A ray from the origin along `dir`, for t in (0, inf).
ts::TsRay from_origin(ts::float3 dir) {
    ts::TsRay ray;
    ray.org = make_float3(0.0f, 0.0f, 0.0f);
    ray.dir = dir;
    ray.tmin = 0.0f;
    ray.tmax = ts::TS_INF;
    return ray;
}

// A region that never roulettes (margin 0: ts_far_importance gives 1 everywhere).
ts::TsFarRegion everywhere() {
    ts::TsFarRegion r;
    r.lo = make_float3(-ts::TS_INF, -ts::TS_INF, -ts::TS_INF);
    r.hi = make_float3(ts::TS_INF, ts::TS_INF, ts::TS_INF);
    r.margin = 0.0f;
    return r;
}

TEST(LightPathMedium, FarRouletteKeepsTheVplFluxUnbiasedAndEndsTheWalk) {
    // A medium that scatters without absorbing, filling space (mean free path 1), and a
    // region of a unit box at the origin with a margin of 1: without the far roulette
    // every event's VPL has flux exactly 1 and no path ends. With it, event j's mean flux
    // is still 1 (the survivors' weights carry the ended paths'), within 5 standard
    // errors; a VPL's flux is at most (d / margin)², d the farthest its path has been from
    // the box (the survivals telescope); and the paths walking away end: fewer than half
    // reach event 24 (measured 0.044; all do without the roulette).
    const ts::TsMedium m = unbounded(make_float3(0.0f, 0.0f, 0.0f), make_float3(1.0f, 1.0f, 1.0f));
    ts::TsFarRegion region;
    region.lo = make_float3(-0.5f, -0.5f, -0.5f);
    region.hi = make_float3(0.5f, 0.5f, 0.5f);
    region.margin = 1.0f;
    const int n = 100000, events = 24;
    double sum[events] = {}, sum2[events] = {}, worst = 0.0;
    int reached = 0;
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (int i = 0; i < n; ++i) {
        ts::TsSpectralMis sm = ts::ts_spectral_mis_start();
        ts::float3 alpha = make_float3(1.0f, 1.0f, 1.0f);
        float boost = 1.0f, farthest = 0.0f;
        ts::TsRay ray = from_origin(make_float3(0.0f, 1.0f, 0.0f));
        for (int j = 0; j < events; ++j) {
            float u[5];
            for (float& x : u) x = std::min(uni(rng), 0x1.fffffep-1f);
            float t_event;
            ts::float3 pos, flux;
            const uint32_t what = ts::ts_light_path_medium(&m, &region, ts::TS_INF, u, 1.0f, &alpha, &sm, &boost, &ray,
                                                           &t_event, &pos, &flux);
            ASSERT_TRUE(what & TS_LIGHT_PATH_VPL);
            sum[j] += flux.x;
            sum2[j] += double(flux.x) * flux.x;
            // The flux was set before this event's roulette: bounded by the path's earlier
            // distances.
            const double bound = std::max(1.0, double(farthest) * farthest);
            worst = std::max(worst, flux.x / bound);
            const ts::float3 out = ts::fmax(ts::fmax(region.lo - pos, pos - region.hi), make_float3(0.0f, 0.0f, 0.0f));
            farthest = std::max(farthest, ts::length(out) / region.margin);
            if (j == events - 1) ++reached;
            if (!(what & TS_LIGHT_PATH_CONTINUES)) break;
        }
    }
    for (int j = 0; j < events; ++j) {
        const double mean = sum[j] / n, sd = std::sqrt(std::max(0.0, sum2[j] / n - mean * mean));
        EXPECT_NEAR(mean, 1.0, 5.0 * sd / std::sqrt(double(n)) + 1e-6) << "event " << j;
    }
    std::printf("  paths reaching event %d: %.3f; largest flux over its bound %.4f\n", events, double(reached) / n,
                worst);
    EXPECT_LE(worst, 1.0 + 1e-5);
    EXPECT_LT(reached, n / 2);
}

TEST(LightPathMedium, ChromaticEventsLeaveUnbiasedBoundedVpls) {
    // Event j of a path in an unbounded medium leaves a VPL of mean flux a_c^(j+1) per
    // channel (a_c the single-scattering albedo, the path's weight 1 at the light), the
    // roulette included. The roulette keeps a path with q = min(1, max_c w_c), the event's
    // weights being at most 3 a_c^(j+1) over the path without it (shared/medium.h): the
    // largest flux measured here is 5.2, so 10 bounds it. With q from the luminance, a
    // red-drawn path in red fog (w ≈ (0.99, ε, ε), q ≈ 0.21) grew ~4.7× an event: the
    // largest flux was 3,400, the means missed by more than 5 standard errors, and a
    // foggy frame's red read 12% dark over 8 seeds (docs/path-tracing.md §4).
    const ts::float3 sa = make_float3(0.05f, 0.05f, 0.05f), ss = make_float3(5.0f, 0.5f, 0.05f);
    const ts::TsMedium m = unbounded(sa, ss);
    const int n = 200000, events = 8;
    double sum[events][3] = {}, sum2[events][3] = {}, largest = 0.0;
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const ts::TsFarRegion region = everywhere();
    for (int i = 0; i < n; ++i) {
        ts::TsSpectralMis sm = ts::ts_spectral_mis_start();
        ts::float3 alpha = make_float3(1.0f, 1.0f, 1.0f);
        float boost = 1.0f;
        ts::TsRay ray = from_origin(make_float3(1.0f, 0.0f, 0.0f));
        for (int j = 0; j < events; ++j) {
            float u[5];
            for (float& x : u) x = std::min(uni(rng), 0x1.fffffep-1f);  // [0, 1) whatever the library
            float t_event;
            ts::float3 pos, flux;
            const uint32_t what = ts::ts_light_path_medium(&m, &region, ts::TS_INF, u, 1.0f, &alpha, &sm, &boost, &ray,
                                                           &t_event, &pos, &flux);
            ASSERT_TRUE(what & TS_LIGHT_PATH_VPL) << "an unbounded medium scatters every path";
            const double f[3] = {flux.x, flux.y, flux.z};
            for (int c = 0; c < 3; ++c) {
                sum[j][c] += f[c];
                sum2[j][c] += f[c] * f[c];
                largest = std::max(largest, f[c]);
            }
            if (!(what & TS_LIGHT_PATH_CONTINUES)) break;
        }
    }
    std::printf("  largest VPL flux %.3g\n", largest);
    EXPECT_LE(largest, 10.0);
    const float st[3] = {sa.x + ss.x, sa.y + ss.y, sa.z + ss.z}, s[3] = {ss.x, ss.y, ss.z};
    for (int c = 0; c < 3; ++c) {
        for (int j = 0; j < events; ++j) {
            const double mean = sum[j][c] / n, sd = std::sqrt(std::max(0.0, sum2[j][c] / n - mean * mean));
            // 5 standard errors of the mean: a one-in-a-million miss per comparison.
            EXPECT_NEAR(mean, std::pow(s[c] / st[c], j + 1), 5.0 * sd / std::sqrt(double(n)) + 1e-6)
                << "channel " << c << ", event " << j;
        }
    }
}

}  // namespace
}  // namespace tessera
