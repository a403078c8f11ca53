// AIS guidance and scheduling on synthetic base buffers: the expected pixels are
// flagged, A grades and A-MAX saturates, and the schedule is deterministic.
#include "gi/ais_schedule.h"

#include <gtest/gtest.h>

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
    for (int c : {kAisSS, kAisID})
        for (uint8_t n : s.sets[c]) ASSERT_EQ(n, 1);
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

TEST(AisSchedule, AGradesAMaxSaturatesAndExtraSetsFollowTheOwnSet) {
    AisGuidance g;
    g.g[kAisID].assign(W * H, 0.0f);
    g.g[kAisID][4 * W + 4] = 0.5f;  // own set (4 mod 3) + 3 (4 mod 3) = 4
    AisThresholds t;
    t.id_trigger = 0.25f;  // flag g = 0.5
    AisSchedule a = make_schedule(g, t, AisMode::A, W, H, 3), m = make_schedule(g, t, AisMode::AMax, W, H, 3);
    EXPECT_EQ(a.sets[kAisID][4 * W + 4], 5);  // 1 + ceil(0.5 · 8)
    EXPECT_EQ(m.sets[kAisID][4 * W + 4], 9);
    ASSERT_EQ(a.item_pixels.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(a.item_pixels[i], uint32_t(4 * W + 4));
        EXPECT_EQ(a.item_sets[i], (4 + 1 + i) % 9) << "sets k+1, k+2, ... after the own set";
        EXPECT_EQ(a.item_components[i], 1u << kAisID);
    }
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

}  // namespace
}  // namespace tessera
