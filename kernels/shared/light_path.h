/* Light paths of instant radiosity (Keller 1997): emission at a light and scattering at
 * each surface hit, leaving the VPLs the igi kernels (shared/igi.h) and the instant
 * cache gather from. The host traces them (host/gi/light_paths.cpp: rays batched
 * through the backend, one Halton point per path fixing every random decision), or, on a
 * GPU, the light-path kernel does, a path per work item (shared/light_path_trace.h); the
 * transport is here, next to the camera paths', so there is one material switch
 * (ts_specular_bounce) for all paths. docs/igi.md §3 is our reading.
 *
 * Estimator (pbrt-v2 IGI convention): a path starts at a light picked in proportion to
 * power, at a uniform point y0 (area pdf p_A including the selection) in a
 * cosine-distributed direction, with weight α = Le·π / p_A (the cosine of the emission
 * cancels the cosine pdf). Each segment attenuates α by the medium's transmittance (the
 * single-scattering model of shared/igi_media.h), or, for multiple scattering, samples a
 * free-flight distance and may scatter there (ts_light_path_medium). At a diffuse hit y with
 * albedo ρ the path leaves a VPL of flux weight C = α·ρ/π · inv_paths, then continues
 * with probability q = min(1, luminance(ρ)) in a cosine direction, α ← α·ρ/q. Mirrors and
 * dielectrics scatter it (ts_specular_bounce) and leave no VPL. */
#ifndef TS_LIGHT_PATH_H
#define TS_LIGHT_PATH_H
#include "shared/bsdf.h"
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/halton.h"
#include "shared/layout_light_path.h"
#include "shared/layout_rays.h"
#include "shared/layout_scene.h"
#include "shared/material.h"
#include "shared/medium.h"
#include "shared/rng.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

/* Starts a light path from five numbers in [0, 1): light selection (`u_select`, as
 * ts_sample_light), the point on the light (u, v) and the direction (d0, d1). Sets
 * *alpha = Le·π / p_A and *ray (from the point offset off the light, t in (0, inf)).
 * Returns 0, setting neither, when the point has zero pdf. Requires light_count > 0. */
TS_INLINE int ts_light_path_start(const TsSceneView* sv, float u_select, float u, float v, float d0, float d1,
                                  float3* alpha, TsRay* ray) {
    TsLightSample ls = ts_sample_light(sv->lights, sv->light_cdf, sv->light_count, u_select, u, v);
    if (!(ls.pdf_area > 0.0f)) return 0;
    float3 d = ts_from_local(ls.normal, ts_sample_cosine_hemisphere(d0, d1));
    *alpha = ls.radiance * (TS_PI / ls.pdf_area);
    ray->org = ts_offset_ray_origin(ls.position, ls.normal, ls.pos_scale);
    ray->dir = d;
    ray->tmin = 0.0f;
    ray->tmax = TS_INF;
    return 1;
}

/* Bits of ts_light_path_vertex's result. */
#define TS_LIGHT_PATH_VPL 1u       /* the vertex left a VPL: *s and *vpl_flux are set */
#define TS_LIGHT_PATH_CONTINUES 2u /* the path goes on along *ray with weight *alpha */

#define TS_LIGHT_PATH_MEDIUM 4u    /* ts_light_path_medium: the path scattered in the medium */

/* Multiple scattering (docs/igi.md §6; Raab et al. 2008, "Unbiased global illumination
 * with participating media"): free-flight sampling along the segment *ray up to the
 * surface at parameter hit_t (+inf when the ray escapes), as the path tracer does
 * (ts_medium_sample_distance, with the path's spectral state *sm; `u` holds five numbers
 * in [0, 1): channel (read on the path's first medium segment), distance, two for the
 * Henyey–Greenstein direction, roulette). A scattering event at x multiplies
 * *alpha by the event's weight w and leaves a medium VPL at *vpl_pos of flux
 * *vpl_flux = α·w · inv_paths, the light's propagation direction being ray->dir; the
 * path then goes on with probability q = min(1, max_c w_c) · f in a phase-sampled
 * direction, α ← α/q. The largest channel, not the luminance: a red-drawn path in a
 * red-scattering medium has w ≈ (0.99, ε, ε), and 1/luminance lifted its red ~4.7× an
 * event (docs/igi.md §6, "Chromatic media"). f = min(1, I(x) · B) is the far roulette's
 * share (I the importance of `region`, ts_far_importance in shared/medium.h; B =
 * *far_boost, the product of the path's earlier 1/f, which becomes B/f): 1 within the
 * region's margin while B is 1. Returns TS_LIGHT_PATH_MEDIUM |
 * TS_LIGHT_PATH_VPL (| _CONTINUES), with *t_event the event's ray parameter; or, the
 * segment passed, TS_LIGHT_PATH_CONTINUES with *alpha times the pass weight (the surface
 * vertex then must not apply the transmittance again); or 0 when the path is lost in an
 * unbounded medium. */
