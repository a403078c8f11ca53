#include "gi/vpl_generator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>

#include "gi/light_paths.h"
#include "kernels/shared/layout_igi.h"
#include "kernels/shared/rng.h"

namespace tessera {

namespace {

// Replaces each set's candidates by the VPLs select_vpls keeps of them.
void keep_for_view(Backend& backend, const VplSettings& settings, uint32_t oversampling, VplList& list) {
    const std::vector<float> importance =
        vpl_view_importance(backend, *settings.view, list.vpls, settings.importance_clamp);
    std::vector<float> kept;
    std::vector<uint32_t> start(settings.sets + 1, 0u);
    for (uint32_t k = 0; k < settings.sets; ++k)
        start[k + 1] = start[k] + select_vpls(list.vpls, importance, list.set_start[k], list.set_start[k + 1],
                                              oversampling, light_path_seed_mix(settings.seed), kept);
    list.vpls.swap(kept);
    list.set_start.swap(start);
}

// Keeps 1/K of each set's ray lights, their flux times K: one systematic sample
// (systematic_sample) over the set's candidates in path order, its offset keyed by the
// seed and the set's first path. Ray lights light the medium, which the view points do not
// see, so each is as likely as the next (as keep_probabilities treats medium VPLs).
void keep_ray_lights(const VplSettings& settings, uint32_t oversampling, VplList& list) {
    std::vector<float> kept;
    std::vector<uint32_t> start(settings.sets + 1, 0u);
    const double p = 1.0 / oversampling;
    for (uint32_t k = 0; k < settings.sets; ++k) {
        const uint32_t begin = list.vrl_set_start[k], end = list.vrl_set_start[k + 1];
        uint32_t first = 0;
        if (end > begin) std::memcpy(&first, &list.vrls[size_t(TS_VRL_FLOATS) * begin + TS_VRL_PATH], 4);
        ts::TsRng rng = ts::ts_rng_seed(0x76726c6bu ^ light_path_seed_mix(settings.seed), first, k);
        const std::vector<bool> keep = systematic_sample(std::vector<double>(end - begin, p), ts::ts_rng_next(&rng));
        for (uint32_t i = begin; i < end; ++i) {
            if (!keep[i - begin]) continue;
            const float* v = &list.vrls[size_t(TS_VRL_FLOATS) * i];
            const size_t at = kept.size();
            kept.insert(kept.end(), v, v + TS_VRL_FLOATS);
            for (int c = 0; c < 3; ++c) kept[at + TS_VRL_FLUX + c] = static_cast<float>(v[TS_VRL_FLUX + c] / p);
        }
        start[k + 1] = static_cast<uint32_t>(kept.size() / TS_VRL_FLOATS);
    }
    list.vrls.swap(kept);
    list.vrl_set_start.swap(start);
}

// The device time of kernels `ids` launched since the dispatch counts `before` were taken
// (Backend::kernel_seconds of each that launched since; each launches at most once a stage).
using StageKernels = std::array<KernelId, 2>;

double kernel_seconds_since(Backend& backend, const StageKernels& ids, const std::vector<uint64_t>& before) {
    double seconds = 0.0;
    size_t i = 0;
    for (KernelId k : ids)
        if (backend.dispatch_count(k) != before[i++]) seconds += backend.kernel_seconds(k);
    return seconds;
}

std::vector<uint64_t> dispatch_counts(const Backend& backend, const StageKernels& ids) {
    std::vector<uint64_t> n;
    for (KernelId k : ids) n.push_back(backend.dispatch_count(k));
    return n;
}

constexpr StageKernels kPathKernels = {KernelId::LightPaths, KernelId::LightPathsMedia};
constexpr StageKernels kImportanceKernels = {KernelId::VplImportancePoints, KernelId::VplImportanceVpls};

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
    ls.ray_lights = settings.ray_lights;
    ls.inv_paths = 1.0f / static_cast<float>(per_set);
    ls.segments = false;  // VPLs only: a GPU traces the paths in one kernel
    using Clock = std::chrono::steady_clock;
    const std::vector<uint64_t> paths_before = dispatch_counts(backend, kPathKernels);
    const auto t0 = Clock::now();
    out.rays = trace_light_paths(backend, scene, ls, paths);
    const auto t1 = Clock::now();
    out.trace_seconds = std::chrono::duration<double>(t1 - t0).count();
    out.trace_kernel_seconds = kernel_seconds_since(backend, kPathKernels, paths_before);
    const std::vector<uint64_t> select_before = dispatch_counts(backend, kImportanceKernels);
    const auto t2 = Clock::now();  // after the kernel time's wait, which is the paths'
    // Paths are in set order, so concatenating them sorts the VPLs and ray lights by set.
    out.vrl_set_start.assign(settings.sets + 1, 0u);
    for (const LightPath& p : paths) {
        out.set_start[p.set + 1] += static_cast<uint32_t>(p.vpls.size() / TS_VPL_FLOATS);
        out.vpls.insert(out.vpls.end(), p.vpls.begin(), p.vpls.end());
        out.vrl_set_start[p.set + 1] += static_cast<uint32_t>(p.vrls.size() / TS_VRL_FLOATS);
        out.vrls.insert(out.vrls.end(), p.vrls.begin(), p.vrls.end());
    }
    for (uint32_t k = 0; k < settings.sets; ++k) {
        out.set_start[k + 1] += out.set_start[k];
        out.vrl_set_start[k + 1] += out.vrl_set_start[k];
    }
    if (oversampling > 1) keep_for_view(backend, settings, oversampling, out);
    if (oversampling > 1 && !out.vrls.empty()) keep_ray_lights(settings, oversampling, out);
    out.select_seconds = std::chrono::duration<double>(Clock::now() - t2).count();
    out.select_kernel_seconds = kernel_seconds_since(backend, kImportanceKernels, select_before);
    if (out.vpls.empty()) out.vpls.assign(TS_VPL_FLOATS, 0.0f);  // device buffers cannot be empty
    if (out.vrls.empty()) out.vrls.assign(TS_VRL_FLOATS, 0.0f);
    return out;
}

}  // namespace tessera
