/* Instant caching, the record-VPL work that needs no tracer (docs/instant-caching.md §3):
 * a record's surface and the gather sum of its E over the VPLs its visibility row marks
 * visible. The pair and gather kernels (shared/ic.h) call these; host code may too. */
#ifndef TS_IC_GATHER_H
#define TS_IC_GATHER_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout.h"
#include "shared/medium.h"
#include "shared/vpl.h"

TS_NAMESPACE_BEGIN

/* The surface a record was made at, from its G-buffer entry (TS_IC_GBUF_FLOATS): what
 * ts_vpl_geometry reads. */
TS_INLINE TsSurface ts_ic_record_surface(TS_GLOBAL const float* g) {
    TsSurface s;
    s.position = ts_f3_load(g + TS_IC_GBUF_POSITION);
    s.geo_normal = ts_f3_load(g + TS_IC_GBUF_GEO_NORMAL);
    s.shading_normal = ts_f3_load(g + TS_IC_GBUF_NORMAL);
    s.uv = make_float2(0.0f, 0.0f);
    s.material = 0u;
    s.front_face = 1;
    s.origin = ts_f3_load(g + TS_IC_GBUF_ORIGIN);
    s.pos_scale = g[TS_IC_GBUF_POS_SCALE];
    return s;
}

/* E = (1/π) Σ_j C_j T_j min(G_j, b) over the `count` VPLs (in order) whose bit in the
 * mask `visible` (TS_IC_VISIBLE_WORDS(count) uints, layout.h) is set, and the harmonic
 * mean distance to them (+inf for none): the
 * radius estimate of docs/instant-caching.md §4 that needs no extra rays. Sums in double
 * where the device has it (bit-identical to the host's former double sums), else in
 * compensated float (shared/vpl.h). Writes TS_IC_GATHER_FLOATS to out. */
TS_INLINE void ts_ic_gather(const TsSurface* s, TS_GLOBAL const uint* visible, uint count, TS_GLOBAL const float* vpls,
                            const TsMedium* med, float b, float* out) {
#ifdef TS_HAS_DOUBLE
    TsDouble3 sum = {0.0, 0.0, 0.0};
    double inv_dist = 0.0;
#else
    TsSum3 sum = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    float inv_dist = 0.0f, inv_dist_c = 0.0f;
#endif
    uint seen = 0u;
    /* The shadow ray matters only for the medium's transmittance: without a medium it is
     * not built, and the transmittance is 1 as ts_shadow_transmittance would return (same
     * sums; a tic re-sum of 18k records on the Cornell box, Embree: 28 → 24.5 ms). */
    float3 org = ts_offset_ray_origin(s->origin, s->geo_normal, s->pos_scale);
    for (uint j = 0; j < count; ++j) {
        if (!((visible[j >> 5] >> (j & 31u)) & 1u)) continue;
        TS_GLOBAL const float* v = vpls + (size_t)TS_VPL_FLOATS * j;
        float g = ts_vpl_geometry_term(s, v, b, med->g);
        if (!(g > 0.0f)) continue;
        float3 tr = med->present ? ts_shadow_transmittance(med, ts_vpl_shadow_ray(org, v)) : make_float3(1.0f, 1.0f, 1.0f);
        float3 d = ts_f3_load(v + TS_VPL_POSITION) - s->position;
#ifdef TS_HAS_DOUBLE
        ts_vpl_gather_add_double(&sum, v, tr, g);
        inv_dist += 1.0 / sqrt((double)dot(d, d));
#else
        ts_vpl_gather_add_compensated(&sum, v, tr, g);
        ts_sum_compensated_add(&inv_dist, &inv_dist_c, 1.0f / sqrt(dot(d, d)));
#endif
        ++seen;
    }
#ifdef TS_HAS_DOUBLE
    float3 e = ts_vpl_gather_result_double(sum);
#else
    float3 e = ts_vpl_gather_result_compensated(sum);
    inv_dist += inv_dist_c;
#endif
    ts_f3_store(out + TS_IC_GATHER_E, e);
    out[TS_IC_GATHER_HARMONIC] = seen > 0u && inv_dist > 0 ? (float)(seen / inv_dist) : TS_INF;
}

TS_NAMESPACE_END

#endif /* TS_IC_GATHER_H */
