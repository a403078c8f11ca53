// Choosing an integrator from the method: the settings every integrator may read, what
// integrators report, and the factory. The frame loop (render/renderer.h) uses only this
// header and integrators/integrator.h; adding a method adds a case to make_integrator.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "backend/backend.h"
#include "gi/igi_frame.h"
#include "gi/ic_passes.h"
#include "integrators/integrator.h"
#include "integrators/method.h"
#include "scene/scene.h"

namespace tessera {

/// The method and its settings (the part of RenderSettings below the frame loop).
struct IntegratorSettings {
    Method method = Method::Direct;
    uint32_t max_depth = 128;       ///< pt: path vertices before a path is cut
    uint32_t max_scatter = 0;       ///< pt: medium scattering vertices per path, 0 = unlimited
    IgiSettings igi;                ///< igi (set_shadow_samples comes from shadow_samples)
    IcSettings ic;                  ///< ic, tic (temporal is set from the method)
    /// tic: the caches (one per pass) kept across the frames of a sequence (render it
    /// frame by frame with the same settings; render_sequence makes them); null: caches
    /// for this call only. They must belong to the scene being rendered (its object table).
    /// ic uses non-temporal ones when given (only so that a caller can inspect them).
    std::shared_ptr<IcPassCaches> ic_state;
    uint32_t shadow_samples = 8;    ///< area-light samples per camera hit and pass
    /// Textures at camera hits are read from the mip level of the pixel's ray cone
    /// (TsFrame::pixel_cone); false: always the finest level. pt ignores it (it
    /// supersamples: the reference).
    bool texture_filter = true;
};

/// What an integrator reports about its last pass (Integrator::report).
struct IntegratorStats {
    std::string detail;              ///< method-specific log line ("" for none)
    IgiFrameStats igi;               ///< igi-family methods: the last pass's counts and stage times
    IcFrameStats ic;                 ///< ic, tic: the cache counts (records, rays) summed over the frame's passes
};

/// The integrator of settings.method for `scene` (flattened into `buffers`, which
/// `backend` was made from). `backend` and `buffers` must outlive it.
std::unique_ptr<Integrator> make_integrator(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                                            const IntegratorSettings& settings);

/// Before a sequence of frames of `rest` rendered with `settings`: makes the state a
/// method keeps across frames (tic: its temporal instant caches, in settings.ic_state).
void prepare_sequence(IntegratorSettings& settings, const Scene& rest);

}  // namespace tessera
