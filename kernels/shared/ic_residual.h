/* The clamp's residual at an instant-cache pixel: what the geometry-term clamp b took
 * from the VPL estimate there, estimated with one short ray per pixel and pass (bias
 * compensation after Kollig & Keller, "Illumination in the presence of weak
 * singularities", MCQMC 2004; docs/instant-caching.md §9 is our reading).
 *
 * A surface VPL at y adds C·min(G, b) at x, G = cosθx cosθy / d². The VPLs sample the
 * light leaving the surfaces, L(y) = ρ(y)/π · (E_direct(y) + E_indirect(y)), so the part
 * the clamp drops, Σ_v C_v (G_v − b)⁺, estimates
 *     ΔE(x) = ∫ L(y(ω)) cosθx (1 − b/G)⁺ dω,
 * an integral over the directions ω whose first hit y lies within d < 1/√b (G ≤ 1/d² > b
 * needs it). One cosine-distributed ray (pdf cosθx/π) gives ΔE/π ≈ L(y) · (1 − b/G)⁺, with
 * E_direct(y) from one light sample and E_indirect(y) read from the cache itself (the
 * clamped records of this pass; the nearest E known where no record covers y, below). The
 * light at y lost its own
 * residual too, so the estimate goes on from y the same way, up to TS_IC_RESIDUAL_BOUNCES
 * bounces. What this leaves out: bounces past that, the error of reading another point's E
 * where no record covers y, and the medium VPLs' clamp. */
#ifndef TS_IC_RESIDUAL_H
#define TS_IC_RESIDUAL_H
#include "shared/bsdf.h"
#include "shared/compat.h"
#include "shared/direct.h"
#include "shared/geometry.h"
#include "shared/ic_lookup.h"
#include "shared/material.h"
#include "shared/medium.h"
#include "shared/rng.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

/* Direct irradiance / π at y from one light sample (u3: selection and position), through
 * the medium: ts_direct_irradiance's estimator with m = 1 and the shadow ray's
 * transmittance. */
TS_INLINE float3 ts_ic_residual_direct(const TsSceneView* sv, const TsTracer* tracer, const TsMedium* med,
                                       const TsSurface* y, float3 u3) {
    if (sv->light_count == 0u) return make_float3(0.0f, 0.0f, 0.0f);
    TsLightSample ls = ts_sample_light(sv->lights, sv->light_cdf, sv->light_count, u3.x, u3.y, u3.z);
    TsRay shadow;
    float3 c = ts_light_contribution_from(sv->lights, y, ls, &shadow);
    if (!(c.x + c.y + c.z > 0.0f) || ts_trace_occluded(tracer, shadow)) return make_float3(0.0f, 0.0f, 0.0f);
    return c * ts_shadow_transmittance(med, shadow) * TS_INV_PI;
}

/* Bounces the residual follows at most: it recurs, since the light at y lost its own
 * residual to the clamp, and in a corner the walls pass it back and forth. Each bounce
 * weighs ρ(1 − b/G)⁺ < 1. On the Cornell box (32², c = 0.3 fixed, 16 spp, seeds 1-2) one
 * bounce returned 0.86-0.89 of what the clamp removed, two 1.01-1.03, three 1.03-1.06
 * and twelve 1.04-1.07: past two the nearest-E reading below overshoots more than the
 * bounces add. */
#define TS_IC_RESIDUAL_BOUNCES 2

/* ΔE/π at the ic G-buffer surface x of pixel `pixel` for clamp b = f->igi_g_clamp (0 for
 * b = +inf, no clamp): per bounce one ray and at most one shadow ray, drawn from the
 * stream (f->seed, pixel, f->pass) of its own. The cache (sv's ic_nodes, ic_refs,
 * ic_records, Ward's a = f->ic_error_bound) gives E_indirect at each hit; where no record
 * covers a hit, the previous vertex's (e_x, the cache's E at x, for the first). Records
 * exist only where the camera sees, and the hidden sides of objects meet the walls in
 * corners too: reading 0 there returned 0.75 of what the clamp removed on the Cornell box
 * (32², c = 0.3 fixed, 64 spp, three seeds, twelve bounces), the nearest E 1.03-1.05. */
TS_INLINE float3 ts_ic_clamp_residual(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                      const TsSurface* x, float3 e_x, uint pixel) {
    float3 sum = make_float3(0.0f, 0.0f, 0.0f);
    float b = f->igi_g_clamp;
    if (!(b > 0.0f) || !(b < TS_INF)) return sum;
    TsRng rng = ts_rng_seed(f->seed ^ 0x636c6d70u, pixel, f->pass);
    TsMedium med = ts_medium_load(sv->medium);
    float3 beta = make_float3(1.0f, 1.0f, 1.0f);
    TsSurface at = *x;
    float3 e_at = e_x;
    for (int bounce = 0; bounce < TS_IC_RESIDUAL_BOUNCES; ++bounce) {
        /* One draw per statement: the order of a call's arguments is left open by C, and
         * GCC and PoCL's clang take them in different orders. */
        float u0 = ts_rng_next(&rng);
        float u1 = ts_rng_next(&rng);
        float light_select = ts_rng_next(&rng);
        float light_u = ts_rng_next(&rng);
        float light_v = ts_rng_next(&rng);
        float3 u3 = make_float3(light_select, light_u, light_v);
        float3 w = ts_from_local(at.shading_normal, ts_sample_cosine_hemisphere(u0, u1));
        if (dot(w, at.geo_normal) <= 0.0f) break; /* as a VPL below the surface: G = 0 */
        TsRay ray;
        ray.org = ts_offset_ray_origin(at.origin, at.geo_normal, at.pos_scale);
        ray.dir = w;
        ray.tmin = 0.0f;
        ray.tmax = 1.0f / sqrt(b); /* beyond it G ≤ 1/d² < b: nothing was clamped */
        TsHit hit = ts_trace_closest(tracer, ray);
        if (hit.prim == TS_NO_HIT) break;
        TsSurface y = ts_surface_at(sv, ray, hit);
        TS_GLOBAL const float* M = sv->materials + TS_MATERIAL_FLOATS * y.material;
        if (ts_is_specular(as_uint(M[TS_MAT_KIND]))) break; /* leaves no VPL */
        float3 albedo = ts_material_albedo(sv, &y);
        float3 d = y.position - at.position;
        float g = dot(at.shading_normal, w) * -dot(y.shading_normal, w) / dot(d, d);
        if (!(ts_max3(albedo) > 0.0f) || !(g > b)) break;
        TsRay segment = ray;
        segment.tmax = hit.t;
        beta = beta * albedo * ts_shadow_transmittance(&med, segment) * (1.0f - b / g);
        float3 e_y;
        if (!(ts_ic_interpolate(sv->ic_nodes, sv->ic_refs, sv->ic_records, y.position, y.shading_normal,
                                f->ic_error_bound, &e_y) > 0.0f))
            e_y = e_at; /* no record covers y (the camera does not see it): the nearest E known */
        sum += beta * (ts_ic_residual_direct(sv, tracer, &med, &y, u3) + e_y);
        at = y;
        e_at = e_y;
    }
    return sum;
}

TS_NAMESPACE_END

#endif /* TS_IC_RESIDUAL_H */
