// AIS guidance and scheduling on synthetic base buffers: the expected pixels are
// flagged, A grades and A-MAX saturates, and the schedule is deterministic.
#include "gi/ais_schedule.h"

#include <bit>
#include <cmath>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "kernels/shared/ais_guidance.h"

namespace tessera {
namespace {

constexpr int W = 12, H = 9;

// A flat wall facing the camera at depth 2, fully lit, constant indirect light.
AisBaseBuffers flat_wall() {
    AisBaseBuffers b;
    b.geometry.width = W;
    b.geometry.height = H;
    for (int i = 0; i < W * H; ++i) {
        b.geometry.normal.insert(b.geometry.normal.end(), {0.0f, 0.0f, 1.0f});
        b.geometry.depth.push_back(2.0f);
    }
    b.visibility.assign(W * H, 1.0f);
    b.indirect.assign(W * H, 0.3f);
    return b;
}

const DiscontinuitySettings kFilter{3, 0.9f, 0.05f};
const std::array<bool, kAisComponents> kSurface{true, true, false};

TEST(AisGuidance, FlatLitWallFlagsNothing) {
    AisBaseBuffers b = flat_wall();
    AisGuidance g = compute_guidance(b, kFilter, AisThresholds{}, kSurface);
    AisSchedule s = make_schedule(g, AisThresholds{}, AisMode::AMax, W, H, 3);
    for (int c : {kAisSS, kAisID}) {
        ASSERT_EQ(s.sets[c].size(), size_t(W * H));
        for (uint8_t n : s.sets[c]) ASSERT_EQ(n, 1);
    }
    EXPECT_TRUE(s.item_pixels.empty());
    EXPECT_TRUE(g.g[kAisPM].empty()) << "no medium: no PM guidance";
}

TEST(AisGuidance, HardShadowEdgeFlagsTheColumnsBesideIt) {
    // Lit (v = 1) for x < 6, umbra (v = 0) from x = 6: the 3×3 windows of columns 5 and
    // 6 see both, so exactly those columns are flagged for SS, with g = 1.
    AisBaseBuffers b = flat_wall();
    for (int y = 0; y < H; ++y)
        for (int x = 6; x < W; ++x) b.visibility[y * W + x] = 0.0f;
    AisGuidance g = compute_guidance(b, kFilter, AisThresholds{}, kSurface);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            ASSERT_EQ(g.g[kAisSS][y * W + x], (x == 5 || x == 6) ? 1.0f : 0.0f) << x << "," << y;
    AisSchedule a = make_schedule(g, AisThresholds{}, AisMode::A, W, H, 3);
    for (int y = 0; y < H; ++y) EXPECT_EQ(a.sets[kAisSS][y * W + 5], 9) << "g = 1 gives all sets in A too";
    EXPECT_NEAR(a.flagged[kAisSS], 2.0 / W, 1e-12);
}

TEST(AisGuidance, DepthEdgeFlagsIndirectOnBothSides) {
    // The right part is 30% deeper (a step the filter will not cross): pixels next to
    // the step have a rejected 3×3 neighbour and get g_ID = 1; the rest 0.
    AisBaseBuffers b = flat_wall();
    for (int y = 0; y < H; ++y)
        for (int x = 7; x < W; ++x) b.geometry.depth[y * W + x] = 2.6f;
    AisGuidance g = compute_guidance(b, kFilter, AisThresholds{}, kSurface);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            ASSERT_EQ(g.g[kAisID][y * W + x], (x == 6 || x == 7) ? 1.0f : 0.0f) << x << "," << y;
    for (float v : g.g[kAisSS]) ASSERT_EQ(v, 0.0f) << "fully lit on both sides: no penumbra";
}

TEST(AisGuidance, MediumFlagsLengthDiscontinuitiesAndShaftsNotSlopes) {
    // A medium in front of the wall: the camera segment grows 10% per column (a slanted
    // view: smooth, not flagged), the lit fraction is 1 everywhere. Then (a) a depth step
    // at x = 7 with a 30% longer segment beyond it flags columns 6 and 7 (g_len = 1), and
    // (b) a volumetric shadow from x = 6 (lit fraction 0) flags columns 5 and 6 (g_shaft 1).
    const std::array<bool, kAisComponents> all{true, true, true};
    AisBaseBuffers b = flat_wall();
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            b.medium_length.push_back(1.0f + 0.1f * x);
            b.lit_fraction.push_back(1.0f);
        }
    AisGuidance g = compute_guidance(b, kFilter, AisThresholds{}, all);
    for (float v : g.g[kAisPM]) ASSERT_EQ(v, 0.0f) << "a smooth length change is no discontinuity";
    AisBaseBuffers step = b;
    for (int y = 0; y < H; ++y)
        for (int x = 7; x < W; ++x) {
            step.geometry.depth[y * W + x] = 2.6f;
            step.medium_length[y * W + x] *= 1.3f;
        }
    g = compute_guidance(step, kFilter, AisThresholds{}, all);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            ASSERT_EQ(g.g[kAisPM][y * W + x], (x == 6 || x == 7) ? 1.0f : 0.0f) << x << "," << y;
    AisBaseBuffers shaft = b;
    for (int y = 0; y < H; ++y)
        for (int x = 6; x < W; ++x) shaft.lit_fraction[y * W + x] = 0.0f;
    g = compute_guidance(shaft, kFilter, AisThresholds{}, all);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            ASSERT_EQ(g.g[kAisPM][y * W + x], (x == 5 || x == 6) ? 1.0f : 0.0f) << x << "," << y;
            ASSERT_EQ(g.grade[kAisPM][y * W + x], g.g[kAisPM][y * W + x]);
        }
    const AisSchedule s = make_schedule(g, AisThresholds{}, AisMode::A, W, H, 3);
    EXPECT_EQ(s.sets[kAisPM][4 * W + 5], 9) << "g_shaft 1: strength 1 above the trigger, all sets";
    EXPECT_NEAR(s.flagged[kAisPM], 2.0 / W, 1e-12);
}

