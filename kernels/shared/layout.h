/* Buffer layouts shared by the host (C++) and the kernels (OpenCL C). Declared once,
 * here: each record is a set of named offsets (TS_<RECORD>_<FIELD>, in floats from the
 * record's start) and its size TS_<RECORD>_FLOATS. Every buffer is an array of 32-bit
 * `float` or `uint`; no float3 (its size differs between OpenCL and C++), no pointers.
 * Index a buffer only through these names; the C++ block at the end of this file checks
 * at compile time that each record's fields tile it exactly (no gap, no overlap, the
 * last field ending at the record size), so a field added or resized here without the
 * check's list (or the other way round) does not build.
 *
 * BVH (built by host/bvh/bvh_builder.cpp with Embree's rtcBuildBVH, MEDIUM quality =
 * binned SAH, maxBranchingFactor 4, maxLeafSize TS_BVH_LEAF_MAX, maxDepth
 * TS_BVH_MAX_DEPTH; the limits and the stack bound are explained at their defines):
 *   nodes: TS_NODE_FLOATS floats per node, node 0 is the root. A 4-wide node keeps its
 *   children's boxes as structure of arrays so one float4 load serves four children:
 *     TS_NODE_MIN(a)  4 floats: the four children's box minima on axis a (0 = x, 1 = y, 2 = z)
 *     TS_NODE_MAX(a)  4 floats: their box maxima on axis a
 *       (so [0..3] min x, [4..7] max x, [8..11] min y, [12..15] max y, [16..19] min z,
 *       [20..23] max z)
 *     TS_NODE_REFS    4 child references (int bits, read with as_int)
 *     TS_NODE_UNUSED  4 floats (pads the node to 128 bytes, two cache lines)
 *   A child reference r >= 0 is an inner node index. r < 0 is a leaf: with v = ~r,
 *   its triangles are bvh_tris entries [v >> 3, (v >> 3) + (v & 7)). An unused slot
 *   holds r = -1 (a leaf of 0 triangles) and an empty box (min +inf, max -inf), which
 *   the slab test rejects for every ray.
 *   bvh_tris: TS_BVH_TRI_FLOATS floats per triangle, in leaf order:
 *     TS_BVH_TRI_VERTEX(k)  3 floats: vertex k (k = 0, 1, 2), each starting a float4
 *     TS_BVH_TRI_PRIM       original triangle index (uint bits), in v0's fourth float
 *     the fourth floats of v1 and v2 are 0.
 *
 * Shading data, indexed by the original (scene) triangle index `prim`:
 *   tri_pos   TS_TRI_POS_FLOATS (9) floats: p0, p1, p2 (world space, scene units)
 *   tri_nrm   TS_TRI_NRM_FLOATS (9) floats: shading normals n0, n1, n2 (unit length)
 *   tri_uv    TS_TRI_UV_FLOATS (6) floats: uv0, uv1, uv2
 *   tri_mat   1 uint:   material index
 * materials: TS_MATERIAL_FLOATS floats:
 *   TS_MAT_ALBEDO     3 floats: albedo (Kd, linear)
 *   TS_MAT_TEXTURE    texture index (int bits, -1 = none)
 *   TS_MAT_EMISSION   3 floats: emitted radiance Le in W/(sr·m²)
 *   TS_MAT_KIND       uint bits: TS_MAT_DIFFUSE, TS_MAT_MIRROR, TS_MAT_DIELECTRIC
 *   TS_MAT_SPECULAR   3 floats: specular reflectance (Ks; the mirror's)
 *   TS_MAT_IOR        index of refraction (dielectric)
 *   TS_MAT_SELECTION  selection luminance: the luminance of the emission lights are
 *                     picked by (the animation's maximum, so the pick probabilities stay
 *                     the same over frames; ts_light_pdf_area)
 *   TS_MAT_UNUSED     3 floats
 * medium: TS_MEDIUM_FLOATS floats:
 *   TS_MEDIUM_SIGMA_A 3 floats, TS_MEDIUM_SIGMA_S 3 floats (per scene unit),
 *   TS_MEDIUM_G       Henyey–Greenstein g,
 *   TS_MEDIUM_BOUNDED 1 if bounded by the box else 0,
 *   TS_MEDIUM_BOX_MIN 3 floats, TS_MEDIUM_BOX_MAX 3 floats,
 *   TS_MEDIUM_PRESENT 1 if the scene has a medium at all, TS_MEDIUM_UNUSED 1 float.
 * textures: tex_info TS_TEX_INFO_UINTS uints per texture: TS_TEX_OFFSET texel offset of
 *   level 0, TS_TEX_WIDTH, TS_TEX_HEIGHT (level 0), TS_TEX_LEVELS mip levels (>= 1);
 *   tex_texels: uint RGBA8 (R in the low byte), sRGB-encoded, row 0 at the top. A
 *   texture's levels follow each other from its offset: level l is max(1, w >> l) by
 *   max(1, h >> l) texels (host/device/texture_mips.h builds them).
 * lights: TS_LIGHT_FLOATS floats per emissive triangle:
 *   TS_LIGHT_P0 3 floats: p0, TS_LIGHT_E1 3 floats: e1 = p1 - p0,
 *   TS_LIGHT_E2 3 floats: e2 = p2 - p0, TS_LIGHT_RADIANCE 3 floats: Le (W/(sr·m²)),
 *   TS_LIGHT_AREA (scene units²), TS_LIGHT_PRIM original triangle index (uint bits),
 *   TS_LIGHT_UNUSED 2 floats.
 *   light_cdf: one float per light, the running sum of power (Le luminance × area)
 *   normalised so the last entry is 1; light i is picked with probability
 *   cdf[i] - cdf[i-1].
 *
 * Ray batches (trace_closest / trace_occluded, kernels/trace.cl and Backend):
 *   rays: TS_RAY_FLOATS floats per ray: TS_RAY_ORG 3 floats, TS_RAY_TMIN,
 *   TS_RAY_DIR 3 floats, TS_RAY_TMAX.
 *   closest hits: TS_HIT_FLOATS words per ray: TS_HIT_T, TS_HIT_U, TS_HIT_V (floats),
 *   TS_HIT_PRIM (uint bits, TS_NO_HIT on a miss). Occlusion: 1 uint per ray.
 */
