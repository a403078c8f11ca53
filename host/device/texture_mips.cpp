#include "device/texture_mips.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "kernels/shared/srgb_table.h"

namespace tessera {
namespace {

// Linear RGB and alpha of texel (x, y) of a level w texels wide.
void decode(const uint32_t* level, uint32_t w, uint32_t x, uint32_t y, float* rgba) {
    const uint32_t t = level[size_t(y) * w + x];
    for (int c = 0; c < 3; ++c) rgba[c] = ts::ts_srgb_table[(t >> (8 * c)) & 0xffu];
    rgba[3] = static_cast<float>(t >> 24) / 255.0f;
}

uint32_t encode(const float* rgba) {
    uint32_t t = 0;
    for (int c = 0; c < 3; ++c) t |= encode_srgb8(rgba[c]) << (8 * c);
    const float a = std::clamp(rgba[3], 0.0f, 1.0f) * 255.0f + 0.5f;
    return t | (static_cast<uint32_t>(a) << 24);
}

// Level l+1 from level l (sw × sh texels).
std::vector<uint32_t> half_level(const uint32_t* src, uint32_t sw, uint32_t sh) {
    const uint32_t w = std::max(1u, sw >> 1), h = std::max(1u, sh >> 1);
    std::vector<uint32_t> out;
    out.reserve(size_t(w) * h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float sum[4] = {}, t[4];
            for (uint32_t dy = 0; dy < 2; ++dy)
                for (uint32_t dx = 0; dx < 2; ++dx) {
                    decode(src, sw, std::min(2 * x + dx, sw - 1), std::min(2 * y + dy, sh - 1), t);
                    for (int c = 0; c < 4; ++c) sum[c] += t[c];
                }
            for (float& s : sum) s *= 0.25f;
            out.push_back(encode(sum));
        }
    return out;
}

}  // namespace

uint32_t mip_level_count(uint32_t w, uint32_t h) {
    uint32_t levels = 1;
    while (w > 1 || h > 1) {
        w = std::max(1u, w >> 1);
        h = std::max(1u, h >> 1);
        ++levels;
    }
    return levels;
}

uint32_t encode_srgb8(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    const float* table = ts::ts_srgb_table;
    const float* hi = std::lower_bound(table, table + 256, v);  // first code decoding to >= v
    if (hi == table) return 0;
    if (hi == table + 256) return 255;
    return (*hi - v) < (v - hi[-1]) ? static_cast<uint32_t>(hi - table) : static_cast<uint32_t>(hi - table - 1);
}

std::vector<uint32_t> build_mip_chain(const std::vector<uint32_t>& rgba8, uint32_t w, uint32_t h) {
    if (w == 0 || h == 0 || rgba8.size() != size_t(w) * h)
        throw std::invalid_argument("build_mip_chain: " + std::to_string(rgba8.size()) + " texels for a " +
                                    std::to_string(w) + "x" + std::to_string(h) + " texture");
    std::vector<uint32_t> out = rgba8, level = rgba8;
    for (uint32_t sw = w, sh = h; sw > 1 || sh > 1; sw = std::max(1u, sw >> 1), sh = std::max(1u, sh >> 1)) {
        level = half_level(level.data(), sw, sh);
        out.insert(out.end(), level.begin(), level.end());
    }
    return out;
}

}  // namespace tessera