TEST(AisGuidance, MediumVarianceFlagsWhereTheSetsDisagreeOnlyWhenAsked) {
    // Lit everywhere, a smooth length: only the media estimates speak. Columns 0..5 hold
    // one value in every set (CoV 0); from column 6 the sets alternate 0.1 and 0.3 along
    // rows and columns (every 3×3 window there: mean 0.2 ± 0.1, a CoV near 0.5).
    const std::array<bool, kAisComponents> all{true, true, true};
    AisBaseBuffers b = flat_wall();
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            b.medium_length.push_back(1.0f);
            b.lit_fraction.push_back(1.0f);
            b.media.push_back(x < 6 ? 0.2f : ((x + y) % 2 ? 0.3f : 0.1f));
        }
    AisGuidance off = compute_guidance(b, kFilter, AisThresholds{}, all);
    for (float v : off.g[kAisPM]) ASSERT_EQ(v, 0.0f) << "pm_cov 0: the seed's g_len and g_shaft alone";
    AisThresholds t;
    t.pm_cov = 0.5f;
    const AisGuidance on = compute_guidance(b, kFilter, t, all);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float g = on.g[kAisPM][y * W + x];
            if (x < 5) {
                ASSERT_EQ(g, 0.0f) << x << "," << y;  // every window uniform
            }
            if (x >= 7) {
                ASSERT_GT(g, t.pm_trigger) << x << "," << y;  // every window mixed
            }
            ASSERT_EQ(on.grade[kAisPM][y * W + x], g) << "no length edge: g is the grade";
            ASSERT_LE(g, 1.0f);
        }
}

TEST(AisSchedule, AGradesFarthestSetsFirstAndAMaxSaturates) {
    AisGuidance g;
    g.g[kAisID].assign(W * H, 0.0f);
    g.g[kAisID][4 * W + 4] = 0.5f;  // own set (4 mod 3) + 3 (4 mod 3) = 4
    AisThresholds t;
    t.id_trigger = 0.0f;  // flag g = 0.5; A's strength above the trigger is 0.5
    AisSchedule a = make_schedule(g, t, AisMode::A, W, H, 3), m = make_schedule(g, t, AisMode::AMax, W, H, 3);
    EXPECT_EQ(a.sets[kAisID][4 * W + 4], 5);  // 1 + ceil(0.5 · 8)
    t.id_trigger = 0.25f;  // strength (0.5 − 0.25) / 0.75 = 1/3: 1 + ceil(8/3)
    EXPECT_EQ(make_schedule(g, t, AisMode::A, W, H, 3).sets[kAisID][4 * W + 4], 4);
    EXPECT_EQ(m.sets[kAisID][4 * W + 4], 9);
    // The four extra sets are those of the window's corners (distance √2, farther than
    // the edge neighbours): (3,3) → 0, (5,3) → 2, (3,5) → 6, (5,5) → 8; items by set.
    const uint8_t corners[4] = {0, 2, 6, 8};
    ASSERT_EQ(a.item_pixels.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(a.item_pixels[i], uint32_t(4 * W + 4));
        EXPECT_EQ(a.item_sets[i], corners[i]);
        EXPECT_EQ(a.item_components[i], 1u << kAisID);
    }
    EXPECT_EQ(a.masks[kAisID][4 * W + 4], (1u << 4) | 1u | (1u << 2) | (1u << 6) | (1u << 8));
    EXPECT_EQ(m.masks[kAisID][4 * W + 4], 0x1ffu);
    EXPECT_EQ(a.masks[kAisID][0], 1u) << "unflagged: own set only";
}

