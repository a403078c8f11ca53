#include "gi/ais_items.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/shared/layout_igi.h"

namespace tessera {
namespace {

template <class F>
void parallel_range(size_t n, F&& f) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) f(i);
    });
}

uint32_t word(const float* m, int i) { return std::bit_cast<uint32_t>(m[i]); }

uint64_t mask_of(const float* m, int c) {
    return uint64_t(word(m, TS_AIS_MASK_SETS(c) + 1)) << 32 | word(m, TS_AIS_MASK_SETS(c));
}

// The sets pixel (x, y) evaluates beyond its own, over all components.
uint64_t extra_sets(const float* m, int x, int y, int tile) {
    const uint64_t all = mask_of(m, kAisSS) | mask_of(m, kAisID) | mask_of(m, kAisPM);
    return all & ~(1ull << interleave_set(x, y, tile));
}

// The item code of set k for the pixel with masks m: k | the components evaluating it << 8.
uint32_t item_code(const float* m, int k) {
    uint32_t bits = 0;
    for (int c = 0; c < kAisComponents; ++c)
        if (mask_of(m, c) >> k & 1) bits |= 1u << c;
    return uint32_t(k) | bits << 8;
}

// Exclusive prefix sums of `counts` into `offsets` (one more entry: the total).
void prefix(const std::vector<uint32_t>& counts, std::vector<uint32_t>& offsets) {
    offsets.resize(counts.size() + 1);
    uint64_t sum = 0;
    for (size_t i = 0; i < counts.size(); ++i) {
        offsets[i] = static_cast<uint32_t>(sum);
        sum += counts[i];
    }
    if (sum > UINT32_MAX) throw std::length_error("AIS item tables: " + std::to_string(sum) + " entries");
    offsets[counts.size()] = static_cast<uint32_t>(sum);
}

}  // namespace

std::vector<uint32_t> ais_item_list(const AisSchedule& s) {
    std::vector<uint32_t> list(TS_AIS_ITEM_WORDS * s.item_pixels.size());
    for (size_t i = 0; i < s.item_pixels.size(); ++i) {
        list[TS_AIS_ITEM_WORDS * i + TS_AIS_ITEM_PIXEL] = s.item_pixels[i];
        list[TS_AIS_ITEM_WORDS * i + TS_AIS_ITEM_CODE] = s.item_sets[i] | uint32_t(s.item_components[i]) << 8;
    }
    return list;
}

