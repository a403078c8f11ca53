/* The OpenCL backend's tracer for the shared shading code: BVH4 traversal
 * (bvh_traverse.h) over the Embree-built BVH. See shared/direct.h for the interface. */
#ifndef TS_TRACER_CL_H
#define TS_TRACER_CL_H
#include "bvh_traverse.h"

typedef struct TsTracer {
    __global const float* nodes;
    __global const float* tris;
} TsTracer;

static inline TsHit ts_trace_closest(const TsTracer* tr, TsRay ray) {
    return ts_bvh_closest(tr->nodes, tr->tris, ray);
}
static inline int ts_trace_occluded(const TsTracer* tr, TsRay ray) {
    return ts_bvh_occluded(tr->nodes, tr->tris, ray);
}

/* The argument list every per-pixel method kernel takes, in this order. */
#define TS_PIXEL_KERNEL_ARGS                                                              \
    TsFrame frame, __global const float *nodes, __global const float *tris,              \
        __global const float *tri_pos, __global const float *tri_nrm,                    \
        __global const float *tri_uv, __global const uint *tri_mat,                      \
        __global const float *materials, __global const uint *tex_info,                  \
        __global const uint *tex_texels, __global const float *lights,                   \
        __global const float *light_cdf, __global const float *medium,                   \
        __global const float *vpls, __global const uint *vpl_set_start, __global float *out

/* Body of a per-pixel kernel: one work-item per pixel runs `pixel_fn` (a ts_*_pixel
 * function of the shared code) and stores its `floats` outputs at the pixel's place.
 * Work-items are ordered by interleave set when frame.igi_tile > 1 (de-interleaved
 * shading, Segovia et al. 2006): consecutive work-items then share their set's VPLs and
 * light samples and stay coherent, and writing at the pixel's place re-interleaves. */
#define TS_KERNEL_VIEWS                                                                   \
    TsTracer tracer = {nodes, tris};                                                     \
    TsSceneView sv = {tri_pos, tri_nrm, tri_uv, tri_mat, materials, tex_info, tex_texels, \
                      lights, light_cdf, medium, vpls, vpl_set_start, frame.light_count};

#define TS_PIXEL_KERNEL_BODY(pixel_fn, floats)                                           \
    uint i = get_global_id(0);                                                           \
    if (i >= frame.width * frame.height) return;                                         \
    uint px_, py_;                                                                       \
    ts_pixel_of_work_item(&frame, i, &px_, &py_);                                        \
    TS_KERNEL_VIEWS                                                                      \
    float v_[floats];                                                                    \
    pixel_fn(&sv, &tracer, &frame, px_, py_, v_);                                        \
    size_t o_ = ((size_t)py_ * frame.width + px_) * (floats);                            \
    for (int k = 0; k < (floats); ++k) out[o_ + k] = v_[k];

#endif /* TS_TRACER_CL_H */
