/* The VPLs' importance for the view (after Georgiev and Slusallek 2010; docs/igi.md §3b)
 * where the kernels run: its terms and both of its sums.
 *
 * With E_j = Σ_i c_ij over the candidate surface VPLs i at view point j and
 * Φ_i = Σ_j c_ij w_j, w_j = 1 / max(E_j, 10⁻³ · mean E), c_ij = luminance(C_i) · G'_ij
 * (ts_vpl_importance_term): KernelId::VplImportancePoints sums E_j, one work item a
 * point, or one a point and chunk of VPLs whose parts the host adds; the host then forms
 * the w_j (a mean over all points) and KernelId::VplImportanceVpls sums Φ_i, one work
 * item a VPL. host/gi/vpl_importance.h's vpl_view_importance is the reference: it builds
 * each c_ij with ts_vpl_importance_term, sums E_j in VPL order (exact in any order in
 * practice: vpl_view_importance_in_kernels) and
 * Φ_i in point order, in double, and so do these (a device without doubles sums in float: Φ then differs in its last bits, which
 * the keep probabilities' 1/64 steps absorb). A GPU thus keeps the matrix of terms (VPLs ×
 * points, 0.5 M at K = 4 and a 16² grid) off the host, which reads back one float a VPL.
 *
 * Inputs (layout_igi.h, TS_VI_*): TsSceneView.vpl_importance (the points, their count,
 * the clamp and the weights) and the Vpls input as one set (vpl_set_start[1] VPLs);
 * medium VPLs count for nothing and get Φ = 0. The item kernels are in
 * shared/vpl_importance_items.h (they take the backend's TsTracer; this part the host's
 * reference includes too). */
#ifndef TS_VPL_IMPORTANCE_H
#define TS_VPL_IMPORTANCE_H

#include "shared/compat.h"
#include "shared/frame.h"
#include "shared/geometry.h"
#include "shared/layout_igi.h"
#include "shared/sampling.h"
#include "shared/vpl.h"

TS_NAMESPACE_BEGIN

/* c_ij: surface VPL `vpl` of flux luminance `lum` at a view point at x with shading and
 * geometric normals n and ng, its geometry term clamped to `g_clamp` (scene units^-2);
 * visibility is not tested. */
TS_INLINE float ts_vpl_importance_term_at(float3 x, float3 n, float3 ng, TS_GLOBAL const float* vpl, float lum,
                                          float g_clamp) {
    return lum * ts_vpl_geometry_term_of(x, n, ng, vpl, g_clamp, 0.0f, 0);
}

/* The same at point j of the np points whose coordinates are the 9 arrays from `pts`
 * (TS_VI_COORD(np, k) − TS_VI_HEADER). */
TS_INLINE float ts_vpl_importance_term(TS_GLOBAL const float* pts, uint np, uint j, TS_GLOBAL const float* vpl,
                                       float lum, float g_clamp) {
    const float3 x = make_float3(pts[j], pts[np + j], pts[2u * np + j]);
    const float3 n = make_float3(pts[3u * np + j], pts[4u * np + j], pts[5u * np + j]);
    const float3 ng = make_float3(pts[6u * np + j], pts[7u * np + j], pts[8u * np + j]);
    return ts_vpl_importance_term_at(x, n, ng, vpl, lum, g_clamp);
}

/* The luminance of VPL `vpl`'s flux, the c_ij's factor. */
TS_INLINE float ts_vpl_importance_luminance(TS_GLOBAL const float* vpl) {
    return ts_luminance(ts_f3_load(vpl + TS_VPL_FLUX));
}

TS_NAMESPACE_END
#endif /* TS_VPL_IMPORTANCE_H */
