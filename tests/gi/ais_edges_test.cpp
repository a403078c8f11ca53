// AIS edge samples on synthetic buffers: the guidance flags geometric edges with contrast
// and nothing else, A grades and A-MAX saturates, a sample takes the neighbour on its own
// surface, and the merge is the mean of the pixel's samples.
#include "gi/ais_edges.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <tuple>

#include <gtest/gtest.h>

#include "kernels/shared/edge_guidance.h"
#include "kernels/shared/layout_igi.h"
#include "kernels/shared/layout_pass.h"

namespace tessera {
namespace {

constexpr int W = 8, H = 6;
const DiscontinuitySettings kFilter{3, 0.9f, 0.05f};
constexpr float kInf = std::numeric_limits<float>::infinity();

// Columns x < 4: a wall facing the camera at depth 2; x >= 4: at depth `right_depth`
// (a parallel wall behind it: a depth edge between columns 3 and 4), positions on z.
GeometryBuffer two_walls(float right_depth) {
    GeometryBuffer g;
    g.width = W;
    g.height = H;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float z = x < 4 ? 2.0f : right_depth;
            g.normal.insert(g.normal.end(), {0.0f, 0.0f, 1.0f});
            g.position.insert(g.position.end(), {0.1f * x, 0.1f * y, -z});
            g.depth.push_back(z);
        }
    return g;
}

// A pass image with radiance `left` for x < 4 and `right` elsewhere.
std::vector<float> pass_image(float left, float right) {
    std::vector<float> out(size_t(W) * H * TS_PASS_FLOATS, 0.0f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) out[(size_t(y) * W + x) * TS_PASS_FLOATS + TS_PASS_RADIANCE + c] = x < 4 ? left : right;
    return out;
}

TEST(AisEdgeGuidance, DepthEdgeWithContrastFlagsBothSides) {
    const GeometryBuffer g = two_walls(4.0f);
    const std::vector<float> guidance = edge_guidance(g, kFilter, pass_image(1.0f, 0.25f), 0.01f);
    // ε = 0.01 · mean Y = 0.01 · 0.625; contrast (1 − 0.25) / (1.25 + ε).
    const float expected = 0.75f / (1.25f + 0.00625f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            SCOPED_TRACE(testing::Message() << "pixel " << x << "," << y);
            EXPECT_NEAR(guidance[size_t(y) * W + x], x == 3 || x == 4 ? expected : 0.0f, 1e-6f);
        }
}

TEST(AisEdgeGuidance, PrecomputedWindowMasksGiveTheSameGuidance) {
    // The frame's discontinuity masks stand in for the test wherever the filter's window
    // covers the guidance's 3×3 one: tile 3 and every tile from 4 on (tile 2's window,
    // offsets -1..0, does not, and the test runs per pair).
    for (int tile : {2, 3, 4, 5, 8}) {
        SCOPED_TRACE(testing::Message() << "tile " << tile);
        const DiscontinuitySettings filter{tile, 0.9f, 0.05f};
        GeometryBuffer g = two_walls(4.0f);
        g.normal[3 * (2 * W + 1) + 0] = 1.0f, g.normal[3 * (2 * W + 1) + 2] = 0.0f;  // a crease at (1, 2)
        g.depth[4 * W + 6] = kInf;                                                    // an escaped ray at (6, 4)
        std::vector<float> img = pass_image(1.0f, 0.25f);
        for (int c = 0; c < 3; ++c) img[(4 * W + 6) * TS_PASS_FLOATS + TS_PASS_RADIANCE + c] = 0.0f;  // black sky
        const std::vector<float> tested = edge_guidance(g, filter, img, 0.01f);
        discontinuity_precompute(g, filter);
        ASSERT_EQ(g.accepted.size(), size_t(W * H));
        EXPECT_EQ(edge_guidance(g, filter, img, 0.01f), tested);
        EXPECT_EQ(tested[2 * W + 1], 0.0f);  // a crease with no contrast across it
        EXPECT_GT(tested[4 * W + 5], 0.0f);  // beside the escaped ray, with contrast
    }
}

TEST(AisEdgeGuidance, NoContrastOrNoGeometricEdgeFlagsNothing) {
    // The same depth edge with equal radiance on both sides: nothing to anti-alias.
    for (float g_value : edge_guidance(two_walls(4.0f), kFilter, pass_image(0.5f, 0.5f), 0.01f))
        EXPECT_EQ(g_value, 0.0f);
    // Contrast on one wall (a shadow edge): the light's edge, not coverage; SS's business.
    for (float g_value : edge_guidance(two_walls(2.0f), kFilter, pass_image(1.0f, 0.0f), 0.01f))
        EXPECT_EQ(g_value, 0.0f);
}

TEST(AisEdgeGuidance, ALightInItsHoldersPlaneIsAnEdge) {
    // One plane (no geometric edge); the left half is a light 100 times brighter, as a
    // ceiling panel set into the ceiling. Geometry alone sees no edge; the emitter mask
    // flags the two columns beside the light's edge and nothing else.
    const GeometryBuffer g = two_walls(2.0f);
    const std::vector<float> img = pass_image(100.0f, 1.0f);
    for (float g_value : edge_guidance(g, kFilter, img, 0.01f)) EXPECT_EQ(g_value, 0.0f);
    std::vector<uint8_t> emitter(size_t(W) * H, 0);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < 4; ++x) emitter[size_t(y) * W + x] = 1;
    const std::vector<float> guidance = edge_guidance(g, kFilter, img, 0.01f, emitter);
    // ε = 0.01 · mean Y = 0.01 · 50.5; contrast 99 / (101 + ε).
    const float expected = 99.0f / (101.0f + 0.505f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            SCOPED_TRACE(testing::Message() << "pixel " << x << "," << y);
            EXPECT_NEAR(guidance[size_t(y) * W + x], x == 3 || x == 4 ? expected : 0.0f, 1e-5f);
        }
}

