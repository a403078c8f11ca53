#include "gi/ais_reconstruct.h"

#include <bit>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ais_schedule.h"

namespace tessera {

void ais_reconstruct(const GeometryBuffer& g, const DiscontinuitySettings& s, const std::vector<float>& base,
                     const std::vector<double>& own_sum, const std::vector<uint64_t>& masks,
                     std::vector<float>& out) {
    discontinuity_filter(g, s, 3, base, out);
    const int w = g.width, h = g.height, n = s.tile;
    int lo, hi;
    discontinuity_window(n, &lo, &hi);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                const size_t p = size_t(y) * w + x;
                const uint64_t mask = masks[p];
                if (std::popcount(mask) < 2) continue;  // the filter's value stands
                double sum[3] = {own_sum[3 * p], own_sum[3 * p + 1], own_sum[3 * p + 2]};
                int count = std::popcount(mask);
                const uint64_t accepted = discontinuity_window_mask(g, s, x, y);
                int i = 0;
                for (int dy = lo; dy <= hi; ++dy)
                    for (int dx = lo; dx <= hi; ++dx, ++i) {
                        if (!(accepted >> i & 1)) continue;  // outside the image, or rejected
                        const int qx = x + dx, qy = y + dy;
                        if (mask >> interleave_set(qx, qy, n) & 1) continue;  // p has its own
                        const size_t q = size_t(qy) * w + qx;
                        for (int j = 0; j < 3; ++j) sum[j] += base[3 * q + j];
                        ++count;
                    }
                for (int j = 0; j < 3; ++j) out[3 * p + j] = static_cast<float>(sum[j] / count);
            }
    });
}

}  // namespace tessera
