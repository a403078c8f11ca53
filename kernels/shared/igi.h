/* Instant Global Illumination (Wald et al., EGWR 2002), per-pixel part: the surface
 * shading of one interleaved sample set. The participating-media ray march is in
 * shared/igi_media.h, AIS's extra evaluations in shared/ais_item.h. The host generates
 * the VPLs (host/gi/vpl_generator.cpp), filters and composites
 * (host/integrators/igi_frame.cpp); docs/igi.md is our reading.
 *
 * Interleaving (Keller & Heidrich 2001): pixel (x, y) uses sample set
 * k = (x mod n) + n (y mod n). Set k owns
 *   - light samples k·m .. k·m + m - 1 of one N·m-point Hammersley set (N = n²) over
 *     (light selection, square of the light), shifted per frame by igi_rotation: every
 *     pixel of the set uses the same points, so its noise is structured and the n×n
 *     discontinuity filter, whose window holds each set once, removes it;
 *   - the VPLs of its own light paths (vpl_set_start[k] .. vpl_set_start[k+1]);
 *   - ray-march offsets (k + ξ)/N of the step, so the N sets stratify the march N-fold.
 *
 * Transport: surfaces get direct light from the area lights and indirect diffuse light
 * from the VPLs, each connection attenuated by the medium's transmittance; the surface
 * behind the camera segment is attenuated by that segment's transmittance. The march
 * (shared/igi_media.h) adds the light the camera segment scatters: from the lights once
 * (with --single-scattering the whole transport then equals `pt --max-scatter 1`), and by
 * default also from the VPLs and ray lights, light scattered more than once.
 *
 * The VPL geometry term is clamped, G' = min(G, b) with b = igi_g_clamp (docs/igi.md
 * §4): it bounds each VPL's contribution at C·b, removing the 1/d² splotches near VPLs
 * at the cost of energy lost at short range (corners come out darker).
 *
 * Uses the tracer interface documented in shared/direct.h.
 */
#ifndef TS_IGI_H
#define TS_IGI_H
#include "shared/bsdf.h"
#include "shared/camera_path.h"
#include "shared/compat.h"
#include "shared/direct.h"
#include "shared/geometry.h"
#include "shared/frame.h"
#include "shared/layout_igi.h"
#include "shared/layout_rays.h"
#include "shared/layout_scene.h"
#include "shared/material.h"
#include "shared/medium.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/vpl.h"

TS_NAMESPACE_BEGIN

/* Light sample j of the frame's N·m-point set (j < N·m), as three numbers in [0, 1):
 * light selection, and the two coordinates on the light's parameter square. */
TS_INLINE float3 ts_igi_light_point(const TsFrame* f, uint j) {
    uint total = f->igi_tile * f->igi_tile * f->shadow_samples;
    return make_float3(ts_rotate01(ts_radical_inverse3(j), f->igi_rotation[0]),
                       ts_rotate01(((float)j + 0.5f) / (float)total, f->igi_rotation[1]),
                       ts_rotate01(ts_radical_inverse2(j), f->igi_rotation[2]));
}

/* The shadow connections ("links") of sample set k at a surface, in a fixed order: the
 * set's m light samples (j < m, when `mask` has TS_COMPONENT_SS and the scene has lights),
 * then its VPLs (when `mask` has TS_COMPONENT_ID). Each link is an unoccluded
 * contribution and the shadow ray deciding its visibility; the gather adds the visible
 * ones in link order. The loop over links is the caller's, so a backend may trace the
 * links of many pixels together (the Embree backend's 16-ray packets, one link of 16
 * pixels of one set per packet, docs/ray-batches.md) while the transport stays here. */
typedef struct TsIgiLink {
    TsRay shadow;
    float3 c;   /* light sample: ts_light_contribution_from, unoccluded */
    float g;    /* VPL: the clamped geometry term G' */
    uint vpl;   /* VPL index, or TS_NO_HIT for a light sample */
} TsIgiLink;

