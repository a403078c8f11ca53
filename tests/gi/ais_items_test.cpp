// The item tables of an AIS frame (host/gi/ais_items.h): the host path's, from its
// schedule, and a device frame's, built in parallel straight from the schedule kernels'
// per-pixel output, which must be the same tables word for word.
#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gi/ais_items.h"
#include "kernels/shared/layout_igi.h"

namespace tessera {
namespace {

// The serial reference layouts: each pixel's items from the list, read as the device
// resolve reads them, and each pixel's first edge sample and count.
std::vector<uint32_t> ais_pixel_items(const std::vector<uint32_t>& list, size_t pixels) {
    const size_t items = list.size() / TS_AIS_ITEM_WORDS;
    std::vector<uint32_t> t(pixels + 1 + TS_AIS_ENTRY_WORDS * items, 0u);
    for (size_t i = 0; i < items; ++i) ++t[list[TS_AIS_ITEM_WORDS * i + TS_AIS_ITEM_PIXEL] + 1];
    for (size_t p = 0; p < pixels; ++p) t[p + 1] += t[p];
    std::vector<uint32_t> next(t.begin(), t.begin() + pixels);
    // List order: grouped by set in increasing order, so each pixel's entries come out in
    // increasing set order, the order the host's merge adds them in.
    for (size_t i = 0; i < items; ++i) {
        const uint32_t p = list[TS_AIS_ITEM_WORDS * i + TS_AIS_ITEM_PIXEL];
        uint32_t* e = &t[pixels + 1 + TS_AIS_ENTRY_WORDS * size_t(next[p]++)];
        e[TS_AIS_ENTRY_ITEM] = static_cast<uint32_t>(i);
        e[TS_AIS_ENTRY_CODE] = list[TS_AIS_ITEM_WORDS * i + TS_AIS_ITEM_CODE];
    }
    return t;
}

std::vector<uint32_t> edge_pixel_samples(const EdgeSchedule& schedule) {
    std::vector<uint32_t> code(schedule.samples.size(), 0u);
    const size_t n = schedule.items.size() / TS_EDGE_ITEM_WORDS;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t* it = &schedule.items[TS_EDGE_ITEM_WORDS * i];
        if (it[TS_EDGE_ITEM_SAMPLE] == 1)
            code[it[TS_EDGE_ITEM_PIXEL]] = static_cast<uint32_t>(i) << TS_EDGE_PIXEL_FIRST_SHIFT | it[TS_EDGE_ITEM_COUNT];
    }
    return code;
}

// The items of each pixel, as the device reads them: offsets over the pixels, then each
// pixel's entries in increasing set order (the list's order), with the item's index and code.
TEST(AisPixelItems, ListEachPixelsItemsInSetOrder) {
    // Pixels 0..3; items grouped by set as make_schedule lists them: set 1 (pixels 2, 0),
    // set 4 (pixel 2), set 7 (pixels 0, 2).
    const std::vector<uint32_t> list = {2, 1 | 2u << 8, 0, 1 | 1u << 8, 2, 4 | 7u << 8, 0, 7 | 2u << 8, 2, 7 | 4u << 8};
    const std::vector<uint32_t> t = ais_pixel_items(list, 4);
    ASSERT_EQ(t.size(), 5u + TS_AIS_ENTRY_WORDS * 5u);
    EXPECT_EQ(std::vector<uint32_t>(t.begin(), t.begin() + 5), (std::vector<uint32_t>{0, 2, 2, 5, 5}));
    auto entry = [&](uint32_t k, int w) { return t[5 + TS_AIS_ENTRY_WORDS * k + w]; };
    // Pixel 0: items 1 (set 1) and 3 (set 7); pixel 2: items 0, 2, 4 (sets 1, 4, 7).
    const uint32_t items[5] = {1, 3, 0, 2, 4};
    for (uint32_t k = 0; k < 5; ++k) {
        EXPECT_EQ(entry(k, TS_AIS_ENTRY_ITEM), items[k]) << k;
        EXPECT_EQ(entry(k, TS_AIS_ENTRY_CODE), list[2 * items[k] + 1]) << k;
    }
}

TEST(AisPixelItems, EdgeSamplesCodeFirstAndCount) {
    EdgeSchedule s;
    s.samples = {0, 2, 0, 1};
    s.items = {1, 1, 2, 1, 2, 2, 3, 1, 1};
    const std::vector<uint32_t> code = edge_pixel_samples(s);
    EXPECT_EQ(code, (std::vector<uint32_t>{0u, 0u << TS_EDGE_PIXEL_FIRST_SHIFT | 2u, 0u,
                                           2u << TS_EDGE_PIXEL_FIRST_SHIFT | 1u}));
}

// Random masks as AisSchedule's kernel writes them (own set always in, flagged pixels with
// extra sets per component) against make_schedule's item order and ais_pixel_items.
void expect_tables_equal(int width, int height, int tile, uint32_t seed, uint32_t flag_one_in = 4) {
    std::mt19937 rng(seed);
    const size_t pixels = size_t(width) * height;
    const int sets = tile * tile;
    std::vector<float> masks(pixels * TS_AIS_MASK_FLOATS);
    AisSchedule s;
    for (int c = 0; c < kAisComponents; ++c) s.masks[c].resize(pixels);
    size_t flagged[kAisComponents] = {0, 0, 0};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t p = size_t(y) * width + x;
            uint32_t flags = 0;
            for (int c = 0; c < kAisComponents; ++c) {
                uint64_t mask = 1ull << interleave_set(x, y, tile);
                if (flag_one_in && rng() % flag_one_in == 0) {  // flagged: some extra sets
                    flags |= 1u << c;
                    ++flagged[c];
                    mask |= (uint64_t(rng()) << 32 | rng()) & (sets == 64 ? ~0ull : (1ull << sets) - 1);
                }
                s.masks[c][p] = mask;
                masks[p * TS_AIS_MASK_FLOATS + TS_AIS_MASK_SETS(c)] = std::bit_cast<float>(uint32_t(mask));
                masks[p * TS_AIS_MASK_FLOATS + TS_AIS_MASK_SETS(c) + 1] = std::bit_cast<float>(uint32_t(mask >> 32));
            }
            masks[p * TS_AIS_MASK_FLOATS + TS_AIS_MASK_FLAGS] = std::bit_cast<float>(flags);
        }
    schedule_items(s, width, height, tile);
    EXPECT_EQ(s.item_pixels.empty(), tile == 1 || flag_one_in == 0);
    const std::vector<uint32_t> list = ais_item_list(s);
    AisItemTables t;
    t.list.assign(3, 7u);  // stale contents from an earlier frame
    ais_item_tables(masks, width, height, tile, t);
    EXPECT_EQ(t.list, list);
    EXPECT_EQ(t.pixel_items, ais_pixel_items(list, pixels));
    for (int c = 0; c < kAisComponents; ++c) EXPECT_EQ(t.flagged[c], double(flagged[c]) / double(pixels)) << c;
}

