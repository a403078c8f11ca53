/* The IGI media estimate of one pixel and sample set (docs/igi.md §6): the ray march
 * along the camera segment in the medium, single scattering from the lights by MIS of a
 * light sample and a phase sample at each step, and with multiple scattering the step's
 * share of the set's VPLs and ray lights. The steps are in shared/igi_march.h and
 * shared/igi_ray_lights.h. */
#ifndef TS_IGI_MEDIA_H
#define TS_IGI_MEDIA_H
#include "shared/igi_march.h"
#include "shared/igi_ray_lights.h"

TS_NAMESPACE_BEGIN

/* A visible VPL link's term (ts_igi_march_vpl_link): C · Tr · w · tint, Tr the medium's
 * transmittance along its shadow ray. */
TS_INLINE float3 ts_igi_march_vpl_term(TS_GLOBAL const float* vpl, float3 tr, float w, float3 tint) {
    return ts_vpl_gather_term(vpl, tr, w) * tint;
}

/* Adds a visible VPL link (ts_igi_march_vpl_link) to *sum: C · Tr · w · tint. */
TS_INLINE void ts_igi_march_vpl_add(float3* sum, TS_GLOBAL const float* vpl, const TsMedium* med, TsRay shadow,
                                    float w, float3 tint) {
    *sum += ts_igi_march_vpl_term(vpl, ts_shadow_transmittance(med, shadow), w, tint);
}

/* Adds the VPL share's sum of step i (the share's terms times its stride) where its links
 * put it: to the step's in-scattered light `in`, or with m->equiangular, where each link
 * carries its own distance, to the march's radiance. */
TS_INLINE void ts_igi_march_vpls_add(TsIgiMarch* m, float3 share, float3* in) {
    if (m->equiangular) m->L += share;
    else *in += share;
}

/* The VPL share's sum at step i of march m (distance t): the links of the share of set
 * k's VPLs that step i gathers (ts_igi_march_vpl_share), times the share's stride: over
 * all its steps a pixel traces one shadow ray per VPL, as a surface does (ours,
 * docs/igi.md §6). Light scattered more than once, for ts_igi_march_vpls_add. */
TS_INLINE float3 ts_igi_media_vpls(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                   const TsMedium* med, const TsIgiMarch* m, float t, uint k, uint i) {
    float3 sum = make_float3(0.0f, 0.0f, 0.0f);
    uint first, stride;
    ts_igi_march_vpl_share(sv, f, k, i, &first, &stride);
    for (uint j = first; j < sv->vpl_set_start[k + 1u]; j += stride) {
        TS_GLOBAL const float* vpl = sv->vpls + j * TS_VPL_FLOATS;
        TsRay shadow;
        float w;
        float3 tint;
        if (ts_igi_march_vpl_link(f, med, m, t, vpl, &shadow, &w, &tint) && !ts_trace_occluded(tracer, shadow))
            ts_igi_march_vpl_add(&sum, vpl, med, shadow, w, tint);
    }
    sum = sum * (float)stride;
    if (f->igi_media_vpls == TS_MEDIA_VPLS_RAYS) {
        float3 rays = make_float3(0.0f, 0.0f, 0.0f);
        ts_igi_march_vrl_share(sv, f, k, i, &first, &stride);
        for (uint j = first; j < sv->vrl_set_start[k + 1u]; j += stride) {
            TS_GLOBAL const float* vrl = sv->vrls + j * TS_VRL_FLOATS;
            TsRay shadow;
            float w;
            float3 tint;
            if (ts_igi_march_vrl_link(med, m, t, ts_igi_vrl_u(f, m, j), (float)stride, vrl, &shadow, &w, &tint) &&
                !ts_trace_occluded(tracer, shadow))
                ts_igi_march_vpl_add(&rays, vrl, med, shadow, w, tint);
        }
        sum += rays;
    }
    return sum;
}

/* Ends step i at distance t: adds its in-scattered light `in`, attenuated back to the
 * segment's start, to the march's radiance. */
