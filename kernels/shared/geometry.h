/* Rays, hits, camera rays and surface interactions, shared by every backend. */
#ifndef TS_GEOMETRY_H
#define TS_GEOMETRY_H
#include "shared/compat.h"
#include "shared/frame.h"
#include "shared/layout_rays.h"
#include "shared/layout_scene.h"
#include "shared/kernel_inputs.h"

TS_NAMESPACE_BEGIN

/* A ray org + t dir for t in (tmin, tmax). `dir` need not be unit length; t is in units
 * of |dir|. */
typedef struct TsRay {
    float3 org;
    float3 dir;
    float tmin;
    float tmax;
} TsRay;

/* Closest hit: `prim` is the original triangle index (TS_NO_HIT on a miss); the hit
 * point is (1 - u - v) p0 + u p1 + v p2 (Embree's barycentric convention). */
typedef struct TsHit {
    float t;
    float u;
    float v;
    uint prim;
} TsHit;

TS_INLINE float ts_f3_get(float3 a, int i) { return i == 0 ? a.x : (i == 1 ? a.y : a.z); }

TS_INLINE float ts_max_abs3(float3 a) { return fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z))); }

/* Clips the ray interval (*t0, *t1) of org + t dir to the box [box_min, box_max] (a slab
 * test; a zero direction component keeps the interval when org lies within that slab);
 * returns whether the clipped interval is non-empty. */
TS_INLINE int ts_ray_box_clip(float3 org, float3 dir, float3 box_min, float3 box_max, float* t0, float* t1) {
    float lo = *t0, hi = *t1;
    float o[3] = {org.x, org.y, org.z}, d[3] = {dir.x, dir.y, dir.z};
    float bmin[3] = {box_min.x, box_min.y, box_min.z};
    float bmax[3] = {box_max.x, box_max.y, box_max.z};
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) {
            if (o[a] < bmin[a] || o[a] > bmax[a]) return 0;
            continue;
        }
        float inv = 1.0f / d[a];
        float ta = (bmin[a] - o[a]) * inv, tb = (bmax[a] - o[a]) * inv;
        lo = fmax(lo, fmin(ta, tb));
        hi = fmin(hi, fmax(ta, tb));
    }
    *t0 = lo;
    *t1 = hi;
    return *t0 < *t1;
}

/* Offsets a surface point along the unit geometric normal `n` (pointing to the side the
 * new ray leaves from), so that a ray started there cannot hit the surface it starts on,
 * at any scene scale and any distance from the origin. `scale` bounds the magnitude of
 * the coordinates the point was computed from: the largest absolute vertex coordinate of
 * its triangle (TsSurface.pos_scale, TsLightSample.pos_scale).
 *
 * The offset is TS_OFFSET_ULPS float ulps of `scale` (2^-23 · scale each), taken along n.
 * A point interpolated from its triangle's vertices lies within ~6 such ulps of the
 * triangle's plane, and a ray–triangle test (ours in bvh_traverse.h, or Embree's) that
 * works on vertices relative to the ray origin adds ~2 more; 32 leaves a 4x margin.
 * Per axis the addition rounds by at most half an ulp of that coordinate (<= 2^-24 ·
 * scale), so the displacement along n is at least 31 of those ulps.
 *
 * Not Wächter & Binder's integer offset ("A Fast and Robust Method for Avoiding
 * Self-Intersection", Ray Tracing Gems, 2019, ch. 6: 256 ulps of each coordinate), which
 * is sized for hit points computed as org + t dir: ours are barycentric interpolations,
 * eight times more accurate, and 256 ulps is far too large away from the origin
 * (docs/ray-tracing.md §3; tests/hard_cases/scale_test.cpp). Like pbrt-v4 (Pharr et al.,
 * 4th ed., §6.8.6), the offset follows from the position's error bound, here the coarser
 * max-coordinate form of it. */
#define TS_OFFSET_ULPS 32.0f
TS_INLINE float3 ts_offset_ray_origin(float3 p, float3 n, float scale) {
    float d = TS_OFFSET_ULPS * 1.1920928955078125e-7f * scale + 1e-30f;
    return p + n * d;
}

