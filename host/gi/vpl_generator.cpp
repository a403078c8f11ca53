#include "gi/vpl_generator.h"

#include <algorithm>

#include "gi/light_paths.h"

namespace tessera {

namespace {

// Replaces each set's candidates by the VPLs select_vpls keeps of them.
void keep_for_view(const VplSettings& settings, uint32_t oversampling, VplList& list) {
    const std::vector<float> importance = vpl_view_importance(*settings.view, list.vpls, settings.importance_clamp);
    std::vector<float> kept;
    std::vector<uint32_t> start(settings.sets + 1, 0u);
    for (uint32_t k = 0; k < settings.sets; ++k)
        start[k + 1] = start[k] + select_vpls(list.vpls, importance, list.set_start[k], list.set_start[k + 1],
                                              oversampling, light_path_seed_mix(settings.seed), kept);
    list.vpls.swap(kept);
    list.set_start.swap(start);
}

}  // namespace

VplList generate_vpls(Backend& backend, const SceneBuffers& scene, const VplSettings& settings) {
    VplList out;
    out.set_start.assign(settings.sets + 1, 0u);
    std::vector<LightPath> paths;
    const uint32_t oversampling = settings.view ? std::max(1u, settings.importance_oversampling) : 1u;
    const uint64_t per_set = uint64_t(settings.paths_per_set) * oversampling;
    const uint64_t first = uint64_t(settings.frame) * settings.sets * per_set;
    for (uint32_t k = 0; k < settings.sets; ++k)
        for (uint64_t j = 0; j < per_set; ++j) {
            LightPath p;
            p.index = first + uint64_t(k) * per_set + j;
            p.set = k;
            paths.push_back(std::move(p));
        }
    LightPathSettings ls;
    ls.max_bounces = settings.max_bounces;
    ls.halton_seed = settings.halton_seed;
    ls.seed = settings.seed;
    ls.medium_scattering = settings.medium_scattering;
    ls.inv_paths = 1.0f / static_cast<float>(per_set);
    out.rays = trace_light_paths(backend, scene, ls, paths);
    // Paths are in set order, so concatenating them sorts the VPLs by set.
    for (const LightPath& p : paths) {
        out.set_start[p.set + 1] += static_cast<uint32_t>(p.vpls.size() / TS_VPL_FLOATS);
        out.vpls.insert(out.vpls.end(), p.vpls.begin(), p.vpls.end());
    }
    for (uint32_t k = 0; k < settings.sets; ++k) out.set_start[k + 1] += out.set_start[k];
    if (oversampling > 1) keep_for_view(settings, oversampling, out);
    if (out.vpls.empty()) out.vpls.assign(TS_VPL_FLOATS, 0.0f);  // device buffers cannot be empty
    return out;
}

}  // namespace tessera
