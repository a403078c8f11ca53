// Which effects a scene calls for, decided once at load: the kernels built, their
// defines and the work scheduled all follow from this, so a scene without an effect
// never pays for it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace tessera {

struct EffectPlan {
    bool area_lights = false;  ///< some triangle emits: direct light / soft shadows (SS)
    bool textures = false;     ///< some material has map_Kd: texture lookups compiled in
    bool indirect = false;     ///< lights and a non-black surface: indirect diffuse (ID)
    bool medium = false;       ///< a medium with non-zero coefficients is declared (PM)
    bool reflects = false;     ///< some used material has albedo > 0 (for describe()'s reason)
    bool medium_declared = false;  ///< the scene declares a medium, zero or not (for describe())

    /// Whether `components` (TS_COMPONENT_* bits) leaves any light to compute on this
    /// scene: SS or ID, or PM where a medium is called for. Where it does not, an igi-family
    /// image holds the emitters alone (docs/ais.md: components a scene does not call for
    /// are skipped), so render and view both refuse such a choice.
    bool components_compute(uint32_t components) const;
    /// OpenCL build options that follow from the plan, e.g. "-DTS_HAS_TEXTURES".
    std::vector<std::string> cl_defines() const;
    /// One line per effect, "name: yes|no (reason)", for `tessera info` and the log.
    std::vector<std::string> describe() const;
};

/// Decides the plan. Indirect light is called for only if some surface reflects
/// (albedo > 0 in any channel) while lights exist; an all-black scene shoots no VPLs.
EffectPlan plan_effects(const Scene& scene);

}  // namespace tessera
