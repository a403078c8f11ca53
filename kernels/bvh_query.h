/* The single-ray BVH queries the kernels call (ts_bvh_closest, ts_bvh_occluded): the
 * full-stack traversal of bvh_traverse.h, or on GPU devices the short stack with restart
 * of bvh_short_stack.h. Kept apart from both so that each of the three headers compiles
 * by itself (tests/kernels/standalone_headers_test.cpp). */
#ifndef TS_BVH_QUERY_H
#define TS_BVH_QUERY_H
#include "bvh_short_stack.h"
#include "bvh_traverse.h"

/* The traversal the kernels use: the full stack of bvh_traverse.h, or with -DTS_GPU_TRAVERSAL (the
 * OpenCL backend's choice on GPU devices, host/backend/opencl_backend.cpp) the short
 * stack with restart of bvh_short_stack.h; both return the same hits. */
#ifdef TS_GPU_TRAVERSAL
#define TS_BVH_TRAVERSE ts_bvh_traverse_short
#else
#define TS_BVH_TRAVERSE ts_bvh_traverse
#endif

static inline TsHit ts_bvh_closest(__global const float* nodes, __global const float* tris, TsRay ray) {
    return TS_BVH_TRAVERSE(nodes, tris, ray, 0);
}

static inline int ts_bvh_occluded(__global const float* nodes, __global const float* tris, TsRay ray) {
    return TS_BVH_TRAVERSE(nodes, tris, ray, 1).prim != TS_NO_HIT;
}

#endif /* TS_BVH_QUERY_H */
