// The item tables an AIS frame sends its kernels. The host path sends its AisSchedule's
// list (ais_item_list; KernelId::AisItem) and EdgeSchedule's items (KernelId::EdgeSample).
// A device frame lists nothing: its kernels count the pixels of each 16 × 16 tile that
// evaluate each extra set (KernelId::AisTileSets) and the edge samples of each tile row
// (EdgeSegmentCounts), the host reads the counts back and uploads their prefix sums
// (ais_item_offsets, edge_segment_offsets), and the extra sets' and edge samples' kernels
// find their pixels from those (kernels/shared/ais_compact.h; docs/ray-batches.md §5).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "gi/ais_schedule.h"
#include "kernels/shared/layout_igi.h"

namespace tessera {

static_assert(kItemTile == TS_AIS_TILE, "the device's compact tables keep the host list's order");

/// The order the host path dispatches s's items in, a permutation of 0 .. items − 1 (entry
/// j: the schedule's item dispatched j-th): s's sets in s's order and, within a set, first
/// the items that gather VPLs (TS_COMPONENT_ID), then the others, each group in s's order.
/// Why: a packet backend traces 16 consecutive items together and loops over all of the
/// set's VPLs when any of the 16 gathers ID, so an SS- or PM-only item among ID items costs
/// a masked lane in every VPL packet. Images do not change: each item is computed alone, and
/// the merge adds a pixel's items in s's order (docs/ais.md §2).
std::vector<uint32_t> ais_dispatch_order(const AisSchedule& s);

/// s's item list in dispatch order: entry j holds item order[j], TS_AIS_ITEM_WORDS words
/// (layout_igi.h).
std::vector<uint32_t> ais_item_list(const AisSchedule& s, const std::vector<uint32_t>& order);

/// T, the TS_AIS_TILE² pixel tiles of a width × height frame (rows of tiles).
size_t ais_tile_count(uint32_t width, uint32_t height);

/// A device frame's extra-set offsets (named input AisItemOffsets, layout_igi.h).
struct AisItemOffsets {
    std::vector<uint32_t> offsets;                 ///< n²·T + 1 words; the last: the item count
    std::array<double, kAisComponents> flagged{};  ///< fraction of pixels each component flags
    size_t items() const { return offsets.empty() ? 0 : offsets.back(); }
};

/// From `tile_sets` (TS_AIS_TILE_SET_FLOATS per work item t·sets + k, k < `sets` = n²,
/// t < `tiles`: KernelId::AisTileSets's output) the counts' exclusive prefix sums in the
/// item list's order, j = k·T + t, and the flagged fractions over `pixels`, reusing out's
/// capacity. Throws std::length_error past 2^32 items.
void ais_item_offsets(const std::vector<float>& tile_sets, size_t sets, size_t tiles, size_t pixels,
                      AisItemOffsets& out);

/// A device frame's edge-sample offsets (named input EdgeSegmentOffsets, layout_igi.h).
struct EdgeSegmentOffsets {
    std::vector<uint32_t> offsets;  ///< T·TS_AIS_TILE + 1 words; the last: the sample count
    double flagged = 0;             ///< fraction of pixels with samples
    size_t samples() const { return offsets.empty() ? 0 : offsets.back(); }
};

/// From `segment_counts` (TS_EDGE_SEGMENT_FLOATS per segment, a tile's row:
/// KernelId::EdgeSegmentCounts's output) the samples' exclusive prefix sums and the
/// flagged fraction over `pixels`, reusing out's capacity. Throws std::length_error past
/// 2^32 samples.
void edge_segment_offsets(const std::vector<float>& segment_counts, size_t pixels, EdgeSegmentOffsets& out);

}  // namespace tessera
