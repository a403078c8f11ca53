#include "device/effect_plan.h"

#include "device/components.h"
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
        // A mirror's or a dielectric's Kd is not read (bsdf.h): they bend light paths on to
        // diffuse surfaces, which alone hold VPLs and gather them.
        if (!m.is_mirror() && !m.is_dielectric() && (m.albedo.x > 0.0f || m.albedo.y > 0.0f || m.albedo.z > 0.0f))
            reflects = true;
    }
    p.reflects = reflects;
    p.indirect = p.area_lights && reflects;
    p.medium_declared = scene.has_medium;
    p.medium = scene.has_medium && (scene.medium.sigma_a != glm::vec3(0.0f) || scene.medium.sigma_s != glm::vec3(0.0f));
    p.medium_scatters = p.medium && glm::any(glm::greaterThan(scene.medium.sigma_s, glm::vec3(0.0f)));
    return p;
}

namespace {

// Why ID or PM is not called for, as describe() and idle_reason() both say it.
std::string no_indirect_reason(const EffectPlan& p) {
    return !p.area_lights ? "no light" : !p.reflects ? "no diffuse surface reflects" : "";
}
std::string no_medium_reason(const EffectPlan& p) {
    return p.medium_declared ? "declared, but sigma_a and sigma_s are zero" : "none declared";
}

}  // namespace

bool EffectPlan::computes(uint32_t bit) const {
    switch (bit) {
        case TS_COMPONENT_SS: return area_lights;
        case TS_COMPONENT_ID: return indirect;
        case TS_COMPONENT_PM: return medium_scatters;
        default: return false;
    }
}

bool EffectPlan::components_compute(uint32_t components) const {
    for (const ComponentName& c : kComponentNames)
        if ((components & c.bit) && computes(c.bit)) return true;
    return false;
}

std::string EffectPlan::idle_reason(uint32_t components, Naming naming) const {
    if (components_compute(components) || !components_compute(TS_COMPONENT_SS | TS_COMPONENT_ID | TS_COMPONENT_PM))
        return "";
    std::string why;
    for (const ComponentName& c : kComponentNames) {
        if (!(components & c.bit) || c.bit == TS_COMPONENT_EDGE) continue;  // edge: below
        const std::string reason = c.bit == TS_COMPONENT_SS   ? "no light"
                                   : c.bit == TS_COMPONENT_ID ? no_indirect_reason(*this)
                                   : medium                   ? "the medium only absorbs: sigma_s is zero"
                                                              : "medium: " + no_medium_reason(*this);
        why += (why.empty() ? "" : ", ") + std::string(c.label) + " computes nothing (" + reason + ")";
    }
    if (components & TS_COMPONENT_EDGE)
        why += (why.empty() ? "" : ", ") + std::string("edge samples only refine the other components' pixels");
    std::vector<std::string> add;
    for (const ComponentName& c : kComponentNames)
        if (computes(c.bit)) add.push_back(naming == Naming::Key ? c.key : c.option);
    std::string list;
    for (size_t i = 0; i < add.size(); ++i)
        list += (i == 0 ? "" : i + 1 == add.size() ? " or " : ", ") + add[i];
    return why + (naming == Naming::Key ? "; turn on " : "; add ") + list;
}

EffectPlan plan_effects_over_animation(const Scene& scene) {
    Scene lit = scene;
    for (Material& m : lit.materials) m.emission = m.emission_bound();
    for (const MaterialTrack& t : scene.animation.materials)
        for (const MaterialKey& k : t.keys)
            if (k.albedo)
                for (uint32_t m : t.materials) lit.materials[m].albedo = glm::max(lit.materials[m].albedo, *k.albedo);
    return plan_effects(lit);
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
    const std::string no_indirect = indirect ? "" : " (" + no_indirect_reason(*this) + ")";
    const std::string no_medium = " (" + no_medium_reason(*this) + ")";
    return {
        "area lights (SS):     " + yn(area_lights),
        "textures:             " + yn(textures),
        "indirect diffuse (ID): " + yn(indirect) + no_indirect,
        "medium (PM):          " + yn(medium) +
            (!medium ? no_medium : medium_scatters ? "" : " (absorbs only: its transmittance, no in-scattered light)"),
    };
}

}  // namespace tessera
