/* The `pt` method (path-traced reference) on OpenCL devices: one work-item per pixel,
 * one pass (1 spp). Light transport in shared/pt.h. Built with -DTS_HAS_MEDIUM only
 * when the scene has a participating medium, -DTS_HAS_TEXTURES only with textures. */
#include "shared/layout.h"
#include "tracer.h"
#include "shared/pt.h"

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void pt_pass(TS_PIXEL_KERNEL_ARGS) {
    TS_PIXEL_KERNEL_BODY(ts_pt_pixel, TS_PASS_FLOATS)
}
