/* The discontinuity buffer's window and acceptance test (Keller's thesis 1998, as IGI
 * uses it, Wald et al. 2002 §4; thresholds and their reasons in docs/igi.md §8), shared by
 * the host's filter (host/gi/discontinuity_filter.cpp: AIS, ic, and igi on the host) and
 * the device's per-pixel resolve (shared/igi_resolve.h). Tracer-free.
 *
 * Window: tile edge n, offsets lo..hi = -(n-1)/2..(n-1)/2 for odd n, -n/2..n/2-1 for
 * even n, so every n×n window holds each interleave set (x mod n, y mod n) once; where
 * that window would cross the image's border it is moved inward, n consecutive pixels
 * still holding every set (ts_discontinuity_lo_at; docs/igi.md §8).
 * Neighbour q is accepted by p when n_p · n_q >= cos_min and |n_p · (x_q - x_p)| <=
 * depth_rel · z_p (the plane distance; or |z_p - z_q| where no positions are kept);
 * pixels whose camera rays escaped (z = +inf) accept only each other. */
#ifndef TS_DISCONTINUITY_H
#define TS_DISCONTINUITY_H
#include "shared/compat.h"

TS_NAMESPACE_BEGIN

/* The window offsets lo..hi (inclusive, on each axis) for tile edge n >= 1. */
TS_INLINE void ts_discontinuity_window(int n, int* lo, int* hi) {
    *lo = n % 2 ? -(n - 1) / 2 : -n / 2;
    *hi = *lo + n - 1;
}

/* The first window offset on one axis for pixel coordinate v of an axis `size` pixels
 * long, tile edge n: ts_discontinuity_window's lo, moved inward where the window would
 * cross the border, so that a border pixel's window, too, holds every interleave set (a
 * window clipped by the image held 6 of 9 sets at a border, whose light samples cover only
 * part of the light: a frame's border rows came out 8% bright or 18% dark). An axis
 * shorter than n: -v (the window starts at the image's first pixel and the image clips it). */
TS_INLINE int ts_discontinuity_lo_at(int v, int size, int n) {
    int lo, hi;
    ts_discontinuity_window(n, &lo, &hi);
    if (v + hi >= size) lo = size - n - v;
    if (v + lo < 0) lo = -v;
    return lo;
}

/* The pixel index shift of pixel (x, y)'s window (w × h image, tile edge n) from the
 * centred one: window position i of p is pixel p + shift + ts_discontinuity_offset(n, w, i). */
TS_INLINE long ts_discontinuity_shift(int x, int y, int w, int h, int n) {
    int lo, hi;
    ts_discontinuity_window(n, &lo, &hi);
    return (long)(ts_discontinuity_lo_at(y, h, n) - lo) * w + (ts_discontinuity_lo_at(x, w, n) - lo);
}

/* The window position of offset (dx, dy) in a window of edge n whose first offsets are
 * lx, ly (ts_discontinuity_lo_at of the pixel's x and y), or -1 where it does not hold it. */
TS_INLINE int ts_discontinuity_position_in(int lx, int ly, int n, int dx, int dy) {
    if (dx < lx || dx >= lx + n || dy < ly || dy >= ly + n) return -1;
    return (dy - ly) * n + (dx - lx);
}

/* The window position (as in ts_discontinuity_mask's bits) of offset (dx, dy) from pixel
 * (x, y), or -1 where the pixel's window does not hold that offset. */
TS_INLINE int ts_discontinuity_position(int x, int y, int w, int h, int n, int dx, int dy) {
    return ts_discontinuity_position_in(ts_discontinuity_lo_at(x, w, n), ts_discontinuity_lo_at(y, h, n), n, dx, dy);
}

/* Whether p (depth zp, unit normal np, position xp) accepts q; use_plane 0 tests depths
 * instead of the plane distance. Written out term by term so C++ and OpenCL round alike. */
TS_INLINE int ts_discontinuity_accepts(float zp, float3 np, float3 xp, float zq, float3 nq, float3 xq,
                                       int use_plane, float cos_min, float depth_rel) {
    int mp = !isfinite(zp), mq = !isfinite(zq);
    if (mp || mq) return mp && mq;
    float c = np.x * nq.x + np.y * nq.y + np.z * nq.z;
    if (c < cos_min) return 0;
    if (!use_plane) return fabs(zp - zq) <= depth_rel * zp;
    float plane = np.x * (xq.x - xp.x) + np.y * (xq.y - xp.y) + np.z * (xq.z - xp.z);
    return fabs(plane) <= depth_rel * zp;
}

