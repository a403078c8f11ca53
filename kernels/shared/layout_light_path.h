/* Layouts of the light-path kernel (KernelId::LightPaths, shared/light_path_trace.h): its
 * items, its per-path output and the light-path table it reads (named input
 * LightPathTable). VPL and ray-light records are layout_igi.h's. */
#ifndef TS_LAYOUT_LIGHT_PATH_H
#define TS_LAYOUT_LIGHT_PATH_H
#include "shared/layout_igi.h"

/* An item, TS_LP_ITEM_WORDS uints: the path's Halton point (low and high 32 bits), its
 * interleave set and its weight (float bits: 1/p of a path kept with probability p). */
#define TS_LP_ITEM_WORDS 4
#define TS_LP_ITEM_INDEX_LO 0
#define TS_LP_ITEM_INDEX_HI 1
#define TS_LP_ITEM_SET 2
#define TS_LP_ITEM_WEIGHT 3

/* A path's output, TS_LP_FLOATS floats (KernelId::LightPaths), or TS_LP_MEDIA_FLOATS with
 * ray-light slots (KernelId::LightPathsMedia, for paths that leave ray lights):
 *   TS_LP_STATUS  TS_LP_OVERFLOW when the path needed more than the slots or bounces below
 *                 (its VPLs are then incomplete: the host traces it again), else 0
 *   TS_LP_LIGHT   the emissive triangle it started on (SceneBuffers::lights order)
 *   TS_LP_RAYS    rays traced (a count, exact in float)
 *   TS_LP_VPLS    VPLs left (a count), in the slots from TS_LP_VPL, path order
 *   TS_LP_VRLS    ray lights left (a count), in the slots from TS_LP_VRL, path order
 * (counts and indices as float values, exact below 2^24; the records' TS_VPL_PATH is bits).
 * Slots: 32 VPLs, 16 ray lights, 48 segments. Paths end by roulette at q = min(1, ρ's
 * luminance), so a path of 33 diffuse vertices has survived q^32: 4e-5 of the paths at q =
 * 0.73 (the Cornell box's white; 1,152 paths a frame: one re-traced path in 20 frames),
 * while the read-back stays 1.6 KB a path (2.3 KB with ray lights, one per segment inside
 * a medium). */
#define TS_LP_MAX_VPLS 32
#define TS_LP_MAX_VRLS 16
#define TS_LP_MAX_BOUNCES 48
#define TS_LP_STATUS 0
#define TS_LP_LIGHT 1
#define TS_LP_RAYS 2
#define TS_LP_VPLS 3
#define TS_LP_VRLS 4
#define TS_LP_VPL 5
#define TS_LP_FLOATS (TS_LP_VPL + TS_LP_MAX_VPLS * TS_VPL_FLOATS)
#define TS_LP_VRL TS_LP_FLOATS
#define TS_LP_MEDIA_FLOATS (TS_LP_VRL + TS_LP_MAX_VRLS * TS_VRL_FLOATS)
#define TS_LP_OVERFLOW 1u

/* KernelId::LightPathGather (item: one uint, a float offset into the LightPathOut input,
 * the paths' output kept where the kernels ran) copies the TS_LP_GATHER_FLOATS floats
 * from there: a VPL or ray-light record (both TS_VPL_FLOATS), or a path's TS_LP_VPL
 * header floats and the first floats of its first slot. So the host reads back the
 * headers, then the records the paths left, not every empty slot. */
#define TS_LP_GATHER_FLOATS TS_VPL_FLOATS

/* The light-path table (uint words): TS_LPT_SCRAMBLE the Halton digits' and medium
 * events' scramble (host/gi/light_paths.h), TS_LPT_MAX_BOUNCES segments per path,
 * TS_LPT_FLAGS TS_LPT_MEDIUM_SCATTERING | TS_LPT_RAY_LIGHTS, TS_LPT_INV_PATHS (float bits)
 * 1 / paths per set, TS_LPT_REGION_LO and TS_LPT_REGION_HI (3 float bits each) the box of
 * the scene's surfaces and TS_LPT_REGION_MARGIN (float bits, scene units) the distance
 * from it past which medium events take the far roulette (shared/light_path.h;
 * ts_far_importance, shared/medium.h); from TS_LPT_HALTON the Halton table of shared/halton.h. */
#define TS_LPT_SCRAMBLE 0
#define TS_LPT_MAX_BOUNCES 1
#define TS_LPT_FLAGS 2
#define TS_LPT_INV_PATHS 3
#define TS_LPT_REGION_LO 4
#define TS_LPT_REGION_HI 7
#define TS_LPT_REGION_MARGIN 10
#define TS_LPT_HALTON 11
#define TS_LPT_MEDIUM_SCATTERING 1u
#define TS_LPT_RAY_LIGHTS 2u

#ifdef __cplusplus
static_assert(TS_LP_VPL <= TS_LP_GATHER_FLOATS && TS_VRL_FLOATS == TS_LP_GATHER_FLOATS &&
                  TS_LP_GATHER_FLOATS <= TS_LP_FLOATS,
              "layout_light_path.h: a gather takes a header, a VPL or a ray light, inside a path's output");
#endif

#endif /* TS_LAYOUT_LIGHT_PATH_H */
