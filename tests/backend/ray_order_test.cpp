// The sort order of incoherent ray batches (host/backend/ray_order.h): the key's layout
// by hand, its handling of non-finite rays, and the radix sort against std::stable_sort.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "backend/ray_order.h"
#include "kernels/shared/layout_rays.h"

namespace tessera {
namespace {

const float kLo[3] = {-1.0f, 0.0f, 2.0f}, kHi[3] = {1.0f, 4.0f, 10.0f};

std::vector<float> ray(float ox, float oy, float oz, float dx, float dy, float dz) {
    return {ox, oy, oz, 0.0f, dx, dy, dz, INFINITY};
}

// 30 bits: octant << 27 | origin Morton (2^4 cells per axis) << 15 | direction Morton
// (2^5 cells per axis on the cube [-1, 1]³). Values worked out by hand.
TEST(RaySortKey, IsOctantThenOriginCellThenDirectionCell) {
    const RayKeyGrid g(kLo, kHi);
    // At the box's low corner, along +x: origin cell (0, 0, 0); direction (1, 0, 0) on
    // the cube is cell (31, 16, 16): spread 31 = 0x1249, 16 = 0x1000, shifted 0, 1, 2.
    EXPECT_EQ(ray_sort_key(ray(-1, 0, 2, 3, 0, 0).data(), g), 0x1249u | 0x2000u | 0x4000u);
    // At the high corner: origin cell (15, 15, 15), every one of its 12 bits set.
    EXPECT_EQ(ray_sort_key(ray(1, 4, 10, 3, 0, 0).data(), g) >> 15 & 0xfffu, 0xfffu);
    // Octant bits: x < 0 is bit 27, y < 0 bit 28, z < 0 bit 29.
    EXPECT_EQ(ray_sort_key(ray(0, 1, 5, -1, 2, 3).data(), g) >> 27, 1u);
    EXPECT_EQ(ray_sort_key(ray(0, 1, 5, 1, -2, -3).data(), g) >> 27, 6u);
    // Only the direction's shape counts: d and 7·d share a key.
    EXPECT_EQ(ray_sort_key(ray(0.3f, 1, 5, 1, -2, 0.5f).data(), g),
              ray_sort_key(ray(0.3f, 1, 5, 7, -14, 3.5f).data(), g));
    // Origins outside the box take its edge cells: x = 5 is cell 15, like x = 1.
    EXPECT_EQ(ray_sort_key(ray(5, 1, 5, 1, 1, 1).data(), g), ray_sort_key(ray(1, 1, 5, 1, 1, 1).data(), g));
}

TEST(RaySortKey, NonFiniteRaysGetAValidKey) {
    const RayKeyGrid g(kLo, kHi);
    // NaN everywhere: no comparison holds, every cell is 0, the octant 0.
    EXPECT_EQ(ray_sort_key(ray(NAN, NAN, NAN, NAN, NAN, NAN).data(), g), 0u);
    // A zero direction divides by zero (0 · inf = NaN): cell 0 on every axis.
    EXPECT_EQ(ray_sort_key(ray(-1, 0, 2, 0, 0, 0).data(), g), 0u);
    // Infinite origin components clamp to the edge cells: x cell 15 (spread: 0x249), y
    // and z (below the box) cell 0.
    EXPECT_EQ(ray_sort_key(ray(INFINITY, -INFINITY, 0, 1, 0, 0).data(), g) >> 15 & 0xfffu, 0x249u);
}

// ray_sort_key is ray_sort_keys of one ray: this checks that the lanes of a block (and of a
// partial last block) do not leak into one another.
TEST(RaySortKey, BlockAndSingleKeysAgree) {
    const RayKeyGrid g(kLo, kHi);
    std::mt19937 rng(3);
    std::normal_distribution<float> n(0.0f, 3.0f);
    std::vector<float> rays;
    for (int i = 0; i < 37; ++i) {  // two full blocks of 16 and a partial one
        const std::vector<float> r = ray(n(rng), n(rng), n(rng), n(rng), n(rng), n(rng));
        rays.insert(rays.end(), r.begin(), r.end());
    }
    std::vector<uint32_t> keys(37);
    ray_sort_keys(rays.data(), 37, g, keys.data());
    for (int i = 0; i < 37; ++i) EXPECT_EQ(keys[i], ray_sort_key(&rays[TS_RAY_FLOATS * i], g)) << "ray " << i;
}

// The radix sort equals a stable comparison sort by key, on a batch large enough for
// five chunks of the parallel passes, with many equal keys (coarse origins, few
// directions) so that stability is tested.
TEST(CoherentRayOrder, IsTheStableSortByKey) {
    const RayKeyGrid g(kLo, kHi);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-2.0f, 12.0f);
    std::uniform_int_distribution<int> dir(0, 5);
    const size_t n = 50001;
    std::vector<float> rays;
    for (size_t i = 0; i < n; ++i) {
        const float d[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {1, 1, 1}, {-1, -1, 1}};
        const int k = dir(rng);
        const std::vector<float> r = ray(u(rng), u(rng), u(rng), d[k][0], d[k][1], d[k][2]);
        rays.insert(rays.end(), r.begin(), r.end());
    }
    // Five threads' worth of chunks whatever the machine's cores, so the passes' prefix
    // sums run across chunks (a one-core machine would otherwise sort in one chunk).
    std::vector<uint32_t> order;
    tbb::task_arena(5).execute([&] { order = coherent_ray_order(rays.data(), n, g); });
    std::vector<uint32_t> expected(n);
    std::iota(expected.begin(), expected.end(), 0u);
    std::stable_sort(expected.begin(), expected.end(), [&](uint32_t a, uint32_t b) {
        return ray_sort_key(&rays[TS_RAY_FLOATS * a], g) < ray_sort_key(&rays[TS_RAY_FLOATS * b], g);
    });
    EXPECT_EQ(order, expected);
    // Not vacuous: the input was far from sorted.
    size_t in_place = 0;
    for (size_t j = 0; j < n; ++j) in_place += order[j] == j;
    EXPECT_LT(in_place, n / 100);
}

TEST(CoherentRayOrder, EmptyAndSingleBatches) {
    const RayKeyGrid g(kLo, kHi);
    EXPECT_TRUE(coherent_ray_order(nullptr, 0, g).empty());
    const std::vector<float> r = ray(0, 1, 5, 1, 0, 0);
    EXPECT_EQ(coherent_ray_order(r.data(), 1, g), std::vector<uint32_t>{0u});
}

}  // namespace
}  // namespace tessera
