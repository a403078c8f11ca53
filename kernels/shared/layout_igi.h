/* The igi and AIS buffers, shared by the host (C++) and the kernels (OpenCL C): VPLs,
 * the surface and media kernels' outputs, the AIS and edge-sample item lists and
 * outputs, and the component bits. The rules of every layout are in
 * shared/layout_check.h. */
#ifndef TS_LAYOUT_IGI_H
#define TS_LAYOUT_IGI_H

/* VPLs (host/gi/light_paths.cpp): TS_VPL_FLOATS floats each, sorted by sample set:
 *   TS_VPL_POSITION  3 floats: position
 *   TS_VPL_NORMAL    3 floats: unit normal of the side it lights; for a medium VPL
 *                    (a light path's scattering vertex in the medium) the unit
 *                    propagation direction of the light that reached it
 *   TS_VPL_FLUX      3 floats: flux weight C/M (the path throughput times albedo/π,
 *                    divided by the paths per set; a medium VPL: the throughput times
 *                    the free-flight sampling weight, divided by the paths per set)
 *   TS_VPL_SET       set index
 *   TS_VPL_PATH      path index (uint bits)
 *   TS_VPL_POS_SCALE the largest vertex coordinate of the triangle it lies on (for
 *                    ts_offset_ray_origin); -1 marks a medium VPL (shared/vpl.h)
 * vpl_set_start[k] .. vpl_set_start[k+1] are set k's VPLs. */
#define TS_VPL_FLOATS 12
#define TS_VPL_POSITION 0
#define TS_VPL_NORMAL 3
#define TS_VPL_FLUX 6
#define TS_VPL_SET 9
#define TS_VPL_PATH 10
#define TS_VPL_POS_SCALE 11

/* Virtual ray lights (host/gi/light_paths.cpp; docs/igi.md §6): one per light-path
 * segment inside the medium, TS_VRL_FLOATS floats each, sorted by sample set, for the ray
 * march by default (TsFrame.igi_media_vpls = TS_MEDIA_VPLS_RAYS; `--point-medium-vpls`: none):
 *   TS_VRL_START  3 floats: where the segment enters the medium
 *   TS_VRL_DIR    3 floats: its unit direction (the light's propagation direction)
 *   TS_VRL_FLUX   3 floats: the path throughput entering it, divided by the paths per
 *                 set, times the keep weight (flux; the medium's σs·Tr along the ray
 *                 light weighs each of its points, shared/igi.h)
 *   TS_VRL_SET    set index
 *   TS_VRL_PATH   path index (uint bits)
 *   TS_VRL_LENGTH its length in the medium (scene units, > 0)
 * The same offsets as a VPL's, so the gather sums take either (ts_vpl_gather_term).
 * vrl_set_start[k] .. vrl_set_start[k+1] are set k's ray lights. */
#define TS_VRL_FLOATS 12
#define TS_VRL_START 0
#define TS_VRL_DIR 3
#define TS_VRL_FLUX 6
#define TS_VRL_SET 9
#define TS_VRL_PATH 10
#define TS_VRL_LENGTH 11

/* TsFrame.igi_media_vpls: what the ray march gathers besides the lights. */
#define TS_MEDIA_VPLS_NONE 0u   /* single scattering */
#define TS_MEDIA_VPLS_POINTS 1u /* every VPL of the set, medium VPLs as points */
#define TS_MEDIA_VPLS_RAYS 2u   /* surface VPLs, and ray lights instead of medium VPLs */

