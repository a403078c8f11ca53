/* The discontinuity buffer's window and acceptance test (Keller's thesis 1998, as IGI
 * uses it, Wald et al. 2002 §4; thresholds and their reasons in docs/igi.md §8), shared by
 * the host's filter (host/gi/discontinuity_filter.cpp: AIS, ic, and igi on the host) and
 * the device's per-pixel resolve (shared/igi_resolve.h). Tracer-free.
 *
 * Window: tile edge n, offsets lo..hi = -(n-1)/2..(n-1)/2 for odd n, -n/2..n/2-1 for
 * even n, so every n×n window holds each interleave set (x mod n, y mod n) once.
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

TS_NAMESPACE_END
#endif /* TS_DISCONTINUITY_H */
