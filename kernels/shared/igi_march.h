/* The IGI ray march's steps (docs/igi.md §6; the estimator is ts_igi_media_set's,
 * shared/igi_media.h): the march's state along a pixel's camera segment, its distances
 * (stratified or equiangular), the light sample's link, the phase-sampled direction's
 * MIS half, and the links of the share of the set's VPLs a step gathers. Written as steps
 * so that the 16-lane march (shared/igi_march16.h) can interleave them across pixels. */
#ifndef TS_IGI_MARCH_H
#define TS_IGI_MARCH_H
#include "shared/igi.h"
#include "shared/igi_emitters.h"

TS_NAMESPACE_BEGIN

/* The ray march of a pixel gathers 1/TS_IGI_MEDIA_VPL_THINNING of its set's VPLs (each
 * step a different share, weighted up to stay unbiased): multiple scattering is smooth,
 * and on the foggy Cornell box (256², 6 passes, PoCL) gathering half of them cost 3.5 s
 * of CPU against 4.4-5.0 s for all, a quarter 3.4-3.6 s, with the same error against the
 * path tracer at 48² (relMSE 0.0029 in each case; single scattering alone: 2.3 s). */
#define TS_IGI_MEDIA_VPL_THINNING 2u

/* One pixel's ray march for sample set k (ts_igi_media_set, which documents the
 * estimator), in steps a packet dispatch can interleave across pixels:
 * shared/igi_march16.h runs 16 marches of one set side by side and traces each link of a
 * step (the light sample, each VPL of the step's share: the same for all 16) as one
 * packet, on Embree and on OpenCL CPU devices. Every lane makes the calls
 * ts_igi_media_set makes, in the same order, so its sums are the same bit for bit.
 * ray: the camera ray; prng: the set's phase-sample stream; [t0, t1]: the camera
 * segment in the medium (scene units along ray) up to the medium's reach, marched in
 * steps of `step` when `marched`; t_end: the segment's end before that cut, to which
 * its transmittance runs (`active`: it meets the medium); L: the in-scattered radiance
 * so far; lit: the steps whose light sample was visible; equiangular:
 * f->igi_equiangular (ts_igi_march_light_link). */
typedef struct TsIgiMarch {
    TsRay ray;
    TsRng prng;
    float t0, t1, t_end, step;
    float3 L;
    uint lit;
    int active;
    int marched; /* active, and the medium scatters: a medium that only absorbs has no steps */
    int equiangular;
    uint key; /* the pixel and set, (py·width + px)·64 + k: keys the ray lights' numbers */
    float t_step;  /* the current step's own distance (ts_igi_march_step_begin; NaN before) */
    float3 tr_step; /* the camera segment's transmittance from t0 to t_step */
} TsIgiMarch;

/* Traces pixel (px, py)'s camera ray and clips its segment to the medium. An escaping
 * ray ends at the medium's box, or for a medium filling space at igi_march_far, beyond
 * which nothing can light it; in either, no farther than the medium's reach. */
TS_INLINE TsIgiMarch ts_igi_march_begin(const TsTracer* tracer, const TsFrame* f, const TsMedium* med, uint px,
                                        uint py, uint k) {
    TsIgiMarch m;
    TsRng rng = ts_rng_seed(f->seed, py * f->width + px, f->pass);
    m.ray = ts_igi_camera_ray(f, px, py, &rng);
    /* The phase samples of set k come from their own stream, so each set's estimate is
     * independent of which other sets a pixel evaluates. */
    m.key = (py * f->width + px) * 64u + k;
    m.prng = ts_rng_seed(f->seed ^ 0x5bd1e995u, m.key, f->pass);
    m.L = make_float3(0.0f, 0.0f, 0.0f);
    m.lit = 0u;
    TsHit hit = ts_trace_closest(tracer, m.ray);
    m.t0 = 0.0f;
    m.t1 = hit.prim != TS_NO_HIT ? hit.t : (med->bounded ? TS_INF : f->igi_march_far);
    m.active = ts_medium_clip(med, m.ray.org, m.ray.dir, &m.t0, &m.t1) && f->igi_steps > 0u;
    m.t_end = m.t1;
    /* No farther than the medium's reach: a box far larger than the scene (1e9 units)
     * put the steps where no light is left. (Not the geometry's bounds: a box around a
     * small light is lit well past them, and a march ended there came out 8x low.) The
     * transmittance still runs to t_end: a channel that only absorbs may be thinner than
     * the scattering ones the reach is of. */
    if (m.active) m.t1 = fmin(m.t1, m.t0 + ts_medium_reach(med) / length(m.ray.dir));
    /* sigma_s = 0: every step would add sigma_s · ... = 0 (44% of a pass's time in an
     * absorbing box), so only the transmittance is computed. */
    m.marched = m.active && ts_medium_scatters(med);
    m.step = m.active ? (m.t1 - m.t0) / (float)f->igi_steps : 0.0f;
    m.equiangular = f->igi_equiangular != 0u;
    m.t_step = TS_NAN; /* no step yet: ts_igi_march_tr computes until ts_igi_march_step_begin */
    m.tr_step = make_float3(1.0f, 1.0f, 1.0f);
    return m;
}

