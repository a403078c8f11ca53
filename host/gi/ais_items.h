// The item tables an AIS frame sends its kernels: the extra sets' list (KernelId::AisItem)
// and each pixel's items (named input AisPixelItems), the edge samples' list
// (KernelId::EdgeSample) and each pixel's samples (EdgePixelSamples). The host path builds
// them from its AisSchedule and EdgeSchedule; a device frame builds them straight from the
// schedule kernels' per-pixel output (KernelId::AisSchedule, EdgeSchedule), over tiles and
// rows in parallel, into buffers kept across frames: the same tables, word for word.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "gi/ais_edges.h"
#include "gi/ais_schedule.h"

namespace tessera {

/// s's item list, TS_AIS_ITEM_WORDS per item (layout_igi.h), in s's item order.
std::vector<uint32_t> ais_item_list(const AisSchedule& s);

/// The device frame's items per pixel (named input AisPixelItems, layout_igi.h TS_AIS_ENTRY_*)
/// from the AIS item list `list` (TS_AIS_ITEM_WORDS per item) of a `pixels`-pixel frame.
std::vector<uint32_t> ais_pixel_items(const std::vector<uint32_t>& list, size_t pixels);

/// Each pixel's first edge sample and count (named input EdgePixelSamples, TS_EDGE_PIXEL_*).
/// Throws std::length_error past 2^28 samples (the code's first-index bits).
std::vector<uint32_t> edge_pixel_samples(const EdgeSchedule& schedule);

/// A device frame's AIS tables.
struct AisItemTables {
    std::vector<uint32_t> list;         ///< ais_item_list's
    std::vector<uint32_t> pixel_items;  ///< ais_pixel_items's
    std::array<double, kAisComponents> flagged{};  ///< fraction of pixels each component flags
};

/// From `masks` (TS_AIS_MASK_FLOATS per pixel of a width × height frame, tile edge `tile`:
/// KernelId::AisSchedule's output) the tables that ais_item_list and ais_pixel_items give
/// for the schedule with those masks (schedule_items' order), reusing out's capacity.
void ais_item_tables(const std::vector<float>& masks, int width, int height, int tile, AisItemTables& out);

/// A device frame's edge tables.
struct EdgeItemTables {
    std::vector<uint32_t> items;          ///< EdgeSchedule::items of edge_schedule_items
    std::vector<uint32_t> pixel_samples;  ///< edge_pixel_samples's
    double flagged = 0;                   ///< fraction of pixels with samples
};

/// From `counts` (one float a pixel of a `width`-pixel-wide frame: KernelId::EdgeSchedule's
/// output) the tables that edge_schedule_items and edge_pixel_samples give for those
/// counts, reusing out's capacity. Throws std::length_error as edge_pixel_samples does.
void edge_item_tables(const std::vector<float>& counts, int width, EdgeItemTables& out);

}  // namespace tessera
