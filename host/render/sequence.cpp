#include "render/sequence.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "render/parameters.h"
#include "render/renderer.h"
#include "scene/posed_frames.h"
#include "util/error.h"

namespace tessera {
namespace fs = std::filesystem;

namespace {

bool parse_int(const std::string& s, int& v) {
    if (s.empty() || s.size() > 9) return false;
    for (const char c : s)
        if (c < '0' || c > '9') return false;
    v = std::stoi(s);
    return true;
}

}  // namespace

FrameRange parse_frame_range(const std::string& text, const Scene& scene) {
    const size_t colon = text.find(':');
    FrameRange r;
    if (colon == std::string::npos || !parse_int(text.substr(0, colon), r.first) ||
        !parse_int(text.substr(colon + 1), r.last))
        throw InputError("--frames " + text + ": expected A:B, two frame numbers >= 0");
    if (r.last < r.first) throw InputError("--frames " + text + ": the last frame is before the first");
    const int count = scene.animation.animated() ? scene.animation.frame_count : 1;
    if (r.last >= count)
        throw InputError("--frames " + text + ": scene " + scene.name + " has frames 0.." + std::to_string(count - 1) +
                         (scene.animation.animated() ? "" : " (it has no animation)"));
    return r;
}

int frame_digits(int last) { return std::max(4, static_cast<int>(std::to_string(std::max(last, 0)).size())); }

int frame_number_digits(const Scene& scene) {
    return frame_digits(scene.animation.animated() ? scene.animation.frame_count - 1 : 0);
}

fs::path frame_output_path(const fs::path& out, int frame, int digits) {
    char number[32];
    std::snprintf(number, sizeof number, ".%0*d", digits, frame);
    fs::path p = out;
    p.replace_filename(out.stem().string() + number + out.extension().string());
    return p;
}

void render_sequence(const Scene& rest, FrameRange range, const BackendOptions& backend_options,
                     const RenderSettings& sequence_settings, const FrameDoneFn& done,
                     const ProgressFn& progress) {
    validate_settings(sequence_settings);  // before the tic cache is made from them
    RenderSettings settings = sequence_settings;
    // tic's caches are made here: ic's M at this spp and size.
    const ImageSize size = render_image_size(settings, rest.camera);
    resolve_ic_subsets(settings, size.width, size.height);
    prepare_sequence(settings, rest);
    // One backend for the sequence, given each frame's scene with set_scene: the BVH is
    // rebuilt and every scene buffer re-uploaded (simple and correct for moving
    // geometry; refitting and uploading only what changed is a later optimisation),
    // while the device and its compiled programs stay. Each frame's buffers take the
    // textures' mip chains from the frame before's (make_scene_buffers).
    std::unique_ptr<SceneBuffers> buffers;  // declared before the backend, which reads it
    std::unique_ptr<Backend> backend;
    const PosedFrames frames(rest);  // the rest scene's motion bounds and frame 0's D, once
    for (int frame = range.first; frame <= range.last; ++frame) {
        const auto start = std::chrono::steady_clock::now();
        const Scene scene = frames.at(frame);
        auto next = std::make_unique<SceneBuffers>(make_scene_buffers(scene, buffers.get()));
        const EffectPlan plan = plan_effects(scene);
        give_scene(backend, backend_options, *next, plan);
        buffers = std::move(next);  // the previous frame's buffers go only now
        RenderStats stats;
        const Image image = render_frame(*backend, scene, *buffers, settings, &stats, progress);
        done(frame, image, stats,
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
}

}  // namespace tessera
