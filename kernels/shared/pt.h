/* The `pt` method: unidirectional volumetric path tracing, the reference every
 * interactive method is judged against (the seed thesis used 2,500 spp).
 *
 * Surfaces: Lambertian (albedo/π, texture-modulated), perfect mirror, smooth dielectric.
 * At each Lambertian vertex: next-event estimation (one power-sampled light point) and a
 * cosine-sampled continuation, combined with multiple importance sampling, power
 * heuristic (Veach 1997, §9.2): a light sample is weighted pl²/(pl² + pb²), an emitter
 * hit by the continuation pb²/(pl² + pb²), both pdfs per steradian. Emitters seen from
 * the camera or through specular bounces count in full.
 *
 * Media (compiled in with TS_HAS_MEDIUM): one homogeneous medium, filling space or a box.
 * Each path segment samples a free-flight distance (shared/medium.h: one channel per path
 * draws them, weighed by path-level MIS over RGB); a distance short of the next surface
 * is a scattering vertex, otherwise the surface is reached with the segment's
 * transmittance carried by the weight. At a scattering vertex: next-event estimation to
 * a light point, multiplied by the Henyey–Greenstein phase function and the Beer–Lambert
 * transmittance of the shadow segment, then a phase-sampled continuation; the two are
 * combined with the power heuristic like surface vertices, the phase function being the
 * continuation's pdf.
 * (Light sampling alone has infinite variance there: near an emitting wall its weight
 * cosθ_y/d² is not tempered by any cosine at the scattering point.)
 *   max_scatter = 0: full multiple scattering.
 *   max_scatter = 1: single scattering, the transport model of the interactive methods
 *     (IGI's PM component, shared/igi_media.h): the camera segment may scatter once, where the
 *     path connects to the lights by next-event estimation (then at full weight) and
 *     ends; every later segment is only attenuated (Beer–Lambert, no scattering).
 *     Surface transport is unchanged.
 * A path has at most max_depth scattering vertices (surface or medium), each connected
 * to the lights, so it counts every light path of up to max_depth + 1 segments: the
 * continuation from the last vertex is still traced, for the emitter it hits (the other
 * half of that vertex's MIS pair, or the light behind a mirror), and ends there
 * (pbrt-v4's maxDepth; Mitsuba 3's max_depth is ours + 1). max_depth = 1 is direct
 * lighting. Paths also end by Russian roulette from the fourth vertex on, with survival
 * probability min(1, max(throughput)) but at least 0.05, and at medium vertices far from
 * the scene and the camera by the far roulette (ts_roulette).
 *
 * Uses the tracer interface documented in shared/direct.h.
 */
#ifndef TS_PT_H
#define TS_PT_H
#include "shared/bsdf.h"
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/frame.h"
#include "shared/layout_pass.h"
#include "shared/layout_rays.h"
#include "shared/layout_scene.h"
#include "shared/material.h"
#include "shared/medium.h"
#include "shared/rng.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

/* A light point seen from x: its radiance arriving at x (after the shadow test and the
 * medium's transmittance) and the solid-angle pdf of having sampled it. */
typedef struct TsLightConnection {
    float3 wi;        /* unit direction from x to the light point */
    float3 radiance;  /* Le · V · Tr, zero if blocked or facing away */
    float pdf;        /* per steradian at x */
} TsLightConnection;

/* Samples a light point and traces the shadow ray from `org` (already offset off any
 * surface) to it. */
TS_INLINE TsLightConnection ts_connect_light(const TsSceneView* sv, const TsTracer* tracer,
                                             const TsMedium* med, float3 org, float3 x, TsRng* rng) {
    TsLightConnection c;
    c.radiance = make_float3(0.0f, 0.0f, 0.0f);
    c.pdf = 0.0f;
    float us = ts_rng_next(rng), u = ts_rng_next(rng), v = ts_rng_next(rng);
    TsLightSample ls = ts_sample_light(sv->lights, sv->light_cdf, sv->light_count, us, u, v);
    float3 d = ls.position - x;
    float dist2 = dot(d, d);
    c.wi = d / sqrt(dist2);
    float cos_y = -dot(ls.normal, c.wi);
    if (!(cos_y > 0.0f) || !(dist2 > 0.0f)) return c;
    c.pdf = ls.pdf_area * dist2 / cos_y;
    TsRay shadow = ts_shadow_ray(org, ls.position, ls.normal, ls.pos_scale);
    if (ts_trace_occluded(tracer, shadow)) return c;
    c.radiance = ls.radiance;
#ifdef TS_HAS_MEDIUM
    c.radiance = c.radiance * ts_medium_transmittance(med, shadow.org, shadow.dir, 0.0f, 1.0f);
#endif
    return c;
}

