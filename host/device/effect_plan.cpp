#include "device/effect_plan.h"

#include "kernels/shared/layout_igi.h"

namespace tessera {

EffectPlan plan_effects(const Scene& scene) {
    EffectPlan p;
    std::vector<bool> used(scene.materials.size(), false);
    for (uint32_t m : scene.material) used[m] = true;
    bool reflects = false;
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const Material& m = scene.materials[i];
        if (m.emission.x > 0.0f || m.emission.y > 0.0f || m.emission.z > 0.0f) p.area_lights = true;
        if (m.texture >= 0) p.textures = true;
        if (m.albedo.x > 0.0f || m.albedo.y > 0.0f || m.albedo.z > 0.0f) reflects = true;
    }
    p.reflects = reflects;
    p.indirect = p.area_lights && reflects;
    p.medium_declared = scene.has_medium;
    p.medium = scene.has_medium && (scene.medium.sigma_a != glm::vec3(0.0f) || scene.medium.sigma_s != glm::vec3(0.0f));
    return p;
}

bool EffectPlan::components_compute(uint32_t components) const {
    return (components & (TS_COMPONENT_SS | TS_COMPONENT_ID)) != 0 || (medium && (components & TS_COMPONENT_PM) != 0);
}

std::vector<std::string> EffectPlan::cl_defines() const {
    std::vector<std::string> d;
    if (textures) d.push_back("-DTS_HAS_TEXTURES");
    if (medium) d.push_back("-DTS_HAS_MEDIUM");
    return d;
}

std::vector<std::string> EffectPlan::describe() const {
    auto yn = [](bool b) { return b ? std::string("yes") : std::string("no"); };
    // The reason names the one cause that holds, so a user knows what to change.
    const std::string no_indirect = !area_lights ? " (no light)" : !reflects ? " (no reflecting surface)" : "";
    const std::string no_medium = medium_declared ? " (declared, but sigma_a and sigma_s are zero)" : " (none declared)";
    return {
        "area lights (SS):     " + yn(area_lights),
        "textures:             " + yn(textures),
        "indirect diffuse (ID): " + yn(indirect) + no_indirect,
        "medium (PM):          " + yn(medium) + (medium ? "" : no_medium),
    };
}

}  // namespace tessera