/* Starts the step whose own distance is t: keeps the camera segment's transmittance up to
 * it, which its light link, its far VPLs and ray lights, and its end all take
 * (ts_igi_march_tr), so a step computes it once, not once a link. */
TS_INLINE void ts_igi_march_step_begin(TsIgiMarch* m, const TsMedium* med, float t) {
    m->t_step = t;
    m->tr_step = ts_exp3(med->sigma_t * (-(t - m->t0)));
}

/* The camera segment's transmittance from t0 to t: the step's, kept by
 * ts_igi_march_step_begin, where t is the step's own distance (the same number exp gives
 * again), else computed. The march must come from ts_igi_march_begin, its steps begun by
 * ts_igi_march_step_begin with the medium passed here (a march filled by hand, with
 * t_step 0 and tr_step 0, would give 0 at t = 0). */
TS_INLINE float3 ts_igi_march_tr(const TsMedium* med, const TsIgiMarch* m, float t) {
    return t == m->t_step ? m->tr_step : ts_exp3(med->sigma_t * (-(t - m->t0)));
}

/* Distance along the camera ray of step i: offset by (k + ξ)/N of a step for set k, ξ the
 * frame's igi_march_rotation. */
TS_INLINE float ts_igi_march_t(const TsFrame* f, const TsIgiMarch* m, uint k, uint i) {
    float N = (float)(f->igi_tile * f->igi_tile);
    return m->t0 + ((float)i + ((float)k + f->igi_march_rotation) / N) * m->step;
}

/* Equiangular sampling pays (its inverse trigonometry costs more than the march's shadow
 * ray saves) only for a point light whose 1/d^2 peak on the camera ray is narrower than a
 * few steps, which the march's stratified points resolve badly: D, its distance from the
 * ray's line (floored), under this many steps. Farther ones keep the stratified point. */
#ifndef TS_IGI_EQUIANGULAR_REACH
#define TS_IGI_EQUIANGULAR_REACH 2.0f
#endif

/* Where march m gathers point light p at the step whose own distance is t: returns the
 * distance and sets *eq, its density relative to the march's uniform one (1/(t1 - t0)).
 * With m->equiangular and p within TS_IGI_EQUIANGULAR_REACH steps of the ray (D floored at
 * d_min), the distance is drawn by equiangular sampling toward p (ts_equiangular_sample)
 * with the step's stratified offset (t - t0)/(t1 - t0) as its uniform number, and *eq is
 * its pdf times the segment's length; else t itself with *eq = 1. *eq = 0: nothing to
 * gather (an empty segment, or a density rounding made unusable). */
TS_INLINE float ts_igi_march_toward(const TsIgiMarch* m, float3 p, float d_min, float t, float* eq) {
    float len = m->t1 - m->t0;
    *eq = len > 0.0f ? 1.0f : 0.0f;
    if (!m->equiangular || !(len > 0.0f)) return t;
    TsEquiangular e = ts_equiangular_setup(m->ray.org, m->ray.dir, m->t1, p, d_min);
    if (!(e.D < TS_IGI_EQUIANGULAR_REACH * m->step)) return t;
    e = ts_equiangular_angles(e, m->t0, m->t1);
    t = ts_equiangular_sample(&e, m->t0, m->t1, (t - m->t0) / len);
    *eq = ts_equiangular_pdf(&e, t) * len;
    if (!(*eq > 0.0f && *eq < TS_INF)) *eq = 0.0f;
    return t;
}

/* The density of light point p's distance t relative to the march's uniform one, as
 * ts_igi_march_toward draws it for a light sample at p: the power heuristic compares it,
 * times the light pdf, with the phase sample's pdf at the same point. */