/* Per-pixel output of the igi surface kernel: TS_IGI_SURF_FLOATS floats:
 *   TS_IGI_SURF_E_SS       3 floats: E_ss, direct (area-light) irradiance / π
 *   TS_IGI_SURF_E_ID       3 floats: E_id, indirect (VPL) irradiance / π (both the
 *                          quantities albedo multiplies)
 *   TS_IGI_SURF_ALBEDO     3 floats: albedo
 *   TS_IGI_SURF_EMISSION   3 floats: emitted radiance seen
 *   TS_IGI_SURF_NORMAL     3 floats: shading normal
 *   TS_IGI_SURF_DISTANCE   distance to the surface along the camera path (+inf on a miss)
 *   TS_IGI_SURF_THROUGHPUT 3 floats: throughput of specular bounces before it (1 for none)
 *   TS_IGI_SURF_VISIBLE    fraction of the set's light samples not blocked, one behind
 *                          the surface's plane counting as not blocked (AIS soft-shadow
 *                          guidance; ts_igi_gather_end)
 *   TS_IGI_SURF_POSITION   3 floats: the surface position (world space; for the filter's
 *                          plane-distance test)
 *   TS_IGI_SURF_GEO_NORMAL 3 floats: geometric normal (toward the viewer)
 *   TS_IGI_SURF_ORIGIN     3 floats: ray origin for rays that leave the surface
 *   TS_IGI_SURF_POS_SCALE  the origin's offset scale (TsSurface.pos_scale)
 *   TS_IGI_SURF_PRIM       triangle index (uint bits; TS_NO_HIT on a miss)
 * The last four are what the instant cache's G-buffer needs besides the first ones
 * (TS_IC_GBUF_*): ic and tic take it from this pass instead of tracing the camera rays
 * a second time (host/gi/instant_cache.cpp, ic_gbuffer_from_surface). */
#define TS_IGI_SURF_FLOATS 31
#define TS_IGI_SURF_E_SS 0
#define TS_IGI_SURF_E_ID 3
#define TS_IGI_SURF_ALBEDO 6
#define TS_IGI_SURF_EMISSION 9
#define TS_IGI_SURF_NORMAL 12
#define TS_IGI_SURF_DISTANCE 15
#define TS_IGI_SURF_THROUGHPUT 16
#define TS_IGI_SURF_VISIBLE 19
#define TS_IGI_SURF_POSITION 20
#define TS_IGI_SURF_GEO_NORMAL 23
#define TS_IGI_SURF_ORIGIN 26
#define TS_IGI_SURF_POS_SCALE 29
#define TS_IGI_SURF_PRIM 30
/* Per-pixel output of the igi media kernel, TS_IGI_MEDIA_FLOATS floats:
 *   TS_IGI_MEDIA_RADIANCE      3 floats: single-scattered radiance along the camera segment
 *   TS_IGI_MEDIA_TRANSMITTANCE 3 floats: transmittance of that segment
 *   TS_IGI_MEDIA_LIT           fraction of the march steps whose light sample was unoccluded
 *   TS_IGI_MEDIA_LENGTH        length of the segment inside the medium (AIS
 *                              participating-media guidance) */
#define TS_IGI_MEDIA_FLOATS 8
#define TS_IGI_MEDIA_RADIANCE 0
#define TS_IGI_MEDIA_TRANSMITTANCE 3
#define TS_IGI_MEDIA_LIT 6
#define TS_IGI_MEDIA_LENGTH 7
/* Per-item output of the ais extra kernel (one pixel, one extra sample set),
 * TS_AIS_ITEM_FLOATS floats, for that set: TS_AIS_ITEM_E_SS 3 floats E_ss, TS_AIS_ITEM_E_ID
 * 3 floats E_id, TS_AIS_ITEM_PM 3 floats single-scattered radiance. Component c (the bit
 * index of TS_COMPONENT_*) starts at TS_AIS_ITEM_COMPONENT(c). */
#define TS_AIS_ITEM_FLOATS 9
#define TS_AIS_ITEM_E_SS 0
#define TS_AIS_ITEM_E_ID 3
#define TS_AIS_ITEM_PM 6
#define TS_AIS_ITEM_COMPONENT(c) (3 * (c))
/* An item of the ais extra kernel's list, TS_AIS_ITEM_WORDS uints: TS_AIS_ITEM_PIXEL the
 * pixel (row-major index), TS_AIS_ITEM_CODE the sample set (low 8 bits) | TS_COMPONENT_*
 * bits << 8. */
