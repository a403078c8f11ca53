#include "integrators/factory.h"

#include "gi/ais_frame.h"
#include "gi/ic_frame.h"
#include "integrators/kernel_integrator.h"
#include "device/effect_plan.h"

namespace tessera {

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
            if (!cache) {
                IcSettings ics = settings.ic;
                ics.temporal = settings.method == Method::Tic;
                ics.multiple_scattering = settings.igi.multiple_scattering;
                cache = std::make_shared<IcPassCaches>(ics, scene.objects);
            }
            return std::make_unique<IcFrame>(backend, buffers, plan_effects(scene), is, std::move(cache));
        }
    }
    return nullptr;
}

void prepare_sequence(IntegratorSettings& settings, const Scene& rest) {
    if (settings.method == Method::Tic) {  // one cache for this sequence, of this scene
        IcSettings ics = settings.ic;
        ics.temporal = true;
        ics.multiple_scattering = settings.igi.multiple_scattering;
        settings.ic_state = std::make_shared<IcPassCaches>(ics, rest.objects);
    }
}

}  // namespace tessera
