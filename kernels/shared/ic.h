/* Instant caching, the kernels' side: the interpolation kernel's per-pixel part, the record-VPL
 * pair kernel (one shadow ray per pair) and the gather kernel (one record's E). The record
 * weight and the octree lookup are in shared/ic_lookup.h, the gather sum in
 * shared/ic_gather.h (both also compiled into host code that has no tracer). The host
 * decides which pairs and records need work (placement, the temporal update's tests) and
 * builds the item lists (host/gi/ic_gather.cpp); the records' surfaces, the VPLs (one set)
 * and the visibility rows are named inputs. */
#ifndef TS_IC_H
#define TS_IC_H
#include "shared/compat.h"
#include "shared/ic_gather.h"
#include "shared/ic_lookup.h"
#include "shared/ic_residual.h"
#include "shared/frame.h"
#include "shared/layout_ic.h"
#include "shared/layout_igi.h"
#include "shared/layout_scene.h"

TS_NAMESPACE_BEGIN

/* The interpolation kernel's pixel (px, py): the cache in sv's named inputs (ic_gbuffer,
 * ic_nodes, ic_refs, ic_records) with Ward's a = f->ic_error_bound, and the clamp's
 * residual for b = f->igi_g_clamp (shared/ic_residual.h; +inf: none); TS_IC_INTERP_FLOATS. */
TS_INLINE void ts_ic_interpolate_kernel_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                              uint px, uint py, float* out) {
    uint p = py * f->width + px;
    ts_ic_interpolate_pixel(sv->ic_gbuffer, sv->ic_nodes, sv->ic_refs, sv->ic_records, f->ic_error_bound, p, out);
    TS_GLOBAL const float* g = sv->ic_gbuffer + (size_t)p * TS_IC_GBUF_FLOATS;
    if (as_uint(g[TS_IC_GBUF_PRIM]) == TS_NO_HIT) return;
    TsSurface x = ts_ic_record_surface(g);
    float3 e = make_float3(out[TS_IC_INTERP_E], out[TS_IC_INTERP_E + 1], out[TS_IC_INTERP_E + 2]);
    ts_f3_store(out + TS_IC_INTERP_RESIDUAL, ts_ic_clamp_residual(sv, tracer, f, &x, e, p));
}

/* Pair i's VPL (index into the Vpls input): from the item list, or in a pair grid
 * (f->ic_pair_grid = n > 0 records) VPL (f->ic_pair_first + i) / n. */
TS_INLINE uint ts_ic_pair_vpl(const TsSceneView* sv, const TsFrame* f, uint i) {
    if (f->ic_pair_grid == 0u) return sv->items[(size_t)TS_IC_PAIR_WORDS * i + TS_IC_PAIR_VPL];
    return (f->ic_pair_first + i) / f->ic_pair_grid;
}

/* Pair i's record (index into the IcRecordSurfaces input): from the item list, or in a
 * pair grid the IcPairRecords input's entry (f->ic_pair_first + i) mod n. The grid spares
 * the host the list (8 bytes a pair) for placement's every record × every VPL. */
TS_INLINE uint ts_ic_pair_record(const TsSceneView* sv, const TsFrame* f, uint i) {
    if (f->ic_pair_grid == 0u) return sv->items[(size_t)TS_IC_PAIR_WORDS * i + TS_IC_PAIR_RECORD];
    return sv->ic_pair_records[(f->ic_pair_first + i) % f->ic_pair_grid];
}

/* Pair i's shadow ray from record to VPL in *shadow; returns 0 when the clamped
 * geometry term (f->igi_g_clamp) is 0 and no ray is needed. */
TS_INLINE int ts_ic_pair_ray(const TsSceneView* sv, const TsFrame* f, uint i, TsRay* shadow) {
    TsSurface s = ts_ic_record_surface(sv->ic_record_surfaces +
                                       (size_t)TS_IC_GBUF_FLOATS * ts_ic_pair_record(sv, f, i));
    return ts_vpl_geometry(&s, sv->vpls + (size_t)TS_VPL_FLOATS * ts_ic_pair_vpl(sv, f, i), f->igi_g_clamp,
                           sv->medium[TS_MEDIUM_G], shadow) > 0.0f;
}

/* Pair item i: a triangle on its shadow ray, the one the any-hit query found (not
 * necessarily the nearest; TS_IC_PAIR_VISIBLE for none), or TS_IC_PAIR_FACING when no ray
 * is needed (ts_ic_pair_ray). Any occluder serves the temporal update as well as the
 * nearest (docs/instant-caching.md §3), and the query stops at it. */
TS_INLINE void ts_ic_pair_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                               float* out) {
    TsRay shadow;
    uint hit = TS_IC_PAIR_FACING;
    if (ts_ic_pair_ray(sv, f, i, &shadow)) hit = ts_trace_any_hit(tracer, shadow);
    out[TS_IC_PAIR_HIT] = as_float(hit);
}

/* Gather item i: record item[TS_IC_GATHER_RECORD]'s sums over the Vpls input (one set,
 * vpl_set_start[1] VPLs) with bit-mask row item[TS_IC_GATHER_ROW] of the IcVisibility
 * input and
 * b = f->igi_g_clamp. */
TS_INLINE void ts_ic_gather_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                 float* out) {
    (void)tracer;
    TS_GLOBAL const uint* item = sv->items + (size_t)TS_IC_GATHER_WORDS * i;
    TsSurface s = ts_ic_record_surface(sv->ic_record_surfaces + (size_t)TS_IC_GBUF_FLOATS * item[TS_IC_GATHER_RECORD]);
    uint count = sv->vpl_set_start[1];
    TsMedium med = ts_medium_load(sv->medium);
    ts_ic_gather(&s, sv->ic_visibility + (size_t)TS_IC_VISIBLE_WORDS(count) * item[TS_IC_GATHER_ROW], count, sv->vpls,
                 &med,
                 f->igi_g_clamp, out);
}

TS_NAMESPACE_END

#endif /* TS_IC_H */
