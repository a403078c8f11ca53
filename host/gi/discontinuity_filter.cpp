#include "gi/discontinuity_filter.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>

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

std::array<ptrdiff_t, 64> discontinuity_window_offsets(int n, int width) {
    static_assert(std::is_same_v<ptrdiff_t, long>, "ts_discontinuity_mean reads the offsets as long");
    std::array<ptrdiff_t, 64> offset{};
    for (int i = 0; i < n * n && i < 64; ++i) offset[i] = ts::ts_discontinuity_offset(n, width, i);
    return offset;
}

namespace {

// Pixel (x, y)'s mask computed now (shared/discontinuity.h, as the device resolve does).
uint64_t compute_window_mask(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y) {
    const bool plane = !g.position.empty();
    return ts::ts_discontinuity_mask(x, y, g.width, g.height, s.tile, g.depth.data(), g.normal.data(),
                                     plane ? g.position.data() : nullptr, 1, 3, plane, s.normal_cos, s.depth_rel);
}

bool same_settings(const DiscontinuitySettings& a, const DiscontinuitySettings& b) {
    return a.tile == b.tile && a.normal_cos == b.normal_cos && a.depth_rel == b.depth_rel;
}

// Pixel y·w + x's bit i of its window mask, for x in [x0, x1) of row y and window offset
// (dx, dy) at position i: one offset over a run of a row, a tight loop over consecutive
// pixels (the per-pixel, per-neighbour calls of compute_window_mask, with their bounds
// checks and vector lookups, took half again as long). The caller keeps (x + dx, y + dy)
// inside the image. Same test, same operands: the same bits. Plane: g has positions (the
// test's use_plane).
template <bool Plane>
void window_bits_run(const GeometryBuffer& g, const DiscontinuitySettings& s, int y, int x0, int x1, int dx, int dy,
                     int i, uint64_t* __restrict bits) {
    // Pointers to pixel p = (x0, y) and its neighbour q = p + (dx, dy); pixel j of the run
    // is element j of each.
    const ptrdiff_t p0 = static_cast<ptrdiff_t>(y) * g.width + x0;
    const ptrdiff_t q0 = p0 + static_cast<ptrdiff_t>(dy) * g.width + dx;
    const float* __restrict zp = g.depth.data() + p0;
    const float* __restrict zq = g.depth.data() + q0;
    const float* __restrict np = g.normal.data() + 3 * p0;
    const float* __restrict nq = g.normal.data() + 3 * q0;
    const float* __restrict xp = Plane ? g.position.data() + 3 * p0 : nullptr;
    const float* __restrict xq = Plane ? g.position.data() + 3 * q0 : nullptr;
    uint64_t* __restrict out = bits + x0;
    const uint64_t bit = 1ull << i;
    const float cos_min = s.normal_cos, depth_rel = s.depth_rel;
    const int count = x1 - x0;
    for (int j = 0; j < count; ++j) {
        const ts::float3 n_p = ts::make_float3(np[3 * j], np[3 * j + 1], np[3 * j + 2]);
        const ts::float3 n_q = ts::make_float3(nq[3 * j], nq[3 * j + 1], nq[3 * j + 2]);
        ts::float3 x_p = ts::make_float3(0.0f, 0.0f, 0.0f), x_q = x_p;
        if constexpr (Plane) {
            x_p = ts::make_float3(xp[3 * j], xp[3 * j + 1], xp[3 * j + 2]);
            x_q = ts::make_float3(xq[3 * j], xq[3 * j + 1], xq[3 * j + 2]);
        }
        const int ok = ts::ts_discontinuity_accepts(zp[j], n_p, x_p, zq[j], n_q, x_q, Plane, cos_min, depth_rel);
        out[j] |= bit & (0ull - static_cast<uint64_t>(ok != 0));
    }
}

// The filter of rows [y0, y1) with C channels: each pixel's mean over its accepted window
// positions (ts_discontinuity_mean, the device resolve's too).
template <int C>
void filter_rows(const GeometryBuffer& g, const DiscontinuitySettings& s, bool precomputed, const float* __restrict in,
                 float* __restrict out, uint8_t* accepted, int y0, int y1) {
    const int w = g.width;
    const std::array<ptrdiff_t, 64> offset = discontinuity_window_offsets(s.tile, w);
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t p = size_t(y) * w + x;
            const uint64_t bits = precomputed ? g.accepted[p] : compute_window_mask(g, s, x, y);
            ts::ts_discontinuity_mean(in, C, C, p, offset.data(), bits, out + p * C);
            if (accepted) accepted[p] = static_cast<uint8_t>(std::popcount(bits));
        }
}

}  // namespace

void discontinuity_precompute(GeometryBuffer& g, const DiscontinuitySettings& s) {
    const int w = g.width, h = g.height;
    int lo, hi;
    discontinuity_window(s.tile, &lo, &hi);
    g.accepted.assign(size_t(w) * h, 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            uint64_t* bits = &g.accepted[size_t(y) * w];
            int i = 0;
            for (int dy = lo; dy <= hi; ++dy)
                for (int dx = lo; dx <= hi; ++dx, ++i) {
                    if (y + dy < 0 || y + dy >= h) continue;
                    if (dx == 0 && dy == 0) {  // p accepts itself
                        for (int x = 0; x < w; ++x) bits[x] |= 1ull << i;
                        continue;
                    }
                    const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
                    if (g.position.empty())
                        window_bits_run<false>(g, s, y, x0, x1, dx, dy, i, bits);
                    else
                        window_bits_run<true>(g, s, y, x0, x1, dx, dy, i, bits);
                }
        }
    });
    g.accepted_for = s;
}

uint64_t discontinuity_window_mask(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y) {
    if (!g.accepted.empty() && same_settings(g.accepted_for, s)) return g.accepted[size_t(y) * g.width + x];
    return compute_window_mask(g, s, x, y);
}

void discontinuity_filter(const GeometryBuffer& g, const DiscontinuitySettings& s, int channels,
                          const std::vector<float>& in, std::vector<float>& out, std::vector<uint8_t>* accepted) {
    if (channels != 1 && channels != 3)
        throw std::invalid_argument("discontinuity_filter: 1 or 3 channels, not " + std::to_string(channels));
    const int w = g.width, h = g.height;
    out.resize(in.size());  // every pixel is written: no zero fill
    if (accepted) accepted->resize(size_t(w) * h);
    const bool precomputed = !g.accepted.empty() && same_settings(g.accepted_for, s);
    uint8_t* acc = accepted ? accepted->data() : nullptr;
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        if (channels == 1)
            filter_rows<1>(g, s, precomputed, in.data(), out.data(), acc, rows.begin(), rows.end());
        else
            filter_rows<3>(g, s, precomputed, in.data(), out.data(), acc, rows.begin(), rows.end());
    });
}

}  // namespace tessera
