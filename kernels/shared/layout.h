/* Buffer layouts shared by the host (C++) and the kernels (OpenCL C). Declared once,
 * here. Every buffer is an array of 32-bit `float` or `uint`; no float3 (its size
 * differs between OpenCL and C++), no pointers.
 *
 * BVH (built by host/bvh/bvh_builder.cpp with Embree's rtcBuildBVH, MEDIUM quality =
 * binned SAH, maxBranchingFactor 4, maxLeafSize 4, maxDepth TS_BVH_MAX_DEPTH):
 *   nodes: TS_NODE_FLOATS floats per node, node 0 is the root. A 4-wide node keeps its
 *   children's boxes as structure of arrays so one float4 load serves four children:
 *     [ 0.. 3] child min x   [ 4.. 7] child max x
 *     [ 8..11] child min y   [12..15] child max y
 *     [16..19] child min z   [20..23] child max z
 *     [24..27] child references (int bits, read with as_int)
 *     [28..31] unused (pads the node to 128 bytes, two cache lines)
 *   A child reference r >= 0 is an inner node index. r < 0 is a leaf: with v = ~r,
 *   its triangles are bvh_tris entries [v >> 3, (v >> 3) + (v & 7)). An unused slot
 *   holds r = -1 (a leaf of 0 triangles) and an empty box (min +inf, max -inf), which
 *   the slab test rejects for every ray.
 *   bvh_tris: TS_BVH_TRI_FLOATS floats per triangle, in leaf order:
 *     [0..2] v0, [3] original triangle index (uint bits), [4..6] v1, [7] 0,
 *     [8..10] v2, [11] 0.
 *
 * Shading data, indexed by the original (scene) triangle index `prim`:
 *   tri_pos   9 floats: p0, p1, p2 (world space, scene units)
 *   tri_nrm   9 floats: shading normals n0, n1, n2 (unit length)
 *   tri_uv    6 floats: uv0, uv1, uv2
 *   tri_mat   1 uint:   material index
 * materials: TS_MATERIAL_FLOATS floats: [0..2] albedo (Kd, linear), [3] texture index
 *   (int bits, -1 = none), [4..6] emitted radiance Le in W/(sr·m²), [7] kind (uint bits:
 *   TS_MAT_DIFFUSE, TS_MAT_MIRROR, TS_MAT_DIELECTRIC), [8..10] specular reflectance (Ks;
 *   the mirror's), [11] index of refraction (dielectric), [12] selection luminance: the
 *   luminance of the emission lights are picked by (the animation's maximum, so the
 *   pick probabilities stay the same over frames; ts_light_pdf_area), [13..15] unused.
 * medium: TS_MEDIUM_FLOATS floats: [0..2] sigma_a, [3..5] sigma_s (per scene unit),
 *   [6] Henyey–Greenstein g, [7] 1 if bounded by the box else 0, [8..10] box min,
 *   [11..13] box max, [14] 1 if the scene has a medium at all, [15] unused.
 * textures: tex_info 4 uints per texture: texel offset, width, height, unused;
 *   tex_texels: uint RGBA8 (R in the low byte), sRGB-encoded, row 0 at the top.
 * lights: TS_LIGHT_FLOATS floats per emissive triangle:
 *   [0..2] p0, [3..5] e1 = p1 - p0, [6..8] e2 = p2 - p0, [9..11] Le (W/(sr·m²)),
 *   [12] area (scene units²), [13] original triangle index (uint bits), [14..15] unused.
 *   light_cdf: one float per light, the running sum of power (Le luminance × area)
 *   normalised so the last entry is 1; light i is picked with probability
 *   cdf[i] - cdf[i-1].
 */
#ifndef TS_LAYOUT_H
#define TS_LAYOUT_H

#define TS_NODE_FLOATS 32
#define TS_NODE_REFS 24
#define TS_BVH_TRI_FLOATS 12
#define TS_BVH_MAX_DEPTH 48
#define TS_BVH_STACK_SIZE 160 /* >= 3 · TS_BVH_MAX_DEPTH + 1: a 4-wide node pushes at most 3 more than it pops */
#define TS_BVH_LEAF_MAX 4
#define TS_MATERIAL_FLOATS 16
#define TS_MAT_DIFFUSE 0u
#define TS_MAT_MIRROR 1u
#define TS_MAT_DIELECTRIC 2u
#define TS_MEDIUM_FLOATS 16
#define TS_LIGHT_FLOATS 16
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
} TsFrame;