#ifndef TS_LAYOUT_H
#define TS_LAYOUT_H

#define TS_NODE_FLOATS 32
#define TS_NODE_MIN(axis) (8 * (axis))
#define TS_NODE_MAX(axis) (8 * (axis) + 4)
#define TS_NODE_REFS 24
#define TS_NODE_UNUSED 28
#define TS_BVH_TRI_FLOATS 12
#define TS_BVH_TRI_VERTEX(k) (4 * (k))
#define TS_BVH_TRI_PRIM 3
/* BVH limits. Depth = inner nodes on the longest root-to-leaf path. The builder refuses
 * a tree deeper than TS_BVH_MAX_DEPTH or with a leaf over TS_BVH_LEAF_MAX triangles
 * (check_bvh_limits in host/bvh/bvh_builder.h), so the traversal stack can never
 * overflow: visiting an inner node pops 1 and pushes at most 4, so at depth d the stack
 * holds at most 3 siblings per level above plus 4 children, 3 d + 1 entries (checked at
 * compile time below). The leaf count is packed in 3 bits of a child reference. */
#define TS_BVH_MAX_DEPTH 48
#define TS_BVH_STACK_SIZE 160
#define TS_BVH_LEAF_MAX 4
#define TS_TRI_POS_FLOATS 9
#define TS_TRI_NRM_FLOATS 9
#define TS_TRI_UV_FLOATS 6
#define TS_MATERIAL_FLOATS 16
#define TS_MAT_ALBEDO 0
#define TS_MAT_TEXTURE 3
#define TS_MAT_EMISSION 4
#define TS_MAT_KIND 7
#define TS_MAT_SPECULAR 8
#define TS_MAT_IOR 11
#define TS_MAT_SELECTION 12
#define TS_MAT_UNUSED 13
#define TS_MAT_DIFFUSE 0u
#define TS_MAT_MIRROR 1u
#define TS_MAT_DIELECTRIC 2u
#define TS_MEDIUM_FLOATS 16
#define TS_MEDIUM_SIGMA_A 0
#define TS_MEDIUM_SIGMA_S 3
#define TS_MEDIUM_G 6
#define TS_MEDIUM_BOUNDED 7
#define TS_MEDIUM_BOX_MIN 8
#define TS_MEDIUM_BOX_MAX 11
#define TS_MEDIUM_PRESENT 14
#define TS_MEDIUM_UNUSED 15
#define TS_TEX_INFO_UINTS 4
#define TS_TEX_OFFSET 0
#define TS_TEX_WIDTH 1
#define TS_TEX_HEIGHT 2
#define TS_TEX_LEVELS 3
#define TS_LIGHT_FLOATS 16
#define TS_LIGHT_P0 0
#define TS_LIGHT_E1 3
#define TS_LIGHT_E2 6
#define TS_LIGHT_RADIANCE 9
#define TS_LIGHT_AREA 12
#define TS_LIGHT_PRIM 13
#define TS_LIGHT_UNUSED 14
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

