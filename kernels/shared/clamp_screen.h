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
 * An igi frame resolved on the device runs ts_clamp_screen_pixel in kernels over the
 * surface pass's output (shared/igi_clamp_screen.h); host code (host/gi/clamp_screen.cpp)
 * runs the same samples in the same order through the same pieces, 16 pixels at a time
 * (shared/clamp_screen16.h), so both give the same bits (no built-in whose rounding may
 * differ: dot and length written out, no cos or sin). C and OpenCL C compatible
 * (shared/compat.h). */
#ifndef TS_CLAMP_SCREEN_H
#define TS_CLAMP_SCREEN_H
#include "shared/compat.h"
#include "shared/discontinuity.h"
#include "shared/frame.h"
#include "shared/layout_igi.h"
#include "shared/medium.h"

TS_NAMESPACE_BEGIN

/* Pixels within this Chebyshev radius of x are taken one by one: the kernel's peak. */
#define TS_CLAMP_SCREEN_NEAR 2
/* Ring radii grow by this factor; TS_CLAMP_SCREEN_RING samples a ring, so that a sample's
 * share of a ring is about as wide as the ring (2π·1.25r/8 ≈ r against 0.5r deep). */
#define TS_CLAMP_SCREEN_GROWTH 1.5f
#define TS_CLAMP_SCREEN_RING 8
#if TS_CLAMP_SCREEN_RING != 8
#error "ts_clamp_screen_pixel's step turn is cos = sin = 1/sqrt(2), 2π/8"
#endif
/* Rings end at this radius (pixels) whatever the clamp radius: cost stays bounded where the
 * camera is far from a corner, whose loss is then a few pixels wide (ours). */
#define TS_CLAMP_SCREEN_MAX_RADIUS 64.0f
/* |n · v| floor for a pixel's area: a patch seen edge-on stands for a long strip whose far
 * part is not where its position says (ours). */
#define TS_CLAMP_SCREEN_MIN_COS 0.1f

/* Dot product and length written out term by term, as shared/discontinuity.h's test:
 * the OpenCL built-ins may round otherwise, and the device's estimate must equal the
 * host's bit for bit (tests/kernels/igi_resolve_test.cpp). */
