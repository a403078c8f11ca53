/* Instant caching (Debattista, Dubla et al., "Instant Caching for Interactive Global
 * Illumination", CGF 2009): an irradiance cache (Ward, Rubinstein & Clear 1988) whose
 * records gather indirect light from the VPLs. This file holds what the kernels and the
 * host share: the weight of a record and the octree lookup that interpolates. Placement, gathering and the temporal update are host code
 * (host/gi/irradiance_cache.h, instant_cache.h); docs/instant-caching.md is our reading.
 *
 * Weight (Ward 1988, shifted): with ε(x, n) = ‖x − x_i‖ / R_i + sqrt(1 − n·n_i), a record
 * is usable at (x, n) iff ε < a (Ward's w = 1/ε > 1/a), and it is weighted by
 *   w_i = 1/ε − 1/a,
 * not Ward's 1/ε: the shifted weight falls to 0 at the edge of the record's validity, so
 * the interpolated irradiance has no seams where a record stops counting (with 1/ε a
 * record enters the sum at weight 1/a). ε is floored at 1e-4·a, bounding w at 1e4/a for a
 * query on the record itself. A record lying in front of x, (x − x_i)·(n + n_i)/2 < −0.01·R_i,
 * is rejected (Ward's test, with a tolerance relative to the record's radius so it does
 * not depend on the scene's scale). No gradients: interpolation is the weighted mean.
 *
 * The octree (layout_ic.h TS_IC_NODE_FLOATS) stores a record in every node of one level
 * whose box meets the bounding box of its validity sphere (radius a·R_i, the largest
 * distance at which ε < a); that level is the deepest whose half edge is still ≥ a·R_i.
 * A lookup walks from the root to the leaf containing x and tests the records of each
 * node on the way: any record usable at x is met, since its level's node containing x
 * meets its sphere. The walk reads only; the host inserts between dispatches. */
#ifndef TS_IC_LOOKUP_H
#define TS_IC_LOOKUP_H
#include "shared/compat.h"
#include "shared/layout_ic.h"
#include "shared/layout_rays.h"

TS_NAMESPACE_BEGIN

/* The shifted Ward weight of `record` (TS_IC_RECORD_FLOATS) at (x, n) for error bound a;
 * 0 when the record is not usable there. */
TS_INLINE float ts_ic_weight(TS_GLOBAL const float* record, float3 x, float3 n, float a) {
    float3 xi = ts_f3_load(record + TS_IC_RECORD_POSITION);
    float radius = record[TS_IC_RECORD_RADIUS];
    float3 d = x - xi;
    /* Most records a lookup meets lie farther than a·radius, where eps >= a: rejected
     * first, without the normal and the two square roots. The 1e-3 margin dwarfs the
     * rounding of either form, so a record near the limit goes on to the exact test below
     * and the result is the same as without this line. */
    float far = a * radius;
    if (dot(d, d) > far * far * 1.001f) return 0.0f;
    float3 ni = ts_f3_load(record + TS_IC_RECORD_NORMAL);
    if (dot(d, n + ni) * 0.5f < -0.01f * radius) return 0.0f;
    float eps = length(d) / radius + sqrt(fmax(0.0f, 1.0f - dot(n, ni)));
    if (!(eps < a)) return 0.0f;
    return 1.0f / fmax(eps, 1e-4f * a) - 1.0f / a;
}

/* The child of `node` (TS_IC_NODE_FLOATS) that contains x, or -1 where it has none there
 * (a leaf, or an octant left out because it held nothing: layout_ic.h). */
TS_INLINE int ts_ic_child(TS_GLOBAL const float* N, float3 x) {
    uint child = as_uint(N[TS_IC_NODE_CHILD]);
    if (child == 0u) return -1;
    TS_GLOBAL const float* c = N + TS_IC_NODE_CENTRE;
    uint octant = (x.x >= c[0] ? 1u : 0u) + (x.y >= c[1] ? 2u : 0u) + (x.z >= c[2] ? 4u : 0u);
    uint mask = as_uint(N[TS_IC_NODE_MASK]);
    if (!((mask >> octant) & 1u)) return -1;
    return (int)(child + (uint)ts_popcount64((ulong)(mask & ((1u << octant) - 1u))));
}

