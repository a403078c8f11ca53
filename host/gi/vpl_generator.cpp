#include "gi/vpl_generator.h"

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

// A light path in flight.
struct PathState {
    uint64_t index;  // Halton point of the path
    uint32_t set;
    float3 alpha;    // throughput weight α
    ts::TsRay ray;
};

void push_ray(std::vector<float>& rays, const ts::TsRay& r) {
    rays.insert(rays.end(), {r.org.x, r.org.y, r.org.z, r.tmin, r.dir.x, r.dir.y, r.dir.z, r.tmax});
}

ts::TsRay ray_from(float3 org, float3 dir) { return ts::TsRay{org, dir, 0.0f, ts::TS_INF}; }

// Starts path `index` at a light: α = Le·π / p_A (cosine emission cancels the cosine).
bool start_path(const ts::TsSceneView& sv, const ScrambledHalton& h, uint64_t index, PathState& p) {
    auto u = [&](int d) { return static_cast<float>(h.sample(index, d)); };
    ts::TsLightSample ls = ts::ts_sample_light(sv.lights, sv.light_cdf, sv.light_count, u(0), u(1), u(2));
    if (!(ls.pdf_area > 0.0f)) return false;
    float3 d = ts::ts_from_local(ls.normal, ts::ts_sample_cosine_hemisphere(u(3), u(4)));
    p.alpha = ls.radiance * (TS_PI / ls.pdf_area);
    p.ray = ray_from(ts::ts_offset_ray_origin(ls.position, ls.normal, ls.pos_scale), d);
    return true;
}

void store_vpl(std::vector<std::vector<float>>& per_set, const PathState& p, const ts::TsSurface& s,
               float3 albedo, float inv_paths) {
    float3 c = p.alpha * albedo * (TS_INV_PI * inv_paths);
    uint32_t path = static_cast<uint32_t>(p.index);
    float v[TS_VPL_FLOATS] = {s.position.x,       s.position.y,       s.position.z,       s.shading_normal.x,
                              s.shading_normal.y, s.shading_normal.z, c.x,                c.y,
                              c.z,                static_cast<float>(p.set), 0.0f,     s.pos_scale};
    std::memcpy(&v[10], &path, 4);
    per_set[p.set].insert(per_set[p.set].end(), v, v + TS_VPL_FLOATS);
}

// Scatters the path at surface s; returns false when it ends. `dim` is the first Halton
// dimension of this bounce.
bool continue_path(const ts::TsSceneView& sv, const ScrambledHalton& h, int dim, const ts::TsSurface& s,
                   PathState& p, std::vector<std::vector<float>>& per_set, float inv_paths) {
    auto u = [&](int d) { return static_cast<float>(h.sample(p.index, dim + d)); };
    const float* M = sv.materials + TS_MATERIAL_FLOATS * s.material;
    uint32_t kind = ts::as_uint(M[7]);
    if (kind == TS_MAT_MIRROR) {
        p.alpha = p.alpha * ts::ts_f3_load(M + 8);
        p.ray = ray_from(ts::ts_offset_ray_origin(s.origin, s.geo_normal, s.pos_scale),
                         ts::ts_reflect(p.ray.dir, s.shading_normal));
        return true;
    }
    if (kind == TS_MAT_DIELECTRIC) {
        int transmitted;
        float3 d = ts::ts_sample_dielectric(p.ray.dir, s.geo_normal, s.front_face, M[11], u(2), &transmitted);
        p.ray = ray_from(ts::ts_offset_ray_origin(s.origin, transmitted ? -s.geo_normal : s.geo_normal, s.pos_scale), d);
        return true;
    }
    float3 albedo = ts::ts_material_albedo(&sv, &s);
    if (!(ts::ts_max3(albedo) > 0.0f)) return false;
    store_vpl(per_set, p, s, albedo, inv_paths);
    float q = std::min(1.0f, ts::ts_luminance(albedo));
    if (!(u(2) < q)) return false;
    float3 d = ts::ts_from_local(s.shading_normal, ts::ts_sample_cosine_hemisphere(u(0), u(1)));
    if (ts::dot(d, s.geo_normal) <= 0.0f) return false;
    p.alpha = p.alpha * albedo / q;
    p.ray = ray_from(ts::ts_offset_ray_origin(s.origin, s.geo_normal, s.pos_scale), d);
    return true;
}

}  // namespace

VplList generate_vpls(Backend& backend, const SceneBuffers& scene, const VplSettings& settings) {
    VplList out;
    out.set_start.assign(settings.sets + 1, 0u);
    const ts::TsSceneView sv = make_scene_view(scene);
    const ts::TsMedium med = ts::ts_medium_load(scene.medium.data());
    const ScrambledHalton halton(5 + 3 * static_cast<int>(settings.max_bounces), settings.halton_seed);
    const float inv_paths = 1.0f / static_cast<float>(settings.paths_per_set);
    std::vector<std::vector<float>> per_set(settings.sets);

    std::vector<PathState> paths;
    if (scene.light_count > 0) {
        const uint64_t first = uint64_t(settings.frame) * settings.sets * settings.paths_per_set;
        for (uint32_t k = 0; k < settings.sets; ++k)
            for (uint32_t j = 0; j < settings.paths_per_set; ++j) {
                PathState p{first + uint64_t(k) * settings.paths_per_set + j, k, {}, {}};
                if (start_path(sv, halton, p.index, p)) paths.push_back(p);
            }
    }
    std::vector<float> rays, hits;
    for (uint32_t bounce = 0; bounce < settings.max_bounces && !paths.empty(); ++bounce) {
        rays.clear();
        for (const PathState& p : paths) push_ray(rays, p.ray);
        backend.trace_closest(rays, hits);
        out.rays += paths.size();
        std::vector<PathState> alive;
        for (size_t i = 0; i < paths.size(); ++i) {
            PathState p = paths[i];
            ts::TsHit hit{hits[4 * i], hits[4 * i + 1], hits[4 * i + 2], 0u};
            std::memcpy(&hit.prim, &hits[4 * i + 3], 4);
            if (hit.prim == TS_NO_HIT) continue;
            p.alpha = p.alpha * ts::ts_medium_transmittance(&med, p.ray.org, p.ray.dir, 0.0f, hit.t);
            ts::TsSurface s = ts::ts_surface_at(&sv, p.ray, hit);
            if (continue_path(sv, halton, 5 + 3 * static_cast<int>(bounce), s, p, per_set, inv_paths))
                alive.push_back(p);
        }
        paths.swap(alive);
    }
    for (uint32_t k = 0; k < settings.sets; ++k) {
        out.set_start[k + 1] = out.set_start[k] + static_cast<uint32_t>(per_set[k].size() / TS_VPL_FLOATS);
        out.vpls.insert(out.vpls.end(), per_set[k].begin(), per_set[k].end());
    }
    if (out.vpls.empty()) out.vpls.assign(TS_VPL_FLOATS, 0.0f);  // device buffers cannot be empty
    return out;
}

}  // namespace tessera
