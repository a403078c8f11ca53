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

}  // namespace
}  // namespace tessera
