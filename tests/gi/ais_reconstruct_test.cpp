// AIS reconstruction: own sets plus the accepted neighbours' other sets, each set once.
#include "gi/ais_reconstruct.h"

#include <gtest/gtest.h>

#include "gi/ais_schedule.h"

namespace tessera {
namespace {

constexpr int W = 12, H = 9, N = 9;
const DiscontinuitySettings kFilter{3, 0.9f, 0.05f};

// A wall at depth 2 with a step to depth 2.6 from x = 7 (the filter rejects across it).
GeometryBuffer stepped_wall() {
    GeometryBuffer g;
    g.width = W;
    g.height = H;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            g.normal.insert(g.normal.end(), {0.0f, 0.0f, 1.0f});
            g.depth.push_back(x < 7 ? 2.0f : 2.6f);
        }
    return g;
}

// Distinct base values per pixel and channel.
std::vector<float> base_values() {
    std::vector<float> v(3 * W * H);
    for (size_t i = 0; i < v.size(); ++i) v[i] = 0.1f + float((i * 29) % 17) / 16.0f;
    return v;
}

std::vector<uint64_t> own_masks() {
    std::vector<uint64_t> m(W * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) m[y * W + x] = 1ull << interleave_set(x, y, 3);
    return m;
}

TEST(AisReconstruct, OwnSetOnlyIsTheDiscontinuityFilterBitForBit) {
    const GeometryBuffer g = stepped_wall();
    const std::vector<float> base = base_values();
    std::vector<float> filtered, got;
    discontinuity_filter(g, kFilter, 3, base, filtered);
    ais_reconstruct(g, kFilter, base, std::vector<double>(base.begin(), base.end()), own_masks(), got);
    EXPECT_EQ(got, filtered);
}

TEST(AisReconstruct, AllSetsIsTheOwnMeanAndTheMissingSetsCompleteAnEdgePixel) {
    const GeometryBuffer g = stepped_wall();
    const std::vector<float> base = base_values();
    std::vector<double> own_sum(base.begin(), base.end());
    std::vector<uint64_t> masks = own_masks();
    // (2,2): all 9 sets, own sum 4.5 per channel -> 0.5 exactly, no neighbour enters.
    const size_t full = 2 * W + 2;
    masks[full] = 0x1ff;
    for (int j = 0; j < 3; ++j) own_sum[3 * full + j] = 4.5;
    // (6,4): own set 3 plus the missing sets {1, 4, 7} of the rejected column 7; the
    // accepted neighbours (5,3) (6,3) (5,4) (5,5) (6,5) hold sets 2, 0, 5, 8, 6.
    const size_t edge = 4 * W + 6;
    masks[edge] = (1u << 3) | (1u << 1) | (1u << 4) | (1u << 7);
    for (int j = 0; j < 3; ++j) own_sum[3 * edge + j] = 2.0;
    std::vector<float> got;
    ais_reconstruct(g, kFilter, base, own_sum, masks, got);
    for (int j = 0; j < 3; ++j) {
        EXPECT_EQ(got[3 * full + j], 0.5f);
        double sum = 2.0;
        for (auto [x, y] : {std::pair{5, 3}, {6, 3}, {5, 4}, {5, 5}, {6, 5}}) sum += base[3 * (y * W + x) + j];
        EXPECT_EQ(got[3 * edge + j], static_cast<float>(sum / N)) << "every set once";
    }
    // A neighbour's reconstruction reads (6,4)'s base value, not its refined sum: (5,4)
    // is unrefined and equals the plain filter.
    std::vector<float> filtered;
    discontinuity_filter(g, kFilter, 3, base, filtered);
    EXPECT_EQ(got[3 * (4 * W + 5)], filtered[3 * (4 * W + 5)]);
}

}  // namespace
}  // namespace tessera
