// A device AIS frame's compact tables (kernels/shared/ais_compact.h) as C++, over frames of
// every shape that matters: smaller than a tile, one pixel wide or tall, cut by tile
// borders, tiles 1 (one set: no extra items) to 8 (64 sets: masks past bit 31), nothing to
// everything flagged. The items decoded from the tiles' bits and prefix sums are the host
// list's (schedule_items) item for item, each pixel finds its own there, and the edge
// samples are the host's (edge_schedule_items), each pixel's consecutive from its first.
// The same code as OpenCL C runs in tests/kernels/ais_guidance_test.cpp (the tables) and
// ais_resolve_test.cpp (whole frames).
#include <array>
#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "backend/embree_tracer.h"
#include "gi/ais_edges.h"
#include "gi/ais_items.h"
#include "gi/ais_schedule.h"
#include "kernels/shared/ais_compact.h"
#include "support/ais_compact_checks.h"

namespace tessera {
namespace {

struct Shape {
    int width, height;
};

// Random set masks: each component flags a pixel with probability 1/one_in (0: never) and
// then holds random sets beside the pixel's own.
std::vector<float> random_masks(const Shape& s, int tile, std::mt19937& rng, int one_in, AisSchedule& host) {
    const size_t pixels = size_t(s.width) * s.height;
    const int sets = tile * tile;
    const uint64_t all = sets == 64 ? ~0ull : (1ull << sets) - 1;
    std::vector<float> m(pixels * TS_AIS_MASK_FLOATS, 0.0f);
    for (auto& k : host.masks) k.assign(pixels, 0);
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const size_t p = size_t(y) * s.width + x;
            uint32_t flags = 0;
            for (int c = 0; c < kAisComponents; ++c) {
                uint64_t mask = 1ull << interleave_set(x, y, tile);
                if (one_in && rng() % one_in == 0) {
                    flags |= 1u << c;
                    mask |= (uint64_t(rng()) << 32 | rng()) & all;
                }
                host.masks[c][p] = mask;
                m[p * TS_AIS_MASK_FLOATS + TS_AIS_MASK_SETS(c)] = std::bit_cast<float>(uint32_t(mask));
                m[p * TS_AIS_MASK_FLOATS + TS_AIS_MASK_SETS(c) + 1] = std::bit_cast<float>(uint32_t(mask >> 32));
            }
            m[p * TS_AIS_MASK_FLOATS + TS_AIS_MASK_FLAGS] = std::bit_cast<float>(flags);
        }
    return m;
}

void expect_items_equal(const Shape& s, int tile, std::mt19937& rng, int one_in) {
    AisSchedule host;
    const std::vector<float> masks = random_masks(s, tile, rng, one_in, host);
    schedule_items(host, s.width, s.height, tile);
    TsFrame f{};
    f.width = uint32_t(s.width), f.height = uint32_t(s.height), f.igi_tile = uint32_t(tile);
    ts::TsSceneView sv{};
    sv.ais_masks = masks.data();
    const size_t sets = size_t(tile) * tile, tiles = ais_tile_count(f.width, f.height);
    ASSERT_EQ(tiles, ts::ts_ais_tile_count(&f));
    std::vector<float> tile_sets(sets * tiles * TS_AIS_TILE_SET_FLOATS);
    for (uint32_t j = 0; j < sets * tiles; ++j)
        ts::ts_ais_tile_sets_item(&sv, nullptr, &f, j, &tile_sets[size_t(j) * TS_AIS_TILE_SET_FLOATS]);
    AisItemOffsets offsets;
    ais_item_offsets(tile_sets, sets, tiles, size_t(s.width) * s.height, offsets);
    test::expect_items_decode_as(f, masks, tile_sets, offsets, host);
}

void expect_edges_equal(const Shape& s, std::mt19937& rng, int one_in) {
    EdgeSchedule host;
    std::vector<float> counts(size_t(s.width) * s.height, 0.0f);
    for (float& n : counts) {
        if (one_in && rng() % one_in == 0) n = float(1 + rng() % 15);
        host.samples.push_back(uint8_t(n));
    }
    edge_schedule_items(host);
    TsFrame f{};
    f.width = uint32_t(s.width), f.height = uint32_t(s.height), f.igi_tile = 3;
    ts::TsSceneView sv{};
    sv.edge_counts = counts.data();
    const size_t segments = ais_tile_count(f.width, f.height) * TS_AIS_TILE;
    ASSERT_EQ(segments, ts::ts_edge_segment_count(&f));
    std::vector<float> segment_counts(segments * TS_EDGE_SEGMENT_FLOATS);
    for (uint32_t s = 0; s < segments; ++s)
        ts::ts_edge_segment_counts_item(&sv, nullptr, &f, s, &segment_counts[size_t(s) * TS_EDGE_SEGMENT_FLOATS]);
    EdgeSegmentOffsets offsets;
    edge_segment_offsets(segment_counts, counts.size(), offsets);
    test::expect_edges_decode_as(f, counts, offsets, host);
}

const Shape kShapes[] = {{37, 29}, {64, 48}, {21, 40}, {5, 3}, {7, 40}, {16, 16}, {17, 17}, {100, 3}, {1, 1}};

TEST(AisCompact, ItemsAreTheHostListsForEveryShapeTileAndRate) {
    std::mt19937 rng(1);
    for (const Shape& s : kShapes)
        for (int tile : {1, 2, 3, 4, 5, 8})
            for (int one_in : {0, 1, 2, 4, 50}) {
                SCOPED_TRACE(::testing::Message() << s.width << "x" << s.height << " tile " << tile << " 1/" << one_in);
                expect_items_equal(s, tile, rng, one_in);
            }
}

TEST(AisCompact, EdgeSamplesAreTheHostsForEveryShapeAndRate) {
    std::mt19937 rng(2);
    for (const Shape& s : kShapes)
        for (int one_in : {0, 1, 3, 50}) {
            SCOPED_TRACE(::testing::Message() << s.width << "x" << s.height << " 1/" << one_in);
            expect_edges_equal(s, rng, one_in);
        }
}

// The run that holds item i, empty runs at either end and between included.
TEST(AisCompact, RunOfSkipsEmptyRuns) {
    const uint32_t offsets[] = {0, 0, 0, 2, 2, 5, 5};  // runs 2 (items 0-1) and 4 (items 2-4)
    const uint32_t expected[] = {2, 2, 4, 4, 4};
    for (uint32_t i = 0; i < 5; ++i) EXPECT_EQ(ts::ts_ais_run_of(offsets, 6, i), expected[i]) << i;
}

}  // namespace
}  // namespace tessera