TEST(AisEdgeGuidance, APixelsOwnSampleDoesNotFlagIt) {
    // One wall, but pixel (2, 2)'s sample met something else (a bright bar thinner than a
    // pixel, nearer): its neighbours, whose rings it lies on, are flagged; it is not, for
    // the merge would average its own sample away (docs/ais.md §9).
    GeometryBuffer g = two_walls(2.0f);
    const size_t p = 2 * W + 2;
    g.depth[p] = 1.0f, g.position[3 * p + 2] = -1.0f;
    std::vector<float> img = pass_image(0.25f, 0.25f);
    for (int c = 0; c < 3; ++c) img[p * TS_PASS_FLOATS + TS_PASS_RADIANCE + c] = 1.0f;
    for (bool masks : {false, true}) {
        if (masks) discontinuity_precompute(g, kFilter);
        const std::vector<float> guidance = edge_guidance(g, kFilter, img, 0.01f);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                SCOPED_TRACE(testing::Message() << "pixel " << x << "," << y << (masks ? ", masks" : ""));
                const bool ring = std::abs(x - 2) <= 1 && std::abs(y - 2) <= 1 && !(x == 2 && y == 2);
                if (ring) EXPECT_GT(guidance[size_t(y) * W + x], 0.5f);
                else EXPECT_EQ(guidance[size_t(y) * W + x], 0.0f);
            }
    }
}

TEST(AisEdgeGuidance, AnImageOnePixelWideOrHighFindsItsEdges) {
    // A column (and a row) of 6 pixels: a near wall for the first 3, a far one behind.
    // Their neighbours lie above and below (left and right) only, never next to each other
    // on the ring; the straight-through pairs find the edge beside pixels 2 and 3.
    for (bool column : {true, false}) {
        SCOPED_TRACE(column ? "column" : "row");
        GeometryBuffer g;
        g.width = column ? 1 : 6;
        g.height = column ? 6 : 1;
        std::vector<float> img(6 * TS_PASS_FLOATS, 0.0f);
        for (int i = 0; i < 6; ++i) {
            const float z = i < 3 ? 2.0f : 4.0f;
            g.normal.insert(g.normal.end(), {0.0f, 0.0f, 1.0f});
            g.position.insert(g.position.end(), {column ? 0.0f : 0.1f * i, column ? 0.1f * i : 0.0f, -z});
            g.depth.push_back(z);
            for (int c = 0; c < 3; ++c) img[i * TS_PASS_FLOATS + TS_PASS_RADIANCE + c] = i < 3 ? 1.0f : 0.25f;
        }
        const std::vector<float> guidance = edge_guidance(g, kFilter, img, 0.01f);
        for (int i = 0; i < 6; ++i) {
            if (i == 2 || i == 3) EXPECT_GT(guidance[i], 0.5f) << i;
            else EXPECT_EQ(guidance[i], 0.0f) << i;
        }
    }
}