TS_INLINE float ts_igi_march_eq_ratio(const TsIgiMarch* m, float3 p, float t) {
    TsEquiangular e = ts_equiangular_setup(m->ray.org, m->ray.dir, m->t1, p, 0.0f);
    if (!(e.D < TS_IGI_EQUIANGULAR_REACH * m->step)) return 1.0f;
    e = ts_equiangular_angles(e, m->t0, m->t1);
    return ts_equiangular_pdf(&e, t) * (m->t1 - m->t0);
}

/* Step i's light-sample link: *ls, one of set k's light samples, taken in turn (step i
 * takes ts_igi_light_sample(sv, f, k, i % f->shadow_samples), the same for every pixel of
 * the set), seen from a point of the camera segment. With m->equiangular (the default) the point is drawn by
 * equiangular sampling toward the light sample (Kulla and Fajardo 2012), with the
 * march's stratified offset (t - t0)/(t1 - t0) as its uniform number, and the link
 * carries its own distance: *radiance is the light's radiance times sigma_s and the
 * camera segment's transmittance up to that point, and *w = phase · w_MIS · step / (pl · eq)
 * (eq: ts_igi_march_eq_ratio, step = (t1 - t0)/N), so that ts_igi_march_light_add adds the
 * step's share of single scattering to the march's radiance directly. w_MIS is the power
 * heuristic of this technique against the phase-sampled one at the march's points
 * (ts_igi_march_phase_add), in the joint density of distance and direction. Without
 * m->equiangular, the link is at the march's point x = org + t·dir with *w = phase ·
 * w_MIS / pl, the direction-only MIS, for the step's `in`. Returns 0 when the sample
 * faces away (nothing to trace); else the shadow ray too, for ts_igi_march_light_add
 * when the ray is unoccluded. */
TS_INLINE int ts_igi_march_light_link(const TsMedium* med, const TsIgiMarch* m, float t, const TsLightSample* ls,
                                      TsRay* shadow, float3* radiance, float* w) {
    float eq = 1.0f;
    if (m->equiangular) {
        t = ts_igi_march_toward(m, ls->position, 0.0f, t, &eq);
        if (!(eq > 0.0f)) return 0;
    }
    float3 x = m->ray.org + m->ray.dir * t;
    float3 d = ls->position - x;
    float dist2 = dot(d, d);
    float3 wi = d / sqrt(dist2);
    float cos_y = -dot(ls->normal, wi);
    if (!(cos_y > 0.0f)) return 0;
    *shadow = ts_shadow_ray(x, ls->position, ls->normal, ls->pos_scale);
    float pl = ls->pdf_area * dist2 / cos_y;
    float phase = ts_hg_phase(dot(m->ray.dir, wi), med->g);
    if (!m->equiangular) {
        *radiance = ls->radiance;
        *w = phase * ts_power_heuristic(pl, phase) / pl;
        return 1;
    }
    *radiance = ls->radiance * med->sigma_s * ts_igi_march_tr(med, m, t);
    /* 1 / (density of t) = (t1 - t0) / eq, over N steps: m->step / eq. */
    *w = phase * ts_power_heuristic(pl * eq, phase) * m->step / (pl * eq);
    return 1;
}

/* ts_igi_march_light_add with the transmittance tr along the link's shadow ray given. */
TS_INLINE void ts_igi_march_light_add_tr(TsIgiMarch* m, float3 tr, float3 radiance, float w, float3* in) {
    ++m->lit;
    if (m->equiangular) m->L += radiance * tr * w;
    else *in += radiance * tr * w;
}

/* Adds a visible light-sample link (ts_igi_march_light_link), with the medium's
 * transmittance along its shadow ray: to the step's in-scattered light `in`, or with
 * m->equiangular, where the link carries its own distance, to the march's radiance. */
TS_INLINE void ts_igi_march_light_add(TsIgiMarch* m, const TsMedium* med, TsRay shadow, float3 radiance, float w,
                                      float3* in) {
    ts_igi_march_light_add_tr(m, ts_medium_transmittance(med, shadow.org, shadow.dir, 0.0f, 1.0f), radiance, w, in);
}

/* The phase-sampled direction of march m's step: a Henyey–Greenstein direction (weight
 * phase/pdf = 1) from two numbers of the march's phase stream. */
