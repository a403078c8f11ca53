#include "gi/light_paths.h"

#include <algorithm>
#include <cstring>

#include "gi/halton.h"
#include "kernels/shared/bsdf.h"
#include "kernels/shared/material.h"
#include "kernels/shared/medium.h"
#include "kernels/shared/sampling.h"
#include "render/scene_view.h"

namespace tessera {
namespace {

using ts::float3;

// A path in flight: its throughput weight α and the ray it traces next.
struct InFlight {
    LightPath* path;
    float3 alpha;
    ts::TsRay ray;
};

ts::TsRay ray_from(float3 org, float3 dir) { return ts::TsRay{org, dir, 0.0f, ts::TS_INF}; }

// Starts a path at a light: α = Le·π / p_A (cosine emission cancels the cosine).
bool start_path(const ts::TsSceneView& sv, const ScrambledHalton& h, InFlight& p) {
    auto u = [&](int d) { return static_cast<float>(h.sample(p.path->index, d)); };
    p.path->light = ts::ts_select_light(sv.light_cdf, sv.light_count, u(0));
    ts::TsLightSample ls = ts::ts_sample_light(sv.lights, sv.light_cdf, sv.light_count, u(0), u(1), u(2));
    if (!(ls.pdf_area > 0.0f)) return false;
    float3 d = ts::ts_from_local(ls.normal, ts::ts_sample_cosine_hemisphere(u(3), u(4)));
    p.alpha = ls.radiance * (TS_PI / ls.pdf_area);
    p.ray = ray_from(ts::ts_offset_ray_origin(ls.position, ls.normal, ls.pos_scale), d);
    return true;
}

void store_vpl(LightPath& path, float3 alpha, const ts::TsSurface& s, float3 albedo, float inv_paths) {
    float3 c = alpha * albedo * (TS_INV_PI * inv_paths);
    const auto index = static_cast<uint32_t>(path.index);
    float v[TS_VPL_FLOATS];
    ts::ts_f3_store(v + TS_VPL_POSITION, s.position);
    ts::ts_f3_store(v + TS_VPL_NORMAL, s.shading_normal);
    ts::ts_f3_store(v + TS_VPL_FLUX, c);
    v[TS_VPL_SET] = static_cast<float>(path.set);
    std::memcpy(&v[TS_VPL_PATH], &index, 4);
    v[TS_VPL_POS_SCALE] = s.pos_scale;
    path.vpls.insert(path.vpls.end(), v, v + TS_VPL_FLOATS);
}

// Scatters the path at surface s; returns false when it ends. `dim` is the first Halton
// dimension of this bounce.
bool continue_path(const ts::TsSceneView& sv, const ScrambledHalton& h, int dim, const ts::TsSurface& s,
                   InFlight& p, float inv_paths) {
    auto u = [&](int d) { return static_cast<float>(h.sample(p.path->index, dim + d)); };
    const float* M = sv.materials + TS_MATERIAL_FLOATS * s.material;
    uint32_t kind = ts::as_uint(M[TS_MAT_KIND]);
    if (kind == TS_MAT_MIRROR) {
        p.alpha = p.alpha * ts::ts_f3_load(M + TS_MAT_SPECULAR);
        p.ray = ray_from(ts::ts_offset_ray_origin(s.origin, s.geo_normal, s.pos_scale),
                         ts::ts_reflect(p.ray.dir, s.shading_normal));
        return true;
    }
    if (kind == TS_MAT_DIELECTRIC) {
        int transmitted;
        float3 d = ts::ts_sample_dielectric(p.ray.dir, s.geo_normal, s.front_face, M[TS_MAT_IOR], u(2), &transmitted);
        p.ray = ray_from(ts::ts_offset_ray_origin(s.origin, transmitted ? -s.geo_normal : s.geo_normal, s.pos_scale), d);
        return true;
    }
    float3 albedo = ts::ts_material_albedo(&sv, &s);
    if (!(ts::ts_max3(albedo) > 0.0f)) return false;
    store_vpl(*p.path, p.alpha, s, albedo, inv_paths);
    float q = std::min(1.0f, ts::ts_luminance(albedo));
    if (!(u(2) < q)) return false;
    float3 d = ts::ts_from_local(s.shading_normal, ts::ts_sample_cosine_hemisphere(u(0), u(1)));
    if (ts::dot(d, s.geo_normal) <= 0.0f) return false;
    p.alpha = p.alpha * albedo / q;
    p.ray = ray_from(ts::ts_offset_ray_origin(s.origin, s.geo_normal, s.pos_scale), d);
    return true;
}

PathSegment segment_of(const ts::TsRay& r, const ts::TsHit& hit) {
    return PathSegment{{r.org.x, r.org.y, r.org.z}, {r.dir.x, r.dir.y, r.dir.z}, hit.t, hit.prim};
}

}  // namespace

uint64_t trace_light_paths(Backend& backend, const SceneBuffers& scene, const LightPathSettings& settings,
                           std::vector<LightPath>& paths) {
    const ts::TsSceneView sv = make_scene_view(scene);
    const ts::TsMedium med = ts::ts_medium_load(scene.medium.data());
    const ScrambledHalton halton(5 + 3 * static_cast<int>(settings.max_bounces), settings.halton_seed);
    std::vector<InFlight> live;
    for (LightPath& p : paths) {
        p.vpls.clear();
        p.segments.clear();
        p.light = 0;
        InFlight f{&p, {}, {}};
        if (scene.light_count > 0 && start_path(sv, halton, f)) live.push_back(f);
    }
    uint64_t traced = 0;
    std::vector<float> rays, hits;
    for (uint32_t bounce = 0; bounce < settings.max_bounces && !live.empty(); ++bounce) {
        rays.assign(TS_RAY_FLOATS * live.size(), 0.0f);
        for (size_t i = 0; i < live.size(); ++i) {
            float* r = &rays[TS_RAY_FLOATS * i];
            ts::ts_f3_store(r + TS_RAY_ORG, live[i].ray.org);
            r[TS_RAY_TMIN] = live[i].ray.tmin;
            ts::ts_f3_store(r + TS_RAY_DIR, live[i].ray.dir);
            r[TS_RAY_TMAX] = live[i].ray.tmax;
        }
        backend.trace_closest(rays, hits);
        traced += live.size();
        std::vector<InFlight> alive;
        for (size_t i = 0; i < live.size(); ++i) {
            InFlight p = live[i];
            const float* h = &hits[TS_HIT_FLOATS * i];
            ts::TsHit hit{h[TS_HIT_T], h[TS_HIT_U], h[TS_HIT_V], 0u};
            std::memcpy(&hit.prim, &h[TS_HIT_PRIM], 4);
            p.path->segments.push_back(segment_of(p.ray, hit));
            if (hit.prim == TS_NO_HIT) continue;
            p.alpha = p.alpha * ts::ts_medium_transmittance(&med, p.ray.org, p.ray.dir, 0.0f, hit.t);
            ts::TsSurface s = ts::ts_surface_at(&sv, p.ray, hit);
            if (continue_path(sv, halton, 5 + 3 * static_cast<int>(bounce), s, p, settings.inv_paths))
                alive.push_back(p);
        }
        live.swap(alive);
    }
    return traced;
}

}  // namespace tessera
