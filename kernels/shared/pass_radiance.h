/* A device frame's radiance-only pass (IgiSettings::pass_aovs false): the pass image's
 * TS_PASS_RADIANCE floats alone, TS_PASS_RADIANCE_FLOATS a pixel, for a display or a
 * benchmark that reads no albedo, normal or depth. The read-back then moves 3 floats a
 * pixel instead of TS_PASS_FLOATS (3.1 MB instead of 10.5 MB at 512²; docs/ray-batches.md §5).
 *
 * Each function runs its full-pass counterpart into a private pass and keeps the radiance,
 * so the radiance is the same bits as the full pass's; the compiler drops the stores of the
 * fields it does not keep. Uses the tracer interface documented in shared/direct.h (for the
 * kernel-table signature only: no ray is traced). */
#ifndef TS_PASS_RADIANCE_H
#define TS_PASS_RADIANCE_H
#include "shared/compat.h"
#include "shared/igi_resolve.h"
#include "shared/layout_pass.h"

TS_NAMESPACE_BEGIN

TS_INLINE void ts_pass_radiance_keep(const float* pass, float* out) {
    for (int c = 0; c < TS_PASS_RADIANCE_FLOATS; ++c) out[c] = pass[TS_PASS_RADIANCE + c];
}

/* Per-pixel kernel IgiResolveRadiance: ts_igi_resolve_pixel's radiance. */
TS_INLINE void ts_igi_resolve_radiance_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* frame,
                                             uint x, uint y, float* out) {
    float pass[TS_PASS_FLOATS];
    ts_igi_resolve_pixel(sv, tracer, frame, x, y, pass);
    ts_pass_radiance_keep(pass, out);
}

/* Per-pixel kernel AisEdgeMergeRadiance: ts_ais_edge_merge_pixel's radiance. */
TS_INLINE void ts_ais_edge_merge_radiance_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* frame,
                                                uint x, uint y, float* out) {
    float pass[TS_PASS_FLOATS];
    ts_ais_edge_merge_pixel(sv, tracer, frame, x, y, pass);
    ts_pass_radiance_keep(pass, out);
}

/* Per-pixel kernel PassRadiance: the radiance of the resolved pass kept on the device
 * (TsSceneView.igi_pass, TS_PASS_FLOATS a pixel), for an AIS frame whose edge schedule
 * gave no samples to merge. */
TS_INLINE void ts_pass_radiance_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* frame, uint x,
                                      uint y, float* out) {
    (void)tracer;
    TS_GLOBAL const float* pass = sv->igi_pass + ((size_t)y * frame->width + x) * TS_PASS_FLOATS;
    for (int c = 0; c < TS_PASS_RADIANCE_FLOATS; ++c) out[c] = pass[TS_PASS_RADIANCE + c];
}

TS_NAMESPACE_END

#endif /* TS_PASS_RADIANCE_H */
