/* Instant caching's buffers, shared by the host (C++) and the kernels (OpenCL C); the
 * rules of every layout are in shared/layout_check.h. */
#ifndef TS_LAYOUT_IC_H
#define TS_LAYOUT_IC_H
#include "shared/layout_rays.h" /* TS_NO_HIT */

/* Instant caching (shared/ic.h, host/gi/irradiance_cache.h).
 * The ic G-buffer, TS_IC_GBUF_FLOATS floats per pixel: the first diffuse surface seen
 * through the pixel, taken from the igi surface pass's output (so the same surface):
 *   TS_IC_GBUF_POSITION   3 floats: position
 *   TS_IC_GBUF_NORMAL     3 floats: shading normal
 *   TS_IC_GBUF_GEO_NORMAL 3 floats: geometric normal (toward the viewer)
 *   TS_IC_GBUF_ORIGIN     3 floats: ray origin for leaving rays
 *   TS_IC_GBUF_POS_SCALE  pos_scale
 *   TS_IC_GBUF_PRIM       triangle index (uint bits; TS_NO_HIT when the camera path finds
 *                         no surface or a surface of albedo 0: no record can serve it)
 *   TS_IC_GBUF_DISTANCE   distance along the camera path (scene units) */
#define TS_IC_GBUF_FLOATS 15
#define TS_IC_GBUF_POSITION 0
#define TS_IC_GBUF_NORMAL 3
#define TS_IC_GBUF_GEO_NORMAL 6
#define TS_IC_GBUF_ORIGIN 9
#define TS_IC_GBUF_POS_SCALE 12
#define TS_IC_GBUF_PRIM 13
#define TS_IC_GBUF_DISTANCE 14
/* A cache record as the interpolation reads it, TS_IC_RECORD_FLOATS floats:
 *   TS_IC_RECORD_POSITION 3 floats: position
 *   TS_IC_RECORD_NORMAL   3 floats: unit shading normal
 *   TS_IC_RECORD_E        3 floats: E = irradiance / π gathered from the VPLs (albedo-free)
 *   TS_IC_RECORD_RADIUS   validity radius R (scene units) */
#define TS_IC_RECORD_FLOATS 10
#define TS_IC_RECORD_POSITION 0
#define TS_IC_RECORD_NORMAL 3
#define TS_IC_RECORD_E 6
#define TS_IC_RECORD_RADIUS 9
/* An octree node, TS_IC_NODE_FLOATS floats:
 *   TS_IC_NODE_CENTRE 3 floats: centre
 *   TS_IC_NODE_HALF   half edge (scene units)
 *   TS_IC_NODE_CHILD  index of its first child (uint bits; 0 = leaf, as the root is
 *                     node 0). The children it has are stored consecutively in octant
 *                     order x + 2y + 4z; an octant whose child would hold no record and
 *                     no child is left out (three in four on Sibenik's cache)
 *   TS_IC_NODE_FIRST  first entry of its record list in the reference array (uint bits)
 *   TS_IC_NODE_COUNT  number of records (uint bits)
 *   TS_IC_NODE_MASK   which octants have a child: bit o for octant o (uint bits); child
 *                     of octant o = CHILD + the bits below o */
#define TS_IC_NODE_FLOATS 8
#define TS_IC_NODE_CENTRE 0
#define TS_IC_NODE_HALF 3
#define TS_IC_NODE_CHILD 4
#define TS_IC_NODE_FIRST 5
#define TS_IC_NODE_COUNT 6
#define TS_IC_NODE_MASK 7
/* Per-pixel output of the ic interpolation kernel, TS_IC_INTERP_FLOATS floats:
 * TS_IC_INTERP_E 3 floats: interpolated E (0 where no record is usable or the pixel has
 * no surface), TS_IC_INTERP_WEIGHT the weight sum Σ w, TS_IC_INTERP_RESIDUAL 3 floats:
 * the pixel's estimate of what the geometry-term clamp removed from E (shared/ic_residual.h;
 * 0 where none was asked for), also irradiance / π. */
#define TS_IC_INTERP_FLOATS 7
#define TS_IC_INTERP_E 0
#define TS_IC_INTERP_WEIGHT 3
#define TS_IC_INTERP_RESIDUAL 4
/* The record-VPL pair kernel (shared/ic_gather.h), one item per pair to trace,
 * TS_IC_PAIR_WORDS uints: TS_IC_PAIR_RECORD the record (index into the IcRecordSurfaces
 * input), TS_IC_PAIR_VPL the VPL (index into the Vpls input). Its output,
 * TS_IC_PAIR_FLOATS floats: TS_IC_PAIR_HIT (uint bits) a triangle the shadow ray hits
 * (the one its any-hit query found), TS_IC_PAIR_VISIBLE (= TS_NO_HIT) when unoccluded,
 * TS_IC_PAIR_FACING when the geometry term is 0 (no ray traced). */
