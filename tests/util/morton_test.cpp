// morton2 (host/util/morton.h): bit interleaving, and blocks of consecutive indices.
#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "util/morton.h"

namespace tessera {
namespace {

TEST(Morton2, InterleavesTheBitsWithXInTheEvenBits) {
    EXPECT_EQ(morton2(0, 0), 0u);
    EXPECT_EQ(morton2(1, 0), 1u);
    EXPECT_EQ(morton2(0, 1), 2u);
    EXPECT_EQ(morton2(3, 3), 15u);
    EXPECT_EQ(morton2(0b101, 0b010), 0b011001u);
    EXPECT_EQ(morton2(0xffff, 0), 0x55555555u);
    EXPECT_EQ(morton2(0xffff, 0xffff), 0xffffffffu);
}

// What placement relies on (instant_cache.cpp): sorted by index, each 16 consecutive
// cells of an 8×8 grid are one 4×4 block.
TEST(Morton2, SixteenConsecutiveIndicesAreAFourByFourBlock) {
    std::vector<std::pair<uint32_t, std::pair<uint32_t, uint32_t>>> cells;
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) cells.push_back({morton2(x, y), {x, y}});
    std::sort(cells.begin(), cells.end());
    for (size_t b = 0; b < cells.size(); b += 16) {
        std::set<std::pair<uint32_t, uint32_t>> blocks;
        for (size_t i = b; i < b + 16; ++i) blocks.insert({cells[i].second.first / 4, cells[i].second.second / 4});
        EXPECT_EQ(blocks.size(), 1u) << "cells " << b << ".." << b + 15;
    }
}

// Bit k of x, y, z lands at bit 3k, 3k + 1, 3k + 2, for every k of the 21, against the
// bit-by-bit definition.
TEST(Morton3, InterleavesTwentyOneBitsAnAxis) {
    for (uint32_t x : {0u, 1u, 5u, 0x155555u, 0x1fffffu, 123457u})
        for (uint32_t y : {0u, 2u, 0xaaaaau, 0x1fffffu})
            for (uint32_t z : {0u, 7u, 0x100000u, 0x1fffffu}) {
                uint64_t want = 0;
                for (int k = 0; k < 21; ++k)
                    want |= uint64_t((x >> k) & 1u) << (3 * k) | uint64_t((y >> k) & 1u) << (3 * k + 1) |
                            uint64_t((z >> k) & 1u) << (3 * k + 2);
                EXPECT_EQ(morton3(x, y, z), want) << x << " " << y << " " << z;
            }
}

}  // namespace
}  // namespace tessera
