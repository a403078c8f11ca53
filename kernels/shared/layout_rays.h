/* Ray batches and hits, shared by the host (C++) and the kernels (OpenCL C); the rules
 * of every layout are in shared/layout_check.h.
 *
 * Ray batches (trace_closest / trace_occluded, kernels/trace.cl and Backend):
 *   rays: TS_RAY_FLOATS floats per ray: TS_RAY_ORG 3 floats, TS_RAY_TMIN,
 *   TS_RAY_DIR 3 floats, TS_RAY_TMAX.
 *   closest hits: TS_HIT_FLOATS words per ray: TS_HIT_T, TS_HIT_U, TS_HIT_V (floats),
 *   TS_HIT_PRIM (uint bits, TS_NO_HIT on a miss). Occlusion: 1 uint per ray.
 */
#ifndef TS_LAYOUT_RAYS_H
#define TS_LAYOUT_RAYS_H

#define TS_RAY_FLOATS 8
#define TS_RAY_ORG 0
#define TS_RAY_TMIN 3
#define TS_RAY_DIR 4
#define TS_RAY_TMAX 7
#define TS_HIT_FLOATS 4
#define TS_HIT_T 0
#define TS_HIT_U 1
#define TS_HIT_V 2
#define TS_HIT_PRIM 3
#define TS_NO_HIT 0xffffffffu

#ifdef __cplusplus
/* Compile-time checks of the layouts above (shared/layout_check.h). */
#include "shared/layout_check.h"

static_assert(tessera::layout_check::tiles({{TS_RAY_ORG, 3}, {TS_RAY_TMIN, 1}, {TS_RAY_DIR, 3}, {TS_RAY_TMAX, 1}},
                                           TS_RAY_FLOATS),
              "layout_rays.h: ray fields do not tile TS_RAY_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_HIT_T, 1}, {TS_HIT_U, 1}, {TS_HIT_V, 1}, {TS_HIT_PRIM, 1}},
                                           TS_HIT_FLOATS),
              "layout_rays.h: hit fields do not tile TS_HIT_FLOATS");
#endif /* __cplusplus */

#endif /* TS_LAYOUT_RAYS_H */
