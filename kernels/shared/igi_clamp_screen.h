/* The clamp compensation of shared/clamp_screen.h for an igi frame resolved where the
 * kernels ran (docs/igi.md §4, docs/ray-batches.md §5), over the surface pass's output
 * kept there (TsSceneView.igi_surface), in three per-pixel kernels:
 *   IgiClampRecords  each pixel's record (TS_CLAMP_SCREEN_FLOATS) from its filtered
 *                    E_ss + E_id, into TsSceneView.clamp_records;
 *   IgiClampGather   E_res at the pixels of the even grid (x and y even), into
 *                    TsSceneView.clamp_residual;
 *   IgiResolve       (shared/igi_resolve.h) a pixel off the grid takes the mean of the
 *                    grid neighbours its discontinuity test accepts, or gathers itself,
 *                    and adds E_res to its filtered E_id.
 * Step for step what host/gi/clamp_screen.cpp does over the host's copies, so the images
 * are the same bits (a medium's transmittance takes the shared exponential, ts_exp3, on
 * both sides). A pixel takes part (gets and sends E_res) when it sees a surface
 * directly: finite distance and specular throughput exactly 1. Uses the tracer interface
 * documented in shared/direct.h for the kernel-table signature only: no ray is traced. */
#ifndef TS_IGI_CLAMP_SCREEN_H
#define TS_IGI_CLAMP_SCREEN_H
#include "shared/ais_resolve.h"
#include "shared/clamp_screen.h"
#include "shared/compat.h"
#include "shared/discontinuity.h"
#include "shared/frame.h"
#include "shared/geometry.h"
#include "shared/layout_igi.h"
#include "shared/medium.h"

TS_NAMESPACE_BEGIN

/* The means over pixel (x, y)'s accepted discontinuity window (shared/discontinuity.h, as
 * the host's filter): e[0..2] E_ss, e[3..5] E_id and, when pm, e[6..8] the media
 * radiance; frame->igi_filter 0: the pixel's own values. An AIS frame (frame->igi_ais)
 * takes a component's value from ts_ais_mean where the pixel evaluated extra sets of it. */
TS_INLINE void ts_igi_filtered_means(const TsSceneView* sv, const TsFrame* frame, uint x, uint y, int pm, float* e) {
    const int w = (int)frame->width, h = (int)frame->height;
    const size_t p = (size_t)y * frame->width + x;
    const int n = frame->igi_filter ? (int)frame->igi_tile : 1;
    const ulong bits = ts_discontinuity_mask((int)x, (int)y, w, h, n, sv->igi_surface + TS_IGI_SURF_DISTANCE,
                                             sv->igi_surface + TS_IGI_SURF_NORMAL,
                                             sv->igi_surface + TS_IGI_SURF_POSITION, TS_IGI_SURF_FLOATS,
                                             TS_IGI_SURF_FLOATS, 1, frame->igi_filter_cos, frame->igi_filter_depth);
    long offset[64];
    ts_discontinuity_offsets_at((int)x, (int)y, w, h, n, offset);
    for (int i = 0; i < 9; ++i) e[i] = 0.0f;
    ts_discontinuity_mean(sv->igi_surface + TS_IGI_SURF_E_SS, TS_IGI_SURF_FLOATS, 6, p, offset, bits, e);
    if (pm)
        ts_discontinuity_mean(sv->igi_media + TS_IGI_MEDIA_RADIANCE, TS_IGI_MEDIA_FLOATS, 3, p, offset, bits, e + 6);
    if (frame->igi_ais)
        for (int c = 0; c < (pm ? 3 : 2); ++c) {
            float a[3];
            if (ts_ais_mean(sv, frame, x, y, c, n, bits, offset, a))
                for (int j = 0; j < 3; ++j) e[3 * c + j] = a[j];
        }
}

/* The surface pass's output as the fill's view (shared/clamp_screen.h). */
TS_INLINE TsClampScreenView ts_igi_clamp_view(const TsSceneView* sv) {
    TsClampScreenView g;
    g.depth = sv->igi_surface + TS_IGI_SURF_DISTANCE;
    g.normal = sv->igi_surface + TS_IGI_SURF_NORMAL;
    g.position = sv->igi_surface + TS_IGI_SURF_POSITION;
    g.throughput = sv->igi_surface + TS_IGI_SURF_THROUGHPUT;
    g.depth_stride = g.normal_stride = g.position_stride = g.throughput_stride = TS_IGI_SURF_FLOATS;
    return g;
}

