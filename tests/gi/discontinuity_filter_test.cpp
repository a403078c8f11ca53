// The discontinuity buffer leaves constant images alone and never averages across a
// depth or normal edge.
#include "gi/discontinuity_filter.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace tessera