TS_INLINE uint ts_light_path_medium(const TsMedium* med, const TsFarRegion* region, float hit_t, const float* u,
                                    float inv_paths, float3* alpha, TsSpectralMis* sm, float* far_boost, TsRay* ray,
                                    float* t_event, float3* vpl_pos, float3* vpl_flux) {
    float t0 = 0.0f, t1 = hit_t;
    *t_event = hit_t;
    if (!ts_medium_clip(med, ray->org, ray->dir, &t0, &t1)) return TS_LIGHT_PATH_CONTINUES;
    float len = length(ray->dir), w_len = (t1 - t0) * len;
    float3 w;
    int scattered;
    float t = ts_medium_sample_distance(med, w_len, u[0], u[1], sm, &w, &scattered);
    *alpha = *alpha * w;
    if (!scattered) return isfinite(t1) ? TS_LIGHT_PATH_CONTINUES : 0u;
    *t_event = t0 + t / len;
    float3 dir = ray->dir / len;
    *vpl_pos = ray->org + ray->dir * *t_event;
    *vpl_flux = *alpha * inv_paths;
    float q = fmin(1.0f, ts_max3(w));
    float far_share = fmin(1.0f, ts_far_importance(region, *vpl_pos) * *far_boost);
    q = q * far_share; /* × 1 within the margin: the same bits */
    if (!(u[4] < q)) return TS_LIGHT_PATH_MEDIUM | TS_LIGHT_PATH_VPL;
    *alpha = *alpha / q;
    *far_boost = *far_boost / far_share;
    ray->org = *vpl_pos;
    ray->dir = ts_sample_hg(dir, med->g, u[2], u[3]);
    ray->tmin = 0.0f;
    ray->tmax = TS_INF;
    return TS_LIGHT_PATH_MEDIUM | TS_LIGHT_PATH_VPL | TS_LIGHT_PATH_CONTINUES;
}

/* The vertex where *ray (weight *alpha) hits `hit` (not TS_NO_HIT): attenuates *alpha by
 * the segment's transmittance unless `attenuated` (ts_light_path_medium already weighed
 * the segment), sets *s to the surface there, and scatters. `u` holds the
 * vertex's three numbers in [0, 1): x, y the cosine direction, z the roulette (diffuse)
 * or the Fresnel choice (dielectric). `inv_paths` is 1 / (paths per set). A diffuse
 * surface of albedo ρ > 0 leaves a VPL of flux *vpl_flux = α·ρ/π · inv_paths; a surface
 * of albedo 0 ends the path. Returns TS_LIGHT_PATH_* bits. */
TS_INLINE uint ts_light_path_vertex(const TsSceneView* sv, const TsMedium* med, TsHit hit, float3 u,
                                    float inv_paths, int attenuated, float3* alpha, TsRay* ray, TsSurface* s,
                                    float3* vpl_flux) {
    if (!attenuated) *alpha = *alpha * ts_medium_transmittance(med, ray->org, ray->dir, 0.0f, hit.t);
    *s = ts_surface_at(sv, *ray, hit);
    TS_GLOBAL const float* M = sv->materials + TS_MATERIAL_FLOATS * s->material;
    uint kind = as_uint(M[TS_MAT_KIND]);
    if (ts_is_specular(kind)) {
        (void)ts_specular_bounce(M, kind, s, u.z, ray, alpha);
        return TS_LIGHT_PATH_CONTINUES;
    }
    float3 albedo = ts_material_albedo(sv, s);
    if (!(ts_max3(albedo) > 0.0f)) return 0u;
    *vpl_flux = *alpha * albedo * (TS_INV_PI * inv_paths);
    float q = fmin(1.0f, ts_luminance(albedo));
    if (!(u.z < q)) return TS_LIGHT_PATH_VPL;
    float3 d = ts_from_local(s->shading_normal, ts_sample_cosine_hemisphere(u.x, u.y));
    if (dot(d, s->geo_normal) <= 0.0f) return TS_LIGHT_PATH_VPL;
    *alpha = *alpha * albedo / q;
    ray->org = ts_offset_ray_origin(s->origin, s->geo_normal, s->pos_scale);
    ray->dir = d;
    ray->tmin = 0.0f;
    ray->tmax = TS_INF;
    return TS_LIGHT_PATH_VPL | TS_LIGHT_PATH_CONTINUES;
}

/* ---------------------------------------------------------------- one path, segment by segment
 * What the host's batched tracer (host/gi/light_paths.cpp) and the light-path kernel
 * (shared/light_path_trace.h) both run per path, so that they leave the same VPLs: they
 * differ only in where the rays are traced. */

