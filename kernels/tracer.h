/* The OpenCL backend's tracer for the shared shading code: BVH4 traversal
 * (bvh_query.h) over the Embree-built BVH. See shared/direct.h for the interface. */
#ifndef TS_TRACER_CL_H
#define TS_TRACER_CL_H
#include "bvh_query.h"

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
/* The triangle of the first hit the any-hit walk finds, not necessarily the nearest, or
 * TS_NO_HIT: hits exactly when ts_trace_occluded does. */
static inline uint ts_trace_any_hit(const TsTracer* tr, TsRay ray) {
    return TS_BVH_TRAVERSE(tr->nodes, tr->tris, ray, 1).prim;
}

/* The argument list every kernel of the kernel table (host/device/kernel_table.h) takes,
 * in this order: the frame, the BVH, the scene's shading buffers and the named inputs
 * (both lists in shared/kernel_inputs.h), the launch's item list, the output and the
 * number of work items. */
#define TS_KERNEL_SCENE_ARG(field, type, what) __global const type *field,
#define TS_KERNEL_INPUT_ARG(name, field, type, what) __global const type *field,
#define TS_KERNEL_ARGS                                                                    \
    TsFrame frame, __global const float *nodes, __global const float *tris,              \
        TS_SCENE_BUFFERS(TS_KERNEL_SCENE_ARG) TS_KERNEL_INPUTS(TS_KERNEL_INPUT_ARG)      \
        __global const uint *items, __global float *out, uint work_items

#define TS_KERNEL_SCENE_VIEW(field, type, what) field,
#define TS_KERNEL_INPUT_VIEW(name, field, type, what) field,
#define TS_KERNEL_VIEWS                                                                   \
    TsTracer tracer = {nodes, tris};                                                     \
    TsSceneView sv = {TS_SCENE_BUFFERS(TS_KERNEL_SCENE_VIEW) TS_KERNEL_INPUTS(TS_KERNEL_INPUT_VIEW) \
                      items, frame.light_count};

/* A per-pixel kernel `name`: one work-item per pixel runs `pixel_fn` (a ts_*_pixel
 * function of the shared code) and stores its `floats` outputs at the pixel's place.
 * Work-items are ordered by interleave set when frame.igi_tile > 1 (de-interleaved
 * shading, Segovia et al. 2006): consecutive work-items then share their set's VPLs and
 * light samples and stay coherent, and writing at the pixel's place re-interleaves. */
#define TS_PIXEL_KERNEL(name, pixel_fn, floats)                                          \
    __kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))              \
    void name(TS_KERNEL_ARGS) {                                                          \
        uint i = get_global_id(0);                                                       \
        if (i >= frame.width * frame.height) return;                                     \
        uint px_, py_;                                                                   \
        ts_pixel_of_work_item(&frame, i, &px_, &py_);                                    \
        TS_KERNEL_VIEWS                                                                  \
        float v_[floats];                                                                \
        pixel_fn(&sv, &tracer, &frame, px_, py_, v_);                                    \
        size_t o_ = ((size_t)py_ * frame.width + px_) * (floats);                        \
        for (int k = 0; k < (floats); ++k) out[o_ + k] = v_[k];                          \
    }

/* A per-item kernel `name`: work-item i (< work_items) runs `item_fn(sv, tracer, frame,
 * i, out)` and stores its `floats` outputs at item i's place. */
#define TS_ITEM_KERNEL(name, item_fn, floats)                                            \
    __kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))              \
    void name(TS_KERNEL_ARGS) {                                                          \
        uint i = get_global_id(0);                                                       \
        if (i >= work_items) return;                                                     \
        TS_KERNEL_VIEWS                                                                  \
        float v_[floats];                                                                \
        item_fn(&sv, &tracer, &frame, i, v_);                                            \
        for (int k = 0; k < (floats); ++k) out[(size_t)i * (floats) + k] = v_[k];        \
    }

#endif /* TS_TRACER_CL_H */
