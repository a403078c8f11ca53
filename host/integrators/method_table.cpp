// The method table (integrators/method.h): one row per method, with its factory.
#include <vector>

#include "device/effect_plan.h"
#include "integrators/ais_frame.h"
#include "integrators/ic_frame.h"
#include "integrators/factory.h"
#include "integrators/kernel_integrator.h"
#include "integrators/method.h"

namespace tessera {
namespace {

template <KernelId kernel>
std::unique_ptr<Integrator> make_kernel(Backend& backend, const Scene&, const SceneBuffers&, const IntegratorSettings&) {
    return std::make_unique<KernelIntegrator>(backend, kernel);
}

// The igi settings every igi-family integrator reads: IgiSettings with the light samples
// and the AIS mode of the method.
IgiSettings igi_settings(const IntegratorSettings& settings, AisMode mode = AisMode::A) {
    IgiSettings is = settings.igi;
    is.set_shadow_samples = settings.shadow_samples;
    is.ais_mode = mode;
    return is;
}

std::unique_ptr<Integrator> make_igi(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                                     const IntegratorSettings& settings) {
    return std::make_unique<IgiFrame>(backend, buffers, plan_effects(scene), igi_settings(settings));
}

template <AisMode mode>
std::unique_ptr<Integrator> make_ais(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                                     const IntegratorSettings& settings) {
    return std::make_unique<AisFrame>(backend, buffers, plan_effects(scene), igi_settings(settings, mode));
}

// The caches of an ic-type method (one per pass; temporal for tic) for a scene with `objects`.
std::shared_ptr<IcPassCaches> make_ic_caches(const IntegratorSettings& settings,
                                             const std::vector<SceneObject>& objects) {
    IcSettings ics = settings.ic;
    ics.temporal = method_info(settings.method).temporal;
    ics.multiple_scattering = settings.igi.multiple_scattering;
    ics.light_path_depth = settings.igi.light_path_depth;
    // One switch for the clamp's compensation: igi's screen-space estimate and ic's rays.
    // Here, where the renderer makes every cache (a sequence's and the viewer's before any
    // frame); an IcPassCaches made directly takes ic.clamp_compensation as it is.
    ics.clamp_compensation = settings.ic.clamp_compensation && settings.igi.clamp_compensation;
    return std::make_shared<IcPassCaches>(ics, objects);
}

std::unique_ptr<Integrator> make_ic(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                                    const IntegratorSettings& settings) {
    std::shared_ptr<IcPassCaches> cache;
    // ic may be handed caches too (to look at them afterwards); they make no difference
    // to its image, which rebuilds every pass.
    if (settings.ic_state && settings.ic_state->temporal() == method_info(settings.method).temporal)
        cache = settings.ic_state;
    if (!cache) cache = make_ic_caches(settings, scene.objects);
    return std::make_unique<IcFrame>(backend, buffers, plan_effects(scene), igi_settings(settings), std::move(cache));
}

// tic: one cache for the sequence, of the scene at rest.
void prepare_tic(IntegratorSettings& settings, const Scene& rest) {
    settings.ic_state = make_ic_caches(settings, rest.objects);
}

}  // namespace

const std::vector<MethodInfo>& method_table() {
    // clang-format off
    static const std::vector<MethodInfo> table = {
        // method, name, summary,
        //   igi_family, adaptive, temporal, own_aovs, global, media, make, prepare
        {Method::Direct, "direct", "emission and direct light from area lights",
         false, false, false, false, false, false, make_kernel<KernelId::Direct>, nullptr},
        {Method::PathTrace, "pt", "volumetric path tracing: the reference",
         false, false, false, false, true, true, make_kernel<KernelId::PathTrace>, nullptr},
        {Method::Igi, "igi", "instant global illumination: interleaved VPL sets and the discontinuity filter",
         true, false, false, true, true, true, make_igi, nullptr},
        {Method::Ais, "ais", "adaptive interleaved sampling, mode A: graded extra sets where guidance flags",
         true, true, false, true, true, true, make_ais<AisMode::A>, nullptr},
        {Method::AisMax, "ais-max", "adaptive interleaved sampling, mode A-MAX: all sets where guidance flags",
         true, true, false, true, true, true, make_ais<AisMode::AMax>, nullptr},
        {Method::Ic, "ic", "instant caching: indirect light from an irradiance cache rebuilt each pass",
         true, false, false, true, true, true, make_ic, nullptr},
        {Method::Tic, "tic", "temporal instant caching: the cache kept and updated across frames",
         true, false, true, true, true, true, make_ic, prepare_tic},
    };
    // clang-format on
    return table;
}

}  // namespace tessera
