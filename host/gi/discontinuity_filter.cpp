#include "gi/discontinuity_filter.h"

#include <bit>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/shared/discontinuity.h"

namespace tessera {
bool discontinuity_accepts(const GeometryBuffer& g, const DiscontinuitySettings& s, size_t p, size_t q) {
    const bool plane = !g.position.empty();
    auto at = [](const std::vector<float>& v, size_t i) { return ts::ts_f3_load(&v[3 * i]); };
    const ts::float3 none = ts::make_float3(0.0f, 0.0f, 0.0f);
    return ts::ts_discontinuity_accepts(g.depth[p], at(g.normal, p), plane ? at(g.position, p) : none, g.depth[q],
                                        at(g.normal, q), plane ? at(g.position, q) : none, plane, s.normal_cos,
                                        s.depth_rel) != 0;
}

void discontinuity_window(int n, int* lo, int* hi) { ts::ts_discontinuity_window(n, lo, hi); }

namespace {

uint64_t compute_window_mask(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y) {
    int lo, hi;
    discontinuity_window(s.tile, &lo, &hi);
    const size_t p = size_t(y) * g.width + x;
    uint64_t bits = 0;
    int i = 0;
    for (int dy = lo; dy <= hi; ++dy)
        for (int dx = lo; dx <= hi; ++dx, ++i) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= g.width || qy >= g.height) continue;
            const size_t q = size_t(qy) * g.width + qx;
            if (q == p || discontinuity_accepts(g, s, p, q)) bits |= 1ull << i;
        }
    return bits;
}

bool same_settings(const DiscontinuitySettings& a, const DiscontinuitySettings& b) {
    return a.tile == b.tile && a.normal_cos == b.normal_cos && a.depth_rel == b.depth_rel;
}

}  // namespace

void discontinuity_precompute(GeometryBuffer& g, const DiscontinuitySettings& s) {
    g.accepted.assign(size_t(g.width) * g.height, 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, g.height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < g.width; ++x) g.accepted[size_t(y) * g.width + x] = compute_window_mask(g, s, x, y);
    });
    g.accepted_for = s;
}

uint64_t discontinuity_window_mask(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y) {
    if (!g.accepted.empty() && same_settings(g.accepted_for, s)) return g.accepted[size_t(y) * g.width + x];
    return compute_window_mask(g, s, x, y);
}

void discontinuity_filter(const GeometryBuffer& g, const DiscontinuitySettings& s, int channels,
                          const std::vector<float>& in, std::vector<float>& out, std::vector<uint8_t>* accepted) {
    const int w = g.width, h = g.height, n = s.tile;
    int lo, hi;
    discontinuity_window(n, &lo, &hi);
    out.assign(in.size(), 0.0f);
    if (accepted) accepted->assign(size_t(w) * h, 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        std::vector<double> sum(channels);
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                const size_t p = size_t(y) * w + x;
                std::fill(sum.begin(), sum.end(), 0.0);
                // Window positions in increasing bit order: row by row, as the test ran.
                uint64_t bits = discontinuity_window_mask(g, s, x, y);
                const int count = std::popcount(bits);
                for (; bits; bits &= bits - 1) {
                    const int i = std::countr_zero(bits);
                    const size_t q = size_t(y + lo + i / n) * w + (x + lo + i % n);
                    for (int c = 0; c < channels; ++c) sum[c] += in[q * channels + c];
                }
                for (int c = 0; c < channels; ++c) out[p * channels + c] = static_cast<float>(sum[c] / count);
                if (accepted) (*accepted)[p] = static_cast<uint8_t>(count);
            }
    });
}

}  // namespace tessera