/* The running sums of one pixel's links: E_ss and E_id before normalisation, the number
 * of light samples the surface faces (their shadow rays traced) and of those found
 * visible. */
typedef struct TsIgiGather {
    float3 ss, id;
    uint facing, seen;
} TsIgiGather;

/* Number of light-sample links of a set for `mask` (m, or 0). */
TS_INLINE uint ts_igi_light_links(const TsSceneView* sv, const TsFrame* f, uint mask) {
    return (mask & TS_COMPONENT_SS) && sv->light_count > 0u ? f->shadow_samples : 0u;
}

/* Number of links of set k for `mask`: light samples, then VPLs. */
TS_INLINE uint ts_igi_link_count(const TsSceneView* sv, const TsFrame* f, uint k, uint mask) {
    uint vpls = (mask & TS_COMPONENT_ID) ? sv->vpl_set_start[k + 1u] - sv->vpl_set_start[k] : 0u;
    return ts_igi_light_links(sv, f, mask) + vpls;
}

/* Light sample j (j < m) of set k: the same point on the lights for every pixel of the set
 * (the same parameters (u, v), for surfaces near the light, ts_light_sample_from). */
TS_INLINE TsLightSample ts_igi_light_sample(const TsSceneView* sv, const TsFrame* f, uint k, uint j) {
    float3 q = ts_igi_light_point(f, k * f->shadow_samples + j);
    return ts_sample_light(sv->lights, sv->light_cdf, sv->light_count, q.x, q.y, q.z);
}

/* Whether a light-sample link of unoccluded contribution c needs its shadow ray traced. */
TS_INLINE int ts_igi_light_link_traced(float3 c) { return c.x + c.y + c.z > 0.0f; }

/* Link j of set k at surface s (j < ts_igi_link_count). Returns 1 when its shadow ray
 * must be traced (a nonzero contribution), 0 when the link adds nothing. */
TS_INLINE int ts_igi_link(const TsSceneView* sv, const TsFrame* f, const TsSurface* s, uint k, uint mask, uint j,
                          TsIgiLink* l) {
    uint m = ts_igi_light_links(sv, f, mask);
    l->c = make_float3(0.0f, 0.0f, 0.0f);
    l->g = 0.0f;
    if (j < m) {
        l->vpl = TS_NO_HIT;
        l->c = ts_light_contribution_from(sv->lights, s, ts_igi_light_sample(sv, f, k, j), &l->shadow);
        return ts_igi_light_link_traced(l->c);
    }
    l->vpl = sv->vpl_set_start[k] + (j - m);
    l->g = ts_vpl_geometry(s, sv->vpls + l->vpl * TS_VPL_FLOATS, f->igi_g_clamp, sv->medium[TS_MEDIUM_G], &l->shadow);
    return l->g > 0.0f;
}

TS_INLINE TsIgiGather ts_igi_gather_begin(void) {
    TsIgiGather g;
    g.ss = g.id = make_float3(0.0f, 0.0f, 0.0f);
    g.facing = g.seen = 0u;
    return g;
}

/* A visible light-sample link's term of E_ss: its contribution c times the transmittance
 * tr along its shadow ray. */
TS_INLINE float3 ts_igi_light_term(float3 c, float3 tr) { return c * tr; }

/* Adds link l, whose shadow ray was found unoccluded, attenuated by the medium. */
TS_INLINE void ts_igi_gather_add(TsIgiGather* g, const TsSceneView* sv, const TsMedium* med, const TsIgiLink* l) {
    if (l->vpl == TS_NO_HIT) {
        g->ss += ts_igi_light_term(l->c, ts_shadow_transmittance(med, l->shadow));
        ++g->seen;
    } else {
        ts_vpl_gather_add(&g->id, sv->vpls + l->vpl * TS_VPL_FLOATS, med, l->shadow, l->g);
    }
}