/* Fixed OpenCL work-group size for every kernel: PoCL runs a work-group as a loop over
 * work-items, so one size keeps one compiled variant; 64 divides all our launch sizes
 * after rounding up. */
#define TS_WORKGROUP_SIZE 64

/* Per-frame parameters, passed by value to the kernels and to the Embree path.
 * Only 4-byte scalars, so the layout is the same in OpenCL C and C++.
 * The camera ray through pixel (x, y) with sub-pixel offset (jx, jy) in [0,1)^2 is
 *   dir = forward + (2 (x + jx) / width - 1) right + (1 - 2 (y + jy) / height) up,
 * where |right| = tan(vfov/2) · width/height and |up| = tan(vfov/2). */
typedef struct TsFrame {
    float cam_pos[3];
    float cam_forward[3];
    float cam_right[3];
    float cam_up[3];
    unsigned int width;
    unsigned int height;
    unsigned int pass;           /* sample pass index, 0-based; one pass = 1 spp */
    unsigned int shadow_samples; /* area-light samples per camera hit */
    unsigned int seed;
    unsigned int light_count;
    unsigned int max_depth;      /* pt: path vertices (surface or medium) before stopping */
    unsigned int max_scatter;    /* pt: medium scattering vertices per path; 0 = unlimited */
    float light_power;           /* sum over lights of selection luminance × area (for pdfs) */
    unsigned int igi_tile;       /* igi: interleave tile edge n (n² sample sets) */
    unsigned int igi_steps;      /* igi: ray-march steps per pixel along the camera ray */
    float igi_g_clamp;           /* igi: bound b on the VPL geometry term (scene units^-2) */
    float igi_rotation[3];       /* igi: per-frame Cranley–Patterson shift of the set samples */
    float igi_march_far;         /* igi: march limit for rays that escape a medium filling space:
                                    past it (twice the scene diagonal beyond the camera's
                                    distance to the origin) no geometry can light them */
    unsigned int igi_components; /* igi/ais: TS_COMPONENT_* bits of what to compute */
    float ic_error_bound;        /* ic: Ward's a of the interpolation kernel (shared/ic_lookup.h) */
    unsigned int igi_media_vpls; /* igi: 1 = the ray march gathers VPLs too (multiple
                                    scattering; light paths then scatter in the medium) */
    float pixel_cone;            /* texture filtering: spread angle of a pixel's ray cone
                                    (radians, 2·tan(vfov/2)/height); 0 = finest mip level
                                    only (pt, the reference, supersamples instead) */
    unsigned int igi_filter;     /* igi resolve: 1 = the discontinuity filter (window edge
                                    igi_tile), 0 = components unfiltered (shared/igi_resolve.h) */
    float igi_filter_cos;        /* igi resolve: the filter's normal threshold (cos) */
    float igi_filter_depth;      /* igi resolve: the filter's plane distance, relative to depth */
    unsigned int igi_equiangular; /* igi: 1 = the ray march's light samples at equiangular
                                     distances, MIS with the march's (shared/igi.h); 0 = at
                                     the march's own points */
    float igi_march_rotation;     /* igi: per-frame Cranley–Patterson shift of the ray march's
                                     points, apart from igi_rotation: one shared shift would tie
                                     each step's distance to its light sample's position
                                     (shared/igi.h, ts_igi_march_t) */
} TsFrame;

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

