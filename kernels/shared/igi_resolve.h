/* The igi frame's reconstruction, per pixel: the discontinuity buffer (Keller 1998, as
 * IGI uses it, Wald et al. 2002 §4; docs/igi.md §8) over the interleaved components, then
 * the composite of shared/composite.h. The host runs the same two functions over its
 * copies of the components (host/gi/discontinuity_filter.cpp, host/integrators/igi_frame.cpp);
 * ts_igi_resolve_pixel runs them where the kernels ran, reading the surface and media
 * kernels' outputs in place (TsSceneView.igi_surface / igi_media), so a device frame
 * comes back as its TS_PASS_FLOATS image only (docs/ray-batches.md §5).
 *
 * The window and the acceptance test are shared/discontinuity.h's. Sums run in window
 * order in double where the device has it (bit-identical to the host), else with
 * compensation. Uses the tracer interface documented in shared/direct.h (for the
 * kernel-table signature only: no ray is traced). */
#ifndef TS_IGI_RESOLVE_H
#define TS_IGI_RESOLVE_H
#include "shared/compat.h"
#include "shared/composite.h"
#include "shared/discontinuity.h"
#include "shared/geometry.h"
#include "shared/layout.h"
#include "shared/vpl.h"

TS_NAMESPACE_BEGIN

/* Per-pixel kernel IgiResolve (host/device/kernel_table.h): filters the SS, ID and (when
 * frame->igi_components has PM) PM components over p's accepted window, composites
 *   L = Tr · β · (Le + ρ · (Ẽ_ss + Ẽ_id)) + L̃_pm
 * and writes TS_PASS_FLOATS (radiance W/(sr·m²), albedo, normal, depth) to out, as the
 * host's IgiFrame does. frame->igi_filter 0: no filtering (the window is p alone). */
TS_INLINE void ts_igi_resolve_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* frame, uint x,
                                    uint y, float* out) {
    (void)tracer;
    const int w = (int)frame->width, h = (int)frame->height;
    const int pm = (frame->igi_components & TS_COMPONENT_PM) != 0u;
    const size_t p = (size_t)y * frame->width + x;
    TS_GLOBAL const float* sp = sv->igi_surface + p * TS_IGI_SURF_FLOATS;
    const float zp = sp[TS_IGI_SURF_DISTANCE];
    const float3 np = ts_f3_load(sp + TS_IGI_SURF_NORMAL), xp = ts_f3_load(sp + TS_IGI_SURF_POSITION);
    int lo = 0, hi = 0;
    if (frame->igi_filter) ts_discontinuity_window((int)frame->igi_tile, &lo, &hi);
#ifdef TS_HAS_DOUBLE
    double sum[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
#else
    float sum[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, comp[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
#endif
    int count = 0;
    for (int dy = lo; dy <= hi; ++dy)
        for (int dx = lo; dx <= hi; ++dx) {
            const int qx = (int)x + dx, qy = (int)y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const size_t q = (size_t)qy * frame->width + (size_t)qx;
            TS_GLOBAL const float* sq = sv->igi_surface + q * TS_IGI_SURF_FLOATS;
            if (q != p && !ts_discontinuity_accepts(zp, np, xp, sq[TS_IGI_SURF_DISTANCE],
                                                    ts_f3_load(sq + TS_IGI_SURF_NORMAL),
                                                    ts_f3_load(sq + TS_IGI_SURF_POSITION), 1,
                                                    frame->igi_filter_cos, frame->igi_filter_depth))
                continue;
            float v[9];
            for (int c = 0; c < 3; ++c) {
                v[c] = sq[TS_IGI_SURF_E_SS + c];
                v[3 + c] = sq[TS_IGI_SURF_E_ID + c];
                v[6 + c] = pm ? sv->igi_media[q * TS_IGI_MEDIA_FLOATS + TS_IGI_MEDIA_RADIANCE + c] : 0.0f;
            }
            for (int c = 0; c < 9; ++c) {
#ifdef TS_HAS_DOUBLE
                sum[c] += v[c];
#else
                ts_sum_compensated_add(&sum[c], &comp[c], v[c]);
#endif
            }
            ++count;
        }
    float e[9];
    for (int c = 0; c < 9; ++c) {
#ifdef TS_HAS_DOUBLE
        e[c] = (float)(sum[c] / count);
#else
        e[c] = (sum[c] + comp[c]) / (float)count;
#endif
    }
    float3 tr = pm ? ts_f3_load(sv->igi_media + p * TS_IGI_MEDIA_FLOATS + TS_IGI_MEDIA_TRANSMITTANCE)
                   : make_float3(1.0f, 1.0f, 1.0f);
    float3 l = ts_igi_composite(tr, ts_f3_load(sp + TS_IGI_SURF_THROUGHPUT), ts_f3_load(sp + TS_IGI_SURF_EMISSION),
                                ts_f3_load(sp + TS_IGI_SURF_ALBEDO), make_float3(e[0], e[1], e[2]),
                                make_float3(e[3], e[4], e[5]), make_float3(e[6], e[7], e[8]));
    ts_f3_store(out + TS_PASS_RADIANCE, l);
    for (int c = 0; c < 3; ++c) {
        out[TS_PASS_ALBEDO + c] = sp[TS_IGI_SURF_ALBEDO + c];
        out[TS_PASS_NORMAL + c] = sp[TS_IGI_SURF_NORMAL + c];
    }
    out[TS_PASS_DEPTH] = zp;
}

TS_NAMESPACE_END
#endif /* TS_IGI_RESOLVE_H */
