// kernels/shared/math_lanes.h: the lanes' arctangent, tangent and exponential against
// double precision over dense sweeps of their domains, within the bounds the header
// states (a few float ulps: Cephes' own figures are 1.9e-7, 3.0e-7 and 1.7e-7 peak
// relative error), and their special values.
#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

#include "kernels/shared/math_lanes.h"

namespace tessera {
namespace {

// Largest relative error of f against g over n points spread evenly on [lo, hi], and the
// point where it occurred.
template <class F, class G>
double worst(F f, G g, double lo, double hi, int n, double* at) {
    double w = 0.0;
    for (int i = 0; i <= n; ++i) {
        const float x = float(lo + (hi - lo) * i / n);
        const double want = g(double(x)), got = f(x);
        const double rel = want == 0.0 ? std::fabs(got) : std::fabs(got - want) / std::fabs(want);
        if (rel > w) w = rel, *at = x;
    }
    return w;
}

TEST(MathLanes, ArctangentWithinTwoTenMillionths) {
    double at = 0.0;
    const auto f = [](float x) { return ts::ts_lanes_atan(x); };
    const auto g = [](double x) { return std::atan(x); };
    EXPECT_LE(worst(f, g, -4.0, 4.0, 2000000, &at), 2e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1e6, 1e6, 2000000, &at), 2e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1e-3, 1e-3, 200000, &at), 2e-7) << "at " << at;
    // Every power of two: tiny and huge arguments.
    for (int e = -126; e <= 127; ++e) {
        const float x = std::ldexp(1.0f, e);
        EXPECT_NEAR(ts::ts_lanes_atan(x) / std::atan(double(x)), 1.0, 2e-7) << "2^" << e;
        EXPECT_NEAR(ts::ts_lanes_atan(-x) / std::atan(-double(x)), 1.0, 2e-7) << "-2^" << e;
    }
}

TEST(MathLanes, TangentWithinFourTenMillionthsBelowAQuarterTurn) {
    double at = 0.0;
    const auto f = [](float x) { return ts::ts_lanes_tan(x); };
    const auto g = [](double x) { return std::tan(x); };
    const double h = 1.5707963267948966;
    EXPECT_LE(worst(f, g, -h + 1e-6, h - 1e-6, 4000000, &at), 4e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1e-3, 1e-3, 200000, &at), 4e-7) << "at " << at;
    // The floats nearest the quarter turn, from below: tan is ~1e7 there and still right.
    float x = float(h);
    for (int i = 0; i < 64; ++i) {
        x = std::nextafter(x, 0.0f);
        EXPECT_NEAR(ts::ts_lanes_tan(x) / std::tan(double(x)), 1.0, 4e-7) << x;
    }
}

TEST(MathLanes, ExponentialWithinThreeTenMillionths) {
    double at = 0.0;
    const auto f = [](float x) { return ts::ts_lanes_exp(x); };
    const auto g = [](double x) { return std::exp(x); };
    EXPECT_LE(worst(f, g, -87.3, 88.7, 4000000, &at), 3e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1.0, 1.0, 2000000, &at), 3e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1e-4, 1e-4, 200000, &at), 3e-7) << "at " << at;
}

TEST(MathLanes, SpecialValues) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
    EXPECT_TRUE(std::isnan(ts::ts_lanes_atan(nan)));
    EXPECT_TRUE(std::isnan(ts::ts_lanes_tan(nan)));
    EXPECT_TRUE(std::isnan(ts::ts_lanes_exp(nan)));
    EXPECT_FLOAT_EQ(ts::ts_lanes_atan(inf), 1.5707963267948966f);
    EXPECT_FLOAT_EQ(ts::ts_lanes_atan(-inf), -1.5707963267948966f);
    EXPECT_EQ(ts::ts_lanes_exp(-inf), 0.0f);
    EXPECT_EQ(ts::ts_lanes_exp(inf), inf);
    EXPECT_EQ(ts::ts_lanes_exp(89.0f), inf);
    EXPECT_EQ(ts::ts_lanes_exp(-88.0f), 0.0f);  // below 2^-126: flushed
    EXPECT_GT(ts::ts_lanes_exp(-87.3f), 0.0f);
    EXPECT_EQ(ts::ts_lanes_exp(0.0f), 1.0f);
    EXPECT_TRUE(std::isfinite(ts::ts_lanes_exp(88.72f)));
    // Signed zeros come back with their sign.
    EXPECT_TRUE(std::signbit(ts::ts_lanes_atan(-0.0f)) && ts::ts_lanes_atan(-0.0f) == 0.0f);
    EXPECT_TRUE(std::signbit(ts::ts_lanes_tan(-0.0f)) && ts::ts_lanes_tan(-0.0f) == 0.0f);
    EXPECT_FALSE(std::signbit(ts::ts_lanes_atan(0.0f)));
}

}  // namespace
}  // namespace tessera
