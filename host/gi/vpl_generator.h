// Virtual point lights for instant radiosity (Keller 1997), generated on the host and
// shared by every backend: the light paths are traced through Backend::trace_closest,
// so all backends gather from the same VPLs (up to traversal ties).
#pragma once
#include <cstdint>
#include <vector>

#include "backend/backend.h"
#include "device/scene_buffers.h"

namespace tessera {

/// Path index p of set k in frame f is f·sets·paths_per_set + k·paths_per_set + j: fixed
/// indices, so a frame's paths are the same every time it is generated.
struct VplSettings {
    uint32_t sets = 9;             ///< interleave sets N = n²
    uint32_t paths_per_set = 32;   ///< M light paths per set (docs/igi.md §3)
    /// Surface hits per path. Paths end by Russian roulette; this cap only bounds the
    /// work. IGI's customary 5 would drop the light of 6+ bounces (about ρ⁵ of the
    /// indirect light, a few percent in a white room) and make IGI converge to something
    /// other than the path-traced reference, so the cap is set where roulette has long
    /// ended every path in practice.
    uint32_t max_bounces = 64;
    uint32_t frame = 0;            ///< selects the block of path indices
    uint32_t halton_seed = 0x7e55e7a;  ///< the digit scrambling, fixed for the project
    bool medium_scattering = false;    ///< LightPathSettings::medium_scattering
};

struct VplList {
    std::vector<float> vpls;          ///< TS_VPL_FLOATS per VPL, sorted by set
    std::vector<uint32_t> set_start;  ///< sets + 1 offsets into vpls (in VPLs)
    uint64_t rays = 0;                ///< light-path rays traced
    size_t count() const { return set_start.empty() ? 0 : set_start.back(); }
};

/// Shoots the light paths (gi/light_paths.h, which documents the estimator) and
/// records a VPL at every diffuse surface hit, sorted by set.
VplList generate_vpls(Backend& backend, const SceneBuffers& scene, const VplSettings& settings);

}  // namespace tessera
