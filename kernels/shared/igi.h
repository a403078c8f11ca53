/* Instant Global Illumination (Wald et al., EGWR 2002), per-pixel part: the surface
 * shading of one interleaved sample set, and the participating-media ray march. The
 * host generates the VPLs (host/gi/vpl_generator.cpp), filters and composites
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
 * Transport (equal to `pt --max-scatter 1`): surfaces get direct light from the area
 * lights and indirect diffuse light from the VPLs, each connection attenuated by the
 * medium's transmittance; the medium scatters light from the lights once, on the
 * camera segment only; the surface behind is attenuated by that segment's transmittance.
 *
 * The VPL geometry term is clamped, G' = min(G, b) with b = igi_g_clamp (docs/igi.md
 * §4): it bounds each VPL's contribution at C·b, removing the 1/d² splotches near VPLs
 * at the cost of energy lost at short range (corners come out darker).
 *
 * Uses the tracer interface documented in shared/direct.h.
 */
#ifndef TS_IGI_H
#define TS_IGI_H
#include "shared/ais_compact.h"
#include "shared/bsdf.h"
#include "shared/compat.h"
#include "shared/direct.h"
#include "shared/geometry.h"
#include "shared/frame.h"
#include "shared/layout_igi.h"
#include "shared/layout_rays.h"
#include "shared/layout_scene.h"
#include "shared/material.h"
#include "shared/math_lanes.h"
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
    float3 c;   /* light sample: Le cosθx cosθy / (d² p), unoccluded */
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

/* Light sample j (j < m) of set k: the same point on the lights for every pixel of the set. */
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
        l->c = ts_light_contribution(s, ts_igi_light_sample(sv, f, k, j), &l->shadow);
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
 * fraction of the m samples not blocked, a sample behind the surface's plane counting as
 * not blocked. AIS's SS guidance reads it (docs/ais.md §3). Samples behind the plane are
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

/* Follows mirror and dielectric bounces from the camera (at most 5) to the first
 * diffuse surface, `hit` being the closest hit of *ray (already traced); *throughput
 * collects their reflectances. Dielectrics pick reflection or refraction by Fresnel with
 * `u`. Returns the hit (TS_NO_HIT if the path escapes). */
