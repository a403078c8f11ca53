// device/texture_mips: level counts, the chain's layout and its linear-light box filter.
#include "device/texture_mips.h"

#include <stdexcept>

#include <gtest/gtest.h>

#include "kernels/shared/srgb_table.h"

namespace tessera {
namespace {

uint32_t grey(uint32_t c, uint32_t alpha = 255) { return c | c << 8 | c << 16 | alpha << 24; }

TEST(TextureMips, LevelCountHalvesDownToOneTexel) {
    EXPECT_EQ(mip_level_count(1, 1), 1u);
    EXPECT_EQ(mip_level_count(2, 1), 2u);
    EXPECT_EQ(mip_level_count(256, 256), 9u);
    EXPECT_EQ(mip_level_count(5, 3), 3u);    // 5×3, 2×1, 1×1
    EXPECT_EQ(mip_level_count(1, 300), 9u);  // 300, 150, 75, 37, 18, 9, 4, 2, 1
}

TEST(TextureMips, EncodeInvertsTheDecodeTable) {
    for (uint32_t c = 0; c < 256; ++c) EXPECT_EQ(encode_srgb8(ts::ts_srgb_table[c]), c) << c;
    EXPECT_EQ(encode_srgb8(-1.0f), 0u);
    EXPECT_EQ(encode_srgb8(2.0f), 255u);
    // Linear 0.5 lies between codes 187 and 188; 188 decodes nearer.
    EXPECT_EQ(encode_srgb8(0.5f), 188u);
}

TEST(TextureMips, FlatTextureStaysBitForBitFlat) {
    const std::vector<uint32_t> flat(6 * 5, grey(77, 200));
    const std::vector<uint32_t> chain = build_mip_chain(flat, 6, 5);
    ASSERT_EQ(chain.size(), 6u * 5 + 3 * 2 + 1 * 1);  // 6×5, 3×2, 1×1
    for (uint32_t t : chain) EXPECT_EQ(t, grey(77, 200));
}

TEST(TextureMips, CheckerAveragesInLinearLight) {
    // A one-texel black/white checker, 4×4: level 1 is the linear mean 0.5 everywhere
    // (not the sRGB mean 128, which decodes to 0.216), and so is level 2.
    std::vector<uint32_t> checker(16);
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x) checker[y * 4 + x] = (x + y) % 2 ? grey(255) : grey(0);
    const std::vector<uint32_t> chain = build_mip_chain(checker, 4, 4);
    ASSERT_EQ(chain.size(), 16u + 4 + 1);
    for (size_t i = 0; i < 16; ++i) EXPECT_EQ(chain[i], checker[i]);  // level 0 is the input
    for (size_t i = 16; i < chain.size(); ++i) EXPECT_EQ(chain[i], grey(188)) << i;
}

TEST(TextureMips, OddSizesDropTheLastColumnAndRepeatSingleTexels) {
    // 3×1: level 1 (1×1) averages texels 0 and 1 (twice each: the one row repeats);
    // texel 2 is dropped.
    const std::vector<uint32_t> row = {grey(0), grey(255), grey(255)};
    const std::vector<uint32_t> chain = build_mip_chain(row, 3, 1);
    ASSERT_EQ(chain.size(), 4u);
    EXPECT_EQ(chain[3], grey(188));
}

TEST(TextureMips, RejectsSizeMismatch) {
    EXPECT_THROW(build_mip_chain(std::vector<uint32_t>(5), 2, 2), std::invalid_argument);
    EXPECT_THROW(build_mip_chain({}, 0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace tessera
