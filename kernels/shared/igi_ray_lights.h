/* The IGI ray march's virtual ray lights (docs/igi.md §6, "Virtual ray lights"): the
 * share of a set's ray lights a step gathers, and a ray light's link from the march's
 * camera segment, for light scattered more than once in the medium. Its links are traced
 * by the caller; through shared/igi_march.h it takes the tracer interface (TsTracer) of
 * shared/direct.h. */
#ifndef TS_IGI_RAY_LIGHTS_H
#define TS_IGI_RAY_LIGHTS_H
#include "shared/igi_march.h"
#include "shared/math_lanes.h"

TS_NAMESPACE_BEGIN

/* The ray march of a pixel gathers 1/TS_IGI_MEDIA_VRL_THINNING of its set's ray lights,
 * as it gathers a share of the VPLs (TS_IGI_MEDIA_VPL_THINNING). A set has 4-5× as many
 * ray lights as medium VPLs (every segment in the medium leaves one, not only those
 * where the path scatters), and a ray light's link is bounded, so a thinner share costs
 * little noise. 8 (ours): one AIS frame on the five fog scenes scored within a few
 * tenths of a point at shares of 1/2, 1/4 and 1/8 and worse at 1/16, and 1/8 costs
 * 1.08-1.31× the medium VPLs' frame against ~2.7× at 1/2 (bench/results/ray_lights_thinning.md). */
#ifndef TS_IGI_MEDIA_VRL_THINNING
#define TS_IGI_MEDIA_VRL_THINNING 8u
#endif

/* The share of set k's ray lights that step i gathers: indices *first, *first + *stride,
 * ... below sv->vrl_set_start[k + 1] (ts_igi_march_share_offset); the link carries the
 * stride in its tint (ts_igi_march_vrl_link). (With the set index as the offset, the ray
 * lights' part read +4% on the foggy Cornell box at 8 steps.) */
TS_INLINE void ts_igi_march_vrl_share(const TsSceneView* sv, const TsFrame* f, uint k, uint i, uint* first,
                                      uint* stride) {
    *stride = TS_IGI_MEDIA_VRL_THINNING * f->igi_steps;
    *first = sv->vrl_set_start[k] + ts_igi_march_share_offset(f, k, i, TS_IGI_MEDIA_VRL_THINNING, 0x76726c6fu);
}

/* The uniform number that places ray light j's point for march m (its pixel and set) in
 * this pass: counter-based, so the order of the links does not matter (the packet march
 * of shared/igi_march16.h draws it for 16 lanes at once). */
TS_INLINE float ts_igi_vrl_u(const TsFrame* f, const TsIgiMarch* m, uint j) {
    TsRng r = ts_rng_seed(f->seed ^ 0x76726c73u ^ ts_pcg_hash(j), m->key, f->pass);
    return ts_rng_next(&r);
}

/* The pieces of ts_igi_march_vrl_link, which the 16-lane march also runs
 * (ts_igi_march_vrl_links16, shared/igi_march16.h). The camera side: the point *x of march
 * m's camera segment that links to ray light `vrl` from the step whose own distance is t,
 * and the camera side's factor *camera (ts_igi_march_vrl_link says which); 0 when there is
 * nothing to link (an empty segment or ray light, or an unusable density). */
TS_INLINE int ts_igi_march_vrl_point(const TsMedium* med, const TsIgiMarch* m, float t, TS_GLOBAL const float* vrl,
                                     float3* x, float3* camera) {
    float len = m->t1 - m->t0, vlen = vrl[TS_VRL_LENGTH];
    if (!(len > 0.0f) || !(vlen > 0.0f)) return 0;
    *camera = make_float3(1.0f, 1.0f, 1.0f);
    if (m->equiangular) {
        /* As a point light's (ts_igi_march_toward): only a ray light whose line passes
         * within TS_IGI_EQUIANGULAR_REACH steps of the camera ray's draws its distance;
         * farther ones light the segment smoothly and keep the step's own point, eq = 1. */
        float eq = 1.0f;
        float3 start = ts_f3_load(vrl + TS_VRL_START), omega = ts_f3_load(vrl + TS_VRL_DIR);
        TsLineSampler ls = ts_line_setup(m->ray.org, m->ray.dir, m->t0, m->t1, start, omega);
        if (ls.h < TS_IGI_EQUIANGULAR_REACH * m->step) {
            ls = ts_line_bounds(ls, m->t0, m->t1);
            t = ts_line_sample(&ls, m->t0, m->t1, (t - m->t0) / len);
            eq = ts_line_pdf(&ls, t) * len;
            if (!(eq > 0.0f && eq < TS_INF)) return 0;
        }
        *camera = med->sigma_s * ts_igi_march_tr(med, m, t) * (m->step / eq);
    }
    *x = m->ray.org + m->ray.dir * t;
    return 1;
}

