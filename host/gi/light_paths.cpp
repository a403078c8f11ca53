#include "gi/light_paths.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gi/halton.h"
#include "kernels/shared/light_path.h"
#include "kernels/shared/rng.h"
#include "device/ray_records.h"
#include "device/scene_view.h"

namespace tessera {
namespace {

using ts::float3;

// A path in flight: its throughput weight α and the ray it traces next.
struct InFlight {
    LightPath* path;
    float3 alpha;
    ts::TsRay ray;
};

// Starts a path at a light (shared/light_path.h); Halton dimensions 0-4.
bool start_path(const ts::TsSceneView& sv, const ScrambledHalton& h, InFlight& p) {
    auto u = [&](int d) { return static_cast<float>(h.sample(p.path->index, d)); };
    p.path->light = ts::ts_select_light(sv.light_cdf, sv.light_count, u(0));
    return ts::ts_light_path_start(&sv, u(0), u(1), u(2), u(3), u(4), &p.alpha, &p.ray) != 0;
}

// A VPL at `position`; `normal` is a surface VPL's normal or a medium VPL's propagation
// direction, `pos_scale` the surface's (-1 marks a medium VPL; layout_igi.h).
void store_vpl(LightPath& path, float3 position, float3 normal, float3 flux, float pos_scale) {
    const auto index = static_cast<uint32_t>(path.index);
    float v[TS_VPL_FLOATS];
    ts::ts_f3_store(v + TS_VPL_POSITION, position);
    ts::ts_f3_store(v + TS_VPL_NORMAL, normal);
    ts::ts_f3_store(v + TS_VPL_FLUX, flux * path.weight);
    v[TS_VPL_SET] = static_cast<float>(path.set);
    std::memcpy(&v[TS_VPL_PATH], &index, 4);
    v[TS_VPL_POS_SCALE] = pos_scale;
    path.vpls.insert(path.vpls.end(), v, v + TS_VPL_FLOATS);
}

// Multiple scattering: the free-flight decision on the segment that ends at `hit`
// (ts_light_path_medium). Its five numbers come from the counter-based generator keyed
// by path and bounce, not the Halton point, whose dimensions stay those of the surface
// vertices (images without a medium, or with single scattering, keep their VPLs).
// Returns what ts_light_path_medium returns; on an event records the segment up to it.
uint32_t medium_vertex(const ts::TsMedium& med, const LightPathSettings& settings, uint32_t scramble, uint32_t bounce,
                       const ts::TsHit& hit, InFlight& p) {
    ts::TsRng rng = ts::ts_rng_seed(scramble ^ 0x6d656469u, static_cast<uint32_t>(p.path->index), bounce);
    float u[5];
    for (float& x : u) x = ts::ts_rng_next(&rng);
    const ts::TsRay before = p.ray;
    float t_event;
    float3 pos, flux;
    const float hit_t = hit.prim == TS_NO_HIT ? ts::TS_INF : hit.t;
    const uint32_t what =
        ts::ts_light_path_medium(&med, hit_t, u, settings.inv_paths, &p.alpha, &p.ray, &t_event, &pos, &flux);
    if (what & TS_LIGHT_PATH_MEDIUM) {
        p.path->segments.push_back(PathSegment{{before.org.x, before.org.y, before.org.z},
                                               {before.dir.x, before.dir.y, before.dir.z}, t_event, TS_NO_HIT});
        store_vpl(*p.path, pos, ts::normalize(before.dir), flux, -1.0f);
    }
    return what;
}

// The ray light of the segment *ray up to the surface at hit_t (+inf: it escapes): its
// stretch inside the medium, of flux α · inv_paths times the path's weight (docs/igi.md
// §6). A stretch without end (a medium filling space) is cut at 20 mean free paths of the
// thinnest channel, past which it keeps e^-20 of its light.
void store_vrl(LightPath& path, const ts::TsMedium& med, const ts::TsRay& ray, float hit_t, float3 alpha,
               float inv_paths) {
    float t0 = 0.0f, t1 = hit_t;
    if (!ts::ts_medium_clip(&med, ray.org, ray.dir, &t0, &t1)) return;
    const float len = ts::length(ray.dir);
    float length = (t1 - t0) * len;
    if (!std::isfinite(length)) {
        const float thinnest = std::min({med.sigma_t.x, med.sigma_t.y, med.sigma_t.z});
        if (!(thinnest > 0.0f)) return;
        length = 20.0f / thinnest;
    }
    if (!(length > 0.0f)) return;
    const auto index = static_cast<uint32_t>(path.index);
    float v[TS_VRL_FLOATS];
    ts::ts_f3_store(v + TS_VRL_START, ray.org + ray.dir * t0);
    ts::ts_f3_store(v + TS_VRL_DIR, ray.dir / len);
    ts::ts_f3_store(v + TS_VRL_FLUX, alpha * (inv_paths * path.weight));
    v[TS_VRL_SET] = static_cast<float>(path.set);
    std::memcpy(&v[TS_VRL_PATH], &index, 4);
    v[TS_VRL_LENGTH] = length;
    path.vrls.insert(path.vrls.end(), v, v + TS_VRL_FLOATS);
}

PathSegment segment_of(const ts::TsRay& r, const ts::TsHit& hit) {
    return PathSegment{{r.org.x, r.org.y, r.org.z}, {r.dir.x, r.dir.y, r.dir.z}, hit.t, hit.prim};
}

}  // namespace

uint32_t light_path_seed_mix(uint32_t seed) { return ts::ts_pcg_hash(seed) ^ ts::ts_pcg_hash(1u); }

uint64_t trace_light_paths(Backend& backend, const SceneBuffers& scene, const LightPathSettings& settings,
                           std::vector<LightPath>& paths) {
    const ts::TsSceneView sv = make_scene_view(scene);
    const ts::TsMedium med = ts::ts_medium_load(scene.medium.data());
    // The Halton digits and the medium events' generator share one scramble of the seed.
    const uint32_t scramble = settings.halton_seed ^ light_path_seed_mix(settings.seed);
    const ScrambledHalton halton(5 + 3 * static_cast<int>(settings.max_bounces), scramble);
    std::vector<InFlight> live;
    for (LightPath& p : paths) {
        p.vpls.clear();
        p.vrls.clear();
        p.segments.clear();
        p.light = 0;
        InFlight f{&p, {}, {}};
        if (scene.light_count > 0 && start_path(sv, halton, f)) live.push_back(f);
    }
    uint64_t traced = 0;
    std::vector<float> rays, hits;
    for (uint32_t bounce = 0; bounce < settings.max_bounces && !live.empty(); ++bounce) {
        rays.assign(TS_RAY_FLOATS * live.size(), 0.0f);
        for (size_t i = 0; i < live.size(); ++i) store_ray(live[i].ray, &rays[TS_RAY_FLOATS * i]);
        backend.trace_closest(rays, hits);
        traced += live.size();
        std::vector<InFlight> alive;
        for (size_t i = 0; i < live.size(); ++i) {
            InFlight p = live[i];
            const ts::TsHit hit = load_hit(&hits[TS_HIT_FLOATS * i]);
            int attenuated = 0;
            if (settings.medium_scattering && med.present) {
                if (settings.ray_lights)
                    store_vrl(*p.path, med, p.ray, hit.prim == TS_NO_HIT ? ts::TS_INF : hit.t, p.alpha,
                              settings.inv_paths);
                const uint32_t m = medium_vertex(med, settings, scramble, bounce, hit, p);
                if (m & TS_LIGHT_PATH_MEDIUM) {
                    if (m & TS_LIGHT_PATH_CONTINUES) alive.push_back(p);
                    continue;
                }
                if (!(m & TS_LIGHT_PATH_CONTINUES)) {  // lost in an unbounded medium
                    p.path->segments.push_back(segment_of(p.ray, hit));
                    continue;
                }
                attenuated = 1;
            }
            p.path->segments.push_back(segment_of(p.ray, hit));
            if (hit.prim == TS_NO_HIT) continue;
            // This bounce's Halton dimensions: 2 for the direction, 1 for roulette/Fresnel.
            const int dim = 5 + 3 * static_cast<int>(bounce);
            auto u = [&](int d) { return static_cast<float>(halton.sample(p.path->index, dim + d)); };
            ts::TsSurface s;
            float3 flux;
            const uint32_t what = ts::ts_light_path_vertex(&sv, &med, hit, ts::make_float3(u(0), u(1), u(2)),
                                                           settings.inv_paths, attenuated, &p.alpha, &p.ray, &s,
                                                           &flux);
            if (what & TS_LIGHT_PATH_VPL) store_vpl(*p.path, s.position, s.shading_normal, flux, s.pos_scale);
            if (what & TS_LIGHT_PATH_CONTINUES) alive.push_back(p);
        }
        live.swap(alive);
    }
    return traced;
}

}  // namespace tessera
