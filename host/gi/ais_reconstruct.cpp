#include "gi/ais_reconstruct.h"

#include <array>
#include <bit>
#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/shared/ais_guidance.h"

namespace tessera {

void ais_reconstruct(const GeometryBuffer& g, const DiscontinuitySettings& s, const std::vector<float>& base,
                     const std::vector<double>& own_sum, const std::vector<uint64_t>& masks,
                     std::vector<float>& out) {
    discontinuity_filter(g, s, 3, base, out);
    const int w = g.width, h = g.height, n = s.tile;
    const std::array<ptrdiff_t, 64> offset = discontinuity_window_offsets(n, w);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                const size_t p = size_t(y) * w + x;
                const uint64_t mask = masks[p];
                if (std::popcount(mask) < 2) continue;  // the filter's value stands
                double sum[3] = {own_sum[3 * p], own_sum[3 * p + 1], own_sum[3 * p + 2]};
                int count = std::popcount(mask);
                // The set held by window position (row r, column c) is set_col[c] +
                // set_row[r]: the window's first position holds set column sx and row sy.
                const int sx = ts::ts_ais_window_origin(x, w, n), sy = ts::ts_ais_window_origin(y, h, n);
                const ptrdiff_t shift = ts::ts_discontinuity_shift(x, y, w, h, n);  // moved in at the border
                int set_col[8], set_row[8];
                for (int k = 0; k < n; ++k) {
                    set_col[k] = (sx + k) % n;
                    set_row[k] = n * ((sy + k) % n);
                }
                // The accepted positions in window order (outside the image: no bit).
                for (uint64_t b = discontinuity_window_mask(g, s, x, y); b; b &= b - 1) {
                    const int i = std::countr_zero(b);
                    if (mask >> (set_col[i % n] + set_row[i / n]) & 1) continue;  // p has its own
                    const size_t q = static_cast<size_t>(static_cast<ptrdiff_t>(p) + shift + offset[i]);
                    for (int j = 0; j < 3; ++j) sum[j] += base[3 * q + j];
                    ++count;
                }
                for (int j = 0; j < 3; ++j) out[3 * p + j] = static_cast<float>(sum[j] / count);
            }
    });
}

}  // namespace tessera