/* E_ss = direct irradiance / π from the set's m light samples, E_id = indirect
 * irradiance / π from its VPLs (the gather sum of shared/vpl.h), and the visibility: the
 * fraction of the m samples not blocked, a sample behind the surface's plane (or, near a
 * large light, a hemisphere direction that misses it) counting as not blocked. AIS's SS guidance reads it (docs/ais.md §3). Samples behind the plane are
 * no shadow: counted as blocked, every set's visibility differed on a surface that faces
 * part of a light (each set's samples cover a different strip of it), which flagged whole
 * walls the filter cleans; and the fraction of the faced samples that are visible swings
 * from 0 to 1 where a surface faces one sample, which flagged more than it saved. */
TS_INLINE void ts_igi_gather_end(const TsIgiGather* g, const TsFrame* f, float3* e_ss, float3* e_id,
                                 float* visible) {
    float m = (float)f->shadow_samples;
    *e_ss = g->ss * (TS_INV_PI / m);
    *e_id = ts_vpl_gather_result(g->id);
    *visible = (m - (float)(g->facing - g->seen)) / m;
}

/* The camera ray of pixel (px, py), jittered within the pixel by the pixel's own random
 * stream, like the path tracer's. (A ray through the pixel centre would hit edges of
 * axis-aligned geometry exactly in symmetric views, leaving the choice of surface to a
 * traversal tie; a jittered one hits an edge with probability 0.) */
TS_INLINE TsRay ts_igi_camera_ray(const TsFrame* f, uint px, uint py, TsRng* rng) {
    float jx = ts_rng_next(rng), jy = ts_rng_next(rng);
    return ts_camera_ray(f, px, py, jx, jy);
}

/* The first diffuse surface seen through pixel (px, py) on this frame: the same camera
 * ray (same random stream) for the base pass and every AIS extra set. */
typedef struct TsIgiView {
    TsHit hit;
    TsSurface s;
    TsRay ray;
    float3 throughput;
    float distance;
} TsIgiView;

/* The first half of ts_igi_view: pixel (px, py)'s random stream and camera ray, which
 * the caller traces (alone, or in a packet with other pixels' rays). */
TS_INLINE TsRay ts_igi_view_ray(const TsFrame* f, uint px, uint py, TsRng* rng) {
    *rng = ts_rng_seed(f->seed, py * f->width + px, f->pass);
    return ts_igi_camera_ray(f, px, py, rng);
}

/* The second half: the view from camera ray `ray` (of ts_igi_view_ray, with its stream
 * `rng`), given the ray's closest hit. */
TS_INLINE TsIgiView ts_igi_view_from(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, TsRay ray,
                                     TsHit first, TsRng* rng) {
    TsIgiView v;
    v.ray = ray;
    v.hit = ts_find_diffuse(sv, tracer, &v.ray, first, &v.throughput, &v.distance, rng);
    if (v.hit.prim != TS_NO_HIT) {
        v.s = ts_surface_at(sv, v.ray, v.hit);
        /* The cone spreads over the whole path (flat mirrors keep its angle). */
        if (f->pixel_cone > 0.0f) ts_surface_cone(sv, &v.s, v.hit.prim, v.ray.dir, v.distance * ts_pass_cone(f));
    }
    return v;
}

/* The view of pixel (px, py), its camera ray traced on its own. */
TS_INLINE TsIgiView ts_igi_view(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint px,
                                uint py) {
    TsRng rng;
    TsRay ray = ts_igi_view_ray(f, px, py, &rng);
    return ts_igi_view_from(sv, tracer, f, ray, ts_trace_closest(tracer, ray), &rng);
}

/* E_ss and E_id of sample set k at the view's surface, for the components in `mask`,
 * tracing each link's shadow ray on its own. A black surface (an emitter's, or albedo 0)
 * gathers too, though its own radiance is 0: the discontinuity filter averages the
 * irradiance of the pixels around it, and a black pixel that gathered nothing reads as
 * unlit to them (docs/igi.md §8, "Black surfaces"). */