TS_INLINE float3 ts_igi_march_phase_dir(const TsMedium* med, TsIgiMarch* m) {
    /* Two declarations, not two arguments: C leaves argument order open, and both backends
       must draw the two numbers in the same order for one seed. */
    float u1 = ts_rng_next(&m->prng);
    float u2 = ts_rng_next(&m->prng);
    return ts_sample_hg(m->ray.dir, med->g, u1, u2);
}

/* Adds to `in` the light of the phase-sampled direction wp (ts_igi_march_phase_dir) from
 * medium point x (distance t along the camera ray), traced to whatever emitter it meets
 * (ts_igi_emitter_traced): for a direction that may meet one (ts_igi_may_meet_emitter;
 * the others add nothing). Its MIS weight compares the phase pdf with the light-sample
 * technique's density at this point: the light pdf, times with m->equiangular the
 * relative density of the distance toward the emitter point met (ts_igi_march_eq_ratio). */
TS_INLINE void ts_igi_march_phase_gather(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                         const TsMedium* med, const TsIgiMarch* m, float3 x, float t, float3 wp,
                                         float3* in) {
    float pl2, t_hit;
    float3 le = ts_igi_emitter_traced(sv, tracer, f, med, x, wp, &pl2, &t_hit);
    if (!(pl2 > 0.0f)) return;
    if (m->equiangular) pl2 *= ts_igi_march_eq_ratio(m, x + wp * t_hit, t);
    *in += le * ts_power_heuristic(ts_hg_phase(dot(m->ray.dir, wp), med->g), pl2);
}

/* Adds the phase-sampled half of step i's MIS at medium point x (distance t along the
 * camera ray) to `in`: ts_igi_march_phase_dir, then ts_igi_march_phase_gather where the
 * direction may meet an emitter. */
TS_INLINE void ts_igi_march_phase_add(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                      const TsMedium* med, TsIgiMarch* m, float3 x, float t, float3* in) {
    float3 wp = ts_igi_march_phase_dir(med, m);
    if (ts_igi_may_meet_emitter(sv, x, wp)) ts_igi_march_phase_gather(sv, tracer, f, med, m, x, t, wp, in);
}

/* Where step i's share of a set's list starts, relative to the set's first entry, for a
 * share of 1/T of the list over the S steps (stride T·S): the entries of one residue o
 * modulo T, drawn per set and pass, dealt to the steps in turn from a step drawn likewise.
 * Each entry is gathered with probability exactly 1/T, at one step, whatever the list's
 * length, and every frame gathers its share to within one. (The offset used to be the
 * set index k over the residues modulo T·S: a set of fewer than T·S entries then had the
 * first residues gathered and the last not, each weighted as if 1/T were: with T = 2 and
 * full-rate IGI's 72 steps the VPLs' part of the march doubled, PM +40% on the foggy
 * Cornell box; at 8 steps the sets' errors cancelled on average.) `salt` keeps the VPL
 * and ray-light shares apart. */
TS_INLINE uint ts_igi_march_share_offset(const TsFrame* f, uint k, uint i, uint T, uint salt) {
    TsRng r = ts_rng_seed(f->seed ^ salt, k, f->pass);
    uint o = ts_rng_next_uint(&r) % T;
    uint step = ts_rng_next_uint(&r) % f->igi_steps;
    return o + T * ((i + step) % f->igi_steps);
}

/* The share of set k's VPLs that step i gathers: indices *first, *first + *stride, ...
 * below sv->vpl_set_start[k + 1], each weighted by *stride (ts_igi_media_vpls;
 * ts_igi_march_share_offset). */
TS_INLINE void ts_igi_march_vpl_share(const TsSceneView* sv, const TsFrame* f, uint k, uint i, uint* first,
                                      uint* stride) {
    *stride = TS_IGI_MEDIA_VPL_THINNING * f->igi_steps;
    *first = sv->vpl_set_start[k] + ts_igi_march_share_offset(f, k, i, TS_IGI_MEDIA_VPL_THINNING, 0x76706c6fu);
}

/* The pieces of ts_igi_march_vpl_link, which the 16-lane march also runs
 * (ts_igi_march_vpl_links16, shared/igi_march16.h). The clamp b of a VPL's link: a
 * medium VPL's times TS_VPL_MEDIUM_CLAMP_SCALE; returns 0 for a medium VPL when the march
 * takes the medium's light from ray lights instead (ts_igi_march_vrl_link). */