// Three passes: counts per (tile, set) and per row, their prefix sums (the list's order is
// set, then tile, then pixel; the pixel table's is row-major), then each tile writes its
// items and each pixel's entries where the sums put them. Every count is an integer, so
// the tables do not depend on the order the tiles run in.
void ais_item_tables(const std::vector<float>& masks, int width, int height, int tile, AisItemTables& out) {
    const int sets = tile * tile, edge = int(kItemTile);
    const size_t tiles_x = size_t(width + edge - 1) / edge, tiles = tiles_x * size_t((height + edge - 1) / edge);
    const size_t pixels = size_t(width) * height;
    const float* m = masks.data();
    auto at = [&](int x, int y) { return m + (size_t(y) * width + x) * TS_AIS_MASK_FLOATS; };
    // Items per (set, tile), set-major as the list orders them; flags per tile.
    std::vector<uint32_t> count(size_t(sets) * tiles, 0u);
    std::vector<std::array<uint32_t, kAisComponents>> flags(tiles);
    auto for_tile = [&](size_t t, auto&& f) {
        const int x0 = int(t % tiles_x) * edge, y0 = int(t / tiles_x) * edge;
        for (int y = y0; y < std::min(height, y0 + edge); ++y)
            for (int x = x0; x < std::min(width, x0 + edge); ++x) f(x, y);
    };
    parallel_range(tiles, [&](size_t t) {
        std::array<uint32_t, kAisComponents> f{};
        for_tile(t, [&](int x, int y) {
            for (uint64_t e = extra_sets(at(x, y), x, y, tile); e; e &= e - 1) ++count[size_t(std::countr_zero(e)) * tiles + t];
            const uint32_t bits = word(at(x, y), TS_AIS_MASK_FLAGS);
            for (int c = 0; c < kAisComponents; ++c) f[c] += bits >> c & 1u;
        });
        flags[t] = f;
    });
    std::vector<uint32_t> row_count(size_t(height), 0u), item_offset, row_offset;
    parallel_range(size_t(height), [&](size_t y) {
        uint32_t n = 0;
        for (int x = 0; x < width; ++x) n += std::popcount(extra_sets(at(x, int(y)), x, int(y), tile));
        row_count[y] = n;
    });
    prefix(count, item_offset);
    prefix(row_count, row_offset);
    const size_t items = item_offset.back();
    out.list.resize(TS_AIS_ITEM_WORDS * items);
    out.pixel_items.resize(pixels + 1 + TS_AIS_ENTRY_WORDS * items);
    uint32_t* pixel_offset = out.pixel_items.data();
    parallel_range(size_t(height), [&](size_t y) {
        uint32_t o = row_offset[y];
        for (int x = 0; x < width; ++x) {
            pixel_offset[y * width + x] = o;
            o += std::popcount(extra_sets(at(x, int(y)), x, int(y), tile));
        }
    });
    pixel_offset[pixels] = static_cast<uint32_t>(items);
    uint32_t* entries = out.pixel_items.data() + pixels + 1;
    parallel_range(tiles, [&](size_t t) {
        std::vector<uint32_t> next(static_cast<size_t>(sets));
        for (int k = 0; k < sets; ++k) next[k] = item_offset[size_t(k) * tiles + t];
        for_tile(t, [&](int x, int y) {
            const size_t p = size_t(y) * width + x;
            uint32_t e = pixel_offset[p];
            for (uint64_t s = extra_sets(at(x, y), x, y, tile); s; s &= s - 1) {
                const int k = std::countr_zero(s);
                const uint32_t i = next[k]++, code = item_code(at(x, y), k);
                out.list[TS_AIS_ITEM_WORDS * size_t(i) + TS_AIS_ITEM_PIXEL] = static_cast<uint32_t>(p);
                out.list[TS_AIS_ITEM_WORDS * size_t(i) + TS_AIS_ITEM_CODE] = code;
                entries[TS_AIS_ENTRY_WORDS * size_t(e) + TS_AIS_ENTRY_ITEM] = i;
                entries[TS_AIS_ENTRY_WORDS * size_t(e) + TS_AIS_ENTRY_CODE] = code;
                ++e;
            }
        });
    });
    for (int c = 0; c < kAisComponents; ++c) {
        size_t flagged = 0;
        for (const auto& f : flags) flagged += f[c];
        out.flagged[c] = pixels ? double(flagged) / double(pixels) : 0.0;
    }
}

void edge_item_tables(const std::vector<float>& counts, int width, EdgeItemTables& out) {
    const size_t pixels = counts.size(), height = width > 0 ? pixels / size_t(width) : 0;
    std::vector<uint32_t> row_count(height, 0u), row_offset, row_flagged(height, 0u);
    parallel_range(height, [&](size_t y) {
        for (int x = 0; x < width; ++x) {
            const uint32_t n = static_cast<uint32_t>(counts[y * width + x]);
            row_count[y] += n;
            row_flagged[y] += n > 0;
        }
    });
    prefix(row_count, row_offset);
    const size_t samples = row_offset.back();
    if (samples >> (32 - TS_EDGE_PIXEL_FIRST_SHIFT))
        throw std::length_error("edge_item_tables: " + std::to_string(samples) + " edge samples do not fit the pixel codes");
    out.items.resize(TS_EDGE_ITEM_WORDS * samples);
    out.pixel_samples.resize(pixels);
    parallel_range(height, [&](size_t y) {
        uint32_t i = row_offset[y];
        for (int x = 0; x < width; ++x) {
            const size_t p = y * width + x;
            const uint32_t n = static_cast<uint32_t>(counts[p]);
            out.pixel_samples[p] = n ? i << TS_EDGE_PIXEL_FIRST_SHIFT | n : 0u;
            for (uint32_t j = 1; j <= n; ++j, ++i) {
                uint32_t* it = &out.items[TS_EDGE_ITEM_WORDS * size_t(i)];
                it[TS_EDGE_ITEM_PIXEL] = static_cast<uint32_t>(p);
                it[TS_EDGE_ITEM_SAMPLE] = j;
                it[TS_EDGE_ITEM_COUNT] = n;
            }
        }
    });
    size_t flagged = 0;
    for (uint32_t f : row_flagged) flagged += f;
    out.flagged = pixels ? double(flagged) / double(pixels) : 0.0;
}

}  // namespace tessera
