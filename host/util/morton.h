// The Z-order (Morton) index of a 2D grid cell.
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

}  // namespace tessera