TEST(AisEdgeGuidance, EscapedRaysAreAnEdgeAndDarkDifferencesAreNot) {
    GeometryBuffer g = two_walls(kInf);  // right half: the camera rays escaped
    std::vector<float> guidance = edge_guidance(g, kFilter, pass_image(1.0f, 0.0f), 0.01f);
    EXPECT_GT(guidance[3], 0.9f);
    EXPECT_GT(guidance[4], 0.9f);
    EXPECT_EQ(guidance[0], 0.0f);
    // Both sides far below ε: a step of 1e-4 in a frame whose mean luminance is about 1
    // (one pixel holds it all) is no edge to see.
    std::vector<float> img = pass_image(1e-4f, 0.0f);
    img[0 + TS_PASS_RADIANCE] = img[1 + TS_PASS_RADIANCE] = img[2 + TS_PASS_RADIANCE] = 1.0f * W * H;  // the mean
    guidance = edge_guidance(g, kFilter, img, 0.01f);
    EXPECT_LT(guidance[size_t(3) * W + 3], 0.05f);
}

// A w × h G-buffer on one wall (depth 2, facing the camera) where a pixel is odd with
// probability `odd`: farther (4), nearer (1.5), escaped, tilted, a light, or a hair
// farther (2.104: the plain wall's test rejects it, its own accepts the wall), each alike;
// random radiance. odd[p] = 1 where pixel p is one of them. Without `positions` the
// buffer keeps depths only (the depth test instead of the plane distance).
struct ScatteredBuffers {
    GeometryBuffer g;
    std::vector<float> img;
    std::vector<uint8_t> emitter, odd;
};

ScatteredBuffers scattered(int w, int h, float odd, bool positions, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    ScatteredBuffers b;
    b.g.width = w, b.g.height = h;
    b.img.assign(size_t(w) * h * TS_PASS_FLOATS, 0.0f);
    b.emitter.assign(size_t(w) * h, 0);
    b.odd.assign(size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t p = size_t(y) * w + x;
            const int kind = u(rng) < odd ? 1 + int(u(rng) * 6.0f) % 6 : 0;
            const float z = kind == 1 ? 4.0f : kind == 2 ? 1.5f : kind == 3 ? kInf : kind == 6 ? 2.104f : 2.0f;
            const bool tilted = kind == 4;
            b.g.normal.insert(b.g.normal.end(), {tilted ? 1.0f : 0.0f, 0.0f, tilted ? 0.0f : 1.0f});
            if (positions) b.g.position.insert(b.g.position.end(), {0.1f * x, 0.1f * y, -z});
            b.g.depth.push_back(z);
            b.emitter[p] = kind == 5;
            b.odd[p] = kind != 0;
            for (int c = 0; c < 3; ++c) b.img[p * TS_PASS_FLOATS + TS_PASS_RADIANCE + c] = u(rng);
        }
    return b;
}

// edge_guidance against its definition, pixel by pixel: the largest contrast over the
// pairs of ts_edge_pairs around p that lie in the image and that the first's discontinuity
// test rejects or that straddle a light's edge (without an emitter mask, no light edges).
std::vector<float> edge_guidance_by_definition(const GeometryBuffer& g, const DiscontinuitySettings& s,
                                               const std::vector<float>& img, const std::vector<uint8_t>& emitter) {
    const int w = g.width, h = g.height;
    const float eps = edge_epsilon(img, w, 0.01f);
    std::vector<float> expected(size_t(w) * h, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int i = 0; i < 10; ++i) {
                size_t qa, qb;
                if (!ts::ts_edge_pair_pixels(x, y, w, h, i, &qa, &qb)) continue;
                const bool light_edge = !emitter.empty() && emitter[qa] != emitter[qb];
                if (discontinuity_accepts(g, s, qa, qb) && !light_edge) continue;
                const float ya = ts::ts_luminance(ts::ts_f3_load(&img[qa * TS_PASS_FLOATS + TS_PASS_RADIANCE]));
                const float yb = ts::ts_luminance(ts::ts_f3_load(&img[qb * TS_PASS_FLOATS + TS_PASS_RADIANCE]));
                float& e = expected[size_t(y) * w + x];
                e = ts::ts_edge_max(e, ts::ts_edge_contrast(ya, yb, eps));
            }
    return expected;
}