#define TS_AIS_ITEM_WORDS 2
#define TS_AIS_ITEM_PIXEL 0
#define TS_AIS_ITEM_CODE 1
/* A device AIS frame's compact tables (shared/ais_compact.h). The frame is cut into
 * TS_AIS_TILE × TS_AIS_TILE pixel tiles, T of them in rows of tiles (the host list's tiles,
 * kItemTile of host/gi/ais_schedule.h). Work item t·n² + k of KernelId::AisTileSets (set
 * k, tile t; named input AisTileSets) writes TS_AIS_TILE_SET_FLOATS floats:
 *   TS_AIS_TILE_SET_BITS    TS_AIS_TILE_SET_WORDS uints (as_float bits): bit b marks the
 *                           tile's pixel b (row-major in the tile) evaluating set k beyond
 *                           its own
 *   TS_AIS_TILE_SET_COUNT   their number
 *   TS_AIS_TILE_SET_FLAGS+c the tile's pixels component c flags (set 0's items; 0 in
 *                           the others).
 * Named input AisItemOffsets: n²·T + 1 uints, the exclusive prefix sums of the counts in
 * the item list's order, j = k·T + t (set-major; the last: the frame's item count).
 * KernelId::EdgeSegmentCounts writes TS_EDGE_SEGMENT_FLOATS per segment, a tile's row of
 * TS_AIS_TILE pixels (segment t·TS_AIS_TILE + r: row r of tile t; ts_edge_segment): its
 * edge samples and the pixels that take any; named input EdgeSegmentOffsets: S + 1 uints,
 * S = T·TS_AIS_TILE, the samples' exclusive prefix sums. */
#define TS_AIS_TILE 16u
#define TS_AIS_TILE_SET_WORDS 8
#define TS_AIS_TILE_SET_BITS 0
#define TS_AIS_TILE_SET_COUNT 8
#define TS_AIS_TILE_SET_FLAGS 9
#define TS_AIS_TILE_SET_FLOATS 12
#define TS_EDGE_SEGMENT_FLOATS 2
#define TS_EDGE_SEGMENT_SAMPLES 0
#define TS_EDGE_SEGMENT_FLAGGED 1
/* The AIS schedule's parameters (named input AisScheduleTable, shared/ais_guidance.h; the
 * host builds it with ais_schedule_table, host/gi/ais_schedule.h), uints, floats as their
 * bits (as_uint):
 *   TS_AIS_TABLE_TRIGGER + c   component c's (0 SS, 1 ID, 2 PM) trigger (float)
 *   TS_AIS_TABLE_ID_COV        the CoV that saturates ID's g_var (float, scaled to the paths)
 *   TS_AIS_TABLE_PM_COV        the same for PM (float; 0: no g_var)
 *   TS_AIS_TABLE_MIN_ACCEPTED  N_min, the accepted-neighbour count of a cleanable pixel
 *   TS_AIS_TABLE_COMPLETE      A: the distinct sets a flagged pixel completes to
 *   TS_AIS_TABLE_GRADED        A: the graded term's set count G, ⌈a·(min(G, N)−1)⌉ sets
 *   TS_AIS_TABLE_MODE          0 A, 1 A-MAX
 *   TS_AIS_TABLE_COMPONENTS    TS_COMPONENT_* bits of the components guided
 *   TS_AIS_TABLE_EDGE_TRIGGER, TS_AIS_TABLE_EDGE_FULL  edge contrast trigger, full (floats)
 *   TS_AIS_TABLE_EDGE_SAMPLES  edge samples a flagged pixel takes at most (1..15)
 *   TS_AIS_TABLE_EDGE_EPSILON  ε of the edge contrast (float, W/(sr·m²))
 *   TS_AIS_TABLE_ORDER         n² rows of n² − 1 sets: row k, the sets other than k in the
 *                              order a pixel of own set k takes them (far-first) */
#define TS_AIS_TABLE_TRIGGER 0
#define TS_AIS_TABLE_ID_COV 3
#define TS_AIS_TABLE_PM_COV 4
#define TS_AIS_TABLE_MIN_ACCEPTED 5
#define TS_AIS_TABLE_COMPLETE 6
#define TS_AIS_TABLE_MODE 7
#define TS_AIS_TABLE_COMPONENTS 8
#define TS_AIS_TABLE_EDGE_TRIGGER 9
#define TS_AIS_TABLE_EDGE_FULL 10
#define TS_AIS_TABLE_EDGE_SAMPLES 11
#define TS_AIS_TABLE_EDGE_EPSILON 12
#define TS_AIS_TABLE_GRADED 13
#define TS_AIS_TABLE_ORDER 16
/* An edge row sum (KernelId::EdgeRowSums, item = row index), TS_EDGE_ROW_FLOATS floats:
 * TS_EDGE_ROW_DOUBLE and the next the low and high 32 bits of the row's luminance sum as a
 * double, TS_EDGE_ROW_HAS_DOUBLE 1 where the device summed in double (else 0, and
 * TS_EDGE_ROW_FLOAT holds a compensated float sum). */