TS_INLINE void ts_igi_surface_set(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                  const TsIgiView* v, uint k, uint mask, float3* e_ss, float3* e_id,
                                  float* visible) {
    TsMedium med = ts_medium_load(sv->medium);
    TsIgiGather g = ts_igi_gather_begin();
    uint n = ts_igi_link_count(sv, f, k, mask);
    for (uint j = 0u; j < n; ++j) {
        TsIgiLink l;
        if (!ts_igi_link(sv, f, &v->s, k, mask, j, &l)) continue;
        if (l.vpl == TS_NO_HIT) ++g.facing;
        if (!ts_trace_occluded(tracer, l.shadow)) ts_igi_gather_add(&g, sv, &med, &l);
    }
    ts_igi_gather_end(&g, f, e_ss, e_id, visible);
}

/* The surface-pass output of a pixel whose camera path escapes (TS_IGI_SURF_FLOATS). */
TS_INLINE void ts_igi_surface_clear(float* out) {
    for (int i = 0; i < TS_IGI_SURF_FLOATS; ++i) out[i] = 0.0f;
    out[TS_IGI_SURF_DISTANCE] = TS_INF;
    ts_f3_store(out + TS_IGI_SURF_THROUGHPUT, make_float3(1.0f, 1.0f, 1.0f));
    out[TS_IGI_SURF_PRIM] = as_float(TS_NO_HIT);
}

/* The surface-pass output of a pixel that sees surface v->s: its G-buffer and the
 * irradiance terms of its sample set. */
TS_INLINE void ts_igi_surface_store(const TsIgiView* v, float3 albedo, float3 le, float3 e_ss, float3 e_id,
                                    float visible, float* out) {
    ts_f3_store(out + TS_IGI_SURF_E_SS, e_ss);
    ts_f3_store(out + TS_IGI_SURF_E_ID, e_id);
    ts_f3_store(out + TS_IGI_SURF_ALBEDO, albedo);
    ts_f3_store(out + TS_IGI_SURF_EMISSION, le);
    ts_f3_store(out + TS_IGI_SURF_NORMAL, v->s.shading_normal);
    out[TS_IGI_SURF_DISTANCE] = v->distance;
    ts_f3_store(out + TS_IGI_SURF_THROUGHPUT, v->throughput);
    /* AIS's SS guidance reads 1 on a black surface, as when it gathered no links: more
     * sets there change no radiance (with its true visibility a 64² black-walled box
     * took 1,025 extra sets). */
    out[TS_IGI_SURF_VISIBLE] = ts_max3(albedo) > 0.0f ? visible : 1.0f;
    ts_f3_store(out + TS_IGI_SURF_POSITION, v->s.position);
    ts_f3_store(out + TS_IGI_SURF_GEO_NORMAL, v->s.geo_normal);
    ts_f3_store(out + TS_IGI_SURF_ORIGIN, v->s.origin);
    out[TS_IGI_SURF_POS_SCALE] = v->s.pos_scale;
    out[TS_IGI_SURF_PRIM] = as_float(v->hit.prim);
}

/* Surface part of one igi frame for pixel (px, py), its own sample set; writes
 * TS_IGI_SURF_FLOATS values. */
TS_INLINE void ts_igi_surface_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                    uint px, uint py, float* out) {
    ts_igi_surface_clear(out);
    TsIgiView v = ts_igi_view(sv, tracer, f, px, py);
    if (v.hit.prim == TS_NO_HIT) return;
    float3 albedo = ts_material_albedo(sv, &v.s), le = ts_material_emission(sv, &v.s);
    float3 e_ss, e_id;
    float visible;
    ts_igi_surface_set(sv, tracer, f, &v, ts_igi_set(px, py, f->igi_tile), f->igi_components, &e_ss, &e_id,
                       &visible);
    ts_igi_surface_store(&v, albedo, le, e_ss, e_id, visible, out);
}

TS_NAMESPACE_END
#endif /* TS_IGI_H */
