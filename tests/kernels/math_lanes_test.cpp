// kernels/shared/math_lanes.h: the lanes' arctangent, tangent and exponential against
// double precision over dense sweeps of their domains (every float where the arctangent's
// error peaks), within the bounds the header states (2.1e-7, 1.7e-7, 8.2e-8 measured; a
// few float ulps, as Cephes' own figures), and their special values and range ends.
#include <algorithm>
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

TEST(MathLanes, ArctangentWithinTwoPointOneTenMillionths) {
    double at = 0.0;
    const auto f = [](float x) { return ts::ts_lanes_atan(x); };
    const auto g = [](double x) { return std::atan(x); };
    EXPECT_LE(worst(f, g, -4.0, 4.0, 2000000, &at), 2.1e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1e6, 1e6, 2000000, &at), 2.1e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1e-3, 1e-3, 200000, &at), 2.1e-7) << "at " << at;
    // Every float of [0.40, 0.45], where the error peaks (2.08e-7 at 0.427967).
    double peak = 0.0;
    for (float x = 0.40f; x <= 0.45f; x = std::nextafter(x, 1.0f)) {
        const double want = std::atan(double(x));
        peak = std::max(peak, std::fabs(ts::ts_lanes_atan(x) - want) / want);
    }
    EXPECT_LE(peak, 2.1e-7);
    EXPECT_GT(peak, 1.9e-7);  // the sweep reached the peak
    // Every power of two: tiny and huge arguments.
    for (int e = -126; e <= 127; ++e) {
        const float x = std::ldexp(1.0f, e);
        EXPECT_NEAR(ts::ts_lanes_atan(x) / std::atan(double(x)), 1.0, 2.1e-7) << "2^" << e;
        EXPECT_NEAR(ts::ts_lanes_atan(-x) / std::atan(-double(x)), 1.0, 2.1e-7) << "-2^" << e;
    }
}

TEST(MathLanes, TangentWithinTwoTenMillionthsBelowAQuarterTurn) {
    double at = 0.0;
    const auto f = [](float x) { return ts::ts_lanes_tan(x); };
    const auto g = [](double x) { return std::tan(x); };
    const double h = 1.5707963267948966;
    EXPECT_LE(worst(f, g, -h + 1e-6, h - 1e-6, 4000000, &at), 2e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1e-3, 1e-3, 200000, &at), 2e-7) << "at " << at;
    // The floats nearest the quarter turn, from below: tan is ~1e7 there and still right.
    float x = float(h);
    for (int i = 0; i < 64; ++i) {
        x = std::nextafter(x, 0.0f);
        EXPECT_NEAR(ts::ts_lanes_tan(x) / std::tan(double(x)), 1.0, 2e-7) << x;
    }
}

TEST(MathLanes, ExponentialWithinOneTenMillionth) {
    double at = 0.0;
    const auto f = [](float x) { return ts::ts_lanes_exp(x); };
    const auto g = [](double x) { return std::exp(x); };
    EXPECT_LE(worst(f, g, -87.3, 88.7, 4000000, &at), 1e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1.0, 1.0, 2000000, &at), 1e-7) << "at " << at;
    EXPECT_LE(worst(f, g, -1e-4, 1e-4, 200000, &at), 1e-7) << "at " << at;
    // The range's ends, a float apart: the largest finite result and the first Inf (as
    // libm), the smallest normal result and the first flushed one.
    EXPECT_TRUE(std::isfinite(ts::ts_lanes_exp(88.7228317f)));
    EXPECT_NEAR(ts::ts_lanes_exp(88.7228317f) / std::exp(88.7228317), 1.0, 1e-7);
    EXPECT_EQ(ts::ts_lanes_exp(88.7228394f), std::numeric_limits<float>::infinity());
    EXPECT_NEAR(ts::ts_lanes_exp(-87.3365402f) / std::exp(-87.3365402), 1.0, 1e-7);
    EXPECT_GE(ts::ts_lanes_exp(-87.3365402f), std::numeric_limits<float>::min());
    EXPECT_EQ(ts::ts_lanes_exp(-87.3365479f), 0.0f);
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
