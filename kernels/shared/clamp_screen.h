/* Screen-space compensation of the VPL clamp for igi-family frames (igi, ais, ais-max;
 * docs/igi.md §4). The geometry-term clamp G' = min(G, b) of shared/vpl.h removes the
 * light that surfaces nearer than 1/sqrt(b) send beyond the bound, darkening every corner
 * (Kollig and Keller 2004). After Novák, Engelhardt and Dachsbacher 2011 ("Screen-space
 * bias compensation for interactive high-quality global illumination with virtual point
 * lights", I3D), the loss is estimated from the frame's own G-buffer and reconstructed
 * irradiance, with no ray traced:
 *
 *   E_res(x) = (1/π) ∫_A L(y) · max(0, G(x, y) − b) · Tr(x, y) dA_y,
 *   G = cos_x · cos_y / |x − y|²,
 *
 * in the irradiance / π units of shared/composite.h, with L(y) = ρ_y · (E_ss + E_id)(y)
 * the diffuse radiance of the surfaces y. One round: a second, with E_res added to L (the
 * light clamped on its way to y), moved the Cornell box's darkest corner region by 0.2%
 * for 1.15x the frame time (docs/igi.md §4).
 *
 * The integral runs over the surfaces the camera sees. Pixel q stands for its surface
 * patch, of area A_q = a · z_q³ / (d_q · |n_q · v_q|) (ts_clamp_screen_area). Pixels are
 * taken one by one within TS_CLAMP_SCREEN_NEAR of x, and beyond on rings whose radii grow
 * by TS_CLAMP_SCREEN_GROWTH, TS_CLAMP_SCREEN_RING samples each, up to the clamp radius's
 * size on screen: samples thin out as the 1/d² kernel falls. Not tested: visibility
 * between x and y; missing: surfaces off screen or hidden (the paper's approximations;
 * most of the loss is the surface across a corner, which the camera sees with x).
 *
 * Host code runs it per pixel over its copies of the components
 * (host/gi/clamp_screen.cpp); C and OpenCL C compatible (shared/compat.h). */
#ifndef TS_CLAMP_SCREEN_H
#define TS_CLAMP_SCREEN_H
#include "shared/compat.h"
#include "shared/frame.h"
#include "shared/medium.h"

TS_NAMESPACE_BEGIN

/* Pixels within this Chebyshev radius of x are taken one by one: the kernel's peak. */
#define TS_CLAMP_SCREEN_NEAR 2
/* Ring radii grow by this factor; TS_CLAMP_SCREEN_RING samples a ring, so that a sample's
 * share of a ring is about as wide as the ring (2π·1.25r/8 ≈ r against 0.5r deep). */
#define TS_CLAMP_SCREEN_GROWTH 1.5f
#define TS_CLAMP_SCREEN_RING 8
/* Rings end at this radius (pixels) whatever the clamp radius: cost stays bounded where the
 * camera is far from a corner, whose loss is then a few pixels wide (ours). */
#define TS_CLAMP_SCREEN_MAX_RADIUS 64.0f
/* |n · v| floor for a pixel's area: a patch seen edge-on stands for a long strip whose far
 * part is not where its position says (ours). */
#define TS_CLAMP_SCREEN_MIN_COS 0.1f

/* Area of the image plane at unit distance along the view axis per pixel (scene units²),
 * from the camera of shared/frame.h: (2|right| / width) · (2|up| / height). */
TS_INLINE float ts_clamp_screen_pixel_plane(const TsFrame* f) {
    float3 right = make_float3(f->cam_right[0], f->cam_right[1], f->cam_right[2]);
    float3 up = make_float3(f->cam_up[0], f->cam_up[1], f->cam_up[2]);
    return 4.0f * length(right) * length(up) / ((float)f->width * (float)f->height);
}

/* Depth of world point p along the camera's view axis (scene units). */
TS_INLINE float ts_clamp_screen_depth(const TsFrame* f, float3 p) {
    float3 o = make_float3(f->cam_pos[0], f->cam_pos[1], f->cam_pos[2]);
    float3 fwd = normalize(make_float3(f->cam_forward[0], f->cam_forward[1], f->cam_forward[2]));
    return dot(p - o, fwd);
}

/* World area (scene units²) of the surface patch that a pixel whose plane area is `plane`
 * (ts_clamp_screen_pixel_plane) sees at position p with unit normal n:
 * a · z³ / (d · max(|n · v|, TS_CLAMP_SCREEN_MIN_COS)), z the depth, d the distance, v the
 * unit view direction (the pixel's solid angle a · cos³θ, times d² / |n · v|). */
TS_INLINE float ts_clamp_screen_area(const TsFrame* f, float plane, float3 p, float3 n) {
    float3 o = make_float3(f->cam_pos[0], f->cam_pos[1], f->cam_pos[2]);
    float3 v = p - o;
    float d = length(v);
    float z = ts_clamp_screen_depth(f, p);
    if (!(d > 0.0f) || !(z > 0.0f)) return 0.0f;
    float c = fmax(fabs(dot(n, v)) / d, TS_CLAMP_SCREEN_MIN_COS);
    return plane * z * z * z / (d * c);
}

/* Radius (pixels) of the screen window that can hold surfaces y with G(x, y) > b, for x at
 * depth z: the clamp radius 1/sqrt(b) over the side sqrt(plane)·z of x's pixel, with a
 * margin of 1.5 for surfaces seen more obliquely than x, capped at
 * TS_CLAMP_SCREEN_MAX_RADIUS. */
TS_INLINE float ts_clamp_screen_radius(float plane, float z, float b) {
    float r = 1.5f / (sqrt(b * plane) * z);
    return (r > 0.0f) ? fmin(r, TS_CLAMP_SCREEN_MAX_RADIUS) : 0.0f;
}

