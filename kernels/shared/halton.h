/* Scrambled Halton points (Kocis & Whiten 1997: one fixed random permutation of the digits
 * per dimension) over a table the host builds (host/gi/halton.h, ScrambledHalton), so
 * that the host's light paths and the light-path kernel (shared/light_path_trace.h) draw
 * the same numbers: point i is the same in every frame and on every backend (docs/igi.md §3).
 *
 * Table layout, uint words from `h`:
 *   h[0]                 dimensions D
 *   h[1 + d]             base b_d of dimension d (the d-th prime), d < D
 *   h[1 + D + d]         offset from h of dimension d's permutation of {0..b_d − 1}
 *   h[offset + j]        the permutation's digit j */
#ifndef TS_HALTON_H
#define TS_HALTON_H
#include "shared/compat.h"

TS_NAMESPACE_BEGIN

#define TS_HALTON_DIMS 0
#define TS_HALTON_BASES 1

/* Component `dim` (< h[0]) of point `index`, in [0, 1]: the radical inverse lies in [0, 1)
 * and is rounded to float, which gives 1.0f within 2^-25 of 1 (as the host's double-to-float
 * cast always did: the project's sequence). Every digit position is permuted, the leading
 * zeros of the index too; positions past double precision add nothing, so the sum stops
 * below 1e-17. In double (the host's numbers bit for bit: the product and the sum are
 * separate statements, never contracted); devices without fp64 sum in float to 1e-8,
 * within a float's rounding of the double value. */
TS_INLINE float ts_halton_sample(TS_GLOBAL const uint* h, ulong index, uint dim) {
    uint dims = h[TS_HALTON_DIMS];
    uint b = h[TS_HALTON_BASES + dim];
    TS_GLOBAL const uint* perm = h + h[TS_HALTON_BASES + dims + dim];
#ifdef TS_HAS_DOUBLE
    double inv = 1.0 / (double)b, f = inv, r = 0.0;
    while (f > 1e-17) {
        double term = (double)perm[index % b] * f;
        r = r + term;
        index /= b;
        f *= inv;
    }
    double top = 0.99999999999999989; /* the largest double below 1 */
    return (float)(r < top ? r : top);
#else
    float inv = 1.0f / (float)b, f = inv, r = 0.0f;
    while (f > 1e-8f) {
        float term = (float)perm[index % b] * f;
        r = r + term;
        index /= b;
        f *= inv;
    }
    return r < 1.0f ? r : 1.0f;
#endif
}

TS_NAMESPACE_END
#endif /* TS_HALTON_H */
