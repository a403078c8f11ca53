// The discontinuity buffer leaves constant images alone and never averages across a
// depth or normal edge.
#include "gi/discontinuity_filter.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "kernels/shared/discontinuity.h"

namespace tessera {
namespace {

// w × h pixels; left half: a plane facing +z at depth 2, right half set by the caller.
GeometryBuffer two_regions(int w, int h, float right_depth, float right_nz) {
    GeometryBuffer g;
    g.width = w;
    g.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool right = x >= w / 2;
            const float nz = right ? right_nz : 1.0f, nx = std::sqrt(std::max(0.0f, 1.0f - nz * nz));
            g.normal.insert(g.normal.end(), {nx, 0.0f, nz});
            g.depth.push_back(right ? right_depth : 2.0f);
        }
    return g;
}

TEST(DiscontinuityFilter, ConstantImageIsUnchanged) {
    for (int n : {2, 3, 4, 5}) {
        GeometryBuffer g = two_regions(12, 9, 2.0f, 1.0f);
        std::vector<float> in(12 * 9 * 3, 0.625f), out;
        std::vector<uint8_t> accepted;
        discontinuity_filter(g, DiscontinuitySettings{n, 0.9f, 0.05f}, 3, in, out, &accepted);
        for (float v : out) ASSERT_EQ(v, 0.625f);
        EXPECT_EQ(accepted[5 * 12 + 5], n * n);  // an interior pixel sees a full window
    }
}

TEST(DiscontinuityFilter, RemovesInterleavingNoiseWithinASurface) {
    // A value that depends only on the set (x mod 3, y mod 3): every full 3×3 window
    // holds each set once, so interior pixels come out at the mean of the sets.
    GeometryBuffer g = two_regions(12, 12, 2.0f, 1.0f);
    std::vector<float> in(12 * 12), out;
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 12; ++x) in[y * 12 + x] = float((x % 3) + 3 * (y % 3));
    discontinuity_filter(g, DiscontinuitySettings{3, 0.9f, 0.05f}, 1, in, out);
    for (int y = 1; y < 11; ++y)
        for (int x = 1; x < 11; ++x) ASSERT_FLOAT_EQ(out[y * 12 + x], 4.0f);
}

// The border too: a window that would cross the image's edge is moved inward
// (ts_discontinuity_lo_at), so the border rows, columns and corners average every set as
// the interior does. A window clipped by the image averaged 6 of 9 sets there (4 at a
// corner): 3.5 at (0, 0) against 4 here, which left a frame's border rows bright or dark
// (docs/igi.md §8). Tiles 2 to 8 on an image no tile divides, with precomputed masks and
// without; an image narrower than the tile keeps the window the image clips.
TEST(DiscontinuityFilter, ABorderPixelsWindowHoldsEverySet) {
    for (int n : {2, 3, 4, 5, 8}) {
        for (bool precomputed : {false, true}) {
            SCOPED_TRACE(testing::Message() << "tile " << n << (precomputed ? ", precomputed masks" : ""));
            const int w = 23, h = 17;
            GeometryBuffer g = two_regions(w, h, 2.0f, 1.0f);
            const DiscontinuitySettings s{n, 0.9f, 0.05f};
            if (precomputed) discontinuity_precompute(g, s);
            std::vector<float> in(size_t(w) * h), out;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) in[size_t(y) * w + x] = float((x % n) + n * (y % n));
            std::vector<uint8_t> count;
            discontinuity_filter(g, s, 1, in, out, &count);
            const float mean = float(n * n - 1) / 2.0f;  // of the sets 0 .. n² − 1
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    ASSERT_FLOAT_EQ(out[size_t(y) * w + x], mean) << x << "," << y;
                    ASSERT_EQ(count[size_t(y) * w + x], n * n) << x << "," << y;
                }
        }
    }
    // 2 pixels wide, tile 3: each pixel's window is the image's 2 columns by 3 rows.
    GeometryBuffer g = two_regions(2, 6, 2.0f, 1.0f);
    std::vector<float> in(12), out;
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 2; ++x) in[size_t(y) * 2 + x] = float(x + 3 * (y % 3));
    std::vector<uint8_t> count;
    discontinuity_filter(g, DiscontinuitySettings{3, 0.9f, 0.05f}, 1, in, out, &count);
    for (int p = 0; p < 12; ++p) {
        EXPECT_FLOAT_EQ(out[p], 3.5f) << p;  // sets 0, 1, 3, 4, 6, 7
        EXPECT_EQ(count[p], 6) << p;
    }
}

