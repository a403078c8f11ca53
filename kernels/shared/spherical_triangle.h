/* Light samples uniform in solid angle for surfaces near an emitter triangle.
 *
 * Uniform area sampling weighs a light point by cosθx cosθy / (d² p_area). Where the
 * receiver is close to the light (a wall beneath a light that touches it, a box standing
 * on a floor light) d² runs to 0 over the triangle and the estimator's variance has no
 * bound: single pixels come out several times brighter than the light can make them.
 * Sampling the spherical triangle the light subtends instead weighs a point by cosθx Ω,
 * at most 2π (docs/igi.md §5). Farther from the light area sampling's variance is
 * bounded and it keeps its one point per interleave set; so only surfaces near the light
 * switch (ts_light_near).
 * This file is compiled both as OpenCL C and as C++ (shared/compat.h). */
#ifndef TS_SPHERICAL_TRIANGLE_H
#define TS_SPHERICAL_TRIANGLE_H
#include "shared/compat.h"
#include "shared/layout_scene.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

/* Solid angles (sr) outside which ts_light_sample_from does not sample the spherical
 * triangle: below the lower one the area sample is as good; above the upper one (just
 * under 2π) the triangle covers nearly the whole hemisphere and the hemisphere is sampled
 * instead. pbrt-v4 (Triangle::Sample) uses the same two bounds. */
#define TS_SPHERICAL_SAMPLE_MIN 3e-4f
#define TS_SPHERICAL_SAMPLE_MAX 6.22f

/* Relabels unit vectors a, b, c (keeping the winding) so that c and a are the most
 * nearly opposite pair, and returns their sum s = a + c less its component along a − c.
 * For exact unit vectors that component is 0; for float's, whose lengths are 1 ± 6e-8,
 * it is not, and where a and c are nearly opposite (x near the line through an edge)
 * that error outweighs s's true component along a, 1 + a·c = |s|²/2: removed, s keeps
 * its relative precision, as a + c alone does where a and c are far from opposite. */
TS_INLINE float3 ts_spherical_triangle_relabel(float3* a, float3* b, float3* c) {
    float d_ab = dot(*a, *b), d_bc = dot(*b, *c), d_ca = dot(*c, *a);
    if (d_ab < d_ca && d_ab <= d_bc) {
        float3 t = *a;
        *a = *b, *b = *c, *c = t;
    } else if (d_bc < d_ca && d_bc < d_ab) {
        float3 t = *c;
        *c = *b, *b = *a, *a = t;
    }
    float3 s = *a + *c, d = *a - *c;
    return s - d * (dot(s, d) / dot(d, d));
}

/* Solid angle (sr) of the spherical triangle with unit vertices a, b, c (Van Oosterom &
 * Strackee 1983: tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a)), written with the
 * relabelled corners' s = a + c: a·(b×c) = s·(b×c) and 1 + a·b + b·c + c·a =
 * |s|²/2 + b·s, so that neither loses digits where two corners are nearly opposite
 * (the direct form was up to 3e-4 off 1.4e-4 from an edge's line, this one 1e-7). */
TS_INLINE float ts_spherical_triangle_area(float3 a, float3 b, float3 c) {
    float3 s = ts_spherical_triangle_relabel(&a, &b, &c);
    return fabs(2.0f * atan2(dot(s, cross(b, c)), 0.5f * dot(s, s) + dot(b, s)));
}

