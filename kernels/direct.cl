/* The `direct` method on OpenCL devices: one work-item per pixel, one pass (1 spp).
 * The light transport is shared/direct.h, the same source the Embree backend compiles;
 * here tracing is the BVH4 traversal of bvh_traverse.h. Built with -DTS_HAS_TEXTURES
 * only when the scene has textures. */
#include "shared/layout.h"
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

#include "shared/direct.h"

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void direct_pass(TsFrame frame,
                 __global const float* nodes, __global const float* tris,
                 __global const float* tri_pos, __global const float* tri_nrm,
                 __global const float* tri_uv, __global const uint* tri_mat,
                 __global const float* materials, __global const uint* tex_info,
                 __global const uint* tex_texels, __global const float* lights,
                 __global const float* light_cdf, __global float* out) {
    uint i = get_global_id(0);
    if (i >= frame.width * frame.height) return;
    TsTracer tracer = {nodes, tris};
    TsSceneView sv = {tri_pos, tri_nrm, tri_uv, tri_mat, materials, tex_info,
                      tex_texels, lights, light_cdf, frame.light_count};
    float px[TS_PASS_FLOATS];
    ts_direct_pixel(&sv, &tracer, &frame, i % frame.width, i / frame.width, px);
    for (int k = 0; k < TS_PASS_FLOATS; ++k) out[(size_t)i * TS_PASS_FLOATS + k] = px[k];
}
