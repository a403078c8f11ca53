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
#include "shared/igi_clamp_screen.h"
#include "shared/frame.h"
#include "shared/layout_igi.h"
#include "shared/layout_pass.h"
#include "shared/vpl.h"

TS_NAMESPACE_BEGIN

/* Per-pixel kernel IgiResolve (host/device/kernel_table.h): filters the SS, ID and (when
 * frame->igi_components has PM) PM components over p's accepted window, composites
 *   L = Tr · β · (Le + ρ · (Ẽ_ss + Ẽ_id)) + L̃_pm
 * and writes TS_PASS_FLOATS (radiance W/(sr·m²), albedo, normal, depth) to out, as the
 * host's IgiFrame does. frame->igi_filter 0: no filtering (the window is p alone).
 * frame->igi_clamp_screen 1: Ẽ_id gains the clamp's compensation E_res, from
 * TsSceneView.clamp_residual (KernelId::IgiClampGather's output). */
TS_INLINE void ts_igi_resolve_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* frame, uint x,
                                    uint y, float* out) {
    (void)tracer;
    const int pm = (frame->igi_components & TS_COMPONENT_PM) != 0u;
    const size_t p = (size_t)y * frame->width + x;
    TS_GLOBAL const float* sp = sv->igi_surface + p * TS_IGI_SURF_FLOATS;
    const float zp = sp[TS_IGI_SURF_DISTANCE];
    /* The means of E_ss, E_id and the media radiance over the accepted window, then E_id
     * plus the clamp's compensation where the frame asks for it (shared/igi_clamp_screen.h). */
    float e[9];
    ts_igi_filtered_means(sv, frame, x, y, pm, e);
    if (frame->igi_clamp_screen) {
        const float3 r = ts_igi_clamp_residual(sv, frame, x, y);
        e[3] += r.x, e[4] += r.y, e[5] += r.z;
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

/* Per-pixel kernel AisEdgeMerge: the AIS frame's edge samples merged where the kernels ran
 * (host: merge_edge_samples, host/gi/ais_edges.h). Copies pixel p's resolved pass image
 * (TsSceneView.igi_pass, TS_PASS_FLOATS); where the schedule gave p edge samples
 * (TsSceneView.edge_counts; its first in edge_samples ts_edge_compact_first), its radiance becomes the mean
 * of its own and its samples' (TsSceneView.edge_samples), each shaded as the composite with
 * its own throughput, emission and albedo and the reconstructed components of the pixel it
 * lies on (ts_edge_sample_match): E_ss, E_id plus the clamp's E_res, L_pm, and the camera
 * segment's transmittance. Sums in double in sample order. */
TS_INLINE void ts_ais_edge_merge_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* frame, uint x,
                                       uint y, float* out) {
    (void)tracer;
    const size_t p = (size_t)y * frame->width + x;
    TS_GLOBAL const float* base = sv->igi_pass + p * TS_PASS_FLOATS;
    for (int c = 0; c < TS_PASS_FLOATS; ++c) out[c] = base[c];
    const uint n = ts_edge_count_at(sv, frame, x, y);
    if (n == 0u) return;
    const uint first = ts_edge_compact_first(sv, frame, x, y);
    const int pm = (frame->igi_components & TS_COMPONENT_PM) != 0u;
    TsAisSum sum = ts_ais_sum_zero();
    ts_ais_sum_add(&sum, base + TS_PASS_RADIANCE);
    for (uint j = 0u; j < n; ++j) {
        TS_GLOBAL const float* g = sv->edge_samples + (size_t)(first + j) * TS_EDGE_SAMPLE_FLOATS;
        float e[TS_EDGE_SAMPLE_FLOATS];
        for (int k = 0; k < TS_EDGE_SAMPLE_FLOATS; ++k) e[k] = g[k];
        const size_t q = ts_edge_sample_match(sv, frame, (int)x, (int)y, e);
        const uint qx = (uint)(q % frame->width), qy = (uint)(q / frame->width);
        float m[9];
        ts_igi_filtered_means(sv, frame, qx, qy, pm, m);
        if (frame->igi_clamp_screen) {
            const float3 r = ts_igi_clamp_residual(sv, frame, qx, qy);
            m[3] += r.x, m[4] += r.y, m[5] += r.z;
        }
        if (!pm) m[6] = m[7] = m[8] = 0.0f;
        const float3 tr = pm ? ts_f3_load(sv->igi_media + q * TS_IGI_MEDIA_FLOATS + TS_IGI_MEDIA_TRANSMITTANCE)
                             : make_float3(1.0f, 1.0f, 1.0f);
        const float3 l = ts_igi_composite(
            tr, make_float3(e[TS_EDGE_SAMPLE_THROUGHPUT], e[TS_EDGE_SAMPLE_THROUGHPUT + 1], e[TS_EDGE_SAMPLE_THROUGHPUT + 2]),
            make_float3(e[TS_EDGE_SAMPLE_EMISSION], e[TS_EDGE_SAMPLE_EMISSION + 1], e[TS_EDGE_SAMPLE_EMISSION + 2]),
            make_float3(e[TS_EDGE_SAMPLE_ALBEDO], e[TS_EDGE_SAMPLE_ALBEDO + 1], e[TS_EDGE_SAMPLE_ALBEDO + 2]),
            make_float3(m[0], m[1], m[2]), make_float3(m[3], m[4], m[5]), make_float3(m[6], m[7], m[8]));
        ts_ais_sum_add3(&sum, l);
    }
    ts_ais_sum_mean(&sum, (int)n + 1, out + TS_PASS_RADIANCE);
}

TS_NAMESPACE_END
#endif /* TS_IGI_RESOLVE_H */
