// The Z-order (Morton) index of a 2D or 3D grid cell.
#pragma once
#include <cstdint>

namespace tessera {

/// The Z-order index of grid cell (x, y), x and y below 2^16: their bits interleaved (x in
/// the even bits), so cells close in the index are close on the grid; 2^(2k) consecutive
/// indices from a multiple of 2^(2k) are a 2^k × 2^k block (Morton 1966).
inline uint32_t morton2(uint32_t x, uint32_t y) {
    auto spread = [](uint32_t v) {
        v &= 0xffffu;
        v = (v | v << 8) & 0x00ff00ffu;
        v = (v | v << 4) & 0x0f0f0f0fu;
        v = (v | v << 2) & 0x33333333u;
        return (v | v << 1) & 0x55555555u;
    };
    return spread(x) | spread(y) << 1;
}

/// The Z-order index of 3D grid cell (x, y, z), each below 2^21: their bits interleaved
/// (x in bits 0, 3, 6, ...), 63 bits in all.
inline uint64_t morton3(uint32_t x, uint32_t y, uint32_t z) {
    auto spread = [](uint64_t v) {
        v &= 0x1fffffull;
        v = (v | v << 32) & 0x1f00000000ffffull;
        v = (v | v << 16) & 0x1f0000ff0000ffull;
        v = (v | v << 8) & 0x100f00f00f00f00full;
        v = (v | v << 4) & 0x10c30c30c30c30c3ull;
        return (v | v << 2) & 0x1249249249249249ull;
    };
    return spread(x) | spread(y) << 1 | spread(z) << 2;
}

}  // namespace tessera
