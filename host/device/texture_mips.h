// Mip-map chains of the scene's textures, the texture pyramid that the shading code's
// cone-filtered lookup (kernels/shared/material.h ts_texture_lookup) reads.
#pragma once
#include <cstdint>
#include <vector>

namespace tessera {

/// Number of mip levels of a w×h texture: level l is max(1, w >> l) × max(1, h >> l),
/// down to 1×1 (floor(log2(max(w, h))) + 1 levels). w, h >= 1.
uint32_t mip_level_count(uint32_t w, uint32_t h);

/// The full chain of an RGBA8 texture (sRGB-encoded RGB, linear alpha, R in the low byte,
/// row-major, row 0 at the top; w·h texels), levels one after another from level 0 (the
/// input itself), in the layout of kernels/shared/layout_scene.h (textures). Each texel of level
/// l+1 is the mean of the 2×2 texels (2x..2x+1, 2y..2y+1) of level l, averaged in linear
/// light (the decode is ts_srgb_table, the one the kernels use) and encoded back to the
/// 8-bit value whose decode is nearest, so a flat texture stays bit-for-bit flat. A level
/// of odd size drops its last row or column from the average (the box filter of OpenGL's
/// glGenerateMipmap on non-power-of-two textures, which is allowed to do the same);
/// a dimension of 1 repeats its one texel. Throws std::invalid_argument when w·h does not
/// match the texel count or a dimension is 0.
std::vector<uint32_t> build_mip_chain(const std::vector<uint32_t>& rgba8, uint32_t w, uint32_t h);

/// The 8-bit sRGB code whose decode (ts_srgb_table) is nearest to the linear value v;
/// v is clamped to [0, 1].
uint32_t encode_srgb8(float v);

}  // namespace tessera
