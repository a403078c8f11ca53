#include "integrators/factory.h"

#include <vector>

#include "gi/ais_frame.h"
#include "gi/ic_frame.h"
#include "integrators/kernel_integrator.h"
#include "device/effect_plan.h"

namespace tessera {
namespace {

// The caches of `settings.method` (ic or tic) for a scene with `objects`.
std::shared_ptr<IcPassCaches> make_ic_caches(const IntegratorSettings& settings,
                                             const std::vector<SceneObject>& objects) {
    IcSettings ics = settings.ic;
    ics.temporal = settings.method == Method::Tic;
    ics.multiple_scattering = settings.igi.multiple_scattering;
    return std::make_shared<IcPassCaches>(ics, objects);
}

}  // namespace

std::unique_ptr<Integrator> make_integrator(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                                            const IntegratorSettings& settings) {
    IgiSettings is = settings.igi;
    is.set_shadow_samples = settings.shadow_samples;
    is.ais_mode = settings.method == Method::AisMax ? AisMode::AMax : AisMode::A;
    switch (settings.method) {
        case Method::Direct: return std::make_unique<KernelIntegrator>(backend, KernelId::Direct);
        case Method::PathTrace: return std::make_unique<KernelIntegrator>(backend, KernelId::PathTrace);
        case Method::Igi: return std::make_unique<IgiFrame>(backend, buffers, plan_effects(scene), is);
        case Method::Ais:
        case Method::AisMax: return std::make_unique<AisFrame>(backend, buffers, plan_effects(scene), is);
        case Method::Ic:
        case Method::Tic: {
            std::shared_ptr<IcPassCaches> cache;
            // ic may be handed caches too (to look at them afterwards); they make no
            // difference to its image, which rebuilds every pass.
            if (settings.ic_state && settings.ic_state->temporal() == (settings.method == Method::Tic))
                cache = settings.ic_state;
            if (!cache) cache = make_ic_caches(settings, scene.objects);
            return std::make_unique<IcFrame>(backend, buffers, plan_effects(scene), is, std::move(cache));
        }
    }
    return nullptr;
}

void prepare_sequence(IntegratorSettings& settings, const Scene& rest) {
    if (settings.method == Method::Tic) {  // one cache for this sequence, of this scene
        settings.ic_state = make_ic_caches(settings, rest.objects);
    }
}

}  // namespace tessera
