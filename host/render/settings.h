// What a render is asked to do (RenderSettings) and what it reports (RenderStats): the
// frame loop's settings on top of the integrator's, in their own header so that the
// parameter table, checkpoints and the viewer need not include the frame loop.
#pragma once
#include <cstdint>

#include "integrators/settings.h"

namespace tessera {

/// The method and its settings (IntegratorSettings: method, max_depth, max_scatter, igi,
/// ic, ic_state, shadow_samples), and the frame loop's.
struct RenderSettings : IntegratorSettings {
    uint32_t spp = 16;              ///< passes, one camera sample per pixel each
    uint32_t seed = 1;
    int width = 0;                  ///< 0: the scene camera's resolution
    int height = 0;
    bool aovs = false;              ///< add albedo, normal and depth channels
    bool variance = true;           ///< add variance.R/G/B channels

    // Checkpoints (render/checkpoint_session.h); used only when render_frame is given
    // CheckpointOptions.
    double checkpoint_interval_s = 120.0;  ///< save every this many seconds; 0: only on a signal
};

/// The integrator's report (IntegratorStats: detail, igi, ic) and the frame loop's times.
struct RenderStats : IntegratorStats {
    uint32_t passes = 0;
    double seconds = 0.0;            ///< wall time of all passes (excludes set-up)
    double median_pass_seconds = 0.0;
};

}  // namespace tessera
