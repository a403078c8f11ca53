/* The light-path kernel (KernelId::LightPaths): one work-item traces one light path of
 * instant radiosity through all its segments, where the host's batched tracer
 * (host/gi/light_paths.cpp) sends each bounce of every path through the backend and back.
 * Both run ts_light_path_segment (shared/light_path.h) per segment, so a path leaves the
 * same VPLs either way; on a GPU the kernel spares the frame a launch and a read-back per
 * bounce (docs/ray-batches.md §5, "Light paths in one kernel"). Uses the tracer interface of shared/direct.h. */
#ifndef TS_LIGHT_PATH_TRACE_H
#define TS_LIGHT_PATH_TRACE_H
#include "shared/compat.h"
#include "shared/frame.h"
#include "shared/geometry.h"
#include "shared/layout_light_path.h"
#include "shared/light_path.h"

TS_NAMESPACE_BEGIN

/* Copies record `src` (n floats) to `dst`. */
TS_INLINE void ts_light_path_copy(const float* src, int n, float* dst) {
    for (int j = 0; j < n; ++j) dst[j] = src[j];
}

/* Item i of sv->items (TS_LP_ITEM_WORDS: Halton point, set, weight) traced with the
 * parameters and Halton table of sv->light_path_table (layout_light_path.h): writes its
 * header and its VPLs and up to `max_vrls` ray lights, in path order, to out. A path that
 * needs more than TS_LP_MAX_VPLS VPLs, max_vrls ray lights or TS_LP_MAX_BOUNCES segments
 * stops with TS_LP_OVERFLOW; the caller traces it again on the host. */
TS_INLINE void ts_light_path_trace(const TsSceneView* sv, const TsTracer* tracer, uint i, uint max_vrls, float* out) {
    TS_GLOBAL const uint* item = sv->items + TS_LP_ITEM_WORDS * i;
    TS_GLOBAL const uint* table = sv->light_path_table;
    TsLightPathParams lp = ts_light_path_params(table);
    TS_GLOBAL const uint* halton = table + TS_LPT_HALTON;
    TsMedium med = ts_medium_load(sv->medium);
    TsLightPathState st;
    st.index = (ulong)item[TS_LP_ITEM_INDEX_LO] | ((ulong)item[TS_LP_ITEM_INDEX_HI] << 32);
    st.set = item[TS_LP_ITEM_SET];
    st.weight = as_float(item[TS_LP_ITEM_WEIGHT]);
    uint status = 0u, light = 0u, rays = 0u, vpls = 0u, vrls = 0u;
    if (sv->light_count > 0u && ts_light_path_begin(sv, halton, &st, &light)) {
        for (uint bounce = 0u; bounce < lp.max_bounces; ++bounce) {
            if (bounce == TS_LP_MAX_BOUNCES) {
                status = TS_LP_OVERFLOW;
                break;
            }
            TsHit hit = ts_trace_closest(tracer, st.ray);
            ++rays;
            TsLightPathEvent ev;
            uint what = ts_light_path_segment(sv, &med, halton, &lp, bounce, hit, &st, &ev);
            if (((what & TS_LIGHT_PATH_VRL) && vrls == max_vrls) ||
                ((what & TS_LIGHT_PATH_VPL) && vpls == TS_LP_MAX_VPLS)) {
                status = TS_LP_OVERFLOW;
                break;
            }
            if (what & TS_LIGHT_PATH_VRL) ts_light_path_copy(ev.vrl, TS_VRL_FLOATS, out + TS_LP_VRL + TS_VRL_FLOATS * vrls++);
            if (what & TS_LIGHT_PATH_VPL) ts_light_path_copy(ev.vpl, TS_VPL_FLOATS, out + TS_LP_VPL + TS_VPL_FLOATS * vpls++);
            if (!(what & TS_LIGHT_PATH_CONTINUES)) break;
        }
    }
    out[TS_LP_STATUS] = (float)status;
    out[TS_LP_LIGHT] = (float)light;
    out[TS_LP_RAYS] = (float)rays;
    out[TS_LP_VPLS] = (float)vpls;
    out[TS_LP_VRLS] = (float)vrls;
}

/* KernelId::LightPaths: TS_LP_FLOATS, no ray-light slots (a path that leaves one overflows). */
TS_INLINE void ts_light_path_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                  float* out) {
    (void)f;
    ts_light_path_trace(sv, tracer, i, 0u, out);
}

/* KernelId::LightPathsMedia: TS_LP_MEDIA_FLOATS, with TS_LP_MAX_VRLS ray-light slots. */
TS_INLINE void ts_light_path_media_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                        float* out) {
    (void)f;
    ts_light_path_trace(sv, tracer, i, TS_LP_MAX_VRLS, out);
}

/* KernelId::LightPathGather: item i's TS_LP_GATHER_FLOATS floats of the paths' kept
 * output from the float offset sv->items[i] (layout_light_path.h). */
TS_INLINE void ts_light_path_gather_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                         float* out) {
    (void)tracer;
    (void)f;
    TS_GLOBAL const float* from = sv->light_path_out + sv->items[i];
    for (int k = 0; k < TS_LP_GATHER_FLOATS; ++k) out[k] = from[k];
}

TS_NAMESPACE_END
#endif /* TS_LIGHT_PATH_TRACE_H */
