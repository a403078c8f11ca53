/* Sample warping shared by every method: points on triangles and area lights.
 * pdfs are with respect to area (scene units^-2) unless stated. */
#ifndef TS_SAMPLING_H
#define TS_SAMPLING_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout_scene.h"

TS_NAMESPACE_BEGIN

/* Interleaved sampling (Keller & Heidrich 2001): the sample set k = (x mod n) + n (y mod n)
 * of pixel (x, y) for interleave tile edge n (n² sets; every n×n window holds each once).
 * Here, tracer-free, so that the host's AIS schedule uses the kernels' own mapping. */
TS_INLINE uint ts_igi_set(uint px, uint py, uint n) { return (px % n) + n * (py % n); }

/* Uniform point on the triangle p0 + b1 e1 + b2 e2 from (u, v) in [0,1)^2 via the
 * square-root warp (Shirley 1990); (u, v) stratification carries over to area. */
TS_INLINE float2 ts_triangle_barycentrics(float u, float v) {
    float su = sqrt(u);
    return make_float2(su * (1.0f - v), su * v);
}

/* One sampled point on an area light. */
typedef struct TsLightSample {
    float3 position;   /* point on the light, world space */
    float3 normal;     /* unit geometric normal of the emitting (front) face */
    float3 radiance;   /* Le, W/(sr·m²) */
    float pdf_area;    /* selection probability / light area, scene units^-2 */
    float pos_scale;   /* largest absolute vertex coordinate of the light triangle */
    uint light;        /* index of the light triangle (sv->lights) */
    float u, v;        /* the point's coordinates on the light's parameter square */
    /* 0 for a point sampled uniformly by area; for one ts_light_sample_from sampled
     * uniformly in solid angle, the inverse of its pdf per steradian: Ω / selection
     * probability (sr). */
    float inv_pdf_solid_angle;
} TsLightSample;

/* The light `u_select` picks by inverting light_cdf (binary search). Requires
 * light_count > 0. */
TS_INLINE uint ts_select_light(TS_GLOBAL const float* light_cdf, uint light_count, float u_select) {
    uint lo = 0u, hi = light_count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) >> 1;
        if (u_select < light_cdf[mid]) hi = mid; else lo = mid + 1u;
    }
    return lo;
}

/* Picks a light in proportion to power (ts_select_light with `u_select`), then a
 * uniform point on it from (u, v). Requires light_count > 0. */
TS_INLINE TsLightSample ts_sample_light(TS_GLOBAL const float* lights,
                                        TS_GLOBAL const float* light_cdf,
                                        uint light_count, float u_select, float u, float v) {
    uint lo = ts_select_light(light_cdf, light_count, u_select);
    float p_select = light_cdf[lo] - (lo > 0u ? light_cdf[lo - 1u] : 0.0f);
    TS_GLOBAL const float* L = lights + lo * TS_LIGHT_FLOATS;
    float3 p0 = ts_f3_load(L + TS_LIGHT_P0), e1 = ts_f3_load(L + TS_LIGHT_E1), e2 = ts_f3_load(L + TS_LIGHT_E2);
    float2 b = ts_triangle_barycentrics(u, v);
    TsLightSample s;
    s.position = p0 + e1 * b.x + e2 * b.y;
    s.pos_scale = fmax(ts_max_abs3(p0), fmax(ts_max_abs3(p0 + e1), ts_max_abs3(p0 + e2)));
    s.normal = normalize(cross(e1, e2));
    s.radiance = ts_f3_load(L + TS_LIGHT_RADIANCE);
    s.pdf_area = p_select / L[TS_LIGHT_AREA];
    s.light = lo;
    s.u = u;
    s.v = v;
    s.inv_pdf_solid_angle = 0.0f;
    return s;
}

#define TS_PI 3.14159265358979323846f
#define TS_INV_PI 0.318309886183790671538f

TS_INLINE float ts_max3(float3 v) { return fmax(v.x, fmax(v.y, v.z)); }

/* Power heuristic a² / (a² + b²) written as a ratio of the smaller pdf to the larger, so
 * that pdfs beyond 1e19 (a light sampled from a point far away, d² in the pdf) cannot
 * overflow a² into inf/inf. */
