/* Sample warping shared by every method: points on triangles and area lights.
 * pdfs are with respect to area (scene units^-2) unless stated. */
#ifndef TS_SAMPLING_H
#define TS_SAMPLING_H
#include "shared/compat.h"
#include "shared/layout.h"

TS_NAMESPACE_BEGIN

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
} TsLightSample;

/* Picks a light in proportion to power by inverting light_cdf with `u_select`
 * (binary search), then a uniform point on it from (u, v). Requires light_count > 0. */
TS_INLINE TsLightSample ts_sample_light(TS_GLOBAL const float* lights,
                                        TS_GLOBAL const float* light_cdf,
                                        uint light_count, float u_select, float u, float v) {
    uint lo = 0u, hi = light_count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) >> 1;
        if (u_select < light_cdf[mid]) hi = mid; else lo = mid + 1u;
    }
    float p_select = light_cdf[lo] - (lo > 0u ? light_cdf[lo - 1u] : 0.0f);
    TS_GLOBAL const float* L = lights + lo * TS_LIGHT_FLOATS;
    float3 p0 = ts_f3_load(L + 0), e1 = ts_f3_load(L + 3), e2 = ts_f3_load(L + 6);
    float2 b = ts_triangle_barycentrics(u, v);
    TsLightSample s;
    s.position = p0 + e1 * b.x + e2 * b.y;
    s.normal = normalize(cross(e1, e2));
    s.radiance = ts_f3_load(L + 9);
    s.pdf_area = p_select / L[12];
    return s;
}

TS_NAMESPACE_END
#endif /* TS_SAMPLING_H */