/* Kernel IgiClampRecords: pixel (x, y)'s record, all zeros where it is not seen directly. */
TS_INLINE void ts_igi_clamp_records_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* frame,
                                          uint x, uint y, float* out) {
    (void)tracer;
    for (int i = 0; i < TS_CLAMP_SCREEN_FLOATS; ++i) out[i] = 0.0f;
    const TsClampScreenView g = ts_igi_clamp_view(sv);
    if (!ts_clamp_screen_seen(&g, (size_t)y * frame->width + x)) return;
    TS_GLOBAL const float* sp = sv->igi_surface + ((size_t)y * frame->width + x) * TS_IGI_SURF_FLOATS;
    float e[9];
    ts_igi_filtered_means(sv, frame, x, y, 0, e);
    const float3 sum = make_float3(e[0], e[1], e[2]) + make_float3(e[3], e[4], e[5]);
    ts_clamp_screen_record(frame, ts_clamp_screen_pixel_plane(frame), ts_f3_load(sp + TS_IGI_SURF_POSITION),
                           ts_f3_load(sp + TS_IGI_SURF_NORMAL), ts_f3_load(sp + TS_IGI_SURF_ALBEDO), sum, out);
}

/* E_res gathered at pixel (x, y) from the records (the host: ts_clamp_lanes_gather). */
TS_INLINE float3 ts_igi_clamp_gather_at(const TsSceneView* sv, const TsFrame* frame, uint x, uint y) {
    TS_GLOBAL const float* q = sv->clamp_records + ((size_t)y * frame->width + x) * TS_CLAMP_SCREEN_FLOATS;
    const float3 pos = ts_f3_load(q + TS_CLAMP_SCREEN_POSITION);
    const float b = frame->igi_g_clamp;
    const float r = ts_clamp_screen_radius(ts_clamp_screen_pixel_plane(frame), ts_clamp_screen_depth(frame, pos), b);
#ifdef TS_HAS_MEDIUM
    /* A scene without a medium stores none present: transmittance 1, as the host's null. */
    TsMedium med = ts_medium_load(sv->medium);
    const TsMedium* m = &med;
#else
    const TsMedium* m = 0;
#endif
    return ts_clamp_screen_pixel((int)x, (int)y, (int)frame->width, (int)frame->height, pos,
                                 ts_f3_load(q + TS_CLAMP_SCREEN_COLD + TS_CLAMP_SCREEN_NORMAL), r, b, m,
                                 sv->clamp_records);
}

/* Kernel IgiClampGather: E_res at the even grid's pixels seen directly, zero elsewhere. */
TS_INLINE void ts_igi_clamp_gather_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* frame,
                                         uint x, uint y, float* out) {
    (void)tracer;
    float3 r = make_float3(0.0f, 0.0f, 0.0f);
    const TsClampScreenView g = ts_igi_clamp_view(sv);
    if (((x | y) & 1u) == 0u && ts_clamp_screen_seen(&g, (size_t)y * frame->width + x))
        r = ts_igi_clamp_gather_at(sv, frame, x, y);
    ts_f3_store(out, r);
}

/* E_res at pixel (x, y) from the gather's output (host: gather's second loop): the grid's
 * own value; off the grid, ts_clamp_screen_fill, or its own gather at an edge. */
TS_INLINE float3 ts_igi_clamp_residual(const TsSceneView* sv, const TsFrame* frame, uint x, uint y) {
    const size_t p = (size_t)y * frame->width + x;
    const TsClampScreenView g = ts_igi_clamp_view(sv);
    if (!ts_clamp_screen_seen(&g, p)) return make_float3(0.0f, 0.0f, 0.0f);
    if (((x | y) & 1u) == 0u) return ts_f3_load(sv->clamp_residual + p * TS_CLAMP_RESIDUAL_FLOATS);
    float3 r;
    if (ts_clamp_screen_fill(&g, (int)x, (int)y, (int)frame->width, (int)frame->height, sv->clamp_residual,
                             frame->igi_filter_cos, frame->igi_filter_depth, &r))
        return r;
    return ts_igi_clamp_gather_at(sv, frame, x, y);
}

TS_NAMESPACE_END
#endif /* TS_IGI_CLAMP_SCREEN_H */
