/* The camera path's specular part, shared by `direct` (shared/direct.h) and the igi
 * family's view (shared/igi.h): mirrors and dielectrics followed to the first diffuse
 * surface (docs/igi.md §7). Uses the tracer interface documented in shared/direct.h. */
#ifndef TS_CAMERA_PATH_H
#define TS_CAMERA_PATH_H
#include "shared/bsdf.h"
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout_scene.h"
#include "shared/material.h"
#include "shared/rng.h"

TS_NAMESPACE_BEGIN

/* Follows mirror and dielectric bounces from the camera (at most 5) to the first
 * diffuse surface, `hit` being the closest hit of *ray (already traced); *throughput
 * collects their reflectances and *distance the path's length (scene units). Dielectrics
 * pick reflection or refraction by Fresnel with one number of `rng`; mirrors draw none,
 * so a path of diffuse and mirror surfaces leaves the stream as it was. Returns the hit
 * (TS_NO_HIT if the path escapes); *ray is the path's last segment. */
TS_INLINE TsHit ts_find_diffuse(const TsSceneView* sv, const TsTracer* tracer, TsRay* ray, TsHit hit,
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

TS_NAMESPACE_END
#endif /* TS_CAMERA_PATH_H */