/* Per-pixel output of the igi surface kernel: TS_IGI_SURF_FLOATS floats:
 *   TS_IGI_SURF_E_SS       3 floats: E_ss, direct (area-light) irradiance / π
 *   TS_IGI_SURF_E_ID       3 floats: E_id, indirect (VPL) irradiance / π (both the
 *                          quantities albedo multiplies)
 *   TS_IGI_SURF_ALBEDO     3 floats: albedo
 *   TS_IGI_SURF_EMISSION   3 floats: emitted radiance seen
 *   TS_IGI_SURF_NORMAL     3 floats: shading normal
 *   TS_IGI_SURF_DISTANCE   distance to the surface along the camera path (+inf on a miss)
 *   TS_IGI_SURF_THROUGHPUT 3 floats: throughput of specular bounces before it (1 for none)
 *   TS_IGI_SURF_VISIBLE    fraction of the light samples that reached the light
 *                          unoccluded (AIS soft-shadow guidance)
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
 *   TS_IC_NODE_CHILD  index of the first of its 8 children (uint bits, stored
 *                     consecutively in octant order x + 2y + 4z; 0 = leaf, as the root
 *                     is node 0)
 *   TS_IC_NODE_FIRST  first entry of its record list in the reference array (uint bits)
 *   TS_IC_NODE_COUNT  number of records (uint bits)
 *   TS_IC_NODE_UNUSED 1 float */
#define TS_IC_NODE_FLOATS 8
#define TS_IC_NODE_CENTRE 0
#define TS_IC_NODE_HALF 3
#define TS_IC_NODE_CHILD 4
#define TS_IC_NODE_FIRST 5
#define TS_IC_NODE_COUNT 6
#define TS_IC_NODE_UNUSED 7
/* Per-pixel output of the ic interpolation kernel, TS_IC_INTERP_FLOATS floats:
 * TS_IC_INTERP_E 3 floats: interpolated E (0 where no record is usable or the pixel has
 * no surface), TS_IC_INTERP_WEIGHT the weight sum Σ w. */
#define TS_IC_INTERP_FLOATS 4
#define TS_IC_INTERP_E 0
#define TS_IC_INTERP_WEIGHT 3
/* The record-VPL pair kernel (shared/ic_gather.h), one item per pair to trace,
 * TS_IC_PAIR_WORDS uints: TS_IC_PAIR_RECORD the record (index into the IcRecordSurfaces
 * input), TS_IC_PAIR_VPL the VPL (index into the Vpls input). Its output,
 * TS_IC_PAIR_FLOATS floats: TS_IC_PAIR_HIT (uint bits) the triangle the shadow ray hit
 * first, TS_IC_PAIR_VISIBLE (= TS_NO_HIT) when unoccluded, TS_IC_PAIR_FACING when the
 * geometry term is 0 (no ray traced). */
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
 * none). */
#define TS_IC_GATHER_WORDS 2
#define TS_IC_GATHER_RECORD 0
#define TS_IC_GATHER_ROW 1
#define TS_IC_GATHER_FLOATS 4
#define TS_IC_GATHER_E 0
#define TS_IC_GATHER_HARMONIC 3
#define TS_IC_VISIBLE_WORDS(n) (((n) + 31u) / 32u)
/* Depth bound of the octree (root = depth 0). */
#define TS_IC_MAX_DEPTH 24

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

#ifdef __cplusplus
/* Compile-time checks of the layouts above (C++ only; the OpenCL compiler never sees
 * this). Each list gives a record's fields in order with their widths in floats; it must
 * tile the record: every field starts where the one before it ends, and the last ends at
 * the record's size. A field moved, resized or added in the defines without this list (or
 * the other way round) fails to build. */
#include <cstddef>
#include <initializer_list>
#include <type_traits>

