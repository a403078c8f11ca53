// The item tables an AIS frame sends its kernels: the extra sets' list (KernelId::AisItem)
// and each pixel's items (named input AisPixelItems), the edge samples' list
// (KernelId::EdgeSample) and each pixel's samples (EdgePixelSamples). The host path sends
// its AisSchedule's list (ais_item_list) and EdgeSchedule's items; a device frame builds
// the tables straight from the schedule kernels' per-pixel output (KernelId::AisSchedule,
// EdgeSchedule), over tiles and rows in parallel, into buffers kept across frames
// (tests/gi/ais_items_test.cpp checks them against serial layouts of the host's lists).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "gi/ais_edges.h"
#include "gi/ais_schedule.h"

namespace tessera {

/// s's item list, TS_AIS_ITEM_WORDS per item (layout_igi.h), in s's item order.
std::vector<uint32_t> ais_item_list(const AisSchedule& s);

/// A device frame's AIS tables.
struct AisItemTables {
    std::vector<uint32_t> list;         ///< ais_item_list's
    /// Each pixel's items (named input AisPixelItems, layout_igi.h TS_AIS_ENTRY_*): words
    /// 0..P offsets, then each pixel's entries (item index, code) in increasing set order.
    std::vector<uint32_t> pixel_items;
    std::array<double, kAisComponents> flagged{};  ///< fraction of pixels each component flags
};

/// From `masks` (TS_AIS_MASK_FLOATS per pixel of a width × height frame, tile edge `tile`:
/// KernelId::AisSchedule's output) the tables of the schedule with those masks:
/// ais_item_list's list (schedule_items' order) and each pixel's entries, reusing out's
/// capacity. Throws std::length_error past 2^32 entries.
void ais_item_tables(const std::vector<float>& masks, int width, int height, int tile, AisItemTables& out);

/// A device frame's edge tables.
struct EdgeItemTables {
    std::vector<uint32_t> items;          ///< EdgeSchedule::items of edge_schedule_items
    /// Each pixel's first sample << TS_EDGE_PIXEL_FIRST_SHIFT | its count (named input
    /// EdgePixelSamples; 0: none).
    std::vector<uint32_t> pixel_samples;
    double flagged = 0;                   ///< fraction of pixels with samples
};

/// From `counts` (one float a pixel of a `width`-pixel-wide frame: KernelId::EdgeSchedule's
/// output) the tables of those counts (edge_schedule_items' items), reusing out's capacity.
/// Throws std::length_error past 2^28 samples (the pixel codes' first-index bits).
void edge_item_tables(const std::vector<float>& counts, int width, EdgeItemTables& out);

}  // namespace tessera