/* Interpolated E at (x, n) from the octree: writes Σ w_i E_i / Σ w_i to *e (0 when no
 * record is usable) and returns Σ w_i. Sums run in the walk's order (root first, each
 * node's records in reference order), the same on every backend. */
TS_INLINE float ts_ic_interpolate(TS_GLOBAL const float* nodes, TS_GLOBAL const uint* refs,
                                  TS_GLOBAL const float* records, float3 x, float3 n, float a, float3* e) {
    float3 sum = make_float3(0.0f, 0.0f, 0.0f);
    float wsum = 0.0f;
    uint node = 0u;
    for (int depth = 0; depth <= TS_IC_MAX_DEPTH; ++depth) {
        TS_GLOBAL const float* N = nodes + (size_t)node * TS_IC_NODE_FLOATS;
        uint first = as_uint(N[TS_IC_NODE_FIRST]), count = as_uint(N[TS_IC_NODE_COUNT]);
        for (uint r = first; r < first + count; ++r) {
            TS_GLOBAL const float* rec = records + (size_t)refs[r] * TS_IC_RECORD_FLOATS;
            float w = ts_ic_weight(rec, x, n, a);
            if (w > 0.0f) {
                sum += ts_f3_load(rec + TS_IC_RECORD_E) * w;
                wsum += w;
            }
        }
        int next = ts_ic_child(N, x);
        if (next < 0) break;
        node = (uint)next;
    }
    *e = wsum > 0.0f ? sum / wsum : sum;
    return wsum;
}

/* Whether some record is usable at (x, n) with error bound a: ts_ic_interpolate's Σ w > 0,
 * decided without the sums. Weights are never negative (a NaN weight counts in neither),
 * so Σ w > 0 exactly when one weight is positive, and the walk stops at the first. The
 * placement's coverage test (host/gi/instant_cache.cpp) asks only this, for every pixel
 * of its finest grid. */
TS_INLINE int ts_ic_covered(TS_GLOBAL const float* nodes, TS_GLOBAL const uint* refs, TS_GLOBAL const float* records,
                            float3 x, float3 n, float a) {
    uint node = 0u;
    for (int depth = 0; depth <= TS_IC_MAX_DEPTH; ++depth) {
        TS_GLOBAL const float* N = nodes + (size_t)node * TS_IC_NODE_FLOATS;
        uint first = as_uint(N[TS_IC_NODE_FIRST]), count = as_uint(N[TS_IC_NODE_COUNT]);
        for (uint r = first; r < first + count; ++r)
            if (ts_ic_weight(records + (size_t)refs[r] * TS_IC_RECORD_FLOATS, x, n, a) > 0.0f) return 1;
        int next = ts_ic_child(N, x);
        if (next < 0) break;
        node = (uint)next;
    }
    return 0;
}

/* Interpolation for pixel p of the G-buffer: writes TS_IC_INTERP_FLOATS values (layout_ic.h):
 * E and Σ w, both 0 where no record is usable or the pixel has no surface. */
TS_INLINE void ts_ic_interpolate_pixel(TS_GLOBAL const float* gbuffer, TS_GLOBAL const float* nodes,
                                       TS_GLOBAL const uint* refs, TS_GLOBAL const float* records, float a,
                                       uint p, float* out) {
    TS_GLOBAL const float* g = gbuffer + (size_t)p * TS_IC_GBUF_FLOATS;
    for (int i = 0; i < TS_IC_INTERP_FLOATS; ++i) out[i] = 0.0f;
    if (as_uint(g[TS_IC_GBUF_PRIM]) == TS_NO_HIT) return;
    float3 e;
    out[TS_IC_INTERP_WEIGHT] = ts_ic_interpolate(nodes, refs, records, ts_f3_load(g + TS_IC_GBUF_POSITION),
                                                 ts_f3_load(g + TS_IC_GBUF_NORMAL), a, &e);
    ts_f3_store(out + TS_IC_INTERP_E, e);
}

TS_NAMESPACE_END

#endif /* TS_IC_LOOKUP_H */