/* VPLs (host/gi/vpl_generator.cpp): TS_VPL_FLOATS floats each, sorted by sample set:
 * [0..2] position, [3..5] unit normal of the side it lights, [6..8] flux weight C/M
 * (the path throughput times albedo/π, divided by the paths per set), [9] set index,
 * [10] path index (uint bits), [11] the largest vertex coordinate of the triangle it lies
 * on (for ts_offset_ray_origin). vpl_set_start[k] .. vpl_set_start[k+1]
 * are set k's VPLs. */
#define TS_VPL_FLOATS 12

/* Per-pixel output of the igi surface kernel: TS_IGI_SURF_FLOATS floats:
 * [0..2] E_ss, [3..5] E_id: direct (area-light) and indirect (VPL) irradiance / π, the
 * quantities albedo multiplies; [6..8] albedo; [9..11] emitted radiance seen;
 * [12..14] shading normal; [15] distance to the surface along the camera path (+inf on
 * a miss); [16..18] throughput of specular bounces before it (1 for none); [19] fraction
 * of the light samples that reached the light unoccluded (AIS soft-shadow guidance);
 * [20..22] the surface position (world space; for the filter's plane-distance test). */
#define TS_IGI_SURF_FLOATS 23
/* Per-pixel output of the igi media kernel: [0..2] single-scattered radiance along the
 * camera segment, [3..5] transmittance of that segment, [6] fraction of the march steps
 * whose light sample was unoccluded, [7] length of the segment inside the medium (AIS
 * participating-media guidance). */
#define TS_IGI_MEDIA_FLOATS 8
/* Per-item output of the ais extra kernel (one pixel, one extra sample set):
 * [0..2] E_ss, [3..5] E_id, [6..8] single-scattered radiance, for that set. */
#define TS_AIS_ITEM_FLOATS 9
/* An item of the ais extra kernel's list: [0] pixel (row-major index), [1] sample set
 * (low 8 bits) | TS_COMPONENT_* bits << 8. */
#define TS_AIS_ITEM_WORDS 2
/* Components (TsFrame.igi_components). */
#define TS_COMPONENT_SS 1u
#define TS_COMPONENT_ID 2u
#define TS_COMPONENT_PM 4u

/* Instant caching (shared/ic.h, host/gi/irradiance_cache.h).
 * Per-pixel output of the ic G-buffer kernel, TS_IC_GBUF_FLOATS floats: the first diffuse
 * surface seen through the pixel (the igi surface kernel's camera ray, so the same
 * surface): [0..2] position, [3..5] shading normal, [6..8] geometric normal (toward the
 * viewer), [9..11] ray origin for leaving rays, [12] pos_scale, [13] triangle index (uint
 * bits; TS_NO_HIT when the camera path finds no surface or a surface of albedo 0: no
 * record can serve it), [14] distance along the camera path (scene units). */
#define TS_IC_GBUF_FLOATS 15
/* Per-pixel output of the ic interpolation kernel: [0..2] E = irradiance / π, [3] the
 * weight sum (0: no usable record). */
#define TS_IC_INTERP_FLOATS 4
/* A cache record as the interpolation reads it: [0..2] position, [3..5] unit shading
 * normal, [6..8] E = irradiance / π gathered from the VPLs (albedo-free), [9] validity
 * radius R (scene units). */
#define TS_IC_RECORD_FLOATS 10
/* An octree node: [0..2] centre, [3] half edge (scene units), [4] index of the first of
 * its 8 children (uint bits, stored consecutively in octant order x + 2y + 4z; 0 = leaf,
 * as the root is node 0), [5] first entry of its record list in the reference array,
 * [6] number of records, [7] unused. */
#define TS_IC_NODE_FLOATS 8
/* Depth bound of the octree (root = depth 0). */
#define TS_IC_MAX_DEPTH 24

/* Per-pixel output of one pass: TS_PASS_FLOATS floats per pixel:
 * [0..2] radiance (W/(sr·m²)), [3..5] albedo at the first hit, [6..8] shading normal
 * at the first hit, [9] distance to the first hit (scene units; +inf on a miss). */
#define TS_PASS_FLOATS 10

#endif /* TS_LAYOUT_H */
