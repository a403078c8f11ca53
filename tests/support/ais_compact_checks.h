// Checks of a device AIS frame's compact tables (kernels/shared/ais_compact.h), shared by
// the tests that build them as C++ (tests/kernels/ais_compact_test.cpp) and on a backend
// (ais_guidance_test.cpp): the items decoded from the tables are the host's list item for
// item and each pixel finds its own there; the edge samples decoded are the host's, each
// pixel's consecutive from its first.
#pragma once
#include <array>
#include <cstdint>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "backend/embree_tracer.h"
#include "gi/ais_edges.h"
#include "gi/ais_items.h"
#include "gi/ais_schedule.h"
#include "kernels/shared/ais_compact.h"

namespace tessera::test {

/// `masks` (TS_AIS_MASK_FLOATS a pixel of frame f), `tile_sets` (KernelId::AisTileSets's
/// output) and `offsets` (their prefix sums) decoded item by item against `host`'s list.
inline void expect_items_decode_as(const TsFrame& f, const std::vector<float>& masks,
                                   const std::vector<float>& tile_sets, const AisItemOffsets& offsets,
                                   const AisSchedule& host) {
    ASSERT_EQ(offsets.items(), host.item_pixels.size());
    ts::TsSceneView sv{};
    sv.ais_masks = masks.data();
    sv.ais_tile_sets = tile_sets.data();
    sv.ais_item_offsets = offsets.offsets.data();
    for (uint32_t i = 0; i < offsets.items(); ++i) {
        uint32_t x, y, k, mask;
        ts::ts_ais_compact_decode(&sv, &f, i, &x, &y, &k, &mask);
        ASSERT_EQ(y * f.width + x, host.item_pixels[i]) << "item " << i;
        ASSERT_EQ(k, host.item_sets[i]) << "item " << i;
        ASSERT_EQ(mask, host.item_components[i]) << "item " << i;
        ASSERT_EQ(ts::ts_ais_compact_index(&sv, &f, x, y, k), i) << "item " << i;
    }
}

/// `counts` (one float a pixel of frame f) and `offsets` (KernelId::EdgeSegmentCounts's
/// prefix sums) decoded sample by sample against `host`'s items, with its flagged fraction.
inline void expect_edges_decode_as(const TsFrame& f, const std::vector<float>& counts,
                                   const EdgeSegmentOffsets& offsets, const EdgeSchedule& host) {
    ASSERT_EQ(offsets.samples(), host.items.size() / TS_EDGE_ITEM_WORDS);
    EXPECT_EQ(offsets.flagged, host.flagged);
    ts::TsSceneView sv{};
    sv.edge_counts = counts.data();
    sv.edge_segment_offsets = offsets.offsets.data();
    std::set<std::array<uint32_t, 3>> decoded, listed;
    for (uint32_t i = 0; i < offsets.samples(); ++i) {
        uint32_t p, j, n;
        ts::ts_edge_compact_decode(&sv, &f, i, &p, &j, &n);
        ASSERT_EQ(ts::ts_edge_compact_first(&sv, &f, p % f.width, p / f.width) + j - 1, i) << "sample " << i;
        decoded.insert({p, j, n});
    }
    for (size_t i = 0; i < host.items.size(); i += TS_EDGE_ITEM_WORDS)
        listed.insert({host.items[i + TS_EDGE_ITEM_PIXEL], host.items[i + TS_EDGE_ITEM_SAMPLE],
                       host.items[i + TS_EDGE_ITEM_COUNT]});
    EXPECT_EQ(decoded, listed);
}

}  // namespace tessera::test