/* Unit direction uniform in solid angle over the spherical triangle with unit vertices
 * a, b, c and area `omega` (ts_spherical_triangle_area), from (u, v) in [0, 1)²: u picks
 * the area A' = u·Ω of the sub-triangle (a, b, c'), c' on the arc from a to c, v the
 * point on the arc from b to c' (Arvo 1995, "Stratified sampling of spherical
 * triangles"; pbrt-v4 SampleSphericalTriangle). The stratification of (u, v) carries
 * over to solid angle. Requires a triangle of solid angle in [TS_SPHERICAL_SAMPLE_MIN,
 * TS_SPHERICAL_SAMPLE_MAX]; the result may still be NaN in degenerate corners (two
 * corners exactly opposite), which the caller checks.
 * c' is found from the area's closed form rather than from the angle α at a: with
 * c' = a cos t + ĉ sin t (ĉ the unit tangent at a towards c) and T = |a·(b×ĉ)|,
 * tan(A'/2) = T sin t / ((1 + a·b)(1 + cos t) + b·ĉ sin t), which in half angles is
 * linear: (cos(t/2), sin(t/2)) ∝ (T cos(A'/2) − b·ĉ sin(A'/2), (1 + a·b) sin(A'/2)).
 * Arvo's route through α and π + A' subtracts nearly equal numbers of order 1 where the
 * triangle is a sliver (x within ~1e-2 rad of the light's plane: α and A' small, and
 * cos φ + cos α of second order): in float it misplaced 1-18% of the samples where Ω
 * was 1e-2 to 2e-2 sr and 38-71% where it was 7e-4 to 3e-3 sr (x 1e-6 to 1e-3 below a
 * unit light's plane, beside it), biasing the irradiance estimate by up to 9%; here
 * every quantity keeps its relative precision, and the warp is uniform as in double. The relabelling puts
 * two nearly opposite corners (x near an edge's line) at c and a, where they enter only
 * through s and ĉ. */
TS_INLINE float3 ts_sample_spherical_triangle(float3 a, float3 b, float3 c, float omega, float u, float v) {
    float3 s = ts_spherical_triangle_relabel(&a, &b, &c);
    /* ĉ from c − (c·a) a = s − (s·a) a, and T = |a·(b×c)| / |c − (c·a) a|. */
    float3 g = s - a * dot(s, a);
    float inv_g = 1.0f / length(g);
    float3 c_t = g * inv_g;
    float t_abc = fabs(dot(s, cross(b, c))) * inv_g;
    float half_area = 0.5f * omega * u;
    float sin_h = sin(half_area), cos_h = cos(half_area);
    float k = t_abc * cos_h - dot(b, c_t) * sin_h, j = (1.0f + dot(a, b)) * sin_h;
    float r2 = k * k + j * j;
    float cos_t = (k * k - j * j) / r2, sin_t = 2.0f * k * j / r2;
    float3 cp = a * cos_t + c_t * sin_t;
    /* cos θ = 1 − v (1 − b·c') along the arc from b, with 1 ∓ b·c' = |c' ∓ b|²/2: q and p
     * are 1 ∓ cos θ, each with its relative precision, so sin θ = √(p q) keeps its digits
     * at either end of the arc. */
    float3 dm = cp - b, dp = cp + b;
    float q = v * 0.5f * dot(dm, dm), p = 2.0f * (1.0f - v) + v * 0.5f * dot(dp, dp);
    float cos_th = 0.5f * (p - q), sin_th = sqrt(p * q);
    return b * cos_th + normalize(dm - b * dot(dm, b)) * sin_th;
}

/* How far from a light triangle's centroid, in units of its radius r (the largest
 * distance from the centroid to a corner), a surface point counts as near the light.
 * Beyond, every point of the light lies between 0.25 r and 2.25 r away, so area
 * sampling's 1/d² varies by at most 81× over it and its variance is bounded. 1.25 rather
 * than 2 (9×): on bench/scenes/wall-touching-light.json the image's relMSE was the same
 * (0.0026, one igi frame) and the frame 1.8-2.3× the area-sampled one's instead of 2.4-3.3×
 * (bench/results/near_light.md). */
#define TS_LIGHT_NEAR_REACH 1.25f

/* Whether surface point x lies in front of light triangle (p0, p0 + e1, p0 + e2) (on the
 * side it emits to) and closer than TS_LIGHT_NEAR_REACH times its radius to its
 * centroid; behind, the light adds nothing either way. */
TS_INLINE int ts_light_near(float3 p0, float3 e1, float3 e2, float3 x) {
    float3 c = p0 + (e1 + e2) * (1.0f / 3.0f);
    float3 d0 = p0 - c, d1 = d0 + e1, d2 = d0 + e2, dx = x - c;
    float r2 = fmax(dot(d0, d0), fmax(dot(d1, d1), dot(d2, d2)));
    return (dot(dx, dx) < TS_LIGHT_NEAR_REACH * TS_LIGHT_NEAR_REACH * r2) & (dot(cross(e1, e2), x - p0) > 0.0f);
}