// The host's per-pair flags and its quick test of a pixel's ring must neither lose nor
// add a pair: on scattered G-buffers, dense (edges everywhere) and sparse (lone odd pixels
// in a plain wall, where most inner pixels take the quick test beside flagged ones), at
// every border, on images whose sides are no multiple of any tile, every tile (9: no
// masks), with and without the precomputed masks, the emitter mask and positions.
TEST(AisEdgeGuidance, EachPixelTakesItsRingsLargestEdgeContrast) {
    std::mt19937 rng(11);
    for (const float odd : {0.4f, 0.03f})
        for (const auto [w, h] : {std::pair{23, 17}, std::pair{41, 37}, std::pair{2, 9}, std::pair{9, 1}})
            for (const bool positions : {true, false}) {
                const ScatteredBuffers b = scattered(w, h, odd, positions, rng);
                for (int tile : {1, 2, 3, 4, 5, 8, 9})
                    for (const bool lights : {true, false})
                        for (const bool masks : {false, true}) {
                            if (masks && tile > 8) continue;  // 64 window positions at most
                            SCOPED_TRACE(testing::Message() << w << "x" << h << ", odd " << odd << ", tile " << tile
                                                            << (positions ? "" : ", depths only")
                                                            << (lights ? "" : ", no emitter mask")
                                                            << (masks ? ", masks" : ""));
                            const DiscontinuitySettings filter{tile, 0.9f, 0.05f};
                            const std::vector<uint8_t> emitter = lights ? b.emitter : std::vector<uint8_t>{};
                            GeometryBuffer g = b.g;
                            if (masks) discontinuity_precompute(g, filter);
                            const std::vector<float> guidance = edge_guidance(g, filter, b.img, 0.01f, emitter);
                            EXPECT_EQ(guidance, edge_guidance_by_definition(b.g, filter, b.img, emitter));
                            if (odd > 0.1f || w * h > 100)  // a thin sparse image may hold no odd pixel
                                EXPECT_GT(std::count_if(guidance.begin(), guidance.end(), [](float v) { return v > 0.0f; }), 0);
                        }
                if (odd > 0.1f || w < 5 || h < 5) continue;
                // The sparse case reaches the quick test: inner pixels with no odd pixel
                // within 2 (so no flag around them) next to ones with a flag.
                int quick = 0;
                for (int y = 2; y + 2 < h; ++y)
                    for (int x = 2; x + 2 < w; ++x) {
                        bool plain = true;
                        for (int dy = -2; dy <= 2; ++dy)
                            for (int dx = -2; dx <= 2; ++dx) plain &= !b.odd[size_t(y + dy) * w + x + dx];
                        quick += plain && (b.odd[size_t(y) * w + x + 3] || b.odd[size_t(y + 3 < h ? y + 3 : y) * w + x]);
                    }
                EXPECT_GT(quick, 0) << w << "x" << h;
            }
}

TEST(AisEdgeSchedule, AGradesAndAMaxSaturates) {
    EdgeSettings e;  // trigger 0.05, full 0.5
    e.samples = 8;
    const std::vector<float> g = {0.0f, 0.05f, 0.06f, 0.27f, 0.5f, 1.0f};
    const EdgeSchedule a = make_edge_schedule(g, e, AisMode::A);
    // a = (g − 0.05) / 0.45: 0.022 -> 1 sample, 0.49 -> 4, 1 -> 8; at or below the trigger none.
    EXPECT_EQ(std::vector<int>(a.samples.begin(), a.samples.end()), (std::vector<int>{0, 0, 1, 4, 8, 8}));
    const EdgeSchedule m = make_edge_schedule(g, e, AisMode::AMax);
    EXPECT_EQ(std::vector<int>(m.samples.begin(), m.samples.end()), (std::vector<int>{0, 0, 8, 8, 8, 8}));
    EXPECT_DOUBLE_EQ(m.flagged, 4.0 / 6.0);
    // Items: each flagged pixel's samples j = 1..n together, pixels in order.
    ASSERT_EQ(a.items.size(), size_t(TS_EDGE_ITEM_WORDS) * (1 + 4 + 8 + 8));
    EXPECT_EQ(a.items[TS_EDGE_ITEM_PIXEL], 2u);
    EXPECT_EQ(a.items[TS_EDGE_ITEM_SAMPLE], 1u);
    EXPECT_EQ(a.items[TS_EDGE_ITEM_WORDS * 1 + TS_EDGE_ITEM_PIXEL], 3u);
    EXPECT_EQ(a.items[TS_EDGE_ITEM_WORDS * 4 + TS_EDGE_ITEM_SAMPLE], 4u);
    EXPECT_EQ(a.items[TS_EDGE_ITEM_WORDS * 4 + TS_EDGE_ITEM_COUNT], 4u);
}

