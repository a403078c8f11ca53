// Virtual point lights for instant radiosity (Keller 1997), generated on the host and
// shared by every backend: the light paths are traced through Backend::trace_closest,
// so all backends gather from the same VPLs (up to traversal ties).
#pragma once
#include <cstdint>
#include <vector>

#include "backend/backend.h"
#include "device/scene_buffers.h"
#include "gi/light_paths.h"
#include "gi/vpl_importance.h"

namespace tessera {

/// Path index p of set k in frame f is f·sets·P + k·P + j, P = paths_per_set (times
/// importance_oversampling when a view is given): fixed
/// indices, so a frame's paths are the same every time it is generated.
struct VplSettings {
    uint32_t sets = 9;             ///< interleave sets N = n²
    uint32_t paths_per_set = 32;   ///< M light paths per set (docs/igi.md §3)
    uint32_t max_bounces = kLightPathDepth;  ///< segments per path (kLightPathDepth)
    uint32_t frame = 0;            ///< selects the block of path indices
    uint32_t halton_seed = 0x7e55e7a;  ///< the digit scrambling, fixed for the project
    uint32_t seed = 1;                 ///< the render's --seed (LightPathSettings::seed)
    bool medium_scattering = false;    ///< LightPathSettings::medium_scattering
    bool ray_lights = false;           ///< LightPathSettings::ray_lights (VplList::vrls)
    /// VPLs for the view (gi/vpl_importance.h): K > 1 traces K·paths_per_set candidate
    /// paths per set and keeps, on average, paths_per_set paths' worth of VPLs, chosen by
    /// their importance for `view` (unbiased: kept VPLs carry 1/p). 1: every VPL of
    /// paths_per_set paths, as IGI.
    uint32_t importance_oversampling = 1;
    const ViewPoints* view = nullptr;  ///< required when importance_oversampling > 1
    /// Clamp b of the importance's geometry terms (scene units^-2): scene-relative, the
    /// default clamp (c = 0.1) whatever the frame's, which loosens over passes or may be
    /// off. Unclamped, a VPL next to one view point would take that point's whole share
    /// and the other VPLs would look unimportant there.
    float importance_clamp = 0.0f;
};

struct VplList {
    std::vector<float> vpls;          ///< TS_VPL_FLOATS per VPL, sorted by set
    std::vector<uint32_t> set_start;  ///< sets + 1 offsets into vpls (in VPLs)
    /// Ray lights (TS_VRL_FLOATS each, layout_igi.h) with VplSettings::ray_lights, sorted by
    /// set; with importance_oversampling K each set keeps 1/K of its candidates' ray lights
    /// (one systematic sample, so exactly its share to within one), their flux times K.
    std::vector<float> vrls;
    std::vector<uint32_t> vrl_set_start;  ///< sets + 1 offsets into vrls (in ray lights)
    uint64_t rays = 0;                ///< light-path rays traced
    /// Wall time of the light paths (trace_light_paths) and of the selection for the view
    /// (importance, keep decisions, ray lights' share), seconds: the stage-time table's parts.
    double trace_seconds = 0, select_seconds = 0;
    /// Of those, the device time (Backend::kernel_seconds) of the kernels that ran them:
    /// KernelId::LightPaths or LightPathsMedia, and VplImportancePoints plus
    /// VplImportanceVpls; 0 where the host did that work (Embree, OpenCL on CPUs). The rest of
    /// each part is uploads, read-backs, waits and host work: where a GPU's VPL stage goes.
    double trace_kernel_seconds = 0, select_kernel_seconds = 0;
    size_t count() const { return set_start.empty() ? 0 : set_start.back(); }
};

/// Shoots the light paths (gi/light_paths.h, which documents the estimator) and
/// records a VPL at every diffuse surface hit, sorted by set.
VplList generate_vpls(Backend& backend, const SceneBuffers& scene, const VplSettings& settings);

}  // namespace tessera