TS_INLINE float ts_clamp_screen_dot(float3 a, float3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
TS_INLINE float ts_clamp_screen_length(float3 a) { return sqrt(ts_clamp_screen_dot(a, a)); }

/* Area of the image plane at unit distance along the view axis per pixel (scene units²),
 * from the camera of shared/frame.h: (2|right| / width) · (2|up| / height). */
TS_INLINE float ts_clamp_screen_pixel_plane(const TsFrame* f) {
    float3 right = make_float3(f->cam_right[0], f->cam_right[1], f->cam_right[2]);
    float3 up = make_float3(f->cam_up[0], f->cam_up[1], f->cam_up[2]);
    return 4.0f * ts_clamp_screen_length(right) * ts_clamp_screen_length(up) / ((float)f->width * (float)f->height);
}

/* Depth of world point p along the camera's view axis (scene units). */
TS_INLINE float ts_clamp_screen_depth(const TsFrame* f, float3 p) {
    float3 o = make_float3(f->cam_pos[0], f->cam_pos[1], f->cam_pos[2]);
    float3 fwd = make_float3(f->cam_forward[0], f->cam_forward[1], f->cam_forward[2]);
    return ts_clamp_screen_dot(p - o, fwd) / ts_clamp_screen_length(fwd);
}

/* World area (scene units²) of the surface patch that a pixel whose plane area is `plane`
 * (ts_clamp_screen_pixel_plane) sees at position p with unit normal n:
 * a · z³ / (d · max(|n · v|, TS_CLAMP_SCREEN_MIN_COS)), z the depth, d the distance, v the
 * unit view direction (the pixel's solid angle a · cos³θ, times d² / |n · v|). */
TS_INLINE float ts_clamp_screen_area(const TsFrame* f, float plane, float3 p, float3 n) {
    float3 o = make_float3(f->cam_pos[0], f->cam_pos[1], f->cam_pos[2]);
    float3 v = p - o;
    float d = ts_clamp_screen_length(v);
    float z = ts_clamp_screen_depth(f, p);
    if (!(d > 0.0f) || !(z > 0.0f)) return 0.0f;
    float c = fmax(fabs(ts_clamp_screen_dot(n, v)) / d, TS_CLAMP_SCREEN_MIN_COS);
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

/* Whether a sample at offset d from x (|d|² = d2, cos_x = n_x · d unnormalised) can carry
 * clamped light: closer than the clamp radius 1/sqrt(b) (beyond, G ≤ 1/d² < b) and in
 * front of x. Needs only the record's hot part; -1 or 0, so 16 lanes can mask with it. */
TS_INLINE int ts_clamp_screen_in_reach(float d2, float cos_x, float inv_b) {
    return -((d2 > 0.0f) & (d2 < inv_b) & (cos_x > 0.0f));
}

/* G − b of a sample in reach (ts_clamp_screen_in_reach), or 0 where it gets nothing: q's
 * patch faces away from x (cos_y = −n_q · d ≤ 0), G ≤ b, or q sends no light (source s
 * summing to ≤ 0). G is that of q's own patch as a disc of area A_q facing x,
 * cos_x cos_y / (d² + A_q/π) over d² (exact on its axis: ∫ cos cos / r² dA =
 * A / (d² + A/π)): a point's 1/d² would make the pixels next to a corner, whose sub-pixel
 * positions move with the camera jitter, a noise of their own. G > b makes G − b > 0
 * (gradual underflow), so a caller tests the result against 0. */
TS_INLINE float ts_clamp_screen_excess(float d2, float cos_x, float cos_y, float area, float3 s, float b) {
    const float g = cos_x * cos_y / (d2 * (d2 + area * 0.31830989f));
    return ((cos_y > 0.0f) & (g > b) & (s.x + s.y + s.z > 0.0f)) ? g - b : 0.0f;
}

/* A ring sample's share (pixels) of the ring from radius r0 to r1. */
TS_INLINE float ts_clamp_screen_ring_weight(float r0, float r1) {
    return 3.14159265f * (r1 * r1 - r0 * r0) / (float)TS_CLAMP_SCREEN_RING;
}

/* A ring sample's offset (pixels) along one axis: radius rm times the direction's
 * component c, rounded to the nearest pixel. */
TS_INLINE int ts_clamp_screen_offset(float rm, float c) { return (int)floor(rm * c + 0.5f); }

/* Turns the direction (c, s) by the angle whose cosine and sine are (tc, ts). A ring's
 * samples step by 2π/TS_CLAMP_SCREEN_RING (cos = sin = 1/sqrt(2) for 8); each ring starts
 * turned by the golden angle from the last (cos, sin of 2.3999632), so no two rings'
 * samples line up. Constants, not cos/sin calls: those were 2% of an AIS frame, and the
 * device's may round apart from the host's. */
#define TS_CLAMP_SCREEN_STEP_C 0.70710678f
#define TS_CLAMP_SCREEN_STEP_S 0.70710678f
#define TS_CLAMP_SCREEN_GOLDEN_C (-0.73736886f)
#define TS_CLAMP_SCREEN_GOLDEN_S 0.67549032f
TS_INLINE void ts_clamp_screen_turn(float* c, float* s, float tc, float ts) {
    const float c1 = *c * tc - *s * ts;
    *s = *s * tc + *c * ts;
    *c = c1;
}

/* Rings start where a disc has the near square's area: π r0² = (2·NEAR + 1)². */
#define TS_CLAMP_SCREEN_FIRST_RING ((2.0f * TS_CLAMP_SCREEN_NEAR + 1.0f) * 0.5641896f) /* 1/sqrt(π) */

/* Writes the record (TS_CLAMP_SCREEN_FLOATS, layout_igi.h: hot part, then cold part) of a
 * pixel that sees a diffuse surface directly at position p with unit normal n and albedo
 * rho, whose reconstructed irradiance / π is e = E_ss + E_id; plane:
 * ts_clamp_screen_pixel_plane. */
TS_INLINE void ts_clamp_screen_record(const TsFrame* f, float plane, float3 p, float3 n, float3 rho, float3 e,
                                      float* out) {
    const float area = ts_clamp_screen_area(f, plane, p, n);
    ts_f3_store(out + TS_CLAMP_SCREEN_POSITION, p);
    out[TS_CLAMP_SCREEN_AREA] = area;
    ts_f3_store(out + TS_CLAMP_SCREEN_COLD + TS_CLAMP_SCREEN_NORMAL, n);
    ts_f3_store(out + TS_CLAMP_SCREEN_COLD + TS_CLAMP_SCREEN_SOURCE, rho * e * area);
}

/* Adds pixel q's share to *sum, q's record at rec + q · TS_CLAMP_SCREEN_FLOATS: `weight`
 * pixels' worth of q's source times max(0, G − b) · Tr between x (position px, unit normal
 * nx) and q's point (ts_clamp_screen_excess). A ring sample's share is spread around its
 * ring, not a disc about the sample, so it keeps q's own disc (with the share's area it
 * lost 10-20%). The hot part's tests come first, so most samples, beyond the clamp radius
 * or behind x, load 4 floats of the record, not 10 (the order changes no value: every
 * test must pass for q to count). */
TS_INLINE void ts_clamp_screen_add(float3* sum, float3 px, float3 nx, float b, float inv_b, const TsMedium* med,
                                   TS_GLOBAL const float* rec, size_t q, float weight) {
    TS_GLOBAL const float* hot = rec + q * TS_CLAMP_SCREEN_FLOATS;
    float3 d = ts_f3_load(hot + TS_CLAMP_SCREEN_POSITION) - px;
    float d2 = ts_clamp_screen_dot(d, d), cos_x = ts_clamp_screen_dot(nx, d);
    if (!ts_clamp_screen_in_reach(d2, cos_x, inv_b)) return;
    TS_GLOBAL const float* cold = hot + TS_CLAMP_SCREEN_COLD;
    float3 s = ts_f3_load(cold + TS_CLAMP_SCREEN_SOURCE);
    float e = ts_clamp_screen_excess(d2, cos_x, -ts_clamp_screen_dot(ts_f3_load(cold + TS_CLAMP_SCREEN_NORMAL), d),
                                     hot[TS_CLAMP_SCREEN_AREA], s, b);
    if (!(e > 0.0f)) return;
    float3 tr = med ? ts_medium_transmittance(med, px, d, 0.0f, 1.0f) : make_float3(1.0f, 1.0f, 1.0f);
    *sum += s * tr * (e * weight);
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
            ts_clamp_screen_add(&sum, px, nx, b, inv_b, med, rec, (size_t)qy * w + qx, 1.0f);
        }
    float r0 = TS_CLAMP_SCREEN_FIRST_RING;
    float ring_c = 1.0f, ring_s = 0.0f;
    while (r0 < r) {
        float r1 = fmin(r0 * TS_CLAMP_SCREEN_GROWTH, r);
        float rm = 0.5f * (r0 + r1);
        float weight = ts_clamp_screen_ring_weight(r0, r1);
        float c = ring_c, s = ring_s;
        ts_clamp_screen_turn(&ring_c, &ring_s, TS_CLAMP_SCREEN_GOLDEN_C, TS_CLAMP_SCREEN_GOLDEN_S);
        for (int j = 0; j < TS_CLAMP_SCREEN_RING; ++j) {
            int qx = x + ts_clamp_screen_offset(rm, c), qy = y + ts_clamp_screen_offset(rm, s);
            ts_clamp_screen_turn(&c, &s, TS_CLAMP_SCREEN_STEP_C, TS_CLAMP_SCREEN_STEP_S);
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            ts_clamp_screen_add(&sum, px, nx, b, inv_b, med, rec, (size_t)qy * w + qx, weight);
        }
        r0 = r1;
        if (r1 >= r) break;
    }
    return sum * 0.31830989f; /* 1/π */
}

/* The per-pixel G-buffer fields the fill below reads, as strided arrays (element i of a
 * field at field[i * stride]): the distance along the camera path (+inf where it escaped),
 * the unit normal and position (3 floats) and the specular throughput (3 floats). The
 * host's copies (gi/discontinuity_filter.h's GeometryBuffer, the surface pass's
 * throughput) and the device's surface-pass output (stride TS_IGI_SURF_FLOATS) alike. */
typedef struct TsClampScreenView {
    TS_GLOBAL const float* depth;
    TS_GLOBAL const float* normal;
    TS_GLOBAL const float* position;
    TS_GLOBAL const float* throughput;
    int depth_stride, normal_stride, position_stride, throughput_stride;
} TsClampScreenView;

/* Whether pixel p sees a diffuse surface directly, the pixels that get and send E_res:
 * finite distance and specular throughput exactly 1 (seen through a mirror, its screen
 * neighbours are not its surface's). */
TS_INLINE int ts_clamp_screen_seen(const TsClampScreenView* g, size_t p) {
    TS_GLOBAL const float* t = g->throughput + p * g->throughput_stride;
    return isfinite(g->depth[p * g->depth_stride]) && t[0] == 1.0f && t[1] == 1.0f && t[2] == 1.0f;
}

/* E_res of pixel (x, y), seen directly and off the even grid (x or y odd), from the even
 * grid's values in `residual` (3 floats a pixel): the mean of the grid neighbours (2 or 4)
 * seen directly that its discontinuity test (shared/discontinuity.h, normal threshold
 * cos_min, plane distance depth_rel) accepts, in row order, into *out; returns 0 where
 * none is (an edge: the pixel then gathers itself). E_res varies over a surface at the
 * scale of the clamp radius, tens of pixels, so the mean of neighbours two pixels apart
 * loses nothing visible, and the gather, most of the cost, runs at about a quarter of
 * the pixels. */
TS_INLINE int ts_clamp_screen_fill(const TsClampScreenView* g, int x, int y, int w, int h,
                                   TS_GLOBAL const float* residual, float cos_min, float depth_rel, float3* out) {
    const size_t p = (size_t)y * w + x;
    const float zp = g->depth[p * g->depth_stride];
    const float3 np = ts_f3_load(g->normal + p * g->normal_stride);
    const float3 xp = ts_f3_load(g->position + p * g->position_stride);
    const int ox = x % 2, oy = y % 2;
    float3 sum = make_float3(0.0f, 0.0f, 0.0f);
    int n = 0;
    for (int dy = -oy; dy <= oy; dy += 2)
        for (int dx = -ox; dx <= ox; dx += 2) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const size_t q = (size_t)qy * w + qx;
            if (!ts_clamp_screen_seen(g, q) ||
                !ts_discontinuity_accepts(zp, np, xp, g->depth[q * g->depth_stride],
                                          ts_f3_load(g->normal + q * g->normal_stride),
                                          ts_f3_load(g->position + q * g->position_stride), 1, cos_min, depth_rel))
                continue;
            sum += ts_f3_load(residual + q * TS_CLAMP_RESIDUAL_FLOATS);
            ++n;
        }
    if (n) *out = sum * (1.0f / (float)n);
    return n;
}

TS_NAMESPACE_END
#endif /* TS_CLAMP_SCREEN_H */
