// kernels/shared/material.h ts_texture_lookup (mip level from the footprint, trilinear)
// and kernels/shared/geometry.h ts_surface_cone (the footprint of a pixel's ray cone).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "device/texture_mips.h"
#include "kernels/shared/material.h"

namespace tessera {
namespace {

uint32_t grey(uint32_t c) { return c | c << 8 | c << 16 | 0xffu << 24; }

// A 4×4 texture whose levels are told apart by their values: level 0 is code 255 at
// texel (0, 0) and 0 elsewhere, so level 1's top-left texel is a quarter of white (in
// linear light, rounded to 8 bits) and level 2 (1×1) a quarter of that.
struct OneTexture {
    std::vector<uint32_t> info, texels;
    ts::TsSceneView sv{};
    OneTexture() {
        std::vector<uint32_t> level0(16, grey(0));
        level0[0] = grey(255);
        texels = build_mip_chain(level0, 4, 4);
        info = {0u, 4u, 4u, mip_level_count(4, 4)};
        sv.tex_info = info.data();
        sv.tex_texels = texels.data();
    }
    float lookup(float u, float v, float footprint) const {
        return ts::ts_texture_lookup(&sv, 0, ts::make_float2(u, v), footprint).x;
    }
};

TEST(TextureLookup, ZeroFootprintIsTheBilinearLevelZero) {
    const OneTexture t;
    // The centre of texel (0, 0): row 0 is the top, v = 1 - 0.5/4.
    EXPECT_EQ(t.lookup(0.125f, 0.875f, 0.0f), 1.0f);
    EXPECT_EQ(t.lookup(0.375f, 0.875f, 0.0f), 0.0f);
    // Halfway between texels (0, 0) and (1, 0).
    EXPECT_FLOAT_EQ(t.lookup(0.25f, 0.875f, 0.0f), 0.5f);
    // A footprint under one texel (λ <= 0) reads level 0 too.
    EXPECT_EQ(t.lookup(0.375f, 0.875f, 0.2f), 0.0f);
}

TEST(TextureLookup, FootprintPicksAndBlendsLevels) {
    const OneTexture t;
    const float l1 = ts::ts_srgb_table[encode_srgb8(0.25f)];    // level 1, top-left texel
    const float l2 = ts::ts_srgb_table[encode_srgb8(l1 / 4)];   // level 2: level 1's mean
    // At the centre of level 1's top-left texel (u, v) = (0.25, 0.75), bilinear reads
    // that texel alone. λ = log2(footprint · 4).
    EXPECT_FLOAT_EQ(t.lookup(0.25f, 0.75f, 0.5f), l1);                       // λ = 1
    EXPECT_FLOAT_EQ(t.lookup(0.25f, 0.75f, 1.0f), l2);                       // λ = 2
    EXPECT_FLOAT_EQ(t.lookup(0.25f, 0.75f, 100.0f), l2);                     // past the last level
    EXPECT_NEAR(t.lookup(0.25f, 0.75f, std::sqrt(0.5f)), 0.5f * (l1 + l2), 1e-6f);  // λ = 1.5
}

TEST(SurfaceCone, FootprintIsWidthTimesTextureScaleOverRootCosine) {
    // One triangle, 2 × 2 scene units, texture coordinates 0..1: sqrt(A_uv/A_world) = 1/2.
    const std::vector<float> pos = {0, 0, 0, 2, 0, 0, 0, 2, 0};
    const std::vector<float> uv = {0, 0, 1, 0, 0, 1};
    ts::TsSceneView sv{};
    sv.tri_pos = pos.data();
    sv.tri_uv = uv.data();
    ts::TsSurface s{};
    s.geo_normal = ts::make_float3(0, 0, 1);
    ts::ts_surface_cone(&sv, &s, 0u, ts::make_float3(0, 0, -3), 0.1f);  // head-on; dir need not be unit
    EXPECT_FLOAT_EQ(s.uv_footprint, 0.05f);
    ts::ts_surface_cone(&sv, &s, 0u, ts::make_float3(std::sqrt(15.0f), 0, -1), 0.1f);  // cos θ = 1/4
    EXPECT_FLOAT_EQ(s.uv_footprint, 0.1f);
}

}  // namespace
}  // namespace tessera
