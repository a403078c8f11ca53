/* The VPL connection and gather sum of instant radiosity (Keller 1997), shared by the
 * igi kernels (shared/igi.h) and the instant cache's gather kernels (shared/ic_gather.h),
 * so both weigh a VPL identically. VPL layout: layout_igi.h
 * TS_VPL_FLOATS. */
#ifndef TS_VPL_H
#define TS_VPL_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout_igi.h"
#include "shared/medium.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

/* Whether a VPL is a scattering vertex of a light path in the medium rather than a
 * surface hit: layout_igi.h marks it with a negative TS_VPL_POS_SCALE. */
TS_INLINE int ts_vpl_in_medium(TS_GLOBAL const float* vpl) { return vpl[TS_VPL_POS_SCALE] < 0.0f; }

/* The VPL's radiant intensity toward unit direction wo (leaving it) is C · this factor:
 * a surface VPL's cosine to its normal (0 behind it; Lambertian), a medium VPL's
 * Henyey–Greenstein phase value between the propagation direction of the light that
 * reached it and wo (g the medium's). */
TS_INLINE float ts_vpl_emission_factor_of(TS_GLOBAL const float* vpl, float3 wo, float g, int medium) {
    float3 nv = ts_f3_load(vpl + TS_VPL_NORMAL);
    if (medium) return ts_hg_phase(dot(nv, wo), g);
    return dot(nv, wo);
}

/* The same, the kind read from the VPL; the _of form takes it from a caller that knows it
 * (a constant there leaves a loop over receivers without a branch, so it vectorises). */
TS_INLINE float ts_vpl_emission_factor(TS_GLOBAL const float* vpl, float3 wo, float g) {
    return ts_vpl_emission_factor_of(vpl, wo, g, ts_vpl_in_medium(vpl));
}

/* The shadow ray from org to the VPL: off its surface for a surface VPL, to the point
 * itself for a medium VPL. */
TS_INLINE TsRay ts_vpl_shadow_ray(float3 org, TS_GLOBAL const float* vpl) {
    float3 y = ts_f3_load(vpl + TS_VPL_POSITION);
    if (ts_vpl_in_medium(vpl)) return ts_shadow_ray(org, y, make_float3(0.0f, 0.0f, 0.0f), 0.0f);
    return ts_shadow_ray(org, y, ts_f3_load(vpl + TS_VPL_NORMAL), vpl[TS_VPL_POS_SCALE]);
}

/* The far end of every shadow ray to the VPL, as ts_vpl_shadow_ray builds it (org + dir
 * before dir's rounding): the dir of the ray from the origin, exact as x - 0 is. */
TS_INLINE float3 ts_vpl_shadow_end(TS_GLOBAL const float* vpl) {
    return ts_vpl_shadow_ray(make_float3(0.0f, 0.0f, 0.0f), vpl).dir;
}

/* ts_shadow_transmittance(med, shadow) for a ray ts_vpl_shadow_ray built to the VPL, the
 * same bits, without the slab test where both its ends lie in the medium
 * (ts_medium_keeps_span): a link between two points in fog (every link in the foggy
 * Cornell box) costs a length and an exponential. */
TS_INLINE float3 ts_vpl_shadow_transmittance(const TsMedium* med, TsRay shadow, TS_GLOBAL const float* vpl) {
#ifdef TS_HAS_MEDIUM
    const int held = ts_medium_holds(med, shadow.org) & ts_medium_holds(med, ts_vpl_shadow_end(vpl));
    if (ts_medium_keeps_span(held, shadow.dir, shadow.tmin, shadow.tmax))
        return ts_medium_span_transmittance(med, length(shadow.dir), shadow.tmin, shadow.tmax);
#else
    (void)vpl;
#endif
    return ts_shadow_transmittance(med, shadow);
}

/* The log of ts_vpl_shadow_transmittance (its ts_exp3 is that, bit for bit), for the
 * gathers over lanes, which take the exponentials together. */