/* The shadow ray from `org` (already offset off its own surface, or a point in a medium)
 * to the point p of unit normal n on a light or a VPL, n facing org's side. p is offset
 * off its surface too (`scale` as for ts_offset_ray_origin), and dir spans the gap, so t
 * runs over (0, 1); tmax = 0.99999 stops the test just short of the far end. Every
 * connection to a light or VPL point (shared/direct.h, pt.h, igi.h, vpl.h) is built here. */
TS_INLINE TsRay ts_shadow_ray(float3 org, float3 p, float3 n, float scale) {
    TsRay r;
    r.org = org;
    r.dir = ts_offset_ray_origin(p, n, scale) - org;
    r.tmin = 0.0f;
    r.tmax = 0.99999f;
    return r;
}

/* Camera ray through pixel (px + jx, py + jy); see TsFrame for the mapping. */
TS_INLINE TsRay ts_camera_ray(const TsFrame* f, uint px, uint py, float jx, float jy) {
    float sx = 2.0f * ((float)px + jx) / (float)f->width - 1.0f;
    float sy = 1.0f - 2.0f * ((float)py + jy) / (float)f->height;
    float3 fw = make_float3(f->cam_forward[0], f->cam_forward[1], f->cam_forward[2]);
    float3 rt = make_float3(f->cam_right[0], f->cam_right[1], f->cam_right[2]);
    float3 up = make_float3(f->cam_up[0], f->cam_up[1], f->cam_up[2]);
    TsRay r;
    r.org = make_float3(f->cam_pos[0], f->cam_pos[1], f->cam_pos[2]);
    r.dir = normalize(fw + rt * sx + up * sy);
    r.tmin = 0.0f;
    r.tmax = TS_INF;
    return r;
}

/* Pixel shaded by work-item i. Without interleaving (igi_tile <= 1) row-major. With an
 * n×n tile the image is split into N = n² sub-images, one per sample set k; work-items
 * run through set 0's pixels, then set 1's, and so on, each sub-image row-major. */
TS_INLINE void ts_pixel_of_work_item(const TsFrame* f, uint i, uint* px, uint* py) {
    uint n = f->igi_tile;
    if (n <= 1u) {
        *px = i % f->width;
        *py = i / f->width;
        return;
    }
    /* Set k = (x mod n) + n (y mod n) holds the pixels x = kx + n·sx, y = ky + n·sy. */
    uint total = 0u;
    for (uint k = 0u; k < n * n; ++k) {
        uint kx = k % n, ky = k / n;
        uint sw = (f->width - kx + n - 1u) / n, sh = (f->height - ky + n - 1u) / n;
        if (i < total + sw * sh) {
            uint j = i - total;
            *px = kx + n * (j % sw);
            *py = ky + n * (j / sw);
            return;
        }
        total += sw * sh;
    }
    *px = *py = 0u; /* unreachable for i < width · height */
}

/* Packet blocks (docs/ray-batches.md §2, §4): the backends that trace 16 pixels' links
 * together cut each sample set's sub-image (the pixels x = kx + n·sx, y = ky + n·sy of
 * set k = kx + n·ky, n = max(1, igi_tile)) into TS_PACKET_BLOCK × TS_PACKET_BLOCK blocks
 * of (sx, sy), row-major per set, set 0's blocks first. 16 lanes = 4 × 4 pixels n apart
 * on screen (a 12×12-pixel patch at n = 3); blocks at a sub-image's right or bottom edge
 * have idle lanes. */
#define TS_PACKET_BLOCK 4u
#define TS_PACKET_LANES 16

/* Size sw × sh of set k's sub-image. */
TS_INLINE void ts_set_extent(const TsFrame* f, uint k, uint* sw, uint* sh) {
    uint n = f->igi_tile > 1u ? f->igi_tile : 1u, kx = k % n, ky = k / n;
    *sw = (f->width - kx + n - 1u) / n;
    *sh = (f->height - ky + n - 1u) / n;
}

/* Number of packet blocks of set k's sub-image; *bw = blocks per row. */
TS_INLINE uint ts_set_blocks(const TsFrame* f, uint k, uint* bw) {
    uint sw, sh;
    ts_set_extent(f, k, &sw, &sh);
    *bw = (sw + TS_PACKET_BLOCK - 1u) / TS_PACKET_BLOCK;
    return *bw * ((sh + TS_PACKET_BLOCK - 1u) / TS_PACKET_BLOCK);
}