TEST(AisSchedule, AAtADepthEdgeCompletesMissingSetsUpToTheThreshold) {
    // Depth step at x = 7 (as above), smooth indirect light (grade 0): pixel (6,4)
    // rejects column 7 of its window, sets (7 mod 3) + 3·(y mod 3) for y = 3, 4, 5 =
    // {1, 4, 7}, and holds the other 6 (own set 3 included).
    AisBaseBuffers b = flat_wall();
    for (int y = 0; y < H; ++y)
        for (int x = 7; x < W; ++x) b.geometry.depth[y * W + x] = 2.6f;
    AisGuidance g = compute_guidance(b, kFilter, AisThresholds{}, kSurface);
    EXPECT_EQ(g.missing[4 * W + 6], (1u << 1) | (1u << 4) | (1u << 7));
    EXPECT_EQ(g.held[4 * W + 6], 0x1ffu & ~((1u << 1) | (1u << 4) | (1u << 7)));
    EXPECT_EQ(g.grade[kAisID][4 * W + 6], 0.0f);
    AisThresholds all_sets;
    all_sets.complete_sets = 9;
    AisSchedule a = make_schedule(g, AisThresholds{}, AisMode::A, W, H, 3);
    AisSchedule full = make_schedule(g, all_sets, AisMode::A, W, H, 3);
    AisSchedule m = make_schedule(g, AisThresholds{}, AisMode::AMax, W, H, 3);
    // Completing to all 9: own set 3 plus exactly the three missing ones.
    EXPECT_EQ(full.masks[kAisID][4 * W + 6], (1u << 3) | (1u << 1) | (1u << 4) | (1u << 7));
    // Completing to 7: one missing set, the farthest ((7,3) at √2 before (7,4) at 1; the
    // tie with (7,5) goes to the lower set): set 1.
    AisThresholds seven;
    seven.complete_sets = 7;
    EXPECT_EQ(make_schedule(g, seven, AisMode::A, W, H, 3).masks[kAisID][4 * W + 6], (1u << 3) | (1u << 1));
    // Rows 0 and 8 too: their windows are moved in at the border (ts_discontinuity_lo_at),
    // so they hold every set, and reject the same column.
    for (int y = 0; y < H; ++y)
        for (int x : {6, 7}) {
            EXPECT_EQ(a.sets[kAisID][y * W + x], 1) << x << "," << y << ": holds 6 >= ceil(9/2), own set only";
            EXPECT_EQ(full.sets[kAisID][y * W + x], 4) << x << "," << y << ": own + 3 rejected";
            EXPECT_EQ(m.sets[kAisID][y * W + x], 9);
        }
    EXPECT_EQ(m.item_pixels.size(), size_t(2 * H * 8));
    EXPECT_EQ(full.item_pixels.size(), size_t(2 * H * 3));
    EXPECT_EQ(a.item_pixels.size(), size_t(0));
}