namespace tessera::layout_check {
struct Field {
    int offset, width;
};
constexpr bool tiles(std::initializer_list<Field> fields, int total) {
    int next = 0;
    for (const Field& f : fields) {
        if (f.offset != next || f.width <= 0) return false;
        next += f.width;
    }
    return next == total;
}
}  // namespace tessera::layout_check

/* The traversal stack (kernels/bvh_traverse.h) holds every node a tree of the builder's
 * maximum depth can leave pending; the builder enforces the depth and leaf size. */
static_assert(TS_BVH_STACK_SIZE >= 3 * TS_BVH_MAX_DEPTH + 1,
              "layout.h: TS_BVH_STACK_SIZE must be >= 3 * TS_BVH_MAX_DEPTH + 1 (4-wide nodes)");
static_assert(TS_BVH_LEAF_MAX >= 1 && TS_BVH_LEAF_MAX <= 7,
              "layout.h: a leaf's triangle count is packed in 3 bits of its child reference");
static_assert(tessera::layout_check::tiles({{TS_NODE_MIN(0), 4}, {TS_NODE_MAX(0), 4}, {TS_NODE_MIN(1), 4},
                                            {TS_NODE_MAX(1), 4}, {TS_NODE_MIN(2), 4}, {TS_NODE_MAX(2), 4},
                                            {TS_NODE_REFS, 4}, {TS_NODE_UNUSED, 4}},
                                           TS_NODE_FLOATS),
              "layout.h: BVH node fields do not tile TS_NODE_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_BVH_TRI_VERTEX(0), 3}, {TS_BVH_TRI_PRIM, 1}, {TS_BVH_TRI_VERTEX(1), 3},
                                            {TS_BVH_TRI_VERTEX(1) + 3, 1}, {TS_BVH_TRI_VERTEX(2), 3},
                                            {TS_BVH_TRI_VERTEX(2) + 3, 1}},
                                           TS_BVH_TRI_FLOATS),
              "layout.h: BVH triangle fields do not tile TS_BVH_TRI_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_MAT_ALBEDO, 3}, {TS_MAT_TEXTURE, 1}, {TS_MAT_EMISSION, 3},
                                            {TS_MAT_KIND, 1}, {TS_MAT_SPECULAR, 3}, {TS_MAT_IOR, 1},
                                            {TS_MAT_SELECTION, 1}, {TS_MAT_UNUSED, 3}},
                                           TS_MATERIAL_FLOATS),
              "layout.h: material fields do not tile TS_MATERIAL_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_MEDIUM_SIGMA_A, 3}, {TS_MEDIUM_SIGMA_S, 3}, {TS_MEDIUM_G, 1},
                                            {TS_MEDIUM_BOUNDED, 1}, {TS_MEDIUM_BOX_MIN, 3}, {TS_MEDIUM_BOX_MAX, 3},
                                            {TS_MEDIUM_PRESENT, 1}, {TS_MEDIUM_UNUSED, 1}},
                                           TS_MEDIUM_FLOATS),
              "layout.h: medium fields do not tile TS_MEDIUM_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_TEX_OFFSET, 1}, {TS_TEX_WIDTH, 1}, {TS_TEX_HEIGHT, 1},
                                            {TS_TEX_LEVELS, 1}},
                                           TS_TEX_INFO_UINTS),
              "layout.h: texture info fields do not tile TS_TEX_INFO_UINTS");