/* Barycentrics (b1, b2) of where the ray x + t w meets the plane of triangle
 * (p0, p0 + e1, p0 + e2) (Möller & Trumbore 1997); 0 when they are not finite. */
TS_INLINE int ts_triangle_barycentrics_along(float3 p0, float3 e1, float3 e2, float3 x, float3 w, float* b1,
                                             float* b2) {
    float3 s = x - p0, s1 = cross(w, e2);
    float divisor = dot(s1, e1);
    *b1 = dot(s, s1) / divisor;
    *b2 = dot(w, cross(s, e1)) / divisor;
    return isfinite(*b1) && isfinite(*b2);
}

/* Light sample ls (from ts_sample_light) as seen from surface point x. Where x is near
 * the light (ts_light_near), the point is re-drawn from the same (ls.u, ls.v) with a
 * bounded weight, inv_pdf_solid_angle = (solid angle sampled) / selection probability:
 * - for a solid angle Ω within [TS_SPHERICAL_SAMPLE_MIN, TS_SPHERICAL_SAMPLE_MAX],
 *   uniformly in Ω (ts_sample_spherical_triangle);
 * - above, where the light covers nearly all of x's view towards its plane (x just
 *   beneath a large light, or one crossing a wall), uniformly over the hemisphere facing
 *   the light's plane (2π sr), a direction that misses the triangle giving radiance 0.
 * Elsewhere (far, behind, or Ω below the range) ls itself, sampled by area. Either way
 * ts_light_contribution weighs the point by its own pdf, so the estimate stays
 * unbiased. */
TS_INLINE TsLightSample ts_light_sample_from(TS_GLOBAL const float* lights, TsLightSample ls, float3 x) {
    TS_GLOBAL const float* L = lights + ls.light * TS_LIGHT_FLOATS;
    float3 p0 = ts_f3_load(L + TS_LIGHT_P0), e1 = ts_f3_load(L + TS_LIGHT_E1), e2 = ts_f3_load(L + TS_LIGHT_E2);
    if (!ts_light_near(p0, e1, e2, x)) return ls;
    float3 s = x - p0;
    float3 a = normalize(-s), b = normalize(e1 - s), c = normalize(e2 - s);
    float omega = ts_spherical_triangle_area(a, b, c);
    if (!(omega >= TS_SPHERICAL_SAMPLE_MIN)) return ls;
    int hemisphere = omega > TS_SPHERICAL_SAMPLE_MAX;
    float3 w = hemisphere ? ts_from_local(-ls.normal, ts_sample_uniform_hemisphere(ls.u, ls.v))
                          : ts_sample_spherical_triangle(a, b, c, omega, ls.u, ls.v);
    float b1, b2;
    if (!ts_triangle_barycentrics_along(p0, e1, e2, x, w, &b1, &b2)) return ls;
    /* pdf_area = selection probability / area. */
    float p_select = ls.pdf_area * L[TS_LIGHT_AREA];
    if (hemisphere) {
        ls.inv_pdf_solid_angle = 2.0f * TS_PI / p_select;
        if (!(b1 >= 0.0f && b2 >= 0.0f && b1 + b2 <= 1.0f)) {
            ls.radiance = make_float3(0.0f, 0.0f, 0.0f);  /* a miss: its shadow ray is not traced */
            return ls;
        }
    } else {
        /* The sample lies on the triangle up to rounding: clamp it there. */
        b1 = fmin(1.0f, fmax(0.0f, b1));
        b2 = fmin(1.0f, fmax(0.0f, b2));
        if (b1 + b2 > 1.0f) {
            float sum = b1 + b2;
            b1 /= sum;
            b2 /= sum;
        }
        ls.inv_pdf_solid_angle = omega / p_select;
    }
    ls.position = p0 + e1 * b1 + e2 * b2;
    return ls;
}

TS_NAMESPACE_END
#endif