/* Russian roulette; returns 0 when the path ends. From the fourth vertex on the path
 * survives with probability min(1, max(throughput)) but at least 0.05. At a medium vertex
 * the far roulette's importance (ts_far_importance, shared/medium.h; 1 elsewhere, which
 * leaves the numbers as they were) caps that at max(throughput) · importance, at any
 * depth and without the floor: the far roulette raises a throughput to at most
 * 1 / importance. */
TS_INLINE int ts_roulette(float3* beta, uint depth, float importance, TsRng* rng) {
    float u = ts_rng_next(rng);
    float b = ts_max3(*beta);
    float survive = depth < 3u ? 1.0f : clamp(b, 0.05f, 1.0f);
    if (importance < 1.0f) survive = fmin(survive, b * importance);
    if (!(survive < 1.0f)) return 1;
    if (u >= survive) return 0;
    *beta = *beta / survive;
    return 1;
}

/* The frame's far roulette region (TsFrame.far_*). */
TS_INLINE TsFarRegion ts_frame_far_region(const TsFrame* f) {
    TsFarRegion r;
    r.lo = make_float3(f->far_lo[0], f->far_lo[1], f->far_lo[2]);
    r.hi = make_float3(f->far_hi[0], f->far_hi[1], f->far_hi[2]);
    r.margin = f->far_margin;
    return r;
}

/* One pass (1 spp) of the path tracer for pixel (px, py); writes TS_PASS_FLOATS values
 * (layout_pass.h) to out, with albedo, normal and depth from the first camera hit. */