/* Per-pixel record the gather reads (TS_CLAMP_SCREEN_FLOATS floats a pixel, row-major,
 * one cache line's worth, so a sample costs one miss): world position, unit normal, the
 * source s_q = L_q · A_q (radiance times patch area; zero for a pixel that is no diffuse
 * surface seen directly) and the patch area A_q (ts_clamp_screen_area). */
#define TS_CLAMP_SCREEN_FLOATS 10
#define TS_CLAMP_SCREEN_POSITION 0
#define TS_CLAMP_SCREEN_NORMAL 3
#define TS_CLAMP_SCREEN_SOURCE 6
#define TS_CLAMP_SCREEN_AREA 9

/* Adds pixel q's share to *sum: `weight` pixels' worth of q's source times
 * max(0, G − b) · Tr between x (position px, unit normal nx) and q's point. G is that of
 * q's own patch as a disc of area A_q facing x, cos_x cos_y / (d² + A_q/π) (exact on its
 * axis: ∫ cos cos / r² dA = A / (d² + A/π)): a point's 1/d² would make the pixels next
 * to a corner, whose sub-pixel positions move with the camera jitter, a noise of their
 * own. A ring sample's share is spread around its ring, not a disc about the sample, so
 * it keeps q's own disc (with the share's area it lost 10-20%). */
TS_INLINE void ts_clamp_screen_add(float3* sum, float3 px, float3 nx, float b, float inv_b, const TsMedium* med,
                                   TS_GLOBAL const float* q, float weight) {
    float3 s = ts_f3_load(q + TS_CLAMP_SCREEN_SOURCE);
    if (!(s.x + s.y + s.z > 0.0f)) return;
    float3 d = ts_f3_load(q + TS_CLAMP_SCREEN_POSITION) - px;
    float d2 = dot(d, d);
    /* Beyond 1/sqrt(b), G ≤ 1/d² < b: nothing was clamped. */
    if (!(d2 > 0.0f) || !(d2 < inv_b)) return;
    float cos_x = dot(nx, d), cos_y = -dot(ts_f3_load(q + TS_CLAMP_SCREEN_NORMAL), d);
    if (!(cos_x > 0.0f) || !(cos_y > 0.0f)) return;
    float g = cos_x * cos_y / (d2 * (d2 + q[TS_CLAMP_SCREEN_AREA] * 0.31830989f));
    if (!(g > b)) return;
    float3 tr = med ? ts_medium_transmittance(med, px, d, 0.0f, 1.0f) : make_float3(1.0f, 1.0f, 1.0f);
    *sum += s * tr * ((g - b) * weight);
}

/* E_res at pixel (x, y) of a w × h frame (irradiance / π, per colour channel), from the
 * per-pixel records `rec` (TS_CLAMP_SCREEN_FLOATS). px, nx: x's position and normal; r: the
 * window radius in pixels (ts_clamp_screen_radius); b: the frame's clamp; med: the
 * scene's medium or 0. Deterministic: fixed sample offsets, so a smooth surface gets a
 * smooth estimate. */
TS_INLINE float3 ts_clamp_screen_pixel(int x, int y, int w, int h, float3 px, float3 nx, float r, float b,
                                       const TsMedium* med, TS_GLOBAL const float* rec) {
    float3 sum = make_float3(0.0f, 0.0f, 0.0f);
    const float inv_b = 1.0f / b;
    for (int dy = -TS_CLAMP_SCREEN_NEAR; dy <= TS_CLAMP_SCREEN_NEAR; ++dy)
        for (int dx = -TS_CLAMP_SCREEN_NEAR; dx <= TS_CLAMP_SCREEN_NEAR; ++dx) {
            int qx = x + dx, qy = y + dy;
            if ((dx == 0 && dy == 0) || qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            ts_clamp_screen_add(&sum, px, nx, b, inv_b, med, rec + ((ulong)qy * w + qx) * TS_CLAMP_SCREEN_FLOATS, 1.0f);
        }
    /* Rings start where a disc has the near square's area: π r0² = (2·NEAR + 1)². */
    const float side = 2.0f * TS_CLAMP_SCREEN_NEAR + 1.0f;
    float r0 = side * 0.5641896f; /* 1/sqrt(π) */
    /* A ring's samples step by this turn, applied as a rotation: one sine and cosine a
       ring, not a sample (they were 2% of an AIS frame). */
    const float step_c = cos(6.2831853f / (float)TS_CLAMP_SCREEN_RING);
    const float step_s = sin(6.2831853f / (float)TS_CLAMP_SCREEN_RING);
    for (int k = 0; r0 < r; ++k) {
        float r1 = fmin(r0 * TS_CLAMP_SCREEN_GROWTH, r);
        float rm = 0.5f * (r0 + r1);
        float weight = 3.14159265f * (r1 * r1 - r0 * r0) / (float)TS_CLAMP_SCREEN_RING;
        /* Each ring turned by the golden angle, so no two rings' samples line up. */
        float c = cos(2.3999632f * (float)k), s = sin(2.3999632f * (float)k);
        for (int j = 0; j < TS_CLAMP_SCREEN_RING; ++j) {
            int qx = x + (int)floor(rm * c + 0.5f), qy = y + (int)floor(rm * s + 0.5f);
            float c1 = c * step_c - s * step_s;
            s = s * step_c + c * step_s;
            c = c1;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            ts_clamp_screen_add(&sum, px, nx, b, inv_b, med, rec + ((ulong)qy * w + qx) * TS_CLAMP_SCREEN_FLOATS,
                                weight);
        }
        r0 = r1;
        if (r1 >= r) break;
    }
    return sum * 0.31830989f; /* 1/π */
}

TS_NAMESPACE_END
#endif /* TS_CLAMP_SCREEN_H */