/* Number of packet blocks of the frame, all sets. */
TS_INLINE uint ts_packet_block_count(const TsFrame* f) {
    uint n = f->igi_tile > 1u ? f->igi_tile : 1u, total = 0u, bw;
    for (uint k = 0u; k < n * n; ++k) total += ts_set_blocks(f, k, &bw);
    return total;
}

/* Block b (< ts_packet_block_count) of the frame: set *k, block column *bx and row *by
 * of its sub-image. Returns 0 for b beyond the last block. */
TS_INLINE int ts_packet_block(const TsFrame* f, uint b, uint* k, uint* bx, uint* by) {
    uint n = f->igi_tile > 1u ? f->igi_tile : 1u, total = 0u;
    for (uint s = 0u; s < n * n; ++s) {
        uint bw, c = ts_set_blocks(f, s, &bw);
        if (b < total + c) {
            *k = s;
            *bx = (b - total) % bw;
            *by = (b - total) / bw;
            return 1;
        }
        total += c;
    }
    return 0;
}

/* Pixel (px, py) of lane `lane` (< 16, row-major in the block) of set k's block (bx, by).
 * Returns 0 for a lane past the sub-image's right or bottom edge (an idle lane). */
TS_INLINE int ts_packet_block_pixel(const TsFrame* f, uint k, uint bx, uint by, uint lane, uint* px, uint* py) {
    uint n = f->igi_tile > 1u ? f->igi_tile : 1u, sw, sh;
    ts_set_extent(f, k, &sw, &sh);
    uint sx = bx * TS_PACKET_BLOCK + lane % TS_PACKET_BLOCK, sy = by * TS_PACKET_BLOCK + lane / TS_PACKET_BLOCK;
    if (sx >= sw || sy >= sh) return 0;
    *px = k % n + n * sx;
    *py = k / n + n * sy;
    return 1;
}

/* Read-only views of the scene's shading buffers (layouts in shared/layout_scene.h). */
typedef struct TsSceneView {
    /* The scene's buffers, then the named inputs (host/device/kernel_table.h KernelInput;
     * null or a placeholder where the launch does not use them): shared/kernel_inputs.h. */
    TS_SCENE_BUFFERS(TS_VIEW_SCENE_FIELD)
    TS_KERNEL_INPUTS(TS_VIEW_INPUT_FIELD)
    TS_GLOBAL const uint* items; /* the launch's item list (item kernels) */
    uint light_count;
} TsSceneView;

/* What shading needs at a ray hit. Normals face the side the ray came from. */
typedef struct TsSurface {
    float3 position;      /* barycentric interpolation of the vertices (not org + t dir) */
    float3 geo_normal;    /* unit geometric normal, flipped toward the incoming ray */
    float3 shading_normal;/* interpolated unit normal, on the geo_normal side */
    float2 uv;
    uint material;
    int front_face;       /* 1 if the ray hit the side cross(e1, e2) points to */
    float pos_scale;      /* largest absolute vertex coordinate (ts_offset_ray_origin) */
    float3 origin;        /* where rays leave from: position, moved inside the triangle */
    float uv_footprint;   /* width of the pixel's ray-cone footprint in texture coordinates
                             (ts_surface_cone); 0: the finest mip level */
} TsSurface;