TS_INLINE TsHit ts_igi_find_diffuse(const TsSceneView* sv, const TsTracer* tracer, TsRay* ray, TsHit hit,
                                    float3* throughput, float* distance, TsRng* rng) {
    *throughput = make_float3(1.0f, 1.0f, 1.0f);
    *distance = 0.0f;
    for (int bounce = 0; bounce < 6; ++bounce) {
        if (bounce > 0) hit = ts_trace_closest(tracer, *ray);
        if (hit.prim == TS_NO_HIT) return hit;
        *distance += hit.t;
        TS_GLOBAL const float* M = sv->materials + TS_MATERIAL_FLOATS * sv->tri_mat[hit.prim];
        uint kind = as_uint(M[TS_MAT_KIND]);
        if (kind == TS_MAT_DIFFUSE || bounce == 5) return hit;
        TsSurface s = ts_surface_at(sv, *ray, hit);
        float u = kind == TS_MAT_MIRROR ? 0.0f : ts_rng_next(rng); /* the dielectric's Fresnel choice */
        (void)ts_specular_bounce(M, kind, &s, u, ray, throughput);
    }
    return hit;
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
    v.hit = ts_igi_find_diffuse(sv, tracer, &v.ray, first, &v.throughput, &v.distance, rng);
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
 * tracing each link's shadow ray on its own. */
TS_INLINE void ts_igi_surface_set(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                  const TsIgiView* v, float3 albedo, uint k, uint mask, float3* e_ss,
                                  float3* e_id, float* visible) {
    TsMedium med = ts_medium_load(sv->medium);
    TsIgiGather g = ts_igi_gather_begin();
    if (ts_max3(albedo) > 0.0f) {
        uint n = ts_igi_link_count(sv, f, k, mask);
        for (uint j = 0u; j < n; ++j) {
            TsIgiLink l;
            if (!ts_igi_link(sv, f, &v->s, k, mask, j, &l)) continue;
            if (l.vpl == TS_NO_HIT) ++g.facing;
            if (!ts_trace_occluded(tracer, l.shadow)) ts_igi_gather_add(&g, sv, &med, &l);
        }
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
    out[TS_IGI_SURF_VISIBLE] = visible;
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
    ts_igi_surface_set(sv, tracer, f, &v, albedo, ts_igi_set(px, py, f->igi_tile), f->igi_components, &e_ss,
                       &e_id, &visible);
    ts_igi_surface_store(&v, albedo, le, e_ss, e_id, visible, out);
}

/* Emitter triangles up to which ts_igi_may_meet_emitter tests a ray against each one's
 * box before the ray is traced; with more, the test could cost what the trace saves
 * (the standard scenes have 2 and 8). */
#define TS_IGI_EMITTER_BOXES_MAX 16u

/* Emitter triangle i's box (sv->lights: every triangle with emission) for the box test
 * of ts_igi_may_meet_emitter, and the largest coordinate magnitude of its corners. */
typedef struct TsEmitterBox {
    float3 lo, hi;
    float mag;
} TsEmitterBox;

TS_INLINE TsEmitterBox ts_igi_emitter_box(const TsSceneView* sv, uint i) {
    TS_GLOBAL const float* L = sv->lights + i * TS_LIGHT_FLOATS;
    float3 p0 = ts_f3_load(L + TS_LIGHT_P0);
    float3 p1 = p0 + ts_f3_load(L + TS_LIGHT_E1), p2 = p0 + ts_f3_load(L + TS_LIGHT_E2);
    TsEmitterBox b;
    b.lo = fmin(p0, fmin(p1, p2));
    b.hi = fmax(p0, fmax(p1, p2));
    b.mag = fmax(ts_max_abs3(b.lo), ts_max_abs3(b.hi));
    return b;
}

/* The pad that grows an emitter's box for a ray from x (mx = ts_max_abs3(x)): 1e-4 of the
 * largest coordinate magnitude of the box and of x, far more than the rounding between
 * the table's p0 + e1 and the mesh's own vertex and that of the slab test (relative to the
 * coordinates and the distance travelled). */
TS_INLINE float ts_igi_emitter_pad(float mag, float mx) { return 1e-4f * (mx > mag ? mx : mag) + 1e-30f; }

/* Whether the ray from x (mx = ts_max_abs3(x)) with inverse direction inv (1/wi per
 * component) may meet `box` grown by ts_igi_emitter_pad: the slab test, with selects for
 * fmin and fmax (their values wherever no NaN enters; GCC vectorises selects over the
 * lanes of ts_igi_may_meet_emitter_lanes, shared/igi_march16.h). A zero component of wi
 * gives an infinite inverse, and the test still holds: ±inf where x lies outside that
 * slab (an empty interval), (-inf, inf) inside. A NaN slab distance (0·∞: x on a grown
 * face with wi parallel to it; or a NaN x or wi) passes: a ray passed needlessly is only
 * traced, and meets no emitter. */
TS_INLINE int ts_igi_emitter_box_may(TsEmitterBox box, float3 x, float3 inv, float mx) {
    float pad = ts_igi_emitter_pad(box.mag, mx);
    float ax = (box.lo.x - pad - x.x) * inv.x, bx = (box.hi.x + pad - x.x) * inv.x;
    float ay = (box.lo.y - pad - x.y) * inv.y, by = (box.hi.y + pad - x.y) * inv.y;
    float az = (box.lo.z - pad - x.z) * inv.z, bz = (box.hi.z + pad - x.z) * inv.z;
    float nx = ax < bx ? ax : bx, ny = ay < by ? ay : by, nz = az < bz ? az : bz;
    float fx = ax > bx ? ax : bx, fy = ay > by ? ay : by, fz = az > bz ? az : bz;
    float t0 = nx > ny ? nx : ny, t1 = fx < fy ? fx : fy;
    t0 = t0 > nz ? t0 : nz;
    t0 = t0 > 0.0f ? t0 : 0.0f;
    t1 = t1 < fz ? t1 : fz;
    int nan = (ax != ax) | (bx != bx) | (ay != ay) | (by != by) | (az != az) | (bz != bz);
    return (t0 <= t1) | nan;
}

/* Whether a ray from x along wi can hit an emitter: false only when it misses the
 * bounding box of every emitter triangle (ts_igi_emitter_box), each grown by
 * ts_igi_emitter_pad (ts_igi_emitter_box_may); such a ray's closest hit cannot be an emitter, so
 * ts_igi_emitter_traced's answer (nothing) needs no trace. Most phase-sampled rays of the
 * ray march miss the lights this way (a small light seen from the medium); the rest are
 * traced as before, so results do not change. The 16-lane march tests its lanes
 * together (ts_igi_may_meet_emitter_lanes, shared/igi_march16.h). */
TS_INLINE int ts_igi_may_meet_emitter(const TsSceneView* sv, float3 x, float3 wi) {
    if (sv->light_count > TS_IGI_EMITTER_BOXES_MAX) return 1;
    float3 inv = make_float3(1.0f / wi.x, 1.0f / wi.y, 1.0f / wi.z);
    float mx = ts_max_abs3(x);
    for (uint i = 0u; i < sv->light_count; ++i)
        if (ts_igi_emitter_box_may(ts_igi_emitter_box(sv, i), x, inv, mx)) return 1;
    return 0;
}

/* Light arriving at medium point x from direction `wi`, found by tracing a ray, and the
 * pdf (per steradian) with which light sampling would have picked that emitter point and
 * its distance *t_hit: for the phase-sampled half of the ray march's MIS. Zero when the
 * ray misses, hits a non-emitter or an emitter's back. */
TS_INLINE float3 ts_igi_emitter_traced(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                       const TsMedium* med, float3 x, float3 wi, float* pdf_light, float* t_hit) {
    TsRay r;
    r.org = x;
    r.dir = wi;
    r.tmin = 0.0f;
    r.tmax = TS_INF;
    *pdf_light = 0.0f;
    *t_hit = 0.0f;
    TsHit h = ts_trace_closest(tracer, r);
    if (h.prim == TS_NO_HIT) return make_float3(0.0f, 0.0f, 0.0f);
    TsSurface s = ts_surface_at(sv, r, h);
    float3 le = ts_material_emission(sv, &s);
    if (!(ts_max3(le) > 0.0f)) return le;
    float cos_y = -dot(s.geo_normal, wi);
    TS_GLOBAL const float* M = sv->materials + TS_MATERIAL_FLOATS * s.material;
    *pdf_light = ts_light_pdf_area(M[TS_MAT_SELECTION], f->light_power) * h.t * h.t / cos_y;
    *t_hit = h.t;
    return le * ts_medium_transmittance(med, x, wi, 0.0f, h.t);
}

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
 * segment in the medium (scene units along ray), marched in steps of `step` when
 * `active`; L: the in-scattered radiance so far; lit: the steps whose light sample was
 * visible; equiangular: f->igi_equiangular (ts_igi_march_light_link). */
typedef struct TsIgiMarch {
    TsRay ray;
    TsRng prng;
    float t0, t1, step;
    float3 L;
    uint lit;
    int active;
    int equiangular;
    uint key; /* the pixel and set, (py·width + px)·64 + k: keys the ray lights' numbers */
    float t_step;  /* the current step's own distance (ts_igi_march_step_begin; NaN before) */
    float3 tr_step; /* the camera segment's transmittance from t0 to t_step */
} TsIgiMarch;

/* Traces pixel (px, py)'s camera ray and clips its segment to the medium. An escaping
 * ray ends at the medium's box, or for a medium filling space at igi_march_far, beyond
 * which nothing can light it. */
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

/* Adds a visible light-sample link (ts_igi_march_light_link), with the medium's
 * transmittance along its shadow ray: to the step's in-scattered light `in`, or with
 * m->equiangular, where the link carries its own distance, to the march's radiance. */
TS_INLINE void ts_igi_march_light_add(TsIgiMarch* m, const TsMedium* med, TsRay shadow, float3 radiance, float w,
                                      float3* in) {
    ++m->lit;
    float3 tr = ts_medium_transmittance(med, shadow.org, shadow.dir, 0.0f, 1.0f);
    if (m->equiangular) m->L += radiance * tr * w;
    else *in += radiance * tr * w;
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

/* Adds a visible VPL link (ts_igi_march_vpl_link) to *sum: C · Tr · w · tint. */
TS_INLINE void ts_igi_march_vpl_add(float3* sum, TS_GLOBAL const float* vpl, const TsMedium* med, TsRay shadow,
                                    float w, float3 tint) {
    *sum += ts_vpl_gather_term(vpl, ts_shadow_transmittance(med, shadow), w) * tint;
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
        T = ts_exp3(med->sigma_t * (-(m->t1 - m->t0)));
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
    for (uint i = 0u; m.active && i < f->igi_steps; ++i) {
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

/* Decodes item i of sv->items (TS_AIS_ITEM_WORDS,
 * layout_igi.h): pixel (px, py), sample set k, components `mask` (TS_COMPONENT_*). */
TS_INLINE void ts_ais_item_decode(const TsSceneView* sv, const TsFrame* f, uint i, uint* px, uint* py, uint* k,
                                  uint* mask) {
    uint p = sv->items[TS_AIS_ITEM_WORDS * i + TS_AIS_ITEM_PIXEL], code = sv->items[TS_AIS_ITEM_WORDS * i + TS_AIS_ITEM_CODE];
    *px = p % f->width;
    *py = p / f->width;
    *k = code & 0xffu;
    *mask = code >> 8;
}

/* Whether an AIS item needs the surface terms (and so the view's camera path). */
TS_INLINE int ts_ais_item_has_surface(uint mask) { return (mask & (TS_COMPONENT_SS | TS_COMPONENT_ID)) != 0u; }

TS_INLINE void ts_ais_item_store_surface(float3 e_ss, float3 e_id, float* out) {
    ts_f3_store(out + TS_AIS_ITEM_E_SS, e_ss);
    ts_f3_store(out + TS_AIS_ITEM_E_ID, e_id);
}

/* The media part of an AIS item: set k's single-scattering estimate at pixel (px, py). */
TS_INLINE void ts_ais_item_media(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint px, uint py,
                                 uint k, uint mask, float* out) {
#ifdef TS_HAS_MEDIUM
    if (mask & TS_COMPONENT_PM) {
        float m[TS_IGI_MEDIA_FLOATS];
        m[TS_IGI_MEDIA_LIT] = m[TS_IGI_MEDIA_LENGTH] = 0.0f;
        ts_igi_media_set(sv, tracer, f, px, py, k, m);
        for (int c = 0; c < 3; ++c) out[TS_AIS_ITEM_PM + c] = m[TS_IGI_MEDIA_RADIANCE + c];
    }
#else
    (void)sv, (void)tracer, (void)f, (void)px, (void)py, (void)k, (void)mask, (void)out;
#endif
}

/* One AIS extra evaluation: sample set k for pixel (px, py), for the components in mask
 * (TS_COMPONENT_*). Writes TS_AIS_ITEM_FLOATS values; the same camera ray, surface and
 * set samples as the base pass would use for set k, so a pixel evaluated for every set
 * gets exactly the full-rate (non-interleaved) estimate. */
TS_INLINE void ts_ais_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint px, uint py,
                           uint k, uint mask, float* out) {
    for (int i = 0; i < TS_AIS_ITEM_FLOATS; ++i) out[i] = 0.0f;
    if (ts_ais_item_has_surface(mask)) {
        TsIgiView v = ts_igi_view(sv, tracer, f, px, py);
        if (v.hit.prim != TS_NO_HIT) {
            float3 e_ss, e_id;
            float visible;
            ts_igi_surface_set(sv, tracer, f, &v, ts_material_albedo(sv, &v.s), k, mask, &e_ss, &e_id, &visible);
            ts_ais_item_store_surface(e_ss, e_id, out);
        }
    }
    ts_ais_item_media(sv, tracer, f, px, py, k, mask, out);
}

/* The ais extra kernel's work item i: item i of sv->items through ts_ais_item. */
TS_INLINE void ts_ais_extra_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                 float* out) {
    uint px, py, k, mask;
    ts_ais_item_decode(sv, f, i, &px, &py, &k, &mask);
    ts_ais_item(sv, tracer, f, px, py, k, mask, out);
}

/* KernelId::AisCompactItem's work item i of a device frame: item i of the tables kept where
 * the kernels run (ts_ais_compact_decode, shared/ais_compact.h) through ts_ais_item. */
TS_INLINE void ts_ais_compact_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                   float* out) {
    uint px, py, k, mask;
    ts_ais_compact_decode(sv, f, i, &px, &py, &k, &mask);
    ts_ais_item(sv, tracer, f, px, py, k, mask, out);
}

TS_NAMESPACE_END
#endif /* TS_IGI_H */