TEST(AisSchedule, AGradesOverAtMostGradedSetsWhateverTheTile) {
    // ID guidance alone, no missing sets: pixel (10,10) saturated (grade 1), (3,3) half
    // way above the trigger 0.5 (grade 0.75, a = 0.5). A adds ⌈a·(min(G, N)−1)⌉ sets.
    const int w = 20, h = 20;
    AisGuidance g;
    g.g[kAisID].assign(w * h, 0.0f);
    g.g[kAisID][10 * w + 10] = 1.0f;
    g.g[kAisID][3 * w + 3] = 0.75f;
    auto sets = [&](int graded, int tile, AisMode mode) {
        AisThresholds t;
        t.graded_sets = graded;
        const AisSchedule s = make_schedule(g, t, mode, w, h, tile);
        return std::pair<int, int>(s.sets[kAisID][10 * w + 10], s.sets[kAisID][3 * w + 3]);
    };
    using P = std::pair<int, int>;
    EXPECT_EQ(AisThresholds{}.graded_sets, 9);
    EXPECT_EQ(sets(9, 5, AisMode::A), P(9, 5)) << "default: 1 + 8, 1 + ⌈0.5·8⌉ of 25 sets";
    EXPECT_EQ(sets(9, 8, AisMode::A), P(9, 5)) << "the same at 64 sets";
    EXPECT_EQ(sets(0, 5, AisMode::A), P(25, 13)) << "0: all N, 1 + ⌈0.5·24⌉";
    EXPECT_EQ(sets(64, 5, AisMode::A), P(25, 13)) << "G past N counts as N";
    EXPECT_EQ(sets(4, 5, AisMode::A), P(4, 3)) << "1 + 3, 1 + ⌈1.5⌉";
    EXPECT_EQ(sets(1, 5, AisMode::A), P(1, 1)) << "G = 1: no graded sets";
    EXPECT_EQ(sets(9, 3, AisMode::A), sets(0, 3, AisMode::A)) << "tile 3: G = 9 is every set";
    EXPECT_EQ(sets(4, 5, AisMode::AMax), P(25, 25)) << "A-MAX gives all N sets whatever G";
}

TEST(AisSchedule, ItemsRunSetBySetThenTileByTile) {
    // A-MAX on a 40×36 image flagging a diagonal line and row 20 (ID g = 1): every flagged
    // pixel gets its 8 other sets. Items must come set by set, within a set by
    // kItemTile-pixel tile (rows of tiles) and within a tile in scanline order, each
    // (pixel, set) once.
    const int w = 40, h = 36;
    AisGuidance g;
    g.g[kAisID].assign(w * h, 0.0f);
    for (int y = 0; y < h; ++y) g.g[kAisID][y * w + (y + 3) % w] = 1.0f;
    for (int x = 0; x < w; ++x) g.g[kAisID][20 * w + x] = 1.0f;
    size_t flagged = 0;
    for (float v : g.g[kAisID]) flagged += v > 0.0f;
    const AisSchedule s = make_schedule(g, AisThresholds{}, AisMode::AMax, w, h, 3);
    ASSERT_EQ(s.item_pixels.size(), flagged * 8);
    const uint32_t tiles_x = (w + kItemTile - 1) / kItemTile;
    auto tile = [&](uint32_t p) { return (p / w / kItemTile) * tiles_x + (p % w) / kItemTile; };
    std::set<std::pair<uint32_t, uint8_t>> seen;
    int tile_changes = 0;
    for (size_t i = 0; i < s.item_pixels.size(); ++i) {
        ASSERT_TRUE(seen.insert({s.item_pixels[i], s.item_sets[i]}).second) << "item " << i << " repeats";
        if (i == 0) continue;
        const uint32_t a = s.item_pixels[i - 1], b = s.item_pixels[i];
        if (s.item_sets[i] != s.item_sets[i - 1]) {
            ASSERT_GT(s.item_sets[i], s.item_sets[i - 1]) << "item " << i;
            continue;
        }
        ASSERT_TRUE(tile(a) < tile(b) || (tile(a) == tile(b) && a < b)) << "item " << i << ": " << a << " then " << b;
        tile_changes += tile(a) != tile(b);
    }
    EXPECT_GT(tile_changes, 9 * 3);  // row 20 crosses three tiles in every set: not scanline
}

TEST(AisSchedule, RepeatRunsAreBitIdentical) {
    AisBaseBuffers b = flat_wall();
    for (int i = 0; i < W * H; ++i) {
        b.visibility[i] = float((i * 37) % 11) / 10.0f;
        b.indirect[i] = 0.1f + float((i * 13) % 7) / 7.0f;
    }
    auto run = [&] {
        return make_schedule(compute_guidance(b, kFilter, AisThresholds{}, kSurface), AisThresholds{}, AisMode::A, W,
                             H, 3);
    };
    const AisSchedule s1 = run(), s2 = run();
    EXPECT_FALSE(s1.item_pixels.empty());
    EXPECT_EQ(s1.item_pixels, s2.item_pixels);
    EXPECT_EQ(s1.item_sets, s2.item_sets);
    EXPECT_EQ(s1.item_components, s2.item_components);
    for (int c : {kAisSS, kAisID}) EXPECT_EQ(s1.sets[c], s2.sets[c]);
}