static_assert(tessera::layout_check::tiles({{TS_LIGHT_P0, 3}, {TS_LIGHT_E1, 3}, {TS_LIGHT_E2, 3},
                                            {TS_LIGHT_RADIANCE, 3}, {TS_LIGHT_AREA, 1}, {TS_LIGHT_PRIM, 1},
                                            {TS_LIGHT_UNUSED, 2}},
                                           TS_LIGHT_FLOATS),
              "layout.h: light fields do not tile TS_LIGHT_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_RAY_ORG, 3}, {TS_RAY_TMIN, 1}, {TS_RAY_DIR, 3}, {TS_RAY_TMAX, 1}},
                                           TS_RAY_FLOATS),
              "layout.h: ray fields do not tile TS_RAY_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_HIT_T, 1}, {TS_HIT_U, 1}, {TS_HIT_V, 1}, {TS_HIT_PRIM, 1}},
                                           TS_HIT_FLOATS),
              "layout.h: hit fields do not tile TS_HIT_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_VPL_POSITION, 3}, {TS_VPL_NORMAL, 3}, {TS_VPL_FLUX, 3},
                                            {TS_VPL_SET, 1}, {TS_VPL_PATH, 1}, {TS_VPL_POS_SCALE, 1}},
                                           TS_VPL_FLOATS),
              "layout.h: VPL fields do not tile TS_VPL_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IGI_SURF_E_SS, 3}, {TS_IGI_SURF_E_ID, 3}, {TS_IGI_SURF_ALBEDO, 3},
                                            {TS_IGI_SURF_EMISSION, 3}, {TS_IGI_SURF_NORMAL, 3},
                                            {TS_IGI_SURF_DISTANCE, 1}, {TS_IGI_SURF_THROUGHPUT, 3},
                                            {TS_IGI_SURF_VISIBLE, 1}, {TS_IGI_SURF_POSITION, 3},
                                            {TS_IGI_SURF_GEO_NORMAL, 3}, {TS_IGI_SURF_ORIGIN, 3},
                                            {TS_IGI_SURF_POS_SCALE, 1}, {TS_IGI_SURF_PRIM, 1}},
                                           TS_IGI_SURF_FLOATS),
              "layout.h: igi surface-pass fields do not tile TS_IGI_SURF_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IGI_MEDIA_RADIANCE, 3}, {TS_IGI_MEDIA_TRANSMITTANCE, 3},
                                            {TS_IGI_MEDIA_LIT, 1}, {TS_IGI_MEDIA_LENGTH, 1}},
                                           TS_IGI_MEDIA_FLOATS),
              "layout.h: igi media-pass fields do not tile TS_IGI_MEDIA_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_AIS_ITEM_E_SS, 3}, {TS_AIS_ITEM_E_ID, 3}, {TS_AIS_ITEM_PM, 3}},
                                           TS_AIS_ITEM_FLOATS),
              "layout.h: AIS item fields do not tile TS_AIS_ITEM_FLOATS");
/* The AIS item is indexed by component bit index; these must be TS_COMPONENT_*'s bits. */
static_assert(TS_AIS_ITEM_COMPONENT(0) == TS_AIS_ITEM_E_SS && TS_AIS_ITEM_COMPONENT(1) == TS_AIS_ITEM_E_ID &&
                  TS_AIS_ITEM_COMPONENT(2) == TS_AIS_ITEM_PM && TS_COMPONENT_SS == 1u << 0 &&
                  TS_COMPONENT_ID == 1u << 1 && TS_COMPONENT_PM == 1u << 2,
              "layout.h: TS_AIS_ITEM_COMPONENT(c) must start component c = the bit index of TS_COMPONENT_*");
static_assert(tessera::layout_check::tiles({{TS_EDGE_SAMPLE_ALBEDO, 3}, {TS_EDGE_SAMPLE_EMISSION, 3},
                                            {TS_EDGE_SAMPLE_THROUGHPUT, 3}, {TS_EDGE_SAMPLE_NORMAL, 3},
                                            {TS_EDGE_SAMPLE_POSITION, 3}, {TS_EDGE_SAMPLE_DISTANCE, 1}},
                                           TS_EDGE_SAMPLE_FLOATS),
              "layout.h: edge-sample fields do not tile TS_EDGE_SAMPLE_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IC_GBUF_POSITION, 3}, {TS_IC_GBUF_NORMAL, 3},
                                            {TS_IC_GBUF_GEO_NORMAL, 3}, {TS_IC_GBUF_ORIGIN, 3},
                                            {TS_IC_GBUF_POS_SCALE, 1}, {TS_IC_GBUF_PRIM, 1},
                                            {TS_IC_GBUF_DISTANCE, 1}},
                                           TS_IC_GBUF_FLOATS),
              "layout.h: ic G-buffer fields do not tile TS_IC_GBUF_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IC_RECORD_POSITION, 3}, {TS_IC_RECORD_NORMAL, 3}, {TS_IC_RECORD_E, 3},
                                            {TS_IC_RECORD_RADIUS, 1}},
                                           TS_IC_RECORD_FLOATS),
              "layout.h: ic record fields do not tile TS_IC_RECORD_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IC_NODE_CENTRE, 3}, {TS_IC_NODE_HALF, 1}, {TS_IC_NODE_CHILD, 1},
                                            {TS_IC_NODE_FIRST, 1}, {TS_IC_NODE_COUNT, 1}, {TS_IC_NODE_UNUSED, 1}},
                                           TS_IC_NODE_FLOATS),
              "layout.h: ic octree node fields do not tile TS_IC_NODE_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IC_INTERP_E, 3}, {TS_IC_INTERP_WEIGHT, 1}}, TS_IC_INTERP_FLOATS),
              "layout.h: ic interpolation fields do not tile TS_IC_INTERP_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_IC_PAIR_RECORD, 1}, {TS_IC_PAIR_VPL, 1}}, TS_IC_PAIR_WORDS),
              "layout.h: ic pair item fields do not tile TS_IC_PAIR_WORDS");