#define TS_EDGE_ROW_FLOATS 4
#define TS_EDGE_ROW_DOUBLE 0
#define TS_EDGE_ROW_HAS_DOUBLE 2
#define TS_EDGE_ROW_FLOAT 3
/* The VPLs' importance for the view (shared/vpl_importance.h; host/gi/vpl_importance.h).
 * Named input VplImportance, floats: TS_VI_POINTS the view points' count np (exact in
 * float), TS_VI_G_CLAMP the geometry terms' clamp (scene units^-2), TS_VI_CHUNK the VPLs
 * a partial sum of E takes (0: all; exact in float); from TS_VI_HEADER the
 * points' 9 coordinates as 9 arrays of np (position x, y, z, shading normal x, y, z,
 * geometric normal x, y, z: TS_VI_COORD(np, k)); then per point j the weight w_j of the
 * VPLs' pass (TS_VI_WEIGHT(np, j)): the low and high 32 bits of a double, then a float.
 * KernelId::VplImportancePoints (item t = view point t mod np, VPL chunk t div np: one
 * item a point when TS_VI_CHUNK is 0) writes TS_VI_E_FLOATS: that chunk's part of point
 * j's candidates' irradiance E_j as a double's words (TS_VI_E_DOUBLE, TS_VI_E_DOUBLE + 1)
 * with TS_VI_E_HAS_DOUBLE 1, or as a float (TS_VI_E_FLOAT) with 0 where the device has no
 * double; KernelId::VplImportanceVpls (item i = VPL i of the Vpls input) writes one float,
 * Φ_i. */
#define TS_VI_POINTS 0
#define TS_VI_G_CLAMP 1
#define TS_VI_CHUNK 2
#define TS_VI_MAX_CHUNK 16777216u /* 2^24: TS_VI_CHUNK exact in float */
#define TS_VI_HEADER 4
#define TS_VI_POINT_FLOATS 9
#define TS_VI_COORD(np, k) (TS_VI_HEADER + (k) * (np))
#define TS_VI_WEIGHT_FLOATS 3
#define TS_VI_WEIGHT(np, j) (TS_VI_HEADER + TS_VI_POINT_FLOATS * (np) + TS_VI_WEIGHT_FLOATS * (j))
#define TS_VI_FLOATS(np) (TS_VI_HEADER + (TS_VI_POINT_FLOATS + TS_VI_WEIGHT_FLOATS) * (np))
#define TS_VI_E_FLOATS 4
#define TS_VI_E_DOUBLE 0
#define TS_VI_E_HAS_DOUBLE 2
#define TS_VI_E_FLOAT 3
/* The AIS schedule of a pixel (KernelId::AisSchedule, shared/ais_resolve.h),
 * TS_AIS_MASK_FLOATS floats, each a uint's bits (as_float): TS_AIS_MASK_SETS(c) and the
 * next the low and high 32 bits of component c's set mask (bit k: the pixel evaluates set
 * k, its own included), TS_AIS_MASK_FLAGS the TS_COMPONENT_* bits of the components that
 * flag it. KernelId::EdgeSchedule writes one float a pixel: its edge-sample count. */
#define TS_AIS_MASK_FLOATS 7
#define TS_AIS_MASK_SETS(c) (2 * (c))
#define TS_AIS_MASK_FLAGS 6
/* Components (TsFrame.igi_components). */
#define TS_COMPONENT_SS 1u
#define TS_COMPONENT_ID 2u
#define TS_COMPONENT_PM 4u
/* Edge samples (AIS only; shared/edge_samples.h, host/gi/ais_edges.h): extra camera
 * samples in pixels on geometric edges. Host-side only: kernels never see this bit
 * (IgiFrame::prepare masks it out of TsFrame.igi_components). */
