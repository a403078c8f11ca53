/* The igi frame's reconstruction, per pixel: the discontinuity buffer (Keller 1998, as
 * IGI uses it, Wald et al. 2002 §4; docs/igi.md §8) over the interleaved components, then
 * the composite of shared/composite.h. The host runs the same two functions over its
 * copies of the components (host/gi/discontinuity_filter.cpp, host/integrators/igi_frame.cpp);
 * ts_igi_resolve_pixel runs them where the kernels ran, reading the surface and media
 * kernels' outputs in place (TsSceneView.igi_surface / igi_media), so a device frame
 * comes back as its TS_PASS_FLOATS image only (docs/ray-batches.md §5).
 *
 * The window, its mask and its mean are shared/discontinuity.h's, as the host filter's:
 * sums run in window order in double where the device has it (bit-identical to the
 * host), else with compensation. Uses the tracer interface documented in shared/direct.h (for the
 * kernel-table signature only: no ray is traced). */
#ifndef TS_IGI_RESOLVE_H
#define TS_IGI_RESOLVE_H
#include "shared/compat.h"
#include "shared/composite.h"
#include "shared/discontinuity.h"
#include "shared/geometry.h"
#include "shared/frame.h"
#include "shared/layout_igi.h"
#include "shared/layout_pass.h"
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
    /* The window mask, then the means of E_ss and E_id (6 floats from TS_IGI_SURF_E_SS)
     * and of the media radiance over it (shared/discontinuity.h, as the host's filter). */
    const int n = frame->igi_filter ? (int)frame->igi_tile : 1;
    const ulong bits = ts_discontinuity_mask((int)x, (int)y, w, h, n, sv->igi_surface + TS_IGI_SURF_DISTANCE,
                                             sv->igi_surface + TS_IGI_SURF_NORMAL,
                                             sv->igi_surface + TS_IGI_SURF_POSITION, TS_IGI_SURF_FLOATS,
                                             TS_IGI_SURF_FLOATS, 1, frame->igi_filter_cos, frame->igi_filter_depth);
    long offset[64];
    for (int i = 0; i < n * n; ++i) offset[i] = ts_discontinuity_offset(n, w, i);
    float e[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    ts_discontinuity_mean(sv->igi_surface + TS_IGI_SURF_E_SS, TS_IGI_SURF_FLOATS, 6, p, offset, bits, e);
    if (pm)
        ts_discontinuity_mean(sv->igi_media + TS_IGI_MEDIA_RADIANCE, TS_IGI_MEDIA_FLOATS, 3, p, offset, bits, e + 6);
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
