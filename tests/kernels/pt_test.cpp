// Pieces of kernels/shared/pt.h compiled as C++.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "kernels/shared/geometry.h"

#include "support/null_tracer.h"

#include "kernels/shared/pt.h"

namespace tessera {
namespace {

TEST(PowerHeuristic, MatchesTheFormula) {
    EXPECT_FLOAT_EQ(ts::ts_power_heuristic(1.0f, 1.0f), 0.5f);
    EXPECT_FLOAT_EQ(ts::ts_power_heuristic(3.0f, 1.0f), 0.9f);
    EXPECT_FLOAT_EQ(ts::ts_power_heuristic(1.0f, 3.0f), 0.1f);
    EXPECT_EQ(ts::ts_power_heuristic(0.0f, 2.0f), 0.0f);
    EXPECT_EQ(ts::ts_power_heuristic(2.0f, 0.0f), 1.0f);
}

TEST(PowerHeuristic, StaysFiniteForHugePdfs) {
    // A light sampled from a scattering point 1e7 units away: pdf ~ d² ~ 1e20, whose
    // square overflows float (it used to give inf / inf = NaN).
    EXPECT_FLOAT_EQ(ts::ts_power_heuristic(7e19f, 0.08f), 1.0f);
    EXPECT_NEAR(ts::ts_power_heuristic(0.08f, 7e19f), 0.0f, 1e-30f);
    EXPECT_FLOAT_EQ(ts::ts_power_heuristic(3e30f, 1e30f), 0.9f);
    EXPECT_FLOAT_EQ(ts::ts_power_heuristic(INFINITY, 1.0f), 1.0f);
}

TEST(Roulette, AFarFactorOfOneLeavesThePathAsItWas) {
    // Within the far roulette's margin the factor is 1: the path survives where it did,
    // with the same weight's bits, and draws the same one number.
    for (uint32_t depth : {0u, 2u, 3u, 9u})
        for (float b : {1.0f, 0.3f, 2.5f}) {
            ts::float3 beta = ts::make_float3(b, 0.5f * b, 0.1f);
            ts::TsRng rng = ts::ts_rng_seed(5u, depth, 7u), plain = rng;
            const int kept = ts::ts_roulette(&beta, depth, 1.0f, &rng);
            const float u = ts::ts_rng_next(&plain);
            const float survive = depth < 3u ? 1.0f : std::min(1.0f, std::max(b, 0.05f));
            EXPECT_EQ(kept, u < survive ? 1 : 0);
            if (kept) {
                EXPECT_EQ(beta.x, survive < 1.0f ? b / survive : b);
            }
            EXPECT_EQ(ts::ts_rng_next(&rng), ts::ts_rng_next(&plain)) << "one number drawn";
        }
}

TEST(Roulette, TheFarImportanceIsUnbiasedAndBoundsTheWeight) {
    // A far importance f at a throughput of 1: the path survives with probability f and
    // its weight is divided by it, so the mean weight stays 1. 200,000 draws: standard
    // errors of 0.1% (survival) and 0.39% (mean weight at f = 0.25: √(3 / 200,000)), so
    // 0.5% and 2% are five sigma. A path whose throughput is already 1 / f or more
    // survives as it is.
    for (uint32_t depth : {0u, 5u}) {
        const float f = 0.25f;
        const int n = 200000;
        int kept = 0;
        double weight = 0.0;
        for (int i = 0; i < n; ++i) {
            ts::float3 beta = ts::make_float3(1.0f, 1.0f, 1.0f);
            ts::TsRng rng = ts::ts_rng_seed(11u, uint32_t(i), depth);
            if (!ts::ts_roulette(&beta, depth, f, &rng)) continue;
            ++kept;
            weight += beta.x;
        }
        EXPECT_NEAR(double(kept) / n, f, 0.005) << "depth " << depth;
        EXPECT_NEAR(weight / n, 1.0, 0.02) << "depth " << depth;
        ts::float3 boosted = ts::make_float3(4.0f, 1.0f, 0.5f);
        ts::TsRng rng = ts::ts_rng_seed(3u, 1u, depth);
        EXPECT_EQ(ts::ts_roulette(&boosted, depth, f, &rng), 1);
        EXPECT_EQ(boosted.x, 4.0f);
    }
}

}  // namespace
}  // namespace tessera