void expect_no_mixing(float right_depth, float right_nz) {
    GeometryBuffer g = two_regions(10, 6, right_depth, right_nz);
    std::vector<float> in, out;
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 10; ++x) in.push_back(x < 5 ? 1.0f : 100.0f);
    discontinuity_filter(g, DiscontinuitySettings{3, 0.9f, 0.05f}, 1, in, out);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 10; ++x) ASSERT_EQ(out[y * 10 + x], x < 5 ? 1.0f : 100.0f) << x << "," << y;
}

TEST(DiscontinuityFilter, NeverMixesAcrossADepthEdge) { expect_no_mixing(2.2f, 1.0f); }      // 10% deeper
TEST(DiscontinuityFilter, NeverMixesAcrossANormalEdge) { expect_no_mixing(2.0f, 0.7f); }     // 45° crease
TEST(DiscontinuityFilter, NeverMixesSurfaceWithBackground) { expect_no_mixing(INFINITY, 1.0f); }

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// A plane seen at a steep slant: depth grows 20% from one column to the next, far past
// the 5% threshold, yet every point lies on one plane; with positions the filter must
// treat it as one surface. A second plane parallel to it, 0.5 deeper, must stay apart.
GeometryBuffer slanted(int w, int h, bool second_plane) {
    GeometryBuffer g;
    g.width = w;
    g.height = h;
    const float n[3] = {0.8f, 0.0f, 0.6f};  // unit normal of the plane 0.8 x + 0.6 z = d
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float d = second_plane && x >= w / 2 ? 3.5f : 3.0f;
            const float px = 0.5f * x, pz = (d - 0.8f * px) / 0.6f;
            g.position.insert(g.position.end(), {px, 0.1f * y, pz});
            g.normal.insert(g.normal.end(), {n[0], n[1], n[2]});
            g.depth.push_back(2.0f * (1.0f + 0.2f * x));  // the camera distance: steep growth
        }
    return g;
}

TEST(DiscontinuityFilter, PlaneAtASlantIsOneSurface) {
    GeometryBuffer g = slanted(9, 6, false);
    std::vector<float> in, out;
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 9; ++x) in.push_back(float(x % 3));
    std::vector<uint8_t> accepted;
    discontinuity_filter(g, DiscontinuitySettings{3, 0.9f, 0.05f}, 1, in, out, &accepted);
    EXPECT_EQ(accepted[2 * 9 + 4], 9) << "every neighbour lies on the plane";
    EXPECT_FLOAT_EQ(out[2 * 9 + 4], 1.0f);
    g.position.clear();  // the depth test alone calls every column an edge
    discontinuity_filter(g, DiscontinuitySettings{3, 0.9f, 0.05f}, 1, in, out, &accepted);
    EXPECT_EQ(accepted[2 * 9 + 4], 3);
}

TEST(DiscontinuityFilter, ParallelPlanesAtDifferentDepthsStayApart) {
    GeometryBuffer g = slanted(10, 6, true);
    std::vector<float> in, out;
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 10; ++x) in.push_back(x < 5 ? 1.0f : 100.0f);
    discontinuity_filter(g, DiscontinuitySettings{3, 0.9f, 0.05f}, 1, in, out);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 10; ++x) ASSERT_EQ(out[y * 10 + x], x < 5 ? 1.0f : 100.0f) << x << "," << y;
}

