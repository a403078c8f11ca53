// Progressive rendering of a frame: passes dispatched to a backend, accumulated on the
// host (shared by every backend, so all backends accumulate identically).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "backend/backend.h"
#include "image/image_io.h"
#include "integrators/factory.h"
#include "render/settings.h"
#include "device/scene_buffers.h"
#include "scene/scene.h"

namespace tessera {

/// Called after each pass with (passes done, passes total, seconds elapsed in this call,
/// passes restored from a checkpoint before this call: done − restored were rendered in
/// the elapsed time).
using ProgressFn = std::function<void(uint32_t, uint32_t, double, uint32_t)>;

struct CheckpointOptions;  // render/checkpoint_session.h
class Cluster;             // render/cluster.h

/// The integrator settings of a render or view with `settings`: as given, with the igi
/// family's components kept on the host when the method's AOV channels are wanted
/// (IgiSettings::component_aovs) and ic's path subsets resolved (resolve_ic_subsets) for an
/// image of width × height pixels.
IntegratorSettings integrator_settings(const RenderSettings& settings, int width, int height);

/// The image size of a render with `settings` of a scene with `camera`: --width and
/// --height where given, else the camera's (pixels); where only one is given, the other
/// is scaled from the camera's to keep its aspect ratio (rounded, at least 1). Throws
/// InputError naming the option when that side would exceed limits::kImageSide (16384).
struct ImageSize {
    int width, height;
};
ImageSize render_image_size(const RenderSettings& settings, const Camera& camera);

/// Sets ic's path subsets M from settings.spp and the image's width × height pixels where
/// they are 0 (--ic-subsets not given): ic_subsets_for (docs/instant-caching.md §2b).
/// Every caller that makes tic's caches (render_sequence, the viewer) applies it first,
/// so that tic and ic, and a view at rest and a render, draw the same M at the same spp
/// and size.
void resolve_ic_subsets(RenderSettings& settings, int width, int height);

/// The per-pass frame parameters render_frame uses for `camera` at width × height:
/// make_frame (device/frame.h) with the settings' shadow samples, seed, depth and scatter
/// limits and the scene's light power; the caller sets `pass`. The viewer (host/view)
/// builds its frames here too, so that its passes equal render's bit for bit.
TsFrame make_render_frame(const Camera& camera, int width, int height, const SceneBuffers& buffers,
                          const RenderSettings& settings);

/// Validates `settings` (validate_settings in render/parameters.h: throws InputError
/// naming the option and value, e.g. "--spp 0: must be in 1..1000000"), then renders. `buffers` are the
/// SceneBuffers the backend was made from. With `checkpoint`, the render resumes from
/// and saves checkpoints (see CheckpointSession) and throws Interrupted on SIGINT or
/// SIGTERM; stats then count only the passes rendered in this call. A frame resolved on
/// the device reads back its radiance alone unless settings.aovs, `checkpoint` or a
/// cluster needs the whole pass (IgiSettings::pass_aovs).
///
/// With a `cluster` of more than one rank (docs/distributed.md) every rank calls it with
/// the same settings: the ranks render disjoint passes (render/cluster.h, pass_owner) and
/// rank 0 adds them all in pass order, so its image is bit-identical to a one-process
/// render. Only rank 0 uses `checkpoint`, `progress` and `stats` (median_pass_seconds:
/// of the passes it rendered itself); the other ranks return an empty Image. A failure on
/// any rank throws RankFailure on every rank (render/cluster.h).
Image render_frame(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                   const RenderSettings& settings, RenderStats* stats = nullptr,
                   const ProgressFn& progress = {}, const CheckpointOptions* checkpoint = nullptr,
                   Cluster* cluster = nullptr);

}  // namespace tessera
