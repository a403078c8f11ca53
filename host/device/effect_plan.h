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
    bool indirect = false;     ///< lights and a diffuse surface that reflects: indirect diffuse (ID)
    bool medium = false;       ///< a medium with non-zero coefficients is declared (PM)
    /// The medium scatters (sigma_s > 0 in some channel): else PM is its transmittance
    /// alone, with no in-scattered light to march, no ray lights and no AIS guidance.
    bool medium_scatters = false;
    bool reflects = false;     ///< some used diffuse material has albedo > 0 (mirrors' and dielectrics' Kd is unread)
    bool medium_declared = false;  ///< the scene declares a medium, zero or not (for describe())

    /// Whether component `bit` (one TS_COMPONENT_* bit) computes light on this scene: SS
    /// where some triangle emits, ID where that light meets a diffuse surface that reflects, PM where a
    /// medium scatters (one that only absorbs still needs PM's transmittance, but adds no
    /// light); edge samples (TS_COMPONENT_EDGE) only refine the others' pixels.
    bool computes(uint32_t bit) const;
    /// Whether `components` (TS_COMPONENT_* bits) leave any light to compute: some computes().
    bool components_compute(uint32_t components) const;
    /// How idle_reason names the components to add: by --components' names (render) or
    /// by the viewer's keys.
    enum class Naming { Option, Key };
    /// Why `components` compute no light on this scene while another choice would: the
    /// image would be the emitters alone (components a scene does not call for are skipped,
    /// docs/igi.md §1), so render and view refuse such a choice. One clause per component with
    /// its reason, then the components to add, e.g. "PM computes nothing (medium: none
    /// declared); add ss or id" (Naming::Key: "turn on SS (1) or ID (2)"). "" where they
    /// compute some light, or where no choice would (a scene without lights renders its
    /// emitters whatever the components).
    std::string idle_reason(uint32_t components, Naming naming = Naming::Option) const;
    /// OpenCL build options that follow from the plan, e.g. "-DTS_HAS_TEXTURES".
    std::vector<std::string> cl_defines() const;
    /// One line per effect, "name: yes|no (reason)", for `tessera info` and the log.
    std::vector<std::string> describe() const;
};

/// Decides the plan. Indirect light is called for only if some diffuse surface reflects
/// (albedo > 0 in any channel) while lights exist; an all-black scene shoots no VPLs.
EffectPlan plan_effects(const Scene& scene);

/// The plan over a whole animation: a light dark at rest but lit by later keys is a
/// light, a surface black at rest but coloured later reflects (media do not animate).
/// For `tessera info` and for the option checks, which must not refuse a choice some
/// frame calls for; the renderers plan each frame anew.
EffectPlan plan_effects_over_animation(const Scene& scene);

}  // namespace tessera