TS_INLINE TsSurface ts_surface_at(const TsSceneView* sv, TsRay ray, TsHit hit) {
    TS_GLOBAL const float* P = sv->tri_pos + TS_TRI_POS_FLOATS * hit.prim;
    TS_GLOBAL const float* N = sv->tri_nrm + TS_TRI_NRM_FLOATS * hit.prim;
    TS_GLOBAL const float* T = sv->tri_uv + TS_TRI_UV_FLOATS * hit.prim;
    float w = 1.0f - hit.u - hit.v;
    float3 p0 = ts_f3_load(P), p1 = ts_f3_load(P + 3), p2 = ts_f3_load(P + 6);
    TsSurface s;
    /* Rounding can put the interpolated point up to an ulp outside its triangle; at a
     * concave edge that is the far side of the adjoining wall, from where the offset
     * ray sees what the wall hides (a closed box far from the origin leaked light this
     * way). The exact point lies in the triangle's bounding box, so clamp to it. */
    s.position = clamp(p0 * w + p1 * hit.u + p2 * hit.v, fmin(p0, fmin(p1, p2)), fmax(p0, fmax(p1, p2)));
    s.pos_scale = fmax(ts_max_abs3(p0), fmax(ts_max_abs3(p1), ts_max_abs3(p2)));
    /* A point on (or within rounding of) an edge shared with a perpendicular wall: its
     * offset origin would lie on that wall's plane, where a ray leaving along the wall
     * is not blocked by it. Rays therefore leave from `origin`, the point pulled toward
     * the centroid by the offset distance, inside its own triangle by that margin;
     * shading uses the unmoved `position`. */
    float3 to_c = (p0 + p1 + p2) * (1.0f / 3.0f) - s.position;
    float dc = length(to_c), margin = TS_OFFSET_ULPS * 1.1920928955078125e-7f * s.pos_scale;
    s.origin = dc > 0.0f ? s.position + to_c * fmin(1.0f, margin / dc) : s.position;
    float3 ng = normalize(cross(p1 - p0, p2 - p0));
    s.front_face = dot(ng, ray.dir) < 0.0f ? 1 : 0;
    if (!s.front_face) ng = -ng;
    s.geo_normal = ng;
    float3 ns = ts_f3_load(N) * w + ts_f3_load(N + 3) * hit.u + ts_f3_load(N + 6) * hit.v;
    float ls = length(ns);
    ns = (ls > 0.0f && isfinite(ls)) ? ns / ls : ng;
    s.shading_normal = dot(ns, ng) < 0.0f ? -ns : ns;
    s.uv = make_float2(T[0] * w + T[2] * hit.u + T[4] * hit.v,
                       T[1] * w + T[3] * hit.u + T[5] * hit.v);
    s.material = sv->tri_mat[hit.prim];
    s.uv_footprint = 0.0f;
    return s;
}

/* Sets s->uv_footprint for a ray cone of width `width` (scene units) at the hit on
 * triangle prim, arriving along direction dir: the texture-LOD estimate of
 * Akenine-Möller et al. 2019 ("Texture level of detail strategies for real-time ray
 * tracing", Ray Tracing Gems ch. 20, eq. 34), a footprint of width/|cos θ| along the
 * slant and `width` across it, made isotropic by its geometric mean width/sqrt|cos θ|
 * (the same area, so the same number of texels averaged: the cone's width/|cos θ| blurs
 * a floor seen at grazing angles, where width alone aliases), times the triangle's
 * texture-to-world scale sqrt(A_uv / A_world). */
/* The cone spread of pass f->pass's camera sample: the pixel's angle f->pixel_cone over
 * sqrt(pass + 1). N jittered passes each stand for 1/N of the pixel's area, a footprint
 * of width 1/sqrt(N) of the pixel's; so the first pass reads the texture filtered to the
 * whole pixel and the accumulation of many passes tends to the finest level, the pixel
 * mean that the path-traced reference converges to (docs/texture-filtering.md §4). */
TS_INLINE float ts_pass_cone(const TsFrame* f) { return f->pixel_cone / sqrt((float)f->pass + 1.0f); }

TS_INLINE void ts_surface_cone(const TsSceneView* sv, TsSurface* s, uint prim, float3 dir, float width) {
    TS_GLOBAL const float* P = sv->tri_pos + TS_TRI_POS_FLOATS * prim;
    TS_GLOBAL const float* T = sv->tri_uv + TS_TRI_UV_FLOATS * prim;
    float3 p0 = ts_f3_load(P);
    float world2 = length(cross(ts_f3_load(P + 3) - p0, ts_f3_load(P + 6) - p0));
    float uv2 = fabs((T[2] - T[0]) * (T[5] - T[1]) - (T[4] - T[0]) * (T[3] - T[1]));
    float cos_t = fabs(dot(s->geo_normal, normalize(dir)));
    float scale = world2 > 0.0f ? sqrt(uv2 / world2) : 0.0f;
    float f = width * scale / sqrt(fmax(cos_t, 1e-4f));
    s->uv_footprint = isfinite(f) ? f : 0.0f;
}

TS_NAMESPACE_END
#endif /* TS_GEOMETRY_H */
