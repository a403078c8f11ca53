/* One pass's per-pixel output, shared by the host (C++) and the kernels (OpenCL C); the
 * rules of every layout are in shared/layout_check.h. */
#ifndef TS_LAYOUT_PASS_H
#define TS_LAYOUT_PASS_H

/* Per-pixel output of one pass: TS_PASS_FLOATS floats per pixel:
 *   TS_PASS_RADIANCE 3 floats: radiance (W/(sr·m²))
 *   TS_PASS_ALBEDO   3 floats: albedo at the first hit
 *   TS_PASS_NORMAL   3 floats: shading normal at the first hit
 *   TS_PASS_DEPTH    distance to the first hit (scene units; +inf on a miss) */
#define TS_PASS_FLOATS 10
#define TS_PASS_RADIANCE 0
#define TS_PASS_ALBEDO 3
#define TS_PASS_NORMAL 6
#define TS_PASS_DEPTH 9

/* A radiance-only pass (IgiSettings::pass_aovs false, on a frame resolved on the device;
 * shared/pass_radiance.h): TS_PASS_RADIANCE_FLOATS floats per pixel, the radiance alone. */
#define TS_PASS_RADIANCE_FLOATS 3

#ifdef __cplusplus
/* Compile-time checks of the layouts above (shared/layout_check.h). */
#include "shared/layout_check.h"

static_assert(tessera::layout_check::tiles({{TS_PASS_RADIANCE, 3}, {TS_PASS_ALBEDO, 3}, {TS_PASS_NORMAL, 3},
                                            {TS_PASS_DEPTH, 1}},
                                           TS_PASS_FLOATS),
              "layout_pass.h: pass output fields do not tile TS_PASS_FLOATS");
#endif /* __cplusplus */

#endif /* TS_LAYOUT_PASS_H */
