// Progressive rendering of a frame: passes dispatched to a backend, accumulated on the
// host (shared by every backend, so all backends accumulate identically).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "backend/backend.h"
#include "gi/igi_frame.h"
#include "render/scene_buffers.h"
#include "image/image_io.h"
#include "render/method.h"
#include "scene/scene.h"

namespace tessera {

struct RenderSettings {
    Method method = Method::Direct;
    uint32_t max_depth = 128;       ///< pt: path vertices before a path is cut
    uint32_t max_scatter = 0;       ///< pt: medium scattering vertices per path, 0 = unlimited
    IgiSettings igi;                ///< igi (set_shadow_samples comes from shadow_samples)
    IcSettings ic;                  ///< ic, tic (temporal is set from the method)
    /// tic: the cache kept across the frames of a sequence (render it frame by frame with
    /// the same settings; render_sequence makes one); null: a cache for this call only.
    /// It must belong to the scene being rendered (its object table).
    std::shared_ptr<InstantCache> ic_state;
    uint32_t spp = 16;              ///< passes, one camera sample per pixel each
    uint32_t shadow_samples = 8;    ///< area-light samples per camera hit and pass
    uint32_t seed = 1;
    int width = 0;                  ///< 0: the scene camera's resolution
    int height = 0;
    bool aovs = false;              ///< add albedo, normal and depth channels
    bool variance = true;           ///< add variance.R/G/B channels

    // Checkpoints (render/checkpoint_session.h); used only when render_frame is given
    // CheckpointOptions.
    double checkpoint_interval_s = 120.0;  ///< save every this many seconds; 0: only on a signal
};

struct RenderStats {
    uint32_t passes = 0;
    double seconds = 0.0;            ///< wall time of all passes (excludes set-up)
    double median_pass_seconds = 0.0;
    std::string detail;              ///< method-specific log line ("" for none)
    IgiFrameStats igi;               ///< igi-family methods: the last pass's counts and stage times
    IcFrameStats ic;                 ///< ic, tic: the last pass's cache counts (records, rays)
};

/// Called after each pass with (passes done, passes total, seconds elapsed in this call,
/// passes restored from a checkpoint before this call: done − restored were rendered in
/// the elapsed time).
using ProgressFn = std::function<void(uint32_t, uint32_t, double, uint32_t)>;

struct CheckpointOptions;  // render/checkpoint_session.h

/// Validates `settings` (validate_settings in render/parameters.h: throws InputError
/// naming the option and value, e.g. "--spp 0: must be in 1..1000000"), then renders. `buffers` are the
/// SceneBuffers the backend was made from. With `checkpoint`, the render resumes from
/// and saves checkpoints (see CheckpointSession) and throws Interrupted on SIGINT or
/// SIGTERM; stats then count only the passes rendered in this call.
Image render_frame(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                   const RenderSettings& settings, RenderStats* stats = nullptr,
                   const ProgressFn& progress = {}, const CheckpointOptions* checkpoint = nullptr);

}  // namespace tessera