#define TS_IC_PAIR_WORDS 2
#define TS_IC_PAIR_RECORD 0
#define TS_IC_PAIR_VPL 1
#define TS_IC_PAIR_FLOATS 1
#define TS_IC_PAIR_HIT 0
#define TS_IC_PAIR_VISIBLE 0xffffffffu
#define TS_IC_PAIR_FACING 0xfffffffeu
/* The record gather kernel (shared/ic.h), one item per record to (re-)sum,
 * TS_IC_GATHER_WORDS uints: TS_IC_GATHER_RECORD the record (index into
 * IcRecordSurfaces), TS_IC_GATHER_ROW its row in the IcVisibility input. A row is a bit
 * mask of TS_IC_VISIBLE_WORDS(n) uints for n VPLs: VPL j is visible (unoccluded, with a
 * positive geometry term) when bit j % 32 of word j / 32 is set; the bits past n are 0.
 * (One bit a pair, not the host's int32 occluder: 32 times less to copy each frame.) Its output,
 * TS_IC_GATHER_FLOATS floats: TS_IC_GATHER_E 3 floats E = irradiance / π from the visible
 * VPLs, TS_IC_GATHER_HARMONIC the harmonic mean distance to them (scene units; +inf for
 * none); then the sums they come from, for a caller that adds and subtracts sums over
 * VPL subsets (the temporal update's re-sum, docs/instant-caching.md §8), each as a
 * (hi, lo) float pair whose sum is the accumulator's value (a double split in two, or a
 * compensated float sum and its compensation): TS_IC_GATHER_SUM 3 pairs Σ C·T·min(G, b)
 * per channel (E before the 1/π), TS_IC_GATHER_INV_DIST one pair Σ 1/distance, and
 * TS_IC_GATHER_SEEN the visible VPLs' count (a float, exact: --ic-paths ≤ 65536 makes far
 * fewer than 2^24 VPLs). */
#define TS_IC_GATHER_WORDS 2
#define TS_IC_GATHER_RECORD 0
#define TS_IC_GATHER_ROW 1
#define TS_IC_GATHER_FLOATS 13
#define TS_IC_GATHER_E 0
#define TS_IC_GATHER_HARMONIC 3
#define TS_IC_GATHER_SUM 4
#define TS_IC_GATHER_INV_DIST 10
#define TS_IC_GATHER_SEEN 12
#define TS_IC_VISIBLE_WORDS(n) (((n) + 31u) / 32u)
/* Depth bound of the octree (root = depth 0). */
#define TS_IC_MAX_DEPTH 24

#ifdef __cplusplus
/* Compile-time checks of the layouts above (shared/layout_check.h). */
#include "shared/layout_check.h"

static_assert(tessera::layout_check::tiles({{TS_IC_GBUF_POSITION, 3}, {TS_IC_GBUF_NORMAL, 3},
                                            {TS_IC_GBUF_GEO_NORMAL, 3}, {TS_IC_GBUF_ORIGIN, 3},
                                            {TS_IC_GBUF_POS_SCALE, 1}, {TS_IC_GBUF_PRIM, 1},
                                            {TS_IC_GBUF_DISTANCE, 1}},
                                           TS_IC_GBUF_FLOATS),
              "layout_ic.h: ic G-buffer fields do not tile TS_IC_GBUF_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IC_RECORD_POSITION, 3}, {TS_IC_RECORD_NORMAL, 3}, {TS_IC_RECORD_E, 3},
                                            {TS_IC_RECORD_RADIUS, 1}},
                                           TS_IC_RECORD_FLOATS),
              "layout_ic.h: ic record fields do not tile TS_IC_RECORD_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IC_NODE_CENTRE, 3}, {TS_IC_NODE_HALF, 1}, {TS_IC_NODE_CHILD, 1},
                                            {TS_IC_NODE_FIRST, 1}, {TS_IC_NODE_COUNT, 1}, {TS_IC_NODE_MASK, 1}},
                                           TS_IC_NODE_FLOATS),
              "layout_ic.h: ic octree node fields do not tile TS_IC_NODE_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IC_INTERP_E, 3}, {TS_IC_INTERP_WEIGHT, 1}, {TS_IC_INTERP_RESIDUAL, 3}}, TS_IC_INTERP_FLOATS),
              "layout_ic.h: ic interpolation fields do not tile TS_IC_INTERP_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IC_PAIR_RECORD, 1}, {TS_IC_PAIR_VPL, 1}}, TS_IC_PAIR_WORDS),
              "layout_ic.h: ic pair item fields do not tile TS_IC_PAIR_WORDS");
static_assert(tessera::layout_check::tiles({{TS_IC_PAIR_HIT, 1}}, TS_IC_PAIR_FLOATS),
              "layout_ic.h: ic pair output fields do not tile TS_IC_PAIR_FLOATS");
/* An unoccluded pair is a shadow ray that hit nothing; the facing code is no triangle. */
static_assert(TS_IC_PAIR_VISIBLE == TS_NO_HIT && TS_IC_PAIR_FACING != TS_NO_HIT,
              "layout_ic.h: TS_IC_PAIR_VISIBLE must be TS_NO_HIT, TS_IC_PAIR_FACING another code");
static_assert(tessera::layout_check::tiles({{TS_IC_GATHER_RECORD, 1}, {TS_IC_GATHER_ROW, 1}}, TS_IC_GATHER_WORDS),
              "layout_ic.h: ic gather item fields do not tile TS_IC_GATHER_WORDS");
static_assert(TS_IC_VISIBLE_WORDS(0u) == 0u && TS_IC_VISIBLE_WORDS(32u) == 1u && TS_IC_VISIBLE_WORDS(33u) == 2u,
              "layout_ic.h: TS_IC_VISIBLE_WORDS(n) is n bits rounded up to whole uints");
static_assert(tessera::layout_check::tiles({{TS_IC_GATHER_E, 3}, {TS_IC_GATHER_HARMONIC, 1}, {TS_IC_GATHER_SUM, 6},
                                            {TS_IC_GATHER_INV_DIST, 2}, {TS_IC_GATHER_SEEN, 1}},
                                           TS_IC_GATHER_FLOATS),
              "layout_ic.h: ic gather output fields do not tile TS_IC_GATHER_FLOATS");
#endif /* __cplusplus */

#endif /* TS_LAYOUT_IC_H */
