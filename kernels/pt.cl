/* The `pt` method (path-traced reference) on OpenCL devices: one work-item per pixel,
 * one pass (1 spp). Light transport in shared/pt.h. Built with -DTS_HAS_MEDIUM only
 * when the scene has a participating medium, -DTS_HAS_TEXTURES only with textures. */
#include "shared/layout_pass.h"
#include "tracer.h"
#include "shared/pt.h"

TS_PIXEL_KERNEL(pt_pass, ts_pt_pixel, TS_PASS_FLOATS)
