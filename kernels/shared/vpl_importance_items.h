/* The item kernels of the VPLs' importance (shared/vpl_importance.h, which documents the
 * sums): KernelId::VplImportancePoints and VplImportanceVpls. The including backend
 * defines TsTracer first (shared/direct.h); neither kernel traces. */
#ifndef TS_VPL_IMPORTANCE_ITEMS_H
#define TS_VPL_IMPORTANCE_ITEMS_H

#include "shared/vpl_importance.h"

TS_NAMESPACE_BEGIN

/* The sums' type: double where the device has it (the host reference's), else float. */
#ifdef TS_HAS_DOUBLE
typedef double TsImportanceSum;
#else
typedef float TsImportanceSum;
#endif

/* Item kernel VplImportancePoints, launched without a list: item t sums view point
 * j = t mod np's terms over the VPLs of chunk t div np (TS_VI_CHUNK VPLs a chunk, in VPL
 * order; chunk 0: all of them, one item a point). The host adds a point's parts in chunk
 * order. Why chunks: a GPU runs one item a point as np threads (256) each looping over
 * every VPL (2,000+), a chain of dependent loads and adds no other thread hides. */
TS_INLINE void ts_vpl_importance_point_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint t,
                                            float* out) {
    (void)tracer;
    (void)f;
    TS_GLOBAL const float* vi = sv->vpl_importance;
    const uint np = (uint)vi[TS_VI_POINTS], nv = sv->vpl_set_start[1], chunk = (uint)vi[TS_VI_CHUNK];
    const uint j = t % np, first = chunk > 0u ? (t / np) * chunk : 0u;
    const uint end = chunk > 0u && nv - first > chunk ? first + chunk : nv;
    const float b = vi[TS_VI_G_CLAMP];
    out[TS_VI_E_DOUBLE] = out[TS_VI_E_DOUBLE + 1] = out[TS_VI_E_FLOAT] = 0.0f;
    TsImportanceSum e = 0;
    for (uint i = first; i < end; ++i) {
        TS_GLOBAL const float* v = sv->vpls + (size_t)i * TS_VPL_FLOATS;
        if (ts_vpl_in_medium(v)) continue;
        e += ts_vpl_importance_term(vi + TS_VI_HEADER, np, j, v, ts_vpl_importance_luminance(v), b);
    }
#ifdef TS_HAS_DOUBLE
    uint lo, hi;
    ts_double_words(e, &lo, &hi);
    out[TS_VI_E_DOUBLE] = as_float(lo);
    out[TS_VI_E_DOUBLE + 1] = as_float(hi);
    out[TS_VI_E_HAS_DOUBLE] = 1.0f;
#else
    out[TS_VI_E_FLOAT] = e;
    out[TS_VI_E_HAS_DOUBLE] = 0.0f;
#endif
}

/* Item kernel VplImportanceVpls, launched without a list: item i = VPL i; writes Φ_i. */
TS_INLINE void ts_vpl_importance_vpl_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                          float* out) {
    (void)tracer;
    (void)f;
    TS_GLOBAL const float* vi = sv->vpl_importance;
    TS_GLOBAL const float* v = sv->vpls + (size_t)i * TS_VPL_FLOATS;
    out[0] = 0.0f;
    if (ts_vpl_in_medium(v)) return;
    const uint np = (uint)vi[TS_VI_POINTS];
    const float b = vi[TS_VI_G_CLAMP], lum = ts_vpl_importance_luminance(v);
    TsImportanceSum s = 0;
    for (uint j = 0; j < np; ++j) {
        TS_GLOBAL const float* w = vi + TS_VI_WEIGHT(np, j);
        const float c = ts_vpl_importance_term(vi + TS_VI_HEADER, np, j, v, lum, b);
#ifdef TS_HAS_DOUBLE
        s += (double)c * ts_double_of_words(as_uint(w[0]), as_uint(w[1]));
#else
        s += c * w[2];
#endif
    }
    out[0] = (float)s;
}

TS_NAMESPACE_END
#endif /* TS_VPL_IMPORTANCE_ITEMS_H */