#define TS_COMPONENT_EDGE 8u
/* An edge sample's output, TS_EDGE_SAMPLE_FLOATS floats: the first diffuse surface of the
 * sample's camera path, as the surface pass stores it (TS_IGI_SURF_*):
 *   TS_EDGE_SAMPLE_ALBEDO     3 floats: albedo
 *   TS_EDGE_SAMPLE_EMISSION   3 floats: emitted radiance (W/(sr·m²))
 *   TS_EDGE_SAMPLE_THROUGHPUT 3 floats: the specular bounces' throughput
 *   TS_EDGE_SAMPLE_NORMAL     3 floats: shading normal
 *   TS_EDGE_SAMPLE_POSITION   3 floats: hit position (scene units)
 *   TS_EDGE_SAMPLE_DISTANCE   distance along the camera path (scene units; +inf: escaped) */
#define TS_EDGE_SAMPLE_FLOATS 16
#define TS_EDGE_SAMPLE_ALBEDO 0
#define TS_EDGE_SAMPLE_EMISSION 3
#define TS_EDGE_SAMPLE_THROUGHPUT 6
#define TS_EDGE_SAMPLE_NORMAL 9
#define TS_EDGE_SAMPLE_POSITION 12
#define TS_EDGE_SAMPLE_DISTANCE 15
/* An item of the edge-sample kernel's list, TS_EDGE_ITEM_WORDS uints: the pixel
 * (row-major index), the sample's index j >= 1 within the pixel and the pixel's number n
 * of edge samples (its texture footprint shrinks to 1/(n + 1) of the pixel). */
#define TS_EDGE_ITEM_WORDS 3
#define TS_EDGE_ITEM_PIXEL 0
#define TS_EDGE_ITEM_SAMPLE 1
#define TS_EDGE_ITEM_COUNT 2
/* The clamp compensation's per-pixel record (shared/clamp_screen.h, the gather reads it),
 * in two parts: the hot part, TS_CLAMP_SCREEN_HOT_FLOATS floats, which every sample of
 * the gather reads, and the cold part, TS_CLAMP_SCREEN_COLD_FLOATS floats, read only by
 * samples within the clamp radius (most are not). Offsets are within their part:
 *   hot:  TS_CLAMP_SCREEN_POSITION 3 floats: world position (scene units)
 *         TS_CLAMP_SCREEN_AREA     A_q, the pixel's patch area (scene units²)
 *   cold: TS_CLAMP_SCREEN_NORMAL   3 floats: unit normal
 *         TS_CLAMP_SCREEN_SOURCE   3 floats: s_q = L_q · A_q, the diffuse radiance ρ (E_ss + E_id)
 *                                  times the patch area (zero for a pixel that is no diffuse
 *                                  surface seen directly)
 * A pixel's record is TS_CLAMP_SCREEN_FLOATS floats, the hot part then the cold part (at
 * TS_CLAMP_SCREEN_COLD); on a device (KernelId::IgiClampRecords) every field is zero for a
 * pixel not seen directly. The host keeps field k of the records as planes
 * (shared/clamp_screen16.h). The gather's output,
 * KernelId::IgiClampGather's: TS_CLAMP_RESIDUAL_FLOATS floats a pixel, E_res
 * (irradiance / π) at the pixels of the even grid, zero elsewhere. */
#define TS_CLAMP_SCREEN_HOT_FLOATS 4
#define TS_CLAMP_SCREEN_POSITION 0
#define TS_CLAMP_SCREEN_AREA 3
#define TS_CLAMP_SCREEN_COLD_FLOATS 6
#define TS_CLAMP_SCREEN_NORMAL 0
#define TS_CLAMP_SCREEN_SOURCE 3
#define TS_CLAMP_SCREEN_COLD TS_CLAMP_SCREEN_HOT_FLOATS
#define TS_CLAMP_SCREEN_FLOATS (TS_CLAMP_SCREEN_HOT_FLOATS + TS_CLAMP_SCREEN_COLD_FLOATS)
#define TS_CLAMP_RESIDUAL_FLOATS 3

#ifdef __cplusplus
/* Compile-time checks of the layouts above (shared/layout_check.h). */
#include "shared/layout_check.h"

static_assert(TS_VRL_FLOATS == TS_VPL_FLOATS && TS_VRL_FLUX == TS_VPL_FLUX && TS_VRL_SET == TS_VPL_SET &&
                  TS_VRL_PATH == TS_VPL_PATH,
              "layout_igi.h: ray lights share the VPLs' flux, set and path offsets");