// Random geometry: depths from a few levels (some +inf: escaped rays), normals from a
// few directions, positions jittered around a plane, so that about half the pairs pass.
GeometryBuffer random_geometry(int w, int h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> pick(0, 3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const float depths[4] = {2.0f, 2.05f, 3.0f, INFINITY};
    const float nzs[4] = {1.0f, 0.95f, 0.8f, 0.0f};
    GeometryBuffer g;
    g.width = w;
    g.height = h;
    for (int i = 0; i < w * h; ++i) {
        const float nz = nzs[pick(rng)], nx = std::sqrt(1.0f - nz * nz);
        g.normal.insert(g.normal.end(), {nx, 0.0f, nz});
        g.depth.push_back(depths[pick(rng)]);
        g.position.insert(g.position.end(), {float(i % w) * 0.01f, float(i / w) * 0.01f, 0.05f * u(rng)});
    }
    return g;
}

// The masks precomputed once per frame (row by row, one window offset at a time) hold
// exactly the pairwise tests, with positions (plane distances) and without (depths), and
// the filter reading them gives the same bits and counts as the filter testing each pair.
TEST(DiscontinuityFilter, PrecomputedMasksMatchThePairwiseTest) {
    for (int n : {1, 2, 3, 4, 5, 8}) {
        for (bool positions : {true, false}) {
            SCOPED_TRACE(testing::Message() << "tile " << n << (positions ? ", plane test" : ", depth test"));
            const DiscontinuitySettings s{n, 0.9f, 0.05f};
            GeometryBuffer g = random_geometry(23, 17, 11u + n);
            if (!positions) g.position.clear();
            std::vector<float> in(23 * 17 * 3);
            std::mt19937 rng(5);
            for (float& v : in) v = std::uniform_real_distribution<float>(0.0f, 10.0f)(rng);
            std::vector<float> tested, masked;
            std::vector<uint8_t> count_tested, count_masked;
            discontinuity_filter(g, s, 3, in, tested, &count_tested);
            discontinuity_precompute(g, s);
            discontinuity_filter(g, s, 3, in, masked, &count_masked);
            ASSERT_EQ(std::memcmp(tested.data(), masked.data(), tested.size() * 4), 0);
            EXPECT_EQ(count_tested, count_masked);
            size_t accepted = 0, pairs = 0;
            for (int y = 0; y < 17; ++y)
                for (int x = 0; x < 23; ++x) {
                    const uint64_t m = g.accepted[size_t(y) * 23 + x];
                    // The window's first position, moved in at the border.
                    const int lx = ts::ts_discontinuity_lo_at(x, 23, n), ly = ts::ts_discontinuity_lo_at(y, 17, n);
                    for (int i = 0; i < n * n; ++i) {
                        const int qx = x + lx + i % n, qy = y + ly + i / n;
                        const bool inside = qx >= 0 && qy >= 0 && qx < 23 && qy < 17;
                        const size_t p = size_t(y) * 23 + x, q = size_t(qy) * 23 + qx;
                        const bool want = inside && (p == q || discontinuity_accepts(g, s, p, q));
                        ASSERT_EQ(bool(m >> i & 1), want) << x << "," << y << " position " << i;
                        pairs += inside && p != q;
                        accepted += want && p != q;
                    }
                }
            if (n > 1) {
                EXPECT_GT(accepted, pairs / 20) << "the geometry should pass some tests";
                EXPECT_LT(accepted, pairs * 9 / 10) << "... and fail others";
            }
            // Masks made for other settings are not used.
            const DiscontinuitySettings looser{n, 0.0f, 1.0f};
            EXPECT_EQ(discontinuity_window_mask(g, looser, 11, 8), [&] {
                GeometryBuffer fresh = g;
                fresh.accepted.clear();
                return discontinuity_window_mask(fresh, looser, 11, 8);
            }());
        }
    }
}

// The host filter takes four pixels' window sums at once where their windows lie inside
// the image, and ts_discontinuity_mean (the device resolve's) pixel by pixel elsewhere. On
// random geometry and values (a tenth of them 1000, so a position summed that should not
// be shows), 1 and 3 channels, with precomputed masks and without, both give the same
// floats bit for bit as the per-pixel mean.
TEST(DiscontinuityFilter, FourPixelSumsEqualThePerPixelMean) {
    for (int n : {2, 3, 4, 8}) {
        for (int channels : {1, 3}) {
            for (bool precomputed : {false, true}) {
                SCOPED_TRACE(testing::Message() << "tile " << n << ", " << channels << " channels"
                                                << (precomputed ? ", precomputed masks" : ""));
                const DiscontinuitySettings s{n, 0.9f, 0.05f};
                GeometryBuffer g = random_geometry(29, 19, 7u + n);
                if (precomputed) discontinuity_precompute(g, s);
                std::vector<float> in(29 * 19 * channels);
                std::mt19937 rng(9);
                for (float& v : in) v = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng) < 0.1f ? 1e3f : 0.37f;
                std::vector<float> out;
                std::vector<uint8_t> count;
                discontinuity_filter(g, s, channels, in, out, &count);
                for (int y = 0; y < 19; ++y)
                    for (int x = 0; x < 29; ++x) {
                        const size_t p = size_t(y) * 29 + x;
                        const uint64_t bits = discontinuity_window_mask(g, s, x, y);
                        long offset[64];
                        ts::ts_discontinuity_offsets_at(x, y, 29, 19, n, offset);
                        float want[3];
                        ts::ts_discontinuity_mean(in.data(), channels, channels, p, offset, bits, want);
                        ASSERT_EQ(std::memcmp(&out[p * channels], want, 4 * channels), 0) << x << "," << y;
                        ASSERT_EQ(count[p], std::popcount(bits)) << x << "," << y;
                    }
            }
        }
    }
}

