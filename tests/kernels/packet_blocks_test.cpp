// The packet-block enumeration of kernels/shared/geometry.h (ts_packet_block_count,
// ts_packet_block, ts_packet_block_pixel), compiled as C++: the Embree and OpenCL packet
// dispatches cover every pixel exactly once with it, each block holding pixels of one
// sample set only, so every pixel's output is written once and by its own set.
#include <vector>

#include <gtest/gtest.h>

#include "kernels/shared/geometry.h"

namespace tessera {
namespace {

struct Size {
    uint32_t width, height, tile;
};

class PacketBlocks : public ::testing::TestWithParam<Size> {};

TEST_P(PacketBlocks, CoverEveryPixelOnceWithOneSetPerBlock) {
    TsFrame f{};
    f.width = GetParam().width;
    f.height = GetParam().height;
    f.igi_tile = GetParam().tile;
    const uint32_t n = f.igi_tile > 1 ? f.igi_tile : 1;
    std::vector<int> covered(size_t(f.width) * f.height, 0);
    const uint32_t blocks = ts::ts_packet_block_count(&f);
    uint32_t prev_set = 0;
    for (uint32_t b = 0; b < blocks; ++b) {
        uint32_t k, bx, by;
        ASSERT_TRUE(ts::ts_packet_block(&f, b, &k, &bx, &by)) << "block " << b;
        EXPECT_GE(k, prev_set) << "blocks come set by set";
        prev_set = k;
        int lanes = 0;
        for (uint32_t lane = 0; lane < 16; ++lane) {
            uint32_t px, py;
            if (!ts::ts_packet_block_pixel(&f, k, bx, by, lane, &px, &py)) continue;
            ++lanes;
            ASSERT_LT(px, f.width);
            ASSERT_LT(py, f.height);
            EXPECT_EQ(px % n + n * (py % n), k) << "pixel (" << px << ", " << py << ") in set " << k;
            ++covered[size_t(py) * f.width + px];
        }
        EXPECT_GT(lanes, 0) << "block " << b << " is empty";
    }
    uint32_t k, bx, by;
    EXPECT_FALSE(ts::ts_packet_block(&f, blocks, &k, &bx, &by));
    for (size_t i = 0; i < covered.size(); ++i) ASSERT_EQ(covered[i], 1) << "pixel " << i;
}

// Sizes that are and are not multiples of the tile and of the 4×4 block (37×29 at n = 3:
// sets of 13×10, 12×10, 13×9 ... pixels), one row, no interleaving (n = 1 and n = 0).
INSTANTIATE_TEST_SUITE_P(Sizes, PacketBlocks,
                         ::testing::Values(Size{37, 29, 3}, Size{48, 24, 3}, Size{1, 1, 3}, Size{17, 1, 4},
                                           Size{40, 32, 1}, Size{9, 7, 0}, Size{64, 64, 8}));

}  // namespace
}  // namespace tessera
