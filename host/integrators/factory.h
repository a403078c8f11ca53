// Choosing an integrator from the method; the settings every integrator may read and what
// integrators report are in integrators/settings.h. The frame loop (render/renderer.h)
// uses only this header and integrators/integrator.h; make_integrator reads the method
// table (integrators/method.h), so adding a method adds a row there.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "backend/backend.h"
#include "integrators/integrator.h"
#include "integrators/method.h"
#include "integrators/settings.h"
#include "scene/scene.h"

namespace tessera {

/// The integrator of settings.method for `scene` (flattened into `buffers`, which
/// `backend` was made from). `backend` and `buffers` must outlive it.
std::unique_ptr<Integrator> make_integrator(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                                            const IntegratorSettings& settings);

/// Before a sequence of frames of `rest` rendered with `settings`: makes the state a
/// method keeps across frames (tic: its temporal instant caches, in settings.ic_state).
void prepare_sequence(IntegratorSettings& settings, const Scene& rest);

}  // namespace tessera