TS_INLINE float3 ts_vpl_shadow_log_transmittance(const TsMedium* med, TsRay shadow, TS_GLOBAL const float* vpl) {
#ifdef TS_HAS_MEDIUM
    const int held = ts_medium_holds(med, shadow.org) & ts_medium_holds(med, ts_vpl_shadow_end(vpl));
    if (ts_medium_keeps_span(held, shadow.dir, shadow.tmin, shadow.tmax))
        return ts_medium_span_log_transmittance(med, length(shadow.dir), shadow.tmin, shadow.tmax);
#else
    (void)vpl;
#endif
    return ts_shadow_log_transmittance(med, shadow);
}

/* A medium VPL's clamp: b times this, a radius twice a surface VPL's (ours, docs/igi.md
 * §6). A surface VPL's cosine fades its 1/d² spike next to the surfaces that meet it; a
 * medium VPL has none, so a clamp radius of b lets each one paint a bright blob on the
 * walls and the fog near it. One foggy AIS frame (256², HDR-VDP-3 P >= 75%, median of 3
 * seeds): Cornell box 19.6% -> 15.8%, Sibenik 16.9% -> 10.7%, for 0.4% less mean
 * radiance, which the clamp's decay over passes returns; 1/16 gave 13.0% for 1.3% less. */
#ifndef TS_VPL_MEDIUM_CLAMP_SCALE
#define TS_VPL_MEDIUM_CLAMP_SCALE 0.25f
#endif

/* One VPL's clamped geometry term at surface s, and the shadow ray that decides its
 * visibility; 0 when either side faces away. G = cosθx · e / d², e the VPL's emission
 * factor toward s (ts_vpl_emission_factor: cosθv for a surface VPL, the phase value for a
 * medium VPL, g the medium's HG parameter), is clamped to b (a medium VPL's to
 * b·TS_VPL_MEDIUM_CLAMP_SCALE): the contribution C·G' of any VPL is at most C·b, also
 * for a peaked phase function (g near 1: phase values near 1e5; docs/igi.md §6). The shadow ray is set in either case; use it only when G' > 0.
 * ts_vpl_geometry_term is G' alone at x (shading normal n, geometric normal ng), for
 * callers that know the visibility already; ts_vpl_geometry_term_of takes the VPL's kind
 * (ts_vpl_in_medium) from the caller. */
TS_INLINE float ts_vpl_geometry_term_of(float3 x, float3 n, float3 ng, TS_GLOBAL const float* vpl, float b, float g,
                                        int medium) {
    float3 y = ts_f3_load(vpl + TS_VPL_POSITION);
    float3 d = y - x;
    float dist2 = dot(d, d);
    /* Branch-free: with x at the VPL (dist2 = 0) w is NaN, and every test below fails.
     * The facing tests come out either way per pixel, so branches would mispredict, and
     * without them the Embree packet dispatch runs this for 16 pixels in SIMD
     * (host/backend/embree_packets.cpp). One division and three products, not three
     * divisions: division is the slowest step of this function in SIMD too. */
    float3 w = d * (1.0f / sqrt(dist2));
    float cos_x = dot(n, w), cos_v = ts_vpl_emission_factor_of(vpl, -w, g, medium);
    int faces = (dist2 > 0.0f) & (cos_x > 0.0f) & (cos_v > 0.0f) & (dot(ng, w) > 0.0f);
    return faces ? ts_min_bound(cos_x * cos_v / dist2, medium ? b * TS_VPL_MEDIUM_CLAMP_SCALE : b) : 0.0f;
}

TS_INLINE float ts_vpl_geometry_term(float3 x, float3 n, float3 ng, TS_GLOBAL const float* vpl, float b, float g) {
    return ts_vpl_geometry_term_of(x, n, ng, vpl, b, g, ts_vpl_in_medium(vpl));
}

TS_INLINE float ts_vpl_geometry(const TsSurface* s, TS_GLOBAL const float* vpl, float b, float g, TsRay* shadow) {
    *shadow = ts_vpl_shadow_ray(ts_offset_ray_origin(s->origin, s->geo_normal, s->pos_scale), vpl);
    return ts_vpl_geometry_term(s->position, s->shading_normal, s->geo_normal, vpl, b, g);
}

