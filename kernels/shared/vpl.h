/* The VPL connection of instant radiosity (Keller 1997), shared by the igi kernels
 * (shared/igi.h) and the instant cache's host-side gathering (host/gi/instant_cache.cpp),
 * so both weigh a VPL identically. VPL layout: layout.h TS_VPL_FLOATS. */
#ifndef TS_VPL_H
#define TS_VPL_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout.h"

TS_NAMESPACE_BEGIN

/* One VPL's clamped geometry term at surface s, and the shadow ray that decides its
 * visibility; 0 when either side faces away. G = cosθx cosθv / d² is clamped to b: the
 * contribution C·G' of any VPL is at most C·b. */
TS_INLINE float ts_vpl_geometry(const TsSurface* s, TS_GLOBAL const float* vpl, float b, TsRay* shadow) {
    float3 x = s->position, n = s->shading_normal, ng = s->geo_normal;
    float3 y = ts_f3_load(vpl + TS_VPL_POSITION), nv = ts_f3_load(vpl + TS_VPL_NORMAL);
    float3 d = y - x;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0f)) return 0.0f;
    float3 w = d / sqrt(dist2);
    float cos_x = dot(n, w), cos_v = -dot(nv, w);
    if (cos_x <= 0.0f || cos_v <= 0.0f || dot(ng, w) <= 0.0f) return 0.0f;
    shadow->org = ts_offset_ray_origin(s->origin, ng, s->pos_scale);
    shadow->dir = ts_offset_ray_origin(y, nv, vpl[TS_VPL_POS_SCALE]) - shadow->org;
    shadow->tmin = 0.0f;
    shadow->tmax = 0.99999f;
    return fmin(cos_x * cos_v / dist2, b);
}

TS_NAMESPACE_END

#endif /* TS_VPL_H */
