// Accumulator (host/render/accumulator.h): whole passes and radiance-only passes
// (TS_PASS_RADIANCE_FLOATS a pixel, IgiSettings::pass_aovs false) add the same radiance and
// variance sums bit for bit; a pass of any other size is refused.
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "kernels/shared/layout_pass.h"
#include "render/accumulator.h"

namespace tessera {
namespace {

constexpr int kWidth = 5, kHeight = 3;
constexpr size_t kPixels = size_t(kWidth) * kHeight;

// Pass `i`'s whole image: radiance values that do not add exactly in float, AOVs, and
// every third pixel a miss (depth +inf).
std::vector<float> whole_pass(int i) {
    std::vector<float> pass(kPixels * TS_PASS_FLOATS);
    for (size_t p = 0; p < kPixels; ++p) {
        float* o = &pass[p * TS_PASS_FLOATS];
        for (int c = 0; c < 3; ++c) o[TS_PASS_RADIANCE + c] = 0.1f * float(p + 1) + 0.37f * float(i * (c + 1));
        for (int c = 0; c < 6; ++c) o[TS_PASS_ALBEDO + c] = 0.25f * float(c);
        o[TS_PASS_DEPTH] = p % 3 == 0 ? std::numeric_limits<float>::infinity() : 2.0f + float(p);
    }
    return pass;
}

std::vector<float> radiance_of(const std::vector<float>& whole) {
    std::vector<float> r(kPixels * TS_PASS_RADIANCE_FLOATS);
    for (size_t p = 0; p < kPixels; ++p)
        for (int c = 0; c < TS_PASS_RADIANCE_FLOATS; ++c) r[p * 3 + c] = whole[p * TS_PASS_FLOATS + TS_PASS_RADIANCE + c];
    return r;
}

TEST(Accumulator, RadianceOnlyPassesAddTheSameRadianceAndVariance) {
    Accumulator whole(kWidth, kHeight), radiance(kWidth, kHeight);
    for (int i = 0; i < 4; ++i) {
        whole.add(whole_pass(i));
        radiance.add(radiance_of(whole_pass(i)));
    }
    EXPECT_EQ(radiance.passes(), 4u);
    const Image a = whole.mean_image(false, true), b = radiance.mean_image(false, true);
    ASSERT_EQ(a.channels.size(), 6u);
    ASSERT_EQ(b.channels.size(), a.channels.size());
    for (size_t c = 0; c < a.channels.size(); ++c) {
        EXPECT_EQ(a.channels[c].name, b.channels[c].name);
        EXPECT_EQ(std::memcmp(a.channels[c].data.data(), b.channels[c].data.data(), kPixels * sizeof(float)), 0)
            << a.channels[c].name;
    }
    double variance = 0.0;  // non-zero: the comparison above is not of zeros
    for (float v : a.find("variance.G")->data) variance += v;
    EXPECT_GT(variance, 0.0);
    // The radiance-only passes left the AOV sums and hit counts as they were.
    for (size_t p = 0; p < kPixels; ++p) EXPECT_EQ(radiance.hit_counts()[p], 0u);
    EXPECT_EQ(radiance.sums()[TS_PASS_ALBEDO + 1], 0.0);
    EXPECT_EQ(whole.hit_counts()[1], 4u);
}

TEST(Accumulator, RefusesAPassOfAnotherSize) {
    Accumulator acc(kWidth, kHeight);
    EXPECT_THROW(acc.add(std::vector<float>(kPixels * TS_PASS_FLOATS - 1)), std::invalid_argument);
    EXPECT_THROW(acc.add(std::vector<float>(kPixels * TS_PASS_RADIANCE_FLOATS + 3)), std::invalid_argument);
    EXPECT_THROW(acc.add({}), std::invalid_argument);
    EXPECT_EQ(acc.passes(), 0u);
}

}  // namespace
}  // namespace tessera