/* A frame's light-path parameters (the light-path table's header, layout_light_path.h). */
typedef struct TsLightPathParams {
    uint scramble;     /* the Halton digits' and the medium events' scramble */
    uint max_bounces;  /* segments per path */
    uint flags;        /* TS_LPT_MEDIUM_SCATTERING | TS_LPT_RAY_LIGHTS */
    float inv_paths;   /* 1 / (paths per set) */
    TsFarRegion region; /* the far roulette's (ts_far_importance, shared/medium.h) */
} TsLightPathParams;

TS_INLINE TsLightPathParams ts_light_path_params(TS_GLOBAL const uint* table) {
    TsLightPathParams p;
    p.scramble = table[TS_LPT_SCRAMBLE];
    p.max_bounces = table[TS_LPT_MAX_BOUNCES];
    p.flags = table[TS_LPT_FLAGS];
    p.inv_paths = as_float(table[TS_LPT_INV_PATHS]);
    p.region.lo = make_float3(as_float(table[TS_LPT_REGION_LO]), as_float(table[TS_LPT_REGION_LO + 1]),
                              as_float(table[TS_LPT_REGION_LO + 2]));
    p.region.hi = make_float3(as_float(table[TS_LPT_REGION_HI]), as_float(table[TS_LPT_REGION_HI + 1]),
                              as_float(table[TS_LPT_REGION_HI + 2]));
    p.region.margin = as_float(table[TS_LPT_REGION_MARGIN]);
    return p;
}

/* A path in flight: its Halton point, set and weight (1/p of a path kept with probability
 * p), its throughput weight α and the ray it traces next. */
typedef struct TsLightPathState {
    ulong index;
    uint set;
    float weight;
    float3 alpha;
    TsSpectralMis spectral; /* free-flight sampling's channel state (shared/medium.h) */
    float far_boost;        /* the far roulette's 1/f so far (ts_light_path_medium) */
    TsRay ray;
} TsLightPathState;

/* Bit of ts_light_path_segment's result: the segment left a ray light (ev->vrl). */
#define TS_LIGHT_PATH_VRL 8u

/* What one traced segment left: VPL and ray-light records (layout_igi.h), and the segment
 * as the temporal cache records it: the ray traced, up to seg_t on triangle seg_prim
 * (TS_NO_HIT for a medium event or an escape). */
typedef struct TsLightPathEvent {
    float vpl[TS_VPL_FLOATS];
    float vrl[TS_VRL_FLOATS];
    float seg_t;
    uint seg_prim;
} TsLightPathEvent;

/* A VPL record at `position`; `normal` is a surface VPL's normal or a medium VPL's
 * propagation direction, `pos_scale` the surface's (-1 marks a medium VPL). */
TS_INLINE void ts_light_path_store_vpl(const TsLightPathState* st, float3 position, float3 normal, float3 flux,
                                       float pos_scale, float* v) {
    ts_f3_store(v + TS_VPL_POSITION, position);
    ts_f3_store(v + TS_VPL_NORMAL, normal);
    ts_f3_store(v + TS_VPL_FLUX, flux * st->weight);
    v[TS_VPL_SET] = (float)st->set;
    v[TS_VPL_PATH] = as_float((uint)st->index);
    v[TS_VPL_POS_SCALE] = pos_scale;
}

/* The ray light of segment `ray` up to the surface at hit_t (+inf: it escapes): its
 * stretch inside the medium, of flux α · inv_paths times the path's weight (docs/igi.md
 * §6), cut at the medium's reach (ts_medium_reach): a stretch without end (a medium
 * filling space) would have no length, and one through a box far larger than the scene
 * spread its samples where no light is left. Returns 0 where the segment misses the
 * medium. */
TS_INLINE int ts_light_path_store_vrl(const TsMedium* med, const TsLightPathState* st, float hit_t, float inv_paths,
                                      float* v) {
    float t0 = 0.0f, t1 = hit_t;
    if (!ts_medium_clip(med, st->ray.org, st->ray.dir, &t0, &t1)) return 0;
    float len = length(st->ray.dir);
    float stretch = fmin((t1 - t0) * len, ts_medium_reach(med));
    if (!isfinite(stretch)) return 0;
    if (!(stretch > 0.0f)) return 0;
    ts_f3_store(v + TS_VRL_START, st->ray.org + st->ray.dir * t0);
    ts_f3_store(v + TS_VRL_DIR, st->ray.dir / len);
    ts_f3_store(v + TS_VRL_FLUX, st->alpha * (inv_paths * st->weight));
    v[TS_VRL_SET] = (float)st->set;
    v[TS_VRL_PATH] = as_float((uint)st->index);
    v[TS_VRL_LENGTH] = stretch;
    return 1;
}