TS_INLINE void ts_pt_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                           uint px, uint py, float* out) {
    TsRng rng = ts_rng_seed(f->seed, py * f->width + px, f->pass);
    float jx = ts_rng_next(&rng), jy = ts_rng_next(&rng);
    TsRay ray = ts_camera_ray(f, px, py, jx, jy);
    TsMedium med = ts_medium_load(sv->medium);
    float3 L = make_float3(0.0f, 0.0f, 0.0f), beta = make_float3(1.0f, 1.0f, 1.0f);
    float prev_pdf = 0.0f;
    int prev_delta = 1;
    uint scatters = 0u;
#ifdef TS_HAS_MEDIUM
    TsSpectralMis spectral = ts_spectral_mis_start(); /* free-flight sampling's channel state */
    const TsFarRegion far_region = ts_frame_far_region(f);
#endif
    for (int i = 0; i < TS_PASS_DEPTH; ++i) out[i] = 0.0f;
    out[TS_PASS_DEPTH] = TS_INF;

    /* depth == max_depth: the continuation's hit, which only adds the emitter's share. */
    for (uint depth = 0u; depth <= f->max_depth; ++depth) {
        TsHit hit = ts_trace_closest(tracer, ray);
#ifdef TS_HAS_MEDIUM
        float t0 = ray.tmin, t1 = hit.prim == TS_NO_HIT ? TS_INF : hit.t;
        if (ts_medium_clip(&med, ray.org, ray.dir, &t0, &t1)) {
            if (f->max_scatter == 1u && depth > 0u) {
                /* Single scattering happens on the camera segment; later ones attenuate. */
                if (!isfinite(t1)) break;
                beta = beta * ts_exp3(med.sigma_t * (-(t1 - t0)));
            } else {
                float3 w;
                int scattered;
                float uc = ts_rng_next(&rng), ud = ts_rng_next(&rng);
                float t = t0 + ts_medium_sample_distance(&med, t1 - t0, uc, ud, &spectral, &w, &scattered);
                if (!scattered && !isfinite(t1)) break; /* lost in an unbounded medium */
                beta = beta * w;
                if (scattered) {
                    if (depth == f->max_depth) break; /* a vertex past the limit */
                    float3 x = ray.org + ray.dir * t;
                    int last = f->max_scatter > 0u && ++scatters >= f->max_scatter;
                    TsLightConnection c = ts_connect_light(sv, tracer, &med, x, x, &rng);
                    if (c.pdf > 0.0f) {
                        float phase = ts_hg_phase(dot(ray.dir, c.wi), med.g);
                        float mis = last ? 1.0f : ts_power_heuristic(c.pdf, phase);
                        L += beta * c.radiance * (phase * mis / c.pdf);
                    }
                    if (last) break;
                    float u1 = ts_rng_next(&rng); /* sequenced: see ts_igi_march_phase_add */
                    float u2 = ts_rng_next(&rng);
                    float3 d = ts_sample_hg(ray.dir, med.g, u1, u2);
                    prev_pdf = ts_hg_phase(dot(ray.dir, d), med.g);
                    ray.org = x;
                    ray.dir = d;
                    ray.tmin = 0.0f;
                    ray.tmax = TS_INF;
                    prev_delta = 0;
                    if (!ts_roulette(&beta, depth, ts_far_importance(&far_region, x), &rng)) break;
                    continue;
                }
            }
        }
#endif
        if (hit.prim == TS_NO_HIT) break;
        TsSurface s = ts_surface_at(sv, ray, hit);
        TS_GLOBAL const float* M = sv->materials + TS_MATERIAL_FLOATS * s.material;
        float3 albedo = ts_material_albedo(sv, &s);
        if (depth == 0u) {
            ts_f3_store(out + TS_PASS_ALBEDO, albedo);
            ts_f3_store(out + TS_PASS_NORMAL, s.shading_normal);
            out[TS_PASS_DEPTH] = hit.t;
        }
        float3 le = ts_material_emission(sv, &s);
        if (le.x + le.y + le.z > 0.0f) {
            if (prev_delta) {
                L += beta * le;
            } else {
                float cos_y = -dot(s.geo_normal, ray.dir);
                float pl = ts_light_pdf_area(M[TS_MAT_SELECTION], f->light_power) * hit.t * hit.t / cos_y;
                L += beta * le * ts_power_heuristic(prev_pdf, pl);
            }
        }
        if (depth == f->max_depth) break;
        uint kind = as_uint(M[TS_MAT_KIND]);
        float3 ng = s.geo_normal;
        if (ts_is_specular(kind)) {
            float u = kind == TS_MAT_DIELECTRIC ? ts_rng_next(&rng) : 0.0f;
            if (!ts_specular_bounce(M, kind, &s, u, &ray, &beta)) break;
            prev_delta = 1;
        } else {
            if (ts_max3(albedo) <= 0.0f) break;
            float3 ns = s.shading_normal;
            float3 org = ts_offset_ray_origin(s.origin, ng, s.pos_scale);
            if (sv->light_count > 0u) {
                TsLightConnection c = ts_connect_light(sv, tracer, &med, org, s.position, &rng);
                float cos_x = dot(ns, c.wi);
                if (c.pdf > 0.0f && cos_x > 0.0f && dot(ng, c.wi) > 0.0f) {
                    float pb = cos_x * TS_INV_PI;
                    L += beta * albedo * c.radiance *
                         (TS_INV_PI * cos_x * ts_power_heuristic(c.pdf, pb) / c.pdf);
                }
            }
            float u1 = ts_rng_next(&rng); /* sequenced, as above */
            float u2 = ts_rng_next(&rng);
            float3 wi = ts_from_local(ns, ts_sample_cosine_hemisphere(u1, u2));
            float cos_o = dot(ns, wi);
            if (!(cos_o > 0.0f) || dot(ng, wi) <= 0.0f) break;
            beta = beta * albedo;  /* (albedo/π) cosθ / (cosθ/π) */
            prev_pdf = cos_o * TS_INV_PI;
            prev_delta = 0;
            ray.org = org;
            ray.dir = wi;
        }
        ray.tmin = 0.0f;
        ray.tmax = TS_INF;
        if (!ts_roulette(&beta, depth, 1.0f, &rng)) break;
    }
    ts_f3_store(out + TS_PASS_RADIANCE, L);
}

TS_NAMESPACE_END
#endif /* TS_PT_H */