/* (Veach 1997, §9.2.) */
TS_INLINE float ts_power_heuristic(float a, float b) {
    if (!(a > 0.0f)) return 0.0f;
    if (a >= b) {
        float r = b / a;
        return 1.0f / (1.0f + r * r);
    }
    float r = a / b;
    return r * r / (1.0f + r * r);
}

/* Rec. 709 luminance: the power measure lights are picked by (host/device/scene_buffers.cpp),
 * the light paths' roulette (shared/light_path.h) and AIS's indirect guidance
 * (host/integrators/igi_frame.cpp); the one copy of the weights. */
TS_INLINE float ts_luminance(float3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/* Area pdf (scene units^-2) with which ts_sample_light picks a point on an emitter whose
 * material has selection luminance `selection` (materials TS_MAT_SELECTION, layout_scene.h):
 * power-proportional selection times uniform area sampling gives
 * (selection · area / total power) / area = selection / total power. */
TS_INLINE float ts_light_pdf_area(float selection, float light_power) {
    return light_power > 0.0f ? selection / light_power : 0.0f;
}

/* An orthonormal basis (t, b, n) around unit n, without branches on the sign of n.z
 * beyond one copysign (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017). */
TS_INLINE void ts_basis(float3 n, float3* t, float3* b) {
    float sign = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    *t = make_float3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = make_float3(c, sign + n.y * n.y * a, -n.y);
}

TS_INLINE float3 ts_from_local(float3 n, float3 v) {
    float3 t, b;
    ts_basis(n, &t, &b);
    return t * v.x + b * v.y + n * v.z;
}

/* Cosine-weighted direction on the hemisphere around the local +z axis; pdf cosθ/π
 * (per steradian). Malley's method: a uniform disk point lifted to the hemisphere. */
TS_INLINE float3 ts_sample_cosine_hemisphere(float u, float v) {
    float r = sqrt(u), phi = 2.0f * TS_PI * v;
    return make_float3(r * cos(phi), r * sin(phi), sqrt(fmax(0.0f, 1.0f - u)));
}

/* Uniform direction on the hemisphere around the local +z axis; pdf 1/(2π) per
 * steradian. cosθ = 1 − u is uniform (Archimedes), in (0, 1] for u in [0, 1). */
TS_INLINE float3 ts_sample_uniform_hemisphere(float u, float v) {
    float z = 1.0f - u, r = sqrt(fmax(0.0f, 1.0f - z * z)), phi = 2.0f * TS_PI * v;
    return make_float3(r * cos(phi), r * sin(phi), z);
}

/* Henyey–Greenstein phase function (per steradian) for the angle θ between the
 * propagation directions before and after scattering: cosθ = dot(d_in, d_out).
 * g > 0 scatters forward. (Henyey & Greenstein 1941; pbrt-v4 §11.3.1.) */
TS_INLINE float ts_hg_phase(float cos_theta, float g) {
    float d = 1.0f + g * g - 2.0f * g * cos_theta;
    return (1.0f - g * g) / (4.0f * TS_PI * d * sqrt(d));
}

/* Samples a new propagation direction for light travelling along unit `d_in`, with
 * density ts_hg_phase(dot(d_in, d_out), g). Inverts the HG cosine CDF; near g = 0 the
 * closed form is ill-conditioned, so |g| < 1e-3 uses the isotropic cosine. */
TS_INLINE float3 ts_sample_hg(float3 d_in, float g, float u, float v) {
    float cos_t;
    if (fabs(g) < 1e-3f) {
        cos_t = 1.0f - 2.0f * u;
    } else {
        float sq = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
        cos_t = (1.0f + g * g - sq * sq) / (2.0f * g);
    }
    cos_t = clamp(cos_t, -1.0f, 1.0f);
    float sin_t = sqrt(fmax(0.0f, 1.0f - cos_t * cos_t)), phi = 2.0f * TS_PI * v;
    return ts_from_local(d_in, make_float3(sin_t * cos(phi), sin_t * sin(phi), cos_t));
}

TS_NAMESPACE_END
#endif /* TS_SAMPLING_H */