TS_INLINE int ts_igi_march_vpl_clamp(const TsFrame* f, TS_GLOBAL const float* vpl, float* b) {
    if (f->igi_media_vpls == TS_MEDIA_VPLS_RAYS && ts_vpl_in_medium(vpl)) return 0;
    *b = ts_vpl_in_medium(vpl) ? f->igi_g_clamp * TS_VPL_MEDIUM_CLAMP_SCALE : f->igi_g_clamp;
    return 1;
}

/* The point *x of march m's camera segment that links to VPL position y from the step
 * whose own distance is t, and the link's *tint (ts_igi_march_vpl_link says which);
 * 0 when the equiangular density is unusable (nothing to trace). */
TS_INLINE int ts_igi_march_vpl_point(const TsMedium* med, const TsIgiMarch* m, float t, float3 y, float b, float3* x,
                                     float3* tint) {
    *tint = make_float3(1.0f, 1.0f, 1.0f);
    if (m->equiangular) {
        float eq;
        t = ts_igi_march_toward(m, y, 1.0f / sqrt(b), t, &eq);
        if (!(eq > 0.0f)) return 0;
        *tint = med->sigma_s * ts_igi_march_tr(med, m, t) * (m->step / eq);
    }
    *x = m->ray.org + m->ray.dir * t;
    return 1;
}

/* The clamped weight min(e · phase(dir, ω_i) / d², b) of the link from point x of a camera
 * ray of direction dir to the VPL at y (of kind `medium`, ts_vpl_in_medium), and *ok:
 * whether there is a link (d > 0 and the VPL sends light toward x, e > 0). Without
 * branches, so that the lanes' loop vectorises; where *ok is 0 the weight is not used
 * (it may be NaN). ts_min_bound is fmin here: b, a clamp, is never NaN. */
TS_INLINE float ts_igi_march_vpl_weight(float3 x, float3 dir, float3 y, TS_GLOBAL const float* vpl, int medium, float g,
                                        float b, int* ok) {
    float3 d = y - x;
    float dist2 = dot(d, d);
    float3 wi = d / sqrt(dist2);
    float e = ts_vpl_emission_factor_of(vpl, -wi, g, medium);
    *ok = (dist2 > 0.0f) & (e > 0.0f);
    return ts_min_bound(e * ts_hg_phase(dot(dir, wi), g) / dist2, b);
}

/* VPL `vpl`'s link from the camera segment of march m at step i, whose own distance is t:
 * 0 when the VPL sends nothing toward the point (nothing to trace); else the shadow ray,
 * the clamped weight w = min(e · phase(dir, ω_i) / d², b) (e the VPL's emission factor
 * toward the point, ts_vpl_emission_factor; b the geometry clamp, a medium VPL's times
 * TS_VPL_MEDIUM_CLAMP_SCALE, so every VPL adds at most C·b, as at surfaces:
 * shared/vpl.h) and the colour factor *tint. Without m->equiangular the point is the step's own, x = org + t·dir, *tint = 1, and a visible
 * link adds C · Tr · w to the step's in-scattered light. With it (the default) the point
 * is drawn toward the VPL by equiangular sampling (Kulla and Fajardo 2012) with the
 * step's stratified offset as its uniform number, D floored at the clamp's radius
 * 1/sqrt(b), inside which the clamped term no longer falls as 1/d² (so no weight grows
 * without bound when a VPL lies near the camera ray), and *tint = sigma_s · T(t0, t) ·
 * step / eq (eq: the density relative to the uniform one, as in
 * ts_igi_march_light_link): the link then adds its share of the march's radiance
 * directly (ts_igi_march_vpls_add). */
TS_INLINE int ts_igi_march_vpl_link(const TsFrame* f, const TsMedium* med, const TsIgiMarch* m, float t,
                                    TS_GLOBAL const float* vpl, TsRay* shadow, float* w, float3* tint) {
    float b;
    if (!ts_igi_march_vpl_clamp(f, vpl, &b)) return 0;
    float3 y = ts_f3_load(vpl + TS_VPL_POSITION), x;
    if (!ts_igi_march_vpl_point(med, m, t, y, b, &x, tint)) return 0;
    int ok;
    float wv = ts_igi_march_vpl_weight(x, m->ray.dir, y, vpl, ts_vpl_in_medium(vpl), med->g, b, &ok);
    if (!ok) return 0;
    *shadow = ts_vpl_shadow_ray(x, vpl);
    *w = wv;
    return 1;
}

TS_NAMESPACE_END
#endif /* TS_IGI_MARCH_H */
