// Pieces of kernels/shared/pt.h compiled as C++.
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

}  // namespace
}  // namespace tessera
