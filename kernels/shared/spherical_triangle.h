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
 * triangle: below the lower one the area sample is as good and the triangle's closed-form
 * area loses its float digits; above the upper one (just under 2π) the triangle covers
 * nearly the whole hemisphere and the arc construction divides by ~0, so the hemisphere
 * is sampled instead. pbrt-v4 (Triangle::Sample) uses the same two bounds. */
#define TS_SPHERICAL_SAMPLE_MIN 3e-4f
#define TS_SPHERICAL_SAMPLE_MAX 6.22f

/* Solid angle (sr) of the spherical triangle with unit vertices a, b, c
 * (Van Oosterom & Strackee 1983: tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a)). */
TS_INLINE float ts_spherical_triangle_area(float3 a, float3 b, float3 c) {
    return fabs(2.0f * atan2(dot(a, cross(b, c)), 1.0f + dot(a, b) + dot(a, c) + dot(b, c)));
}

/* Unit direction uniform in solid angle over the spherical triangle with unit vertices
 * a, b, c and area `omega` (ts_spherical_triangle_area), from (u, v) in [0, 1)²: u picks
 * the area u·Ω of the sub-triangle (a, b, c'), v the point on the arc from b to c' (Arvo
 * 1995, "Stratified sampling of spherical triangles"; pbrt-v4 SampleSphericalTriangle,
 * with the area from its closed form instead of the angle sum α + β + γ − π, so that of
 * the angles only α's cosine and sine are needed, from the arcs' plane normals). The
 * stratification of (u, v) carries over to solid angle. Requires a triangle of solid
 * angle in [TS_SPHERICAL_SAMPLE_MIN, TS_SPHERICAL_SAMPLE_MAX]; the result may still be
 * NaN in rounding corners, which the caller checks. */
TS_INLINE float3 ts_sample_spherical_triangle(float3 a, float3 b, float3 c, float omega, float u, float v) {
    /* Two nearly opposite vertices (x close to the line through an edge) leave the normal
     * of their arc's plane to float rounding: relabel, keeping the winding, so that they
     * are c and a, whose arc's normal enters only as a direction of α (a point within
     * 1e-4 of the line otherwise came out 6% bright, 1e-5 35% dark). */
    float d_ab = dot(a, b), d_bc = dot(b, c), d_ca = dot(c, a);
    if (d_ab < d_ca && d_ab <= d_bc) {
        float3 t = a;
        a = b, b = c, c = t;
    } else if (d_bc < d_ca && d_bc < d_ab) {
        float3 t = c;
        c = b, b = a, a = t;
    }
    /* α, the angle at a, lies between the normals of the planes of arcs ab and ac. */
    float3 n_ab = normalize(cross(a, b)), n_ca = normalize(cross(c, a));
    float cos_alpha = -dot(n_ab, n_ca), sin_alpha = length(cross(n_ab, n_ca));
    /* The sub-triangle's area plus π. */
    float area_pi = TS_PI + omega * u;
    float sin_ap = sin(area_pi), cos_ap = cos(area_pi);
    float sin_phi = sin_ap * cos_alpha - cos_ap * sin_alpha;
    float cos_phi = cos_ap * cos_alpha + sin_ap * sin_alpha;
    float k1 = cos_phi + cos_alpha;
    float k2 = sin_phi - sin_alpha * dot(a, b);
    float cos_bp = (k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) / ((k2 * sin_phi + k1 * cos_phi) * sin_alpha);
    /* A NaN (the rounding corners) must reach the result, not become −1 in the clamp. */
    if (cos_bp == cos_bp) cos_bp = fmin(1.0f, fmax(-1.0f, cos_bp));
    float sin_bp = sqrt(fmax(0.0f, 1.0f - cos_bp * cos_bp));
    float3 cp = a * cos_bp + normalize(c - a * dot(c, a)) * sin_bp;
    float cos_t = 1.0f - v * (1.0f - dot(cp, b));
    float sin_t = sqrt(fmax(0.0f, 1.0f - cos_t * cos_t));
    return b * cos_t + normalize(cp - b * dot(cp, b)) * sin_t;
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
