/* Specular scattering: perfect mirror (MTL illum 3, 5) and smooth dielectric
 * (illum 7, index of refraction Ni), for the path tracer. */
#ifndef TS_BSDF_H
#define TS_BSDF_H
#include "shared/compat.h"

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

TS_NAMESPACE_END
#endif /* TS_BSDF_H */
