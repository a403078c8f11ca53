// Progressive rendering of a frame: passes dispatched to a backend, accumulated on the
// host (shared by every backend, so all backends accumulate identically).
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "backend/backend.h"
#include "image/image_io.h"
#include "scene/scene.h"

namespace tessera {

struct RenderSettings {
    std::string method = "direct";  ///< only "direct" exists so far
    uint32_t spp = 16;              ///< passes, one camera sample per pixel each
    uint32_t shadow_samples = 8;    ///< area-light samples per camera hit and pass
    uint32_t seed = 1;
    int width = 0;                  ///< 0: the scene camera's resolution
    int height = 0;
    bool aovs = false;              ///< add albedo, normal and depth channels
    bool variance = true;           ///< add variance.R/G/B channels
};

struct RenderStats {
    uint32_t passes = 0;
    double seconds = 0.0;            ///< wall time of all passes (excludes set-up)
    double median_pass_seconds = 0.0;
};

/// Called after each pass with (passes done, passes total, seconds elapsed).
using ProgressFn = std::function<void(uint32_t, uint32_t, double)>;

/// Validates `settings` (throws InputError naming --spp, --shadow-samples, --width,
/// --height or --method when out of range), then renders. `light_count` comes from the
/// SceneBuffers the backend was made from.
Image render_frame(Backend& backend, const Scene& scene, uint32_t light_count,
                   const RenderSettings& settings, RenderStats* stats = nullptr,
                   const ProgressFn& progress = {});

}  // namespace tessera
