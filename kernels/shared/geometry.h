/* Rays, hits, camera rays and surface interactions, shared by every backend. */
#ifndef TS_GEOMETRY_H
#define TS_GEOMETRY_H
#include "shared/compat.h"
#include "shared/layout.h"

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

/* Offsets a surface point along the geometric normal `n` (pointing to the side the
 * new ray leaves from) by a few float ulps, so a ray started there cannot hit the
 * surface it starts on, at any scene scale. Wächter & Binder, "A Fast and Robust
 * Method for Avoiding Self-Intersection", Ray Tracing Gems (2019), ch. 6: integer ulp
 * offsets (256 ulps per unit normal component) away from the origin, and a fixed
 * 1/65536 offset within 1/32 of the origin where ulps are too small. */
TS_INLINE float ts_offset_axis(float p, float n) {
    int of = (int)(256.0f * n);
    float pi = as_float(as_int(p) + (p < 0.0f ? -of : of));
    return fabs(p) < 0.03125f ? p + 1.52587890625e-5f * n : pi;
}
TS_INLINE float3 ts_offset_ray_origin(float3 p, float3 n) {
    return make_float3(ts_offset_axis(p.x, n.x), ts_offset_axis(p.y, n.y),
                       ts_offset_axis(p.z, n.z));
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

/* Read-only views of the scene's shading buffers (layouts in shared/layout.h). */
typedef struct TsSceneView {
    TS_GLOBAL const float* tri_pos;
    TS_GLOBAL const float* tri_nrm;
    TS_GLOBAL const float* tri_uv;
    TS_GLOBAL const uint* tri_mat;
    TS_GLOBAL const float* materials;
    TS_GLOBAL const uint* tex_info;
    TS_GLOBAL const uint* tex_texels;
    TS_GLOBAL const float* lights;
    TS_GLOBAL const float* light_cdf;
    TS_GLOBAL const float* medium;
    TS_GLOBAL const float* vpls;
    TS_GLOBAL const uint* vpl_set_start;
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
} TsSurface;

TS_INLINE TsSurface ts_surface_at(const TsSceneView* sv, TsRay ray, TsHit hit) {
    TS_GLOBAL const float* P = sv->tri_pos + 9u * hit.prim;
    TS_GLOBAL const float* N = sv->tri_nrm + 9u * hit.prim;
    TS_GLOBAL const float* T = sv->tri_uv + 6u * hit.prim;
    float w = 1.0f - hit.u - hit.v;
    float3 p0 = ts_f3_load(P), p1 = ts_f3_load(P + 3), p2 = ts_f3_load(P + 6);
    TsSurface s;
    s.position = p0 * w + p1 * hit.u + p2 * hit.v;
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
    return s;
}

TS_NAMESPACE_END
#endif /* TS_GEOMETRY_H */
