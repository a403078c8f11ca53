// Rendering a range of frames of an animated scene (`tessera render --frames A:B`).
#pragma once
#include <filesystem>
#include <functional>
#include <string>

#include "backend/backend.h"
#include "image/image_io.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace tessera {

/// Frames first..last, inclusive.
struct FrameRange {
    int first = 0;
    int last = 0;
};

/// Parses `--frames A:B` (non-negative integers, A <= B) and checks it against the
/// animation of `scene` (B < frame_count; only 0:0 for a static scene). Throws
/// InputError naming --frames when it is malformed or out of range.
FrameRange parse_frame_range(const std::string& text, const Scene& scene);

/// The file frame `frame` of a sequence is written to: `out` with the frame number,
/// zero-padded to `digits` (default 4), inserted before the extension (out/box.exr, frame
/// 7 → out/box.0007.exr).
std::filesystem::path frame_output_path(const std::filesystem::path& out, int frame, int digits = 4);

/// The digits a sequence whose last frame is `last` numbers its frames with: 4, or as many
/// as `last` has, so that every name of one sequence has as many digits and they sort in
/// frame order (frames 9999 and 10000 of 100,000: .09999 and .10000).
int frame_digits(int last);

/// frame_digits of the last frame of `scene`'s animation (frame 0 for a static scene).
int frame_number_digits(const Scene& scene);

/// Called after each frame with the frame number, its image, its render statistics and
/// the frame's wall time in seconds including posing, flattening and backend set-up.
using FrameDoneFn =
    std::function<void(int frame, const Image& image, const RenderStats& stats, double seconds)>;

/// Renders frames range.first..range.last of `rest` in order: each frame is posed with
/// PosedFrames (equal to scene_at_frame), flattened and rendered on one backend made for the first frame and
/// given each later frame with Backend::set_scene. `settings` is
/// the same for every frame; with --method tic one temporal instant cache is made for
/// the sequence (settings.ic_state is ignored) and kept across its frames. Throws what
/// scene_at_frame, make_backend and render_frame throw.
void render_sequence(const Scene& rest, FrameRange range, const BackendOptions& backend,
                     const RenderSettings& settings, const FrameDoneFn& done, const ProgressFn& progress = {});

}  // namespace tessera
