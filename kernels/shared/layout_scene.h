/* The scene's buffers, shared by the host (C++) and the kernels (OpenCL C); the rules
 * of every layout are in shared/layout_check.h.
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
 *   tri_uv    TS_TRI_UV_FLOATS (6) floats: uv0, uv1, uv2 (textures repeat; the host moves
 *             each triangle's by whole repeats toward [0, 1), so they interpolate precisely)
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
 */
#ifndef TS_LAYOUT_SCENE_H
#define TS_LAYOUT_SCENE_H

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

#ifdef __cplusplus
/* Compile-time checks of the layouts above (shared/layout_check.h). */
#include "shared/layout_check.h"

/* The traversal stack (kernels/bvh_traverse.h) holds every node a tree of the builder's
 * maximum depth can leave pending; the builder enforces the depth and leaf size. */
static_assert(TS_BVH_STACK_SIZE >= 3 * TS_BVH_MAX_DEPTH + 1,
              "layout_scene.h: TS_BVH_STACK_SIZE must be >= 3 * TS_BVH_MAX_DEPTH + 1 (4-wide nodes)");
static_assert(TS_BVH_LEAF_MAX >= 1 && TS_BVH_LEAF_MAX <= 7,
              "layout_scene.h: a leaf's triangle count is packed in 3 bits of its child reference");
static_assert(tessera::layout_check::tiles({{TS_NODE_MIN(0), 4}, {TS_NODE_MAX(0), 4}, {TS_NODE_MIN(1), 4},
                                            {TS_NODE_MAX(1), 4}, {TS_NODE_MIN(2), 4}, {TS_NODE_MAX(2), 4},
                                            {TS_NODE_REFS, 4}, {TS_NODE_UNUSED, 4}},
                                           TS_NODE_FLOATS),
              "layout_scene.h: BVH node fields do not tile TS_NODE_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_BVH_TRI_VERTEX(0), 3}, {TS_BVH_TRI_PRIM, 1}, {TS_BVH_TRI_VERTEX(1), 3},
                                            {TS_BVH_TRI_VERTEX(1) + 3, 1}, {TS_BVH_TRI_VERTEX(2), 3},
                                            {TS_BVH_TRI_VERTEX(2) + 3, 1}},
                                           TS_BVH_TRI_FLOATS),
              "layout_scene.h: BVH triangle fields do not tile TS_BVH_TRI_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_MAT_ALBEDO, 3}, {TS_MAT_TEXTURE, 1}, {TS_MAT_EMISSION, 3},
                                            {TS_MAT_KIND, 1}, {TS_MAT_SPECULAR, 3}, {TS_MAT_IOR, 1},
                                            {TS_MAT_SELECTION, 1}, {TS_MAT_UNUSED, 3}},
                                           TS_MATERIAL_FLOATS),
              "layout_scene.h: material fields do not tile TS_MATERIAL_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_MEDIUM_SIGMA_A, 3}, {TS_MEDIUM_SIGMA_S, 3}, {TS_MEDIUM_G, 1},
                                            {TS_MEDIUM_BOUNDED, 1}, {TS_MEDIUM_BOX_MIN, 3}, {TS_MEDIUM_BOX_MAX, 3},
                                            {TS_MEDIUM_PRESENT, 1}, {TS_MEDIUM_UNUSED, 1}},
                                           TS_MEDIUM_FLOATS),
              "layout_scene.h: medium fields do not tile TS_MEDIUM_FLOATS");
static_assert(tessera::layout_check::tiles({{TS_TEX_OFFSET, 1}, {TS_TEX_WIDTH, 1}, {TS_TEX_HEIGHT, 1},
                                            {TS_TEX_LEVELS, 1}},
                                           TS_TEX_INFO_UINTS),
              "layout_scene.h: texture info fields do not tile TS_TEX_INFO_UINTS");
static_assert(tessera::layout_check::tiles({{TS_LIGHT_P0, 3}, {TS_LIGHT_E1, 3}, {TS_LIGHT_E2, 3},
                                            {TS_LIGHT_RADIANCE, 3}, {TS_LIGHT_AREA, 1}, {TS_LIGHT_PRIM, 1},
                                            {TS_LIGHT_UNUSED, 2}},
                                           TS_LIGHT_FLOATS),
              "layout_scene.h: light fields do not tile TS_LIGHT_FLOATS");
#endif /* __cplusplus */

#endif /* TS_LAYOUT_SCENE_H */