// Where a whole window is accepted (one plane: two_regions with both halves alike) the
// host filter sums it from column sums when its values' exponents allow an exact sum, and
// in window order otherwise. Both give ts_discontinuity_mean's floats bit for bit (a NaN
// as a NaN): values
// in [0, 1) (exact), then with some of 1e-30 and 1e20 (an exponent span past the bound, so
// the column sums would round otherwise), infinities and NaNs, and denormals, zeros and
// negatives.
TEST(DiscontinuityFilter, ColumnSumsEqualTheWindowOrderSums) {
    const int w = 40, h = 30;
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const std::vector<std::function<float()>> draws = {
        [&] { return u(rng); },
        [&] { const float r = u(rng); return r < 0.05f ? 1e-30f : r < 0.1f ? 1e20f : r; },
        [&] { const float r = u(rng); return r < 0.01f ? INFINITY : r < 0.02f ? -INFINITY : r < 0.03f ? NAN : r; },
        [&] { const float r = u(rng); return r < 0.2f ? 1e-40f : r < 0.4f ? 0.0f : r < 0.5f ? -0.0f : r - 0.7f; },
    };
    for (int n : {4, 5, 8}) {
        for (int channels : {1, 3}) {
            for (size_t d = 0; d < draws.size(); ++d) {
                SCOPED_TRACE(testing::Message() << "tile " << n << ", " << channels << " channels, draw " << d);
                const DiscontinuitySettings s{n, 0.9f, 0.05f};
                GeometryBuffer g = two_regions(w, h, 2.0f, 1.0f);
                discontinuity_precompute(g, s);
                std::vector<float> in(size_t(w) * h * channels), out;
                for (float& v : in) v = draws[d]();
                discontinuity_filter(g, s, channels, in, out);
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) {
                        const size_t p = size_t(y) * w + x;
                        long offset[64];
                        ts::ts_discontinuity_offsets_at(x, y, w, h, n, offset);
                        float want[3];
                        ts::ts_discontinuity_mean(in.data(), channels, channels, p, offset,
                                                  discontinuity_window_mask(g, s, x, y), want);
                        for (int c = 0; c < channels; ++c) {
                            // A NaN's sign and payload depend on the operands' order in
                            // each addition, which the compiler may swap: NaN is all.
                            if (std::isnan(want[c]))
                                ASSERT_TRUE(std::isnan(out[p * channels + c])) << x << "," << y;
                            else
                                ASSERT_EQ(std::bit_cast<uint32_t>(out[p * channels + c]),
                                          std::bit_cast<uint32_t>(want[c])) << x << "," << y << " channel " << c;
                        }
                    }
            }
        }
    }
}

// A window whose exponents span too much for an exact sum, built so that the order
// shows in the float: at tile 8 (positions x − 4 .. x + 3) pixel (20, 15)'s window holds
// H = 2^30 first, then 2^-24 down its second column, 3 − 2^-21 and 3.5 elsewhere. In
// window order each 2^-24 is lost against H, giving (2^30 + 192 − 2^-21)/64, just below the
// float tie 2^24 + 3, so 2^24 + 2; the column sums keep them, (2^30 + 192)/64 = 2^24 + 3,
// which rounds to even, 2^24 + 4. The filter must give the window order's float.
TEST(DiscontinuityFilter, ColumnSumsFallBackWhereTheExactSumWouldRoundOtherwise) {
    const int w = 40, h = 30, cx = 20, cy = 15;
    const DiscontinuitySettings s{8, 0.9f, 0.05f};
    GeometryBuffer g = two_regions(w, h, 2.0f, 1.0f);
    discontinuity_precompute(g, s);
    std::vector<float> in(size_t(w) * h, 3.5f), out;
    in[size_t(cy - 4) * w + cx - 4] = 0x1p30f;
    for (int y = cy - 4; y <= cy + 3; ++y) in[size_t(y) * w + cx - 3] = 0x1p-24f;
    in[size_t(cy - 4) * w + cx - 2] = 3.0f - 0x1p-21f;
    ASSERT_EQ(static_cast<float>((0x1p30 + 192.0) / 64), 0x1p24f + 4.0f) << "the exact sum's float";
    discontinuity_filter(g, s, 1, in, out);
    EXPECT_EQ(out[size_t(cy) * w + cx], 0x1p24f + 2.0f);
}

}  // namespace
}  // namespace tessera
