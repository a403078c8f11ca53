// The PNG preview's 8-bit sRGB codes (host/image/srgb8.h): the exact curve's values, and
// the threshold search giving the same code as the curve around every step and over the
// floats of [0, 1].
#include "image/srgb8.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

namespace tessera {
namespace {

TEST(Srgb8, ExactCurveValues) {
    // round(255 · (1.055 v^(1/2.4) − 0.055)) above 0.0031308, round(255 · 12.92 v) below.
    EXPECT_EQ(srgb8_exact(0.18), 118);
    EXPECT_EQ(srgb8_exact(0.5), 188);
    EXPECT_EQ(srgb8_exact(0.0031308), 10);
    EXPECT_EQ(srgb8_exact(0.001), 3);
    EXPECT_EQ(srgb8_exact(0.9999), 255);
    EXPECT_EQ(srgb8_exact(1.0), 255);
    EXPECT_EQ(srgb8_exact(7.0), 255);
    EXPECT_EQ(srgb8_exact(0.0), 0);
    EXPECT_EQ(srgb8_exact(-1.0), 0);
    EXPECT_EQ(srgb8_exact(std::numeric_limits<double>::quiet_NaN()), 0);
}

TEST(Srgb8, SpecialValues) {
    const double inf = std::numeric_limits<double>::infinity();
    for (double v : {0.0, -0.0, -1.0, -inf, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::denorm_min(), 1.0, 2.0, inf, 0.5})
        EXPECT_EQ(srgb8(v), srgb8_exact(v)) << v;
}

// Each code's step: the 200 doubles either side of the least double with that code. A
// threshold one double off, or a search that returns k ± 1, fails here.
TEST(Srgb8, EqualsTheExactCurveAroundEveryStep) {
    size_t checked = 0;
    for (int k = 1; k <= 255; ++k) {
        // The step's place by bisection on the exact curve, as srgb8 finds it.
        std::uint64_t lo = std::bit_cast<std::uint64_t>(0.0), hi = std::bit_cast<std::uint64_t>(1.0);
        while (hi - lo > 1) {
            const std::uint64_t mid = lo + (hi - lo) / 2;
            (srgb8_exact(std::bit_cast<double>(mid)) >= k ? hi : lo) = mid;
        }
        for (std::uint64_t b = hi - 200; b <= hi + 200; ++b) {
            const double v = std::bit_cast<double>(b);
            ASSERT_EQ(srgb8(v), srgb8_exact(v)) << "code " << k << ", v = " << v;
            ++checked;
        }
        EXPECT_EQ(srgb8(std::bit_cast<double>(hi)), k);
        EXPECT_EQ(srgb8(std::bit_cast<double>(hi - 1)), k - 1);
    }
    EXPECT_EQ(checked, 255u * 401u);
}

// Floats (the images' values) spread over [0, 1] by bit pattern, every 97th: ~11M values,
// each code met many times. Exhaustive over all floats of [0, 1] (1.07e9, one run,
// 2026-12-02): no difference.
TEST(Srgb8, EqualsTheExactCurveOnFloats) {
    const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);
    size_t differ = 0;
    for (std::uint32_t b = 0; b <= one; b += 97) {
        const double v = static_cast<double>(std::bit_cast<float>(b));
        differ += srgb8(v) != srgb8_exact(v);
    }
    EXPECT_EQ(differ, 0u);
}

}  // namespace
}  // namespace tessera