TEST(AisItemTables, EqualTheHostScheduleTables) {
    expect_tables_equal(37, 29, 3, 1);    // tiles cut by the image border
    expect_tables_equal(64, 48, 4, 2);    // whole tiles
    expect_tables_equal(21, 40, 8, 3);    // 64 sets
    expect_tables_equal(5, 3, 2, 4);      // smaller than one tile
    expect_tables_equal(7, 40, 3, 5);     // a column of tiles narrower than one
    expect_tables_equal(20, 20, 1, 6);    // one set: flags, no items
    expect_tables_equal(33, 17, 3, 7, 0); // nothing flagged: no items, empty ranges
}

TEST(EdgeItemTables, EqualTheHostScheduleTables) {
    std::mt19937 rng(9);
    const int width = 37, height = 29;
    std::vector<float> counts(size_t(width) * height);
    EdgeSchedule s;
    for (float& n : counts) {
        n = rng() % 3 == 0 ? float(1 + rng() % 15) : 0.0f;
        s.samples.push_back(static_cast<uint8_t>(n));
    }
    edge_schedule_items(s);
    EdgeItemTables t;
    edge_item_tables(counts, width, t);
    EXPECT_EQ(t.items, s.items);
    EXPECT_EQ(t.pixel_samples, edge_pixel_samples(s));
    EXPECT_EQ(t.flagged, s.flagged);
    EXPECT_GT(t.flagged, 0.0);
}

}  // namespace
}  // namespace tessera