TS_INLINE void ts_igi_march_step_end(TsIgiMarch* m, const TsMedium* med, float t, float3 in) {
    m->L += med->sigma_s * ts_igi_march_tr(med, m, t) * in * m->step;
}

/* Writes the march's TS_IGI_MEDIA_FLOATS values: its radiance, the segment's
 * transmittance, and (when the segment met the medium) the lit fraction of the steps and
 * the segment's length; the caller cleared LIT and LENGTH. */
TS_INLINE void ts_igi_march_end(const TsFrame* f, const TsIgiMarch* m, const TsMedium* med, float* out) {
    float3 T = make_float3(1.0f, 1.0f, 1.0f);
    if (m->active) {
        T = ts_exp3(med->sigma_t * (-(m->t_end - m->t0)));
        out[TS_IGI_MEDIA_LIT] = (float)m->lit / (float)f->igi_steps;
        out[TS_IGI_MEDIA_LENGTH] = m->t1 - m->t0;
    }
    ts_f3_store(out + TS_IGI_MEDIA_RADIANCE, m->L);
    ts_f3_store(out + TS_IGI_MEDIA_TRANSMITTANCE, T);
}

/* Media estimate of sample set k for pixel (px, py): single scattering from the lights
 * along the camera segment (up to the first surface), by a ray march of igi_steps steps
 * whose start is offset by (k + ξ)/N of a step for set k. Each step estimates the
 * in-scattered light with two samples combined by the power heuristic (as the path
 * tracer does at medium vertices): one of set k's light samples, taken in turn, and one
 * Henyey–Greenstein direction traced to whatever emitter it meets. Light sampling alone
 * leaves spikes for a peaked phase function (g near ±1: a light sample aligned with the
 * view gets phase values near 1e5). With f->igi_media_vpls each step also gathers its
 * share of set k's VPLs (ts_igi_media_vpls): light scattered more than once. Also the
 * segment's transmittance, the lit fraction of the steps and the segment's length in the
 * medium. Writes TS_IGI_MEDIA_FLOATS values (the caller cleared LIT and LENGTH). */
TS_INLINE void ts_igi_media_set(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint px,
                                uint py, uint k, float* out) {
    TsMedium med = ts_medium_load(sv->medium);
    TsIgiMarch m = ts_igi_march_begin(tracer, f, &med, px, py, k);
    for (uint i = 0u; m.marched && i < f->igi_steps; ++i) {
        float t = ts_igi_march_t(f, &m, k, i);
        ts_igi_march_step_begin(&m, &med, t);
        float3 x = m.ray.org + m.ray.dir * t;
        float3 in = make_float3(0.0f, 0.0f, 0.0f);
        TsRay shadow;
        float3 radiance;
        float w;
        TsLightSample ls = ts_igi_light_sample(sv, f, k, i % f->shadow_samples);
        if (ts_igi_march_light_link(&med, &m, t, &ls, &shadow, &radiance, &w) &&
            !ts_trace_occluded(tracer, shadow))
            ts_igi_march_light_add(&m, &med, shadow, radiance, w, &in);
        ts_igi_march_phase_add(sv, tracer, f, &med, &m, x, t, &in);
        /* Multiple scattering: light that reached the medium or a surface first. */
        if (f->igi_media_vpls) ts_igi_march_vpls_add(&m, ts_igi_media_vpls(sv, tracer, f, &med, &m, t, k, i), &in);
        ts_igi_march_step_end(&m, &med, t, in);
    }
    ts_igi_march_end(f, &m, &med, out);
}

/* Media part of one igi frame for pixel (px, py), its own sample set. */
TS_INLINE void ts_igi_media_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                  uint px, uint py, float* out) {
    out[TS_IGI_MEDIA_LIT] = out[TS_IGI_MEDIA_LENGTH] = 0.0f;
    ts_igi_media_set(sv, tracer, f, px, py, ts_igi_set(px, py, f->igi_tile), out);
}

TS_NAMESPACE_END
#endif /* TS_IGI_MEDIA_H */