static_assert(tessera::layout_check::tiles({{TS_VPL_POSITION, 3}, {TS_VPL_NORMAL, 3}, {TS_VPL_FLUX, 3},
                                            {TS_VPL_SET, 1}, {TS_VPL_PATH, 1}, {TS_VPL_POS_SCALE, 1}},
                                           TS_VPL_FLOATS),
              "layout_igi.h: VPL fields do not tile TS_VPL_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IGI_SURF_E_SS, 3}, {TS_IGI_SURF_E_ID, 3}, {TS_IGI_SURF_ALBEDO, 3},
                                            {TS_IGI_SURF_EMISSION, 3}, {TS_IGI_SURF_NORMAL, 3},
                                            {TS_IGI_SURF_DISTANCE, 1}, {TS_IGI_SURF_THROUGHPUT, 3},
                                            {TS_IGI_SURF_VISIBLE, 1}, {TS_IGI_SURF_POSITION, 3},
                                            {TS_IGI_SURF_GEO_NORMAL, 3}, {TS_IGI_SURF_ORIGIN, 3},
                                            {TS_IGI_SURF_POS_SCALE, 1}, {TS_IGI_SURF_PRIM, 1}},
                                           TS_IGI_SURF_FLOATS),
              "layout_igi.h: igi surface-pass fields do not tile TS_IGI_SURF_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IGI_MEDIA_RADIANCE, 3}, {TS_IGI_MEDIA_TRANSMITTANCE, 3},
                                            {TS_IGI_MEDIA_LIT, 1}, {TS_IGI_MEDIA_LENGTH, 1}},
                                           TS_IGI_MEDIA_FLOATS),
              "layout_igi.h: igi media-pass fields do not tile TS_IGI_MEDIA_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_AIS_ITEM_E_SS, 3}, {TS_AIS_ITEM_E_ID, 3}, {TS_AIS_ITEM_PM, 3}},
                                           TS_AIS_ITEM_FLOATS),
              "layout_igi.h: AIS item fields do not tile TS_AIS_ITEM_FLOATS");
/* The AIS item is indexed by component bit index; these must be TS_COMPONENT_*'s bits. */
static_assert(TS_AIS_ITEM_COMPONENT(0) == TS_AIS_ITEM_E_SS && TS_AIS_ITEM_COMPONENT(1) == TS_AIS_ITEM_E_ID &&
                  TS_AIS_ITEM_COMPONENT(2) == TS_AIS_ITEM_PM && TS_COMPONENT_SS == 1u << 0 &&
                  TS_COMPONENT_ID == 1u << 1 && TS_COMPONENT_PM == 1u << 2,
              "layout_igi.h: TS_AIS_ITEM_COMPONENT(c) must start component c = the bit index of TS_COMPONENT_*");
static_assert(tessera::layout_check::tiles({{TS_EDGE_SAMPLE_ALBEDO, 3}, {TS_EDGE_SAMPLE_EMISSION, 3},
                                            {TS_EDGE_SAMPLE_THROUGHPUT, 3}, {TS_EDGE_SAMPLE_NORMAL, 3},
                                            {TS_EDGE_SAMPLE_POSITION, 3}, {TS_EDGE_SAMPLE_DISTANCE, 1}},
                                           TS_EDGE_SAMPLE_FLOATS),
              "layout_igi.h: edge-sample fields do not tile TS_EDGE_SAMPLE_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_CLAMP_SCREEN_POSITION, 3}, {TS_CLAMP_SCREEN_AREA, 1}},
                                           TS_CLAMP_SCREEN_HOT_FLOATS),
              "layout_igi.h: clamp-screen hot fields do not tile TS_CLAMP_SCREEN_HOT_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_CLAMP_SCREEN_NORMAL, 3}, {TS_CLAMP_SCREEN_SOURCE, 3}},
                                           TS_CLAMP_SCREEN_COLD_FLOATS),
              "layout_igi.h: clamp-screen cold fields do not tile TS_CLAMP_SCREEN_COLD_FLOATS");
#endif /* __cplusplus */

#endif /* TS_LAYOUT_IGI_H */