/* The gather sum E = (1/π) Σ_v C_v · Tr_v · G'_v over the VPLs v whose shadow ray was
 * found unoccluded: C the VPL's flux weight, Tr the medium's transmittance along the
 * shadow ray, G' the clamped geometry term (ts_vpl_geometry). ts_vpl_gather_add adds one
 * VPL's term, ts_vpl_gather_result applies the 1/π; the caller owns the loop, since
 * visibility comes from a tracer in the igi kernels and from stored rows in the instant
 * cache's gather (shared/ic_gather.h).
 *
 * The accumulator is the caller's: igi sums one set's VPLs in float (float3). A cache
 * record's E is formed once from all the VPLs of a frame (thousands of terms, not one
 * set's) and then reused by many pixels, so it sums in double where the device has
 * doubles (TsDouble3: always in C++, with cl_khr_fp64 in OpenCL) and otherwise in float
 * with Neumaier's compensation (TsSum3), whose error does not grow with the number of
 * terms (Neumaier 1974; Higham, Accuracy and Stability of Numerical Algorithms, §4.3).
 * Each form builds a term in its accumulator's precision as (C · Tr) · G' and adds it
 * (ts_vpl_gather_term: the float term, for callers that know Tr, e.g. 1 without a medium;
 * the double and compensated forms take Tr from the caller, who need not build a shadow
 * ray where there is no medium).
 * OpenCL C has no overloading, hence one name per accumulator. */
TS_INLINE float3 ts_vpl_gather_term(TS_GLOBAL const float* vpl, float3 tr, float g) {
    return ts_f3_load(vpl + TS_VPL_FLUX) * tr * g;
}

TS_INLINE void ts_vpl_gather_add(float3* sum, TS_GLOBAL const float* vpl, const TsMedium* med, TsRay shadow,
                                 float g) {
    *sum += ts_vpl_gather_term(vpl, ts_vpl_shadow_transmittance(med, shadow, vpl), g);
}

TS_INLINE float3 ts_vpl_gather_result(float3 sum) { return sum * TS_INV_PI; }

typedef struct TsSum3 {
    float s[3], c[3];
} TsSum3;

TS_INLINE void ts_vpl_gather_add_compensated(TsSum3* sum, TS_GLOBAL const float* vpl, float3 tr, float g) {
    float3 t = ts_f3_load(vpl + TS_VPL_FLUX) * tr * g;
    ts_sum_compensated_add(&sum->s[0], &sum->c[0], t.x);
    ts_sum_compensated_add(&sum->s[1], &sum->c[1], t.y);
    ts_sum_compensated_add(&sum->s[2], &sum->c[2], t.z);
}

TS_INLINE float3 ts_vpl_gather_result_compensated(TsSum3 sum) {
    return make_float3(sum.s[0] + sum.c[0], sum.s[1] + sum.c[1], sum.s[2] + sum.c[2]) * TS_INV_PI;
}

#ifdef TS_HAS_DOUBLE
typedef struct TsDouble3 {
    double x, y, z;
} TsDouble3;

/* One channel of the double form's term, (C · Tr) · G' in double. */
TS_INLINE double ts_vpl_gather_term_double(float c, float tr, float g) { return (double)c * tr * g; }

TS_INLINE void ts_vpl_gather_add_double(TsDouble3* sum, TS_GLOBAL const float* vpl, float3 tr, float g) {
    const float3 c = ts_f3_load(vpl + TS_VPL_FLUX);
    sum->x += ts_vpl_gather_term_double(c.x, tr.x, g);
    sum->y += ts_vpl_gather_term_double(c.y, tr.y, g);
    sum->z += ts_vpl_gather_term_double(c.z, tr.z, g);
}

TS_INLINE float3 ts_vpl_gather_result_double(TsDouble3 sum) {
    const double pi = 3.14159265358979323846;
    return make_float3((float)(sum.x / pi), (float)(sum.y / pi), (float)(sum.z / pi));
}
#endif

TS_NAMESPACE_END

#endif /* TS_VPL_H */
