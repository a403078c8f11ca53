/* Homogeneous participating medium (layout in shared/layout_scene.h): extent, transmittance
 * and free-flight distance sampling with RGB coefficients. */
#ifndef TS_MEDIUM_H
#define TS_MEDIUM_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout_scene.h"

TS_NAMESPACE_BEGIN

typedef struct TsMedium {
    float3 sigma_s;
    float3 sigma_t; /* sigma_a + sigma_s, per scene unit */
    float g;
    int bounded;
    float3 box_min, box_max;
    int present;
} TsMedium;

TS_INLINE TsMedium ts_medium_load(TS_GLOBAL const float* m) {
    TsMedium r;
    r.sigma_s = ts_f3_load(m + TS_MEDIUM_SIGMA_S);
    r.sigma_t = ts_f3_load(m + TS_MEDIUM_SIGMA_A) + r.sigma_s;
    r.g = m[TS_MEDIUM_G];
    r.bounded = m[TS_MEDIUM_BOUNDED] != 0.0f;
    r.box_min = ts_f3_load(m + TS_MEDIUM_BOX_MIN);
    r.box_max = ts_f3_load(m + TS_MEDIUM_BOX_MAX);
    r.present = m[TS_MEDIUM_PRESENT] != 0.0f;
    return r;
}

/* Per channel; a grey argument (every medium of the standard scenes) takes one exp, the
 * same value three exps give: transmittance is a tenth of a foggy igi frame's time. */
TS_INLINE float3 ts_exp3(float3 x) {
    if (x.x == x.y && x.y == x.z) {
        float e = exp(x.x);
        return make_float3(e, e, e);
    }
    return make_float3(exp(x.x), exp(x.y), exp(x.z));
}
TS_INLINE float ts_mean3(float3 x) { return (x.x + x.y + x.z) * (1.0f / 3.0f); }

/* Clips the ray interval (*t0, *t1) to the part inside the medium; returns 0 if empty.
 * For a bounded medium this is a slab test against the box. */
TS_INLINE int ts_medium_clip(const TsMedium* m, float3 org, float3 dir, float* t0, float* t1) {
    if (!m->present) return 0;
    if (m->bounded) return ts_ray_box_clip(org, dir, m->box_min, m->box_max, t0, t1);
    return *t0 < *t1;
}

/* Beer–Lambert transmittance exp(-sigma_t · length) along the ray over (t0, t1); the
 * length counts only the part inside the medium. */
TS_INLINE float3 ts_medium_transmittance(const TsMedium* m, float3 org, float3 dir, float t0, float t1) {
    if (!ts_medium_clip(m, org, dir, &t0, &t1)) return make_float3(1.0f, 1.0f, 1.0f);
    return ts_exp3(m->sigma_t * (-(t1 - t0) * length(dir)));
}

/* Free-flight sampling over a segment of length `len` (scene units) inside the medium.
 * A colour channel is picked uniformly with `u_channel` and a distance drawn from its
 * exponential, t = -ln(1 - u) / sigma_t[c]; the other channels are accounted for by
 * dividing by the pdf averaged over channels ("spectral MIS", the one-sample balance
 * heuristic over channels; Mitsuba 3 volpath, pbrt-v4 §14.2). Returns the distance, or
 * `len` when the sample passes the whole segment; *weight is the throughput factor
 *   scatter: sigma_s · Tr(t) / mean_c(sigma_t[c] Tr_c(t))
 *   pass:    Tr(len) / mean_c(Tr_c(len)).
 * *scattered is set to 1 for a scattering event. */
