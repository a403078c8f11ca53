// A device AIS frame's host part (host/gi/ais_items.h): the tile counts' prefix
// sums in the list's order and the flagged fractions, from kernel outputs laid
// out as KernelId::AisTileSets and EdgeSegmentCounts write them (layout_igi.h).
// The kernels' own counts and the items decoded from these sums:
// tests/kernels/ais_guidance_test.cpp.
#include "gi/ais_items.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace tessera {
namespace {

TEST(AisItemOffsets, PrefixSumsInSetThenTileOrderFromTileMajorCounts) {
    // Two sets of three tiles; counts[k][t] stored tile-major (t·2 + k) as the kernel writes
    // them, summed set-major (k·3 + t) as the list runs.
    const float counts[2][3] = {{2, 0, 5}, {1, 3, 0}}, flags[3][3] = {{4, 1, 0}, {0, 0, 2}, {1, 1, 1}};
    std::vector<float> tile_sets(6 * TS_AIS_TILE_SET_FLOATS, 0.0f);
    for (int t = 0; t < 3; ++t)
        for (int k = 0; k < 2; ++k) {
            float* e = &tile_sets[(t * 2 + k) * TS_AIS_TILE_SET_FLOATS];
            e[TS_AIS_TILE_SET_COUNT] = counts[k][t];
            // Only set 0's entries carry flags; anything in set 1's must not count.
            for (int c = 0; c < 3; ++c) e[TS_AIS_TILE_SET_FLAGS + c] = k == 0 ? flags[t][c] : 99.0f;
        }
    AisItemOffsets out;
    ais_item_offsets(tile_sets, 2, 3, 20, out);
    EXPECT_EQ(out.offsets, (std::vector<uint32_t>{0, 2, 2, 7, 8, 11, 11}));
    EXPECT_EQ(out.items(), 11u);
    EXPECT_DOUBLE_EQ(out.flagged[0], 5.0 / 20);
    EXPECT_DOUBLE_EQ(out.flagged[1], 2.0 / 20);
    EXPECT_DOUBLE_EQ(out.flagged[2], 3.0 / 20);
}

TEST(AisItemOffsets, RefusePastTheUint32Range) {
    std::vector<float> tile_sets(2 * TS_AIS_TILE_SET_FLOATS, 0.0f);
    tile_sets[TS_AIS_TILE_SET_COUNT] = 4e9f;
    tile_sets[TS_AIS_TILE_SET_FLOATS + TS_AIS_TILE_SET_COUNT] = 4e9f;
    AisItemOffsets out;
    EXPECT_THROW(ais_item_offsets(tile_sets, 1, 2, 1, out), std::length_error);
}

TEST(AisItemOffsets, RefuseOutputOfAnotherShape) {
    AisItemOffsets out;
    EXPECT_THROW(ais_item_offsets(std::vector<float>(5 * TS_AIS_TILE_SET_FLOATS), 2, 3, 1, out), std::logic_error);
}

TEST(EdgeSegmentOffsets, PrefixSumsOverSegmentsAndFlaggedFraction) {
    const std::vector<float> tiles = {3, 2, 0, 0, 7, 4};
    EdgeSegmentOffsets out;
    edge_segment_offsets(tiles, 12, out);
    EXPECT_EQ(out.offsets, (std::vector<uint32_t>{0, 3, 3, 10}));
    EXPECT_EQ(out.samples(), 10u);
    EXPECT_DOUBLE_EQ(out.flagged, 6.0 / 12);
}

TEST(AisDispatchOrder, SetsInOrderIdItemsFirstEachGroupInScheduleOrder) {
    // Items of sets 0, 0, 0, 0, 2, 2, 5: set 0's ID-bearing items (1, 3) go first, then its
    // SS- and PM-only ones (0, 2); set 2 has no ID item; set 5 only one.
    AisSchedule s;
    s.item_pixels = {10, 11, 12, 13, 14, 15, 16};
    s.item_sets = {0, 0, 0, 0, 2, 2, 5};
    const uint8_t ss = TS_COMPONENT_SS, id = TS_COMPONENT_ID, pm = TS_COMPONENT_PM;
    s.item_components = {ss, uint8_t(id | ss), pm, id, ss, pm, id};
    const std::vector<uint32_t> order = ais_dispatch_order(s);
    EXPECT_EQ(order, (std::vector<uint32_t>{1, 3, 0, 2, 4, 5, 6}));
    const std::vector<uint32_t> list = ais_item_list(s, order);
    ASSERT_EQ(list.size(), TS_AIS_ITEM_WORDS * order.size());
    for (size_t j = 0; j < order.size(); ++j) {
        EXPECT_EQ(list[TS_AIS_ITEM_WORDS * j + TS_AIS_ITEM_PIXEL], s.item_pixels[order[j]]) << j;
        EXPECT_EQ(list[TS_AIS_ITEM_WORDS * j + TS_AIS_ITEM_CODE],
                  s.item_sets[order[j]] | uint32_t(s.item_components[order[j]]) << 8)
            << j;
    }
    EXPECT_TRUE(ais_dispatch_order(AisSchedule{}).empty());
}

TEST(AisTileCount, RowsOfSixteenPixelTiles) {
    EXPECT_EQ(ais_tile_count(16, 16), 1u);
    EXPECT_EQ(ais_tile_count(17, 16), 2u);
    EXPECT_EQ(ais_tile_count(41, 33), 9u);
    EXPECT_EQ(ais_tile_count(512, 512), 1024u);
}

}  // namespace
}  // namespace tessera