/* Window position i of tile edge n (row by row from (lo, lo): i = (dy - lo)·n + (dx - lo))
 * of the centred window as a pixel index offset in an image `width` pixels wide: q = p +
 * offset (+ ts_discontinuity_shift for a window moved in at the border). */
TS_INLINE long ts_discontinuity_offset(int n, int width, int i) {
    int lo, hi;
    ts_discontinuity_window(n, &lo, &hi);
    return (long)(lo + i / n) * width + (lo + i % n);
}

/* Pixel (x, y)'s window positions (tile edge n <= 8, w × h image) as pixel index offsets
 * from p, offset[i] for i < n², its border shift included: q = p + offset[i]. */
TS_INLINE void ts_discontinuity_offsets_at(int x, int y, int w, int h, int n, long* offset) {
    const long shift = ts_discontinuity_shift(x, y, w, h, n);
    for (int i = 0; i < n * n; ++i) offset[i] = ts_discontinuity_offset(n, w, i) + shift;
}

/* Pixel (x, y)'s accepted window positions for tile edge n (<= 8) in a w × h image: bit i
 * (i = (dy - ly)·n + (dx - lx), lx and ly ts_discontinuity_lo_at's) set where window
 * position i lies in the image and p accepts the pixel there (p accepts itself). Pixel q's depth is depth[q · depth_stride], its unit normal and
 * position normal[q · vec_stride + 0..2] and position[...] (not read when use_plane is
 * 0), in scene units. */
TS_INLINE ulong ts_discontinuity_mask(int x, int y, int w, int h, int n, TS_GLOBAL const float* depth,
                                      TS_GLOBAL const float* normal, TS_GLOBAL const float* position,
                                      uint depth_stride, uint vec_stride, int use_plane, float cos_min,
                                      float depth_rel) {
    const int lx = ts_discontinuity_lo_at(x, w, n), ly = ts_discontinuity_lo_at(y, h, n);
    const size_t p = (size_t)y * (size_t)w + (size_t)x;
    const float zp = depth[p * depth_stride];
    const float3 np = ts_f3_load(normal + p * vec_stride);
    const float3 none = make_float3(0.0f, 0.0f, 0.0f);
    const float3 xp = use_plane ? ts_f3_load(position + p * vec_stride) : none;
    ulong bits = 0ul;
    int i = 0;
    for (int dy = ly; dy < ly + n; ++dy)
        for (int dx = lx; dx < lx + n; ++dx, ++i) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const size_t q = (size_t)qy * (size_t)w + (size_t)qx;
            if (q == p || ts_discontinuity_accepts(zp, np, xp, depth[q * depth_stride],
                                                   ts_f3_load(normal + q * vec_stride),
                                                   use_plane ? ts_f3_load(position + q * vec_stride) : none,
                                                   use_plane, cos_min, depth_rel))
                bits |= (ulong)1 << i;
        }
    return bits;
}

/* The window mean of pixel p: out[c] for c < channels (1..9) is the mean over the window
 * positions in `bits` (not 0; as ts_discontinuity_mask sets them) of in[q · stride + c],
 * q = p + offset[i] (ts_discontinuity_offsets_at's; or `p` p's index plus its
 * ts_discontinuity_shift and offset[i] = ts_discontinuity_offset(n, width, i)). Summed in
 * increasing bit order (the window's row order) in double where the device has it, so
 * host and device agree bit for bit, else with compensation. */
TS_INLINE void ts_discontinuity_mean(TS_GLOBAL const float* in, uint stride, int channels, size_t p,
                                     const long* offset, ulong bits, float* out) {
    const int count = ts_popcount64(bits);
#ifdef TS_HAS_DOUBLE
    double sum[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
#else
    float sum[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, comp[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
#endif
    for (; bits != 0ul; bits &= bits - 1ul) {
        TS_GLOBAL const float* v = in + (size_t)((long)p + offset[ts_ctz64(bits)]) * stride;
        for (int c = 0; c < channels; ++c) {
#ifdef TS_HAS_DOUBLE
            sum[c] += v[c];
#else
            ts_sum_compensated_add(&sum[c], &comp[c], v[c]);
#endif
        }
    }
    for (int c = 0; c < channels; ++c) {
#ifdef TS_HAS_DOUBLE
        out[c] = (float)(sum[c] / count);
#else
        out[c] = (sum[c] + comp[c]) / (float)count;
#endif
    }
}

TS_NAMESPACE_END
#endif /* TS_DISCONTINUITY_H */