static_assert(tessera::layout_check::tiles({{TS_IC_PAIR_HIT, 1}}, TS_IC_PAIR_FLOATS),
              "layout.h: ic pair output fields do not tile TS_IC_PAIR_FLOATS");
/* An unoccluded pair is a shadow ray that hit nothing; the facing code is no triangle. */
static_assert(TS_IC_PAIR_VISIBLE == TS_NO_HIT && TS_IC_PAIR_FACING != TS_NO_HIT,
              "layout.h: TS_IC_PAIR_VISIBLE must be TS_NO_HIT, TS_IC_PAIR_FACING another code");
static_assert(tessera::layout_check::tiles({{TS_IC_GATHER_RECORD, 1}, {TS_IC_GATHER_ROW, 1}}, TS_IC_GATHER_WORDS),
              "layout.h: ic gather item fields do not tile TS_IC_GATHER_WORDS");
static_assert(TS_IC_VISIBLE_WORDS(0u) == 0u && TS_IC_VISIBLE_WORDS(32u) == 1u && TS_IC_VISIBLE_WORDS(33u) == 2u,
              "layout.h: TS_IC_VISIBLE_WORDS(n) is n bits rounded up to whole uints");
static_assert(tessera::layout_check::tiles({{TS_IC_GATHER_E, 3}, {TS_IC_GATHER_HARMONIC, 1}}, TS_IC_GATHER_FLOATS),
              "layout.h: ic gather output fields do not tile TS_IC_GATHER_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_PASS_RADIANCE, 3}, {TS_PASS_ALBEDO, 3}, {TS_PASS_NORMAL, 3},
                                            {TS_PASS_DEPTH, 1}},
                                           TS_PASS_FLOATS),
              "layout.h: pass output fields do not tile TS_PASS_FLOATS");
/* TsFrame crosses to OpenCL by value (clSetKernelArg with sizeof(TsFrame)): 37 4-byte
 * scalars with no padding, so its layout is the same in both languages. */
static_assert(std::is_standard_layout_v<TsFrame> && std::is_trivially_copyable_v<TsFrame>,
              "layout.h: TsFrame must stay a plain struct");
static_assert(sizeof(TsFrame) == 37 * 4 && offsetof(TsFrame, width) == 12 * 4 &&
                  offsetof(TsFrame, light_power) == 20 * 4 && offsetof(TsFrame, igi_components) == 28 * 4 &&
                  offsetof(TsFrame, ic_error_bound) == 29 * 4 && offsetof(TsFrame, pixel_cone) == 31 * 4 &&
                  offsetof(TsFrame, igi_filter_depth) == 34 * 4 && offsetof(TsFrame, igi_equiangular) == 35 * 4 &&
                  offsetof(TsFrame, igi_march_rotation) == 36 * 4,
              "layout.h: TsFrame is not 37 packed 4-byte scalars; update the kernels' copy (same struct) and this check");
#endif /* __cplusplus */

#endif /* TS_LAYOUT_H */