TS_INLINE float ts_medium_sample_distance(const TsMedium* m, float len, float u_channel, float u,
                                          float3* weight, int* scattered) {
    float3 st = m->sigma_t;
    float sc = u_channel < (1.0f / 3.0f) ? st.x : (u_channel < (2.0f / 3.0f) ? st.y : st.z);
    float t = sc > 0.0f ? -log(1.0f - u) / sc : TS_INF;
    if (t < len) {
        float3 tr = ts_exp3(st * (-t));
        *weight = m->sigma_s * tr / ts_mean3(st * tr);
        *scattered = 1;
        return t;
    }
    float3 tr = ts_exp3(st * (-len));
    *weight = tr / ts_mean3(tr);
    *scattered = 0;
    return len;
}

/* Equiangular sampling of a distance along a ray toward a point p (Kulla and Fajardo
 * 2012, "Importance sampling techniques for path tracing in participating media", §4.1):
 * t = delta + D tan(theta), theta uniform in [theta_a, theta_b], so the density
 *   pdf(t) = D / ((theta_b - theta_a) (D^2 + (t - delta)^2))   (per scene unit)
 * follows the 1/distance^2 fall-off of light from p. delta: p's projection on the ray,
 * D: p's distance from the ray's line, floored at d_min and at 1e-5 of the segment's
 * extent from the origin, so that a point on the line gives a finite (narrow) density,
 * not a NaN. A larger floor only widens the density (any D > 0 gives an unbiased
 * estimate): callers whose integrand is clamped near p set d_min to the clamp's radius,
 * where 1/distance^2 stops describing it (shared/igi.h, ts_igi_march_vpl_link). */
typedef struct TsEquiangular {
    float delta, D, theta_a, theta_b;
} TsEquiangular;

/* The sampler's geometry for a segment ending at b of the ray (org, unit dir) toward p:
 * delta and D, at least d_min (scene units; 0: no floor beyond the rounding one). The
 * angles come apart (ts_equiangular_angles), so a caller can look at D before paying for
 * the inverse trigonometry. */
TS_INLINE TsEquiangular ts_equiangular_setup(float3 org, float3 dir, float b, float3 p, float d_min) {
    TsEquiangular e;
    float3 op = p - org;
    e.delta = dot(op, dir);
    float3 perp = op - dir * e.delta;
    e.D = fmax(fmax(length(perp), d_min), 1e-5f * fmax(fabs(b), fabs(e.delta)) + 1e-30f);
    e.theta_a = e.theta_b = 0.0f;
    return e;
}

/* The angles of the segment [a, b]'s ends seen from p (after ts_equiangular_setup). */
TS_INLINE TsEquiangular ts_equiangular_angles(TsEquiangular e, float a, float b) {
    e.theta_a = atan2(a - e.delta, e.D);
    e.theta_b = atan2(b - e.delta, e.D);
    return e;
}

/* The distance for uniform u in [0, 1), clamped to [a, b] against rounding of tan. */
TS_INLINE float ts_equiangular_sample(const TsEquiangular* e, float a, float b, float u) {
    float t = e->delta + e->D * tan(e->theta_a + u * (e->theta_b - e->theta_a));
    return fmin(fmax(t, a), b);
}

/* The density of ts_equiangular_sample at t (per scene unit). */
TS_INLINE float ts_equiangular_pdf(const TsEquiangular* e, float t) {
    float x = t - e->delta;
    return e->D / ((e->theta_b - e->theta_a) * (e->D * e->D + x * x));
}

/* Transmittance along a shadow ray over its (tmin, tmax); 1 where the medium is compiled
 * out (OpenCL builds without TS_HAS_MEDIUM; every C++ build has it, and a scene without a
 * medium gives 1 through ts_medium_clip). */
TS_INLINE float3 ts_shadow_transmittance(const TsMedium* med, TsRay shadow) {
#ifdef TS_HAS_MEDIUM
    return ts_medium_transmittance(med, shadow.org, shadow.dir, shadow.tmin, shadow.tmax);
#else
    (void)med;
    (void)shadow;
    return make_float3(1.0f, 1.0f, 1.0f);
#endif
}

TS_NAMESPACE_END
#endif /* TS_MEDIUM_H */
