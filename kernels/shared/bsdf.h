/* Specular scattering: perfect mirror (MTL illum 3, 5) and smooth dielectric
 * (illum 7, index of refraction Ni), for every path that meets one: the path tracer,
 * igi's camera paths and the light paths that leave VPLs (ts_specular_bounce). */
#ifndef TS_BSDF_H
#define TS_BSDF_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout_scene.h"

TS_NAMESPACE_BEGIN

TS_INLINE float3 ts_reflect(float3 d, float3 n) { return d - n * (2.0f * dot(d, n)); }

/* Unpolarised Fresnel reflectance of a smooth dielectric interface, for light arriving
 * at cosθi > 0 from the side of relative index eta = n_transmitted / n_incident
 * (pbrt-v4 §9.3.6, FrDielectric). Returns 1 under total internal reflection. */
TS_INLINE float ts_fresnel_dielectric(float cos_i, float eta, float* cos_t) {
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) {
        *cos_t = 0.0f;
        return 1.0f;
    }
    float ct = sqrt(1.0f - sin2_t);
    float r_par = (eta * cos_i - ct) / (eta * cos_i + ct);
    float r_perp = (cos_i - eta * ct) / (cos_i + eta * ct);
    *cos_t = ct;
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

/* Samples reflection (probability F) or refraction (1 - F) through a smooth dielectric.
 * `d` is the unit incoming ray direction, `n` the unit geometric normal facing the ray,
 * `front` whether the ray arrives from outside (the side cross(e1, e2) points to).
 * Returns the new direction; *transmitted tells which side to continue on. The
 * throughput factor is 1 either way (F and 1 - F cancel their sampling probabilities).
 * The 1/eta² compression of radiance across the interface is omitted: it cancels on a
 * path that enters and leaves a dielectric, and only an emitter inside one would differ. */
TS_INLINE float3 ts_sample_dielectric(float3 d, float3 n, int front, float ior, float u, int* transmitted) {
    float eta = front ? ior : 1.0f / ior;
    float cos_i = -dot(d, n);
    float cos_t;
    float F = ts_fresnel_dielectric(cos_i, eta, &cos_t);
    if (u < F) {
        *transmitted = 0;
        return ts_reflect(d, n);
    }
    *transmitted = 1;
    return normalize(d / eta + n * (cos_i / eta - cos_t));
}

/* 1 for the specular material kinds ts_specular_bounce handles. */
TS_INLINE int ts_is_specular(uint kind) { return kind == TS_MAT_MIRROR || kind == TS_MAT_DIELECTRIC; }

/* Continues *ray at the specular surface s of material M (TS_MATERIAL_FLOATS, layout_scene.h):
 * kind TS_MAT_MIRROR reflects about the shading normal and multiplies *throughput by Ks;
 * any other kind is the smooth dielectric, reflecting or refracting by Fresnel with `u`
 * in [0, 1) (throughput factor 1, ts_sample_dielectric). The new ray leaves from s's
 * origin offset to the side it goes, over t in (0, inf). Returns 0 when a mirror
 * reflection about the shading normal points into the geometric surface (the ray is
 * updated anyway): the path tracer ends such paths, igi's camera paths and the light
 * paths follow them. Callers draw `u` only for a dielectric, so a mirror consumes no
 * random number. */
TS_INLINE int ts_specular_bounce(TS_GLOBAL const float* M, uint kind, const TsSurface* s, float u, TsRay* ray,
                                 float3* throughput) {
    float3 ng = s->geo_normal;
    int leaves = 1;
    if (kind == TS_MAT_MIRROR) {
        *throughput = *throughput * ts_f3_load(M + TS_MAT_SPECULAR);
        ray->dir = ts_reflect(ray->dir, s->shading_normal);
        leaves = !(dot(ray->dir, ng) <= 0.0f);
        ray->org = ts_offset_ray_origin(s->origin, ng, s->pos_scale);
    } else {
        int transmitted;
        ray->dir = ts_sample_dielectric(ray->dir, ng, s->front_face, M[TS_MAT_IOR], u, &transmitted);
        ray->org = ts_offset_ray_origin(s->origin, transmitted ? -ng : ng, s->pos_scale);
    }
    ray->tmin = 0.0f;
    ray->tmax = TS_INF;
    return leaves;
}

TS_NAMESPACE_END
#endif /* TS_BSDF_H */
