/* The `direct` method: emission plus direct illumination from area lights (the SS
 * component of the seed thesis), estimated at the first diffuse surface of the camera
 * path (mirrors and dielectrics followed as igi follows them, shared/camera_path.h) with
 * `shadow_samples` stratified light samples per pass.
 *
 * Estimator (area form of the rendering equation, Lambertian BRDF albedo/π):
 *   L(x) = Le(x) + albedo/π · (1/m) Σ_j Le(y_j) V(x,y_j) cosθx cosθy / (|x − y_j|² p(y_j))
 * with p(y) = P(light) / area(light); for x near the light, the point is drawn in the
 * light's solid angle instead and the term is Le V cosθx Ω / P(light)
 * (ts_light_sample_from, shared/spherical_triangle.h). The m samples are a Hammersley set
 * ((j+½)/m, φ2(j)) on the light's square parameter domain and φ3(j) for light
 * selection, Cranley–Patterson rotated per pixel and pass, so they are stratified
 * within a pixel and independent between pixels and passes.
 *
 * The including backend must first define the type TsTracer and
 *   TsHit ts_trace_closest(const TsTracer* tracer, TsRay ray);
 *   int   ts_trace_occluded(const TsTracer* tracer, TsRay ray);   (1 = blocked)
 * which is the only place the backends differ.
 */
#ifndef TS_DIRECT_H
#define TS_DIRECT_H
#include "shared/camera_path.h"
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/frame.h"
#include "shared/layout_pass.h"
#include "shared/layout_rays.h"
#include "shared/material.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/spherical_triangle.h"

TS_NAMESPACE_BEGIN

/* Unoccluded contribution of one light sample at surface s, and the shadow ray that
 * decides its visibility: Le cosθx cosθy / (d² p_area) for a point sampled by area, and
 * Le cosθx / p_solid_angle for one ts_light_sample_from drew in solid angle. Returns 0
 * when the light faces away; the shadow ray is set in either case (use it only for a
 * nonzero contribution). Branch-free for the reason ts_vpl_geometry (shared/vpl.h) is:
 * the Embree packets run it over 16 pixels in SIMD. */
TS_INLINE float3 ts_light_contribution(const TsSurface* s, TsLightSample ls, TsRay* shadow) {
    float3 d = ls.position - s->position;
    float dist2 = dot(d, d);
    float3 wi = d / sqrt(dist2);
    float cos_x = dot(s->shading_normal, wi);
    float cos_y = -dot(ls.normal, wi);
    int faces = (cos_x > 0.0f) & (cos_y > 0.0f) & (dot(s->geo_normal, wi) > 0.0f);
    *shadow = ts_shadow_ray(ts_offset_ray_origin(s->origin, s->geo_normal, s->pos_scale), ls.position, ls.normal,
                            ls.pos_scale);
    float w_area = cos_x * cos_y / (dist2 * ls.pdf_area), w_solid_angle = cos_x * ls.inv_pdf_solid_angle;
    float w = faces ? (ls.inv_pdf_solid_angle > 0.0f ? w_solid_angle : w_area) : 0.0f;
    return ls.radiance * w;
}

/* ts_light_contribution of light sample ls as seen from s (ts_light_sample_from: drawn
 * in solid angle where s is near the light). */
TS_INLINE float3 ts_light_contribution_from(TS_GLOBAL const float* lights, const TsSurface* s, TsLightSample ls,
                                           TsRay* shadow) {
    return ts_light_contribution(s, ts_light_sample_from(lights, ls, s->position), shadow);
}

/* Direct irradiance / π (the quantity albedo multiplies) at s from m light samples. */
TS_INLINE float3 ts_direct_irradiance(const TsSceneView* sv, const TsTracer* tracer,
                                      const TsSurface* s, uint m, TsRng* rng) {
    float3 sum = make_float3(0.0f, 0.0f, 0.0f);
    float r0 = ts_rng_next(rng), r1 = ts_rng_next(rng), r2 = ts_rng_next(rng);
    for (uint j = 0u; j < m; ++j) {
        float us = ts_rotate01(ts_radical_inverse3(j), r0);
        float u = ts_rotate01(((float)j + 0.5f) / (float)m, r1);
        float v = ts_rotate01(ts_radical_inverse2(j), r2);
        TsLightSample ls = ts_sample_light(sv->lights, sv->light_cdf, sv->light_count, us, u, v);
        TsRay shadow;
        float3 c = ts_light_contribution_from(sv->lights, s, ls, &shadow);
        if (c.x + c.y + c.z > 0.0f && !ts_trace_occluded(tracer, shadow)) sum += c;
    }
    return sum * (TS_INV_PI / (float)m);
}

/* One pass (1 spp) of the direct method for pixel (px, py); writes TS_PASS_FLOATS
 * values to out (layout in shared/layout_pass.h). */
TS_INLINE void ts_direct_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                               uint px, uint py, float* out) {
    TsRng rng = ts_rng_seed(f->seed, py * f->width + px, f->pass);
    float jx = ts_rng_next(&rng), jy = ts_rng_next(&rng);
    TsRay ray = ts_camera_ray(f, px, py, jx, jy);
    float3 throughput;
    float distance;
    TsHit hit = ts_find_diffuse(sv, tracer, &ray, ts_trace_closest(tracer, ray), &throughput, &distance, &rng);
    for (int i = 0; i < TS_PASS_DEPTH; ++i) out[i] = 0.0f;
    out[TS_PASS_DEPTH] = TS_INF;
    if (hit.prim == TS_NO_HIT) return;
    TsSurface s = ts_surface_at(sv, ray, hit);
    /* The cone spreads over the whole path, as igi's (ts_igi_view_from). */
    if (f->pixel_cone > 0.0f) ts_surface_cone(sv, &s, hit.prim, ray.dir, distance * ts_pass_cone(f));
    float3 albedo = ts_material_albedo(sv, &s);
    float3 L = ts_material_emission(sv, &s);
    if (albedo.x + albedo.y + albedo.z > 0.0f && sv->light_count > 0u)
        L += albedo * ts_direct_irradiance(sv, tracer, &s, f->shadow_samples, &rng);
    ts_f3_store(out + TS_PASS_RADIANCE, throughput * L);
    ts_f3_store(out + TS_PASS_ALBEDO, albedo);
    ts_f3_store(out + TS_PASS_NORMAL, s.shading_normal);
    out[TS_PASS_DEPTH] = distance;
}

TS_NAMESPACE_END
#endif /* TS_DIRECT_H */
