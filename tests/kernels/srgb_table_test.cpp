// kernels/shared/srgb_table.h: every entry is the sRGB decode (IEC 61966-2-1) of c/255
// computed in double and rounded once to float, and ts_srgb_to_linear reads it.
#include <cmath>

#include <gtest/gtest.h>

#include "kernels/shared/material.h"

namespace tessera {
namespace {

double srgb_decode(int c8) {
    const double c = c8 / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST(SrgbTable, EveryEntryIsTheCorrectlyRoundedCurve) {
    for (int c = 0; c < 256; ++c) {
        EXPECT_EQ(ts::ts_srgb_table[c], static_cast<float>(srgb_decode(c))) << "entry " << c;
        EXPECT_EQ(ts::ts_srgb_to_linear(static_cast<uint32_t>(c)), ts::ts_srgb_table[c]);
    }
}

TEST(SrgbTable, EndsAndKnownValues) {
    EXPECT_EQ(ts::ts_srgb_to_linear(0u), 0.0f);
    EXPECT_EQ(ts::ts_srgb_to_linear(255u), 1.0f);
    EXPECT_NEAR(ts::ts_srgb_to_linear(128u), 0.2158605, 1e-7);  // the familiar mid-grey
    EXPECT_NEAR(ts::ts_srgb_to_linear(10u), 10.0 / 255.0 / 12.92, 1e-9);  // linear segment
    for (int c = 1; c < 256; ++c) EXPECT_GT(ts::ts_srgb_table[c], ts::ts_srgb_table[c - 1]) << c;
}

}  // namespace
}  // namespace tessera
