#include "gi/discontinuity_filter.h"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace tessera {
bool discontinuity_accepts(const GeometryBuffer& g, const DiscontinuitySettings& s, size_t p, size_t q) {
    const float zp = g.depth[p], zq = g.depth[q];
    const bool mp = !std::isfinite(zp), mq = !std::isfinite(zq);
    if (mp || mq) return mp && mq;
    const float* np = &g.normal[3 * p];
    const float* nq = &g.normal[3 * q];
    const float cos = np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2];
    if (cos < s.normal_cos) return false;
    if (g.position.empty()) return std::abs(zp - zq) <= s.depth_rel * zp;
    const float* xp = &g.position[3 * p];
    const float* xq = &g.position[3 * q];
    const float plane = np[0] * (xq[0] - xp[0]) + np[1] * (xq[1] - xp[1]) + np[2] * (xq[2] - xp[2]);
    return std::abs(plane) <= s.depth_rel * zp;
}

void discontinuity_window(int n, int* lo, int* hi) {
    *lo = n % 2 ? -(n - 1) / 2 : -n / 2;
    *hi = *lo + n - 1;
}

void discontinuity_filter(const GeometryBuffer& g, const DiscontinuitySettings& s, int channels,
                          const std::vector<float>& in, std::vector<float>& out, std::vector<uint8_t>* accepted) {
    const int w = g.width, h = g.height;
    int lo, hi;
    discontinuity_window(s.tile, &lo, &hi);
    out.assign(in.size(), 0.0f);
    if (accepted) accepted->assign(size_t(w) * h, 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        std::vector<double> sum(channels);
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                const size_t p = size_t(y) * w + x;
                std::fill(sum.begin(), sum.end(), 0.0);
                int count = 0;
                for (int dy = lo; dy <= hi; ++dy)
                    for (int dx = lo; dx <= hi; ++dx) {
                        const int qx = x + dx, qy = y + dy;
                        if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                        const size_t q = size_t(qy) * w + qx;
                        if (q != p && !discontinuity_accepts(g, s, p, q)) continue;
                        for (int c = 0; c < channels; ++c) sum[c] += in[q * channels + c];
                        ++count;
                    }
                for (int c = 0; c < channels; ++c) out[p * channels + c] = static_cast<float>(sum[c] / count);
                if (accepted) (*accepted)[p] = static_cast<uint8_t>(count);
            }
    });
}

}  // namespace tessera