/* The ray light's side of the link from point x of a camera ray of direction dir to the ray
 * light from `start` along unit `omega` over [0, vlen] (scene units), for uniform u: its
 * point *y = start + omega·τ, τ by equiangular sampling toward x (ts_equiangular_*, Kulla
 * and Fajardo 2012), the weight w = e · phase(dir, ω_i) / (d² · pdf(τ)) (returned),
 * *tint = camera · σs · Tr(τ) · stride, and *ok: whether there is a link (a usable
 * density, d > 0, and a finite w > 0; where *ok is 0 the rest is not used). Without
 * branches, its arctangents and tangent (in ts_equiangular_*) and exponential from
 * shared/math_lanes.h, so that the lanes' loop vectorises: these were most of a foggy
 * frame's ray-light links one lane at a time. */
TS_INLINE float ts_igi_march_vrl_weight(const TsMedium* med, float3 x, float3 dir, float3 start, float3 omega,
                                        float vlen, float u, float3 camera, float stride, float3* y, float3* tint,
                                        int* ok) {
    TsEquiangular e = ts_equiangular_angles(ts_equiangular_setup(start, omega, vlen, x, 0.0f), 0.0f, vlen);
    float tau = ts_equiangular_sample(&e, 0.0f, vlen, u);
    float pv = ts_equiangular_pdf(&e, tau);
    *y = start + omega * tau;
    float3 d = *y - x;
    float dist2 = dot(d, d);
    float3 wi = d / sqrt(dist2);
    float ev = ts_hg_phase(dot(omega, -wi), med->g);
    float w = ev * ts_hg_phase(dot(dir, wi), med->g) / (dist2 * pv);
    float3 st = med->sigma_t * (-tau);
    *tint = camera * med->sigma_s * make_float3(ts_lanes_exp(st.x), ts_lanes_exp(st.y), ts_lanes_exp(st.z)) * stride;
    *ok = (pv > 0.0f) & (pv < TS_INF) & (dist2 > 0.0f) & (w > 0.0f) & (w < TS_INF);
    return w;
}

/* Ray light `vrl`'s link (layout_igi.h TS_VRL_*; docs/igi.md §6) from the camera segment
 * of march m at the step whose own distance is t; u places the point on the ray light
 * (ts_igi_vrl_u). A ray light of flux Φ along a segment y(τ), τ in [0, ℓ], sends a point
 * x of the camera segment Φ ∫ σs Tr(τ) f_p(ω, y→x) Tr(y, x) V / |x − y|² dτ, which a
 * point VPL (one τ drawn along the light path) estimates with a 1/d² spike. Here both
 * points are drawn toward each other (Novák et al. 2012, §5): x along the camera segment
 * with density ∝ 1/D(t) toward the ray light's line (ts_line_sampler) from the step's
 * stratified offset, then τ by equiangular sampling toward x, so 1/d² cancels against
 * the densities: w = e · phase(dir, ω_i) / (d² · pdf(τ)) = e · phase · Δθ / D, e the
 * ray light's phase value toward x, with no clamp; *tint = σs·Tr(τ) (the ray light's
 * scattering at τ) times the camera side's σs · T(t0, t) · step / eq as an equiangular
 * VPL link's (eq = pdf(t)·(t1 − t0)), times the share's `stride` (ts_igi_march_vrl_share). With `--uniform-march` (!m->equiangular) x is the
 * step's own point and the camera side is left to the step's end, as for the VPLs.
 * Returns 0 when there is nothing to trace; else the shadow ray from x to y. */
TS_INLINE int ts_igi_march_vrl_link(const TsMedium* med, const TsIgiMarch* m, float t, float u, float stride,
                                    TS_GLOBAL const float* vrl, TsRay* shadow, float* w, float3* tint) {
    float3 x, camera, y;
    if (!ts_igi_march_vrl_point(med, m, t, vrl, &x, &camera)) return 0;
    int ok;
    float wv = ts_igi_march_vrl_weight(med, x, m->ray.dir, ts_f3_load(vrl + TS_VRL_START), ts_f3_load(vrl + TS_VRL_DIR),
                                       vrl[TS_VRL_LENGTH], u, camera, stride, &y, tint, &ok);
    if (!ok) return 0;
    *shadow = ts_shadow_ray(x, y, make_float3(0.0f, 0.0f, 0.0f), 0.0f);
    *w = wv;
    return 1;
}

TS_NAMESPACE_END
#endif /* TS_IGI_RAY_LIGHTS_H */
