#include "integrators/factory.h"

#include "integrators/method.h"

namespace tessera {

std::unique_ptr<Integrator> make_integrator(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                                            const IntegratorSettings& settings) {
    return method_info(settings.method).make(backend, scene, buffers, settings);
}

void prepare_sequence(IntegratorSettings& settings, const Scene& rest) {
    if (const PrepareSequenceFn prepare = method_info(settings.method).prepare) prepare(settings, rest);
}

}  // namespace tessera
