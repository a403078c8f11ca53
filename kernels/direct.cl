/* The `direct` method on OpenCL devices: one work-item per pixel, one pass (1 spp).
 * The light transport is shared/direct.h, the same source the Embree backend compiles.
 * Built with -DTS_HAS_TEXTURES only when the scene has textures. */
#include "shared/layout.h"
#include "tracer.h"
#include "shared/direct.h"

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void direct_pass(TS_PIXEL_KERNEL_ARGS) {
    TS_PIXEL_KERNEL_BODY(ts_direct_pixel, TS_PASS_FLOATS)
}