// The host's guidance takes each window's statistics one window position at a time across
// a row (compute_guidance); the shared per-pixel function (ts_ais_guidance, which the
// device's schedule kernel runs) loops over each pixel's mask bits. On random buffers
// with depth steps, creases, escaped rays and penumbrae, both give the same g and grade
// bit for bit, at tiles whose windows are moved in at the borders in every way (tile 8
// at a height of 14: rows moved both ways), with the frame's precomputed masks and without.
TEST(AisGuidance, RowWiseWindowsEqualThePerPixelGuidance) {
    constexpr int w = 19, h = 14;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    AisBaseBuffers b;
    GeometryBuffer& g = b.geometry;
    g.width = w, g.height = h;
    for (int i = 0; i < w * h; ++i) {
        const float r = u(rng), z = r < 0.1f ? ts::TS_INF : r < 0.4f ? 2.6f : 2.0f;
        const float nz = u(rng) < 0.2f ? 0.7f : 1.0f, nx = std::sqrt(1.0f - nz * nz);
        g.normal.insert(g.normal.end(), {nx, 0.0f, nz});
        g.position.insert(g.position.end(), {0.01f * (i % w), 0.01f * (i / w), -z});
        g.depth.push_back(z);
        b.visibility.push_back(u(rng) < 0.5f ? 1.0f : u(rng));
        b.indirect.push_back(u(rng) < 0.05f ? 40.0f * u(rng) : u(rng));
    }
    AisThresholds t;
    t.id_cov = 0.7f;
    for (int tile : {2, 3, 4, 5, 8}) {
        for (bool precomputed : {false, true}) {
            SCOPED_TRACE(testing::Message() << "tile " << tile << (precomputed ? ", precomputed masks" : ""));
            const DiscontinuitySettings filter{tile, 0.9f, 0.05f};
            if (precomputed) discontinuity_precompute(g, filter);
            else g.accepted.clear();
            const AisGuidance got = compute_guidance(b, filter, t, kSurface);

            ts::TsAisGuideView v{};
            v.depth = g.depth.data(), v.normal = g.normal.data(), v.position = g.position.data();
            v.visibility = b.visibility.data(), v.indirect = b.indirect.data();
            v.depth_stride = v.surf_stride = v.media_stride = 1, v.vec_stride = 3;
            v.width = w, v.height = h, v.tile = tile, v.cos_min = filter.normal_cos, v.depth_rel = filter.depth_rel;
            ts::TsAisParams params{};  // what SS and ID read: N_min (default ⌈N/2⌉) and the CoV scale
            params.min_accepted = (tile * tile + 1) / 2;
            params.id_cov = t.id_cov;
            size_t flagged = 0, partial = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const size_t p = size_t(y) * w + x;
                    const uint64_t in_image = ts::ts_ais_in_image(x, y, w, h, tile);
                    const uint64_t accepted = ts::ts_discontinuity_mask(x, y, w, h, tile, g.depth.data(),
                                                                        g.normal.data(), g.position.data(), 1, 3, 1,
                                                                        filter.normal_cos, filter.depth_rel);
                    partial += accepted != in_image;
                    long offset[64];
                    ts::ts_discontinuity_offsets_at(x, y, w, h, tile, offset);
                    for (int c : {kAisSS, kAisID}) {
                        const ts::TsAisValue want = ts::ts_ais_guidance(&v, &params, offset, c, in_image, accepted, x, y);
                        ASSERT_EQ(std::bit_cast<uint32_t>(got.g[c][p]), std::bit_cast<uint32_t>(want.g))
                            << "component " << c << " pixel " << x << "," << y;
                        ASSERT_EQ(std::bit_cast<uint32_t>(got.grade[c][p]), std::bit_cast<uint32_t>(want.grade))
                            << "component " << c << " pixel " << x << "," << y;
                        flagged += want.grade > 0.0f && want.grade < 1.0f;
                    }
                }
            if (tile > 1) {
                EXPECT_GT(partial, size_t(w * h / 4)) << "the windows should reject some positions";
                EXPECT_GT(flagged, size_t(w * h / 4)) << "and the grades should be fractional";
            }
        }
    }
}

}  // namespace
}  // namespace tessera
