// The settings every integrator may read (IntegratorSettings: the method and its settings,
// the part of RenderSettings below the frame loop) and what integrators report
// (IntegratorStats), apart from the factory so that integrators need not include it.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "gi/ic_passes.h"
#include "integrators/igi_frame.h"
#include "integrators/method.h"

namespace tessera {

/// The method and its settings (the part of RenderSettings below the frame loop).
struct IntegratorSettings {
    Method method = Method::Direct;
    /// pt: scattering vertices per path (1: direct lighting). Roulette ends paths long
    /// before in any scene that absorbs; the cap bounds the work where nothing does (a
    /// medium that only scatters: docs/path-tracing.md §3).
    uint32_t max_depth = 8192;
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

}  // namespace tessera
