/* The `direct` method on OpenCL devices: one work-item per pixel, one pass (1 spp).
 * The light transport is shared/direct.h, the same source the Embree backend compiles.
 * Built with -DTS_HAS_TEXTURES only when the scene has textures. */
#include "shared/layout_pass.h"
#include "tracer.h"
#include "shared/direct.h"

TS_PIXEL_KERNEL(direct_pass, ts_direct_pixel, TS_PASS_FLOATS)