// An edge sample on the plane z = −depth at (px, py) in the two walls' coordinates.
std::vector<float> sample_at(float x, float y, float depth) {
    std::vector<float> s(TS_EDGE_SAMPLE_FLOATS, 0.0f);
    s[TS_EDGE_SAMPLE_NORMAL + 2] = 1.0f;
    s[TS_EDGE_SAMPLE_POSITION] = x, s[TS_EDGE_SAMPLE_POSITION + 1] = y, s[TS_EDGE_SAMPLE_POSITION + 2] = -depth;
    s[TS_EDGE_SAMPLE_DISTANCE] = depth;
    for (int c = 0; c < 3; ++c) s[TS_EDGE_SAMPLE_THROUGHPUT + c] = 1.0f;
    return s;
}

TEST(AisEdgeMatch, SampleTakesTheNeighbourOnItsSurface) {
    const GeometryBuffer g = two_walls(4.0f);
    // Pixel (3, 2) sees the near wall; a sample of it on the far wall takes (4, 2), the
    // far-wall pixel nearest to it; one on the near wall takes (3, 2) itself.
    EXPECT_EQ(edge_sample_match(g, kFilter, 3, 2, sample_at(0.38f, 0.2f, 4.0f).data()), size_t(2 * W + 4));
    EXPECT_EQ(edge_sample_match(g, kFilter, 3, 2, sample_at(0.31f, 0.2f, 2.0f).data()), size_t(2 * W + 3));
    // A sample on the near wall but close to row 3's pixel: the nearest accepted in space.
    EXPECT_EQ(edge_sample_match(g, kFilter, 3, 2, sample_at(0.3f, 0.29f, 2.0f).data()), size_t(3 * W + 3));
    // On neither wall (depth 3): the neighbour nearest in depth.
    EXPECT_EQ(g.depth[edge_sample_match(g, kFilter, 3, 2, sample_at(0.35f, 0.2f, 3.5f).data())], 4.0f);
    // Escaped: p itself when no neighbour escaped.
    std::vector<float> escaped = sample_at(0, 0, kInf);
    EXPECT_EQ(edge_sample_match(g, kFilter, 3, 2, escaped.data()), size_t(2 * W + 3));
}

TEST(AisEdgeMerge, PixelIsTheMeanOfItsSamplesShadedByTheirMatches) {
    const GeometryBuffer g = two_walls(4.0f);
    const size_t pixels = size_t(W) * H;
    // Near wall irradiance/π 1, far wall 0.25; no medium.
    std::vector<float> e_ss(3 * pixels), e_id(3 * pixels, 0.0f), l_pm(3 * pixels, 0.0f), tr(3 * pixels, 1.0f);
    for (size_t p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c) e_ss[3 * p + c] = (p % W) < 4 ? 1.0f : 0.25f;
    std::vector<float> out = pass_image(0.5f, 0.125f);  // albedo 0.5: the base radiance
    EdgeSchedule s;
    s.samples.assign(pixels, 0);
    const size_t p = 2 * W + 3;
    s.samples[p] = 3;
    for (uint32_t j = 1; j <= 3; ++j) s.items.insert(s.items.end(), {static_cast<uint32_t>(p), j, 3u});
    std::vector<float> samples;
    // Two samples on the far wall, one on the near wall, albedo 0.5, one with emission 1.
    const std::tuple<float, float, float> at[] = {{0.38f, 4.0f, 0.0f}, {0.39f, 4.0f, 0.0f}, {0.31f, 2.0f, 1.0f}};
    for (const auto& [x, depth, le] : at) {
        std::vector<float> e = sample_at(x, 0.2f, depth);
        for (int c = 0; c < 3; ++c) e[TS_EDGE_SAMPLE_ALBEDO + c] = 0.5f, e[TS_EDGE_SAMPLE_EMISSION + c] = le;
        samples.insert(samples.end(), e.begin(), e.end());
    }
    merge_edge_samples(g, kFilter, s, samples, {&e_ss, &e_id, &l_pm, &tr}, out);
    // (0.5 base + 0.125 + 0.125 + (1 + 0.5)) / 4
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(out[p * TS_PASS_FLOATS + TS_PASS_RADIANCE + c], 2.25f / 4.0f);
    EXPECT_FLOAT_EQ(out[(p + 1) * TS_PASS_FLOATS + TS_PASS_RADIANCE], 0.125f);  // unflagged: unchanged
}

}  // namespace
}  // namespace tessera
