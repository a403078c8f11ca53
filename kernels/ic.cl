/* Instant caching on OpenCL devices (shared/ic.h): the G-buffer kernel (the surface each
 * pixel's records and lookups use) and the interpolation kernel (octree lookup over the
 * records the host placed and gathered). */
#include "shared/layout.h"
#include "tracer.h"
#include "shared/ic.h"

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void ic_gbuffer_pass(TS_PIXEL_KERNEL_ARGS) {
    TS_PIXEL_KERNEL_BODY(ts_ic_gbuffer_pixel, TS_IC_GBUF_FLOATS)
}

/* Work-item p interpolates pixel p (row-major) of `gbuffer` into the p-th
 * TS_IC_INTERP_FLOATS values of out. */
__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void ic_interpolate(uint pixels, float error_bound, __global const float* gbuffer, __global const float* nodes,
                    __global const uint* refs, __global const float* records, __global float* out) {
    uint p = get_global_id(0);
    if (p >= pixels) return;
    float v[TS_IC_INTERP_FLOATS];
    ts_ic_interpolate_pixel(gbuffer, nodes, refs, records, error_bound, p, v);
    for (int k = 0; k < TS_IC_INTERP_FLOATS; ++k) out[(size_t)p * TS_IC_INTERP_FLOATS + k] = v[k];
}
