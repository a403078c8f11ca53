#include "gi/ais_items.h"

#include <stdexcept>
#include <string>

namespace tessera {
namespace {

// Exclusive prefix sums of count(0..n-1) into `offsets` (one more entry: the total). The
// counts are the kernels' integers below 2^24, exact as floats.
template <class Count>
void prefix(size_t n, Count count, const char* what, std::vector<uint32_t>& offsets) {
    offsets.resize(n + 1);
    uint64_t sum = 0;
    for (size_t i = 0; i < n; ++i) {
        offsets[i] = static_cast<uint32_t>(sum);
        sum += static_cast<uint64_t>(count(i));
    }
    if (sum > UINT32_MAX) throw std::length_error(std::string(what) + ": " + std::to_string(sum) + " entries");
    offsets[n] = static_cast<uint32_t>(sum);
}

}  // namespace

std::vector<uint32_t> ais_dispatch_order(const AisSchedule& s) {
    const size_t n = s.item_pixels.size();
    std::vector<uint32_t> order;
    order.reserve(n);
    for (size_t begin = 0; begin < n;) {  // one set's run of items
        size_t end = begin;
        while (end < n && s.item_sets[end] == s.item_sets[begin]) ++end;
        for (int id_pass = 1; id_pass >= 0; --id_pass)
            for (size_t i = begin; i < end; ++i)
                if (((s.item_components[i] & TS_COMPONENT_ID) != 0) == (id_pass == 1))
                    order.push_back(static_cast<uint32_t>(i));
        begin = end;
    }
    return order;
}

std::vector<uint32_t> ais_item_list(const AisSchedule& s, const std::vector<uint32_t>& order) {
    std::vector<uint32_t> list(TS_AIS_ITEM_WORDS * order.size());
    for (size_t j = 0; j < order.size(); ++j) {
        const uint32_t i = order[j];
        list[TS_AIS_ITEM_WORDS * j + TS_AIS_ITEM_PIXEL] = s.item_pixels[i];
        list[TS_AIS_ITEM_WORDS * j + TS_AIS_ITEM_CODE] = s.item_sets[i] | uint32_t(s.item_components[i]) << 8;
    }
    return list;
}

size_t ais_tile_count(uint32_t width, uint32_t height) {
    return size_t((width + TS_AIS_TILE - 1) / TS_AIS_TILE) * ((height + TS_AIS_TILE - 1) / TS_AIS_TILE);
}

void ais_item_offsets(const std::vector<float>& tile_sets, size_t sets, size_t tiles, size_t pixels,
                      AisItemOffsets& out) {
    if (tile_sets.size() != sets * tiles * TS_AIS_TILE_SET_FLOATS)
        throw std::logic_error("ais_item_offsets: " + std::to_string(tile_sets.size()) + " floats for " +
                               std::to_string(sets) + " sets of " + std::to_string(tiles) + " tiles");
    auto at = [&](size_t k, size_t t) { return &tile_sets[(t * sets + k) * TS_AIS_TILE_SET_FLOATS]; };
    // The list's order is set-major (j = k·T + t); the kernel's output is tile-major.
    prefix(sets * tiles, [&](size_t j) { return at(j / tiles, j % tiles)[TS_AIS_TILE_SET_COUNT]; }, "AIS items",
           out.offsets);
    // Set 0's entries carry the tile's flags.
    for (int c = 0; c < kAisComponents; ++c) {
        double flagged = 0.0;
        for (size_t t = 0; t < tiles; ++t) flagged += at(0, t)[TS_AIS_TILE_SET_FLAGS + c];
        out.flagged[c] = pixels ? flagged / double(pixels) : 0.0;
    }
}

void edge_segment_offsets(const std::vector<float>& segment_counts, size_t pixels, EdgeSegmentOffsets& out) {
    const size_t segments = segment_counts.size() / TS_EDGE_SEGMENT_FLOATS;
    prefix(segments, [&](size_t s) { return segment_counts[s * TS_EDGE_SEGMENT_FLOATS + TS_EDGE_SEGMENT_SAMPLES]; },
           "edge samples", out.offsets);
    double flagged = 0.0;
    for (size_t s = 0; s < segments; ++s) flagged += segment_counts[s * TS_EDGE_SEGMENT_FLOATS + TS_EDGE_SEGMENT_FLAGGED];
    out.flagged = pixels ? flagged / double(pixels) : 0.0;
}

}  // namespace tessera