/* Starts path st->index at a light (Halton dimensions 0-4 of `halton`, shared/halton.h):
 * sets st->alpha, st->ray and *light (the emissive triangle picked). Returns 0 when the
 * point has zero pdf. Requires light_count > 0. */
TS_INLINE int ts_light_path_begin(const TsSceneView* sv, TS_GLOBAL const uint* halton, TsLightPathState* st,
                                  uint* light) {
    float u[5];
    for (uint d = 0u; d < 5u; ++d) u[d] = ts_halton_sample(halton, st->index, d);
    *light = ts_select_light(sv->light_cdf, sv->light_count, u[0]);
    st->spectral = ts_spectral_mis_start();
    st->far_boost = 1.0f;
    return ts_light_path_start(sv, u[0], u[1], u[2], u[3], u[4], &st->alpha, &st->ray);
}

/* Segment `bounce` of a path: st->ray has been traced to `hit`. With multiple scattering
 * (lp->flags) the segment first leaves its ray light (TS_LPT_RAY_LIGHTS) and takes the
 * free-flight decision (ts_light_path_medium; its five numbers from the counter-based
 * generator keyed by path and bounce, not the Halton point, whose dimensions stay the
 * surface vertices': images without a medium, or with single scattering, keep their VPLs);
 * then the surface vertex (ts_light_path_vertex; Halton dimensions 5 + 3·bounce .. + 2
 * while the table `halton` holds them, the counter-based generator past it).
 * Fills *ev, updates *st, and returns TS_LIGHT_PATH_* bits: _VRL, _VPL (ev->vrl, ev->vpl
 * hold them), _MEDIUM, _CONTINUES. */
TS_INLINE uint ts_light_path_segment(const TsSceneView* sv, const TsMedium* med, TS_GLOBAL const uint* halton,
                                     const TsLightPathParams* lp, uint bounce, TsHit hit, TsLightPathState* st,
                                     TsLightPathEvent* ev) {
    uint what = 0u;
    ev->seg_t = hit.t;
    ev->seg_prim = hit.prim;
    int attenuated = 0;
    if ((lp->flags & TS_LPT_MEDIUM_SCATTERING) && med->present) {
        float hit_t = hit.prim == TS_NO_HIT ? TS_INF : hit.t;
        if ((lp->flags & TS_LPT_RAY_LIGHTS) && ts_light_path_store_vrl(med, st, hit_t, lp->inv_paths, ev->vrl))
            what |= TS_LIGHT_PATH_VRL;
        TsRng rng = ts_rng_seed(lp->scramble ^ 0x6d656469u, (uint)st->index, bounce);
        float u[5];
        for (int j = 0; j < 5; ++j) u[j] = ts_rng_next(&rng);
        float3 dir = st->ray.dir, pos, flux;
        float t_event;
        uint m = ts_light_path_medium(med, &lp->region, hit_t, u, lp->inv_paths, &st->alpha, &st->spectral,
                                      &st->far_boost, &st->ray, &t_event, &pos, &flux);
        if (m & TS_LIGHT_PATH_MEDIUM) {
            ev->seg_t = t_event;
            ev->seg_prim = TS_NO_HIT;
            ts_light_path_store_vpl(st, pos, normalize(dir), flux, -1.0f, ev->vpl);
            return what | m;
        }
        if (!(m & TS_LIGHT_PATH_CONTINUES)) return what;  /* lost in an unbounded medium */
        attenuated = 1;
    }
    if (hit.prim == TS_NO_HIT) return what;
    uint dim = 5u + 3u * bounce;
    float3 u;
    if (dim + 2u < halton[TS_HALTON_DIMS]) {
        u = make_float3(ts_halton_sample(halton, st->index, dim), ts_halton_sample(halton, st->index, dim + 1u),
                        ts_halton_sample(halton, st->index, dim + 2u));
    } else {
        /* Past the table's dimensions (deep paths: a dense medium's random walk) the
         * counter-based generator: a Halton base grows with its dimension, and a table
         * for thousands of bounces would hold hundreds of millions of digits. */
        TsRng rng = ts_rng_seed(lp->scramble ^ 0x73757266u, (uint)st->index, bounce);
        u.x = ts_rng_next(&rng);
        u.y = ts_rng_next(&rng);
        u.z = ts_rng_next(&rng);
    }
    TsSurface s;
    float3 flux;
    uint v = ts_light_path_vertex(sv, med, hit, u, lp->inv_paths, attenuated, &st->alpha, &st->ray, &s, &flux);
    if (v & TS_LIGHT_PATH_VPL) ts_light_path_store_vpl(st, s.position, s.shading_normal, flux, s.pos_scale, ev->vpl);
    return what | v;
}

TS_NAMESPACE_END
#endif /* TS_LIGHT_PATH_H */
