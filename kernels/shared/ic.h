/* Instant caching, the kernels' side: the G-buffer kernel's per-pixel part. The
 * record weight and the octree lookup are in shared/ic_lookup.h (also compiled into host
 * code that has no tracer); the method is described there. */
#ifndef TS_IC_H
#define TS_IC_H
#include "shared/compat.h"
#include "shared/ic_lookup.h"
#include "shared/igi.h"
#include "shared/layout.h"

TS_NAMESPACE_BEGIN

/* The G-buffer of one pixel (TS_IC_GBUF_FLOATS, layout.h): the igi surface kernel's
 * first diffuse surface, with what a record needs to trace shadow rays from it. */
TS_INLINE void ts_ic_gbuffer_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint px,
                                   uint py, float* out) {
    for (int i = 0; i < TS_IC_GBUF_FLOATS; ++i) out[i] = 0.0f;
    out[TS_IC_GBUF_PRIM] = as_float(TS_NO_HIT);
    TsIgiView v = ts_igi_view(sv, tracer, f, px, py);
    if (v.hit.prim == TS_NO_HIT) return;
    if (!(ts_max3(ts_material_albedo(sv, &v.s)) > 0.0f)) return;
    const TsSurface* s = &v.s;
    ts_f3_store(out + TS_IC_GBUF_POSITION, s->position);
    ts_f3_store(out + TS_IC_GBUF_NORMAL, s->shading_normal);
    ts_f3_store(out + TS_IC_GBUF_GEO_NORMAL, s->geo_normal);
    ts_f3_store(out + TS_IC_GBUF_ORIGIN, s->origin);
    out[TS_IC_GBUF_POS_SCALE] = s->pos_scale;
    out[TS_IC_GBUF_PRIM] = as_float(v.hit.prim);
    out[TS_IC_GBUF_DISTANCE] = v.distance;
}

/* The interpolation kernel's pixel (px, py): the cache in sv's named inputs (ic_gbuffer,
 * ic_nodes, ic_refs, ic_records) with Ward's a = f->ic_error_bound; TS_IC_INTERP_FLOATS. */
TS_INLINE void ts_ic_interpolate_kernel_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                              uint px, uint py, float* out) {
    (void)tracer;
    ts_ic_interpolate_pixel(sv->ic_gbuffer, sv->ic_nodes, sv->ic_refs, sv->ic_records, f->ic_error_bound,
                            py * f->width + px, out);
}

TS_NAMESPACE_END

#endif /* TS_IC_H */
