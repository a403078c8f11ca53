#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include <memory>

#include "render/accumulator.h"
#include "render/checkpoint_session.h"
#include "device/frame.h"
#include "util/error.h"

namespace tessera {
namespace {

void validate(const RenderSettings& s) {
    if (s.max_depth < 1 || s.max_depth > 100000) throw InputError("--max-depth must be in 1..100000");
    if (s.spp < 1 || s.spp > 1000000) throw InputError("--spp must be in 1..1000000");
    if (s.shadow_samples < 1 || s.shadow_samples > 4096)
        throw InputError("--shadow-samples must be in 1..4096");
    if (s.width < 0 || s.width > 16384) throw InputError("--width must be in 1..16384");
    if (s.height < 0 || s.height > 16384) throw InputError("--height must be in 1..16384");
    if (!(s.checkpoint_interval_s >= 0)) throw InputError("--checkpoint-interval must be >= 0");
    if (s.igi.tile < 1 || s.igi.tile > 8) throw InputError("--tile must be in 1..8");
    if (s.igi.paths_per_set < 1 || s.igi.paths_per_set > 65536) throw InputError("--vpl-paths must be in 1..65536");
    if (!(s.igi.clamp_c >= 0.0f)) throw InputError("--clamp must be >= 0");
    if (s.ic.paths < 1 || s.ic.paths > 65536) throw InputError("--ic-paths must be in 1..65536");
    if (!(s.ic.error_bound >= 1e-3f && s.ic.error_bound <= 2.0f)) throw InputError("--ic-error must be in [0.001, 2]");
}

}  // namespace

Image render_frame(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                   const RenderSettings& settings, RenderStats* stats, const ProgressFn& progress,
                   const CheckpointOptions* checkpoint) {
    validate(settings);
    const int w = settings.width > 0 ? settings.width : scene.camera.width;
    const int h = settings.height > 0 ? settings.height : scene.camera.height;
    TsFrame frame = make_frame(scene.camera, w, h, settings.shadow_samples, settings.seed, buffers.light_count);
    frame.max_depth = settings.max_depth;
    frame.max_scatter = settings.max_scatter;
    frame.light_power = buffers.light_power;
    Accumulator acc(w, h);
    CheckpointSession session(checkpoint, scene, settings, w, h);
    const uint32_t first = session.restore(acc);
    const std::unique_ptr<Integrator> integrator = make_integrator(backend, scene, buffers, settings);
    std::vector<float> pass;
    std::vector<double> pass_seconds;
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    for (uint32_t i = first; i < settings.spp; ++i) {
        const auto t0 = clock::now();
        frame.pass = i;
        integrator->render_pass(frame, pass);
        acc.add(pass);
        pass_seconds.push_back(std::chrono::duration<double>(clock::now() - t0).count());
        if (progress)
            progress(i + 1, settings.spp, std::chrono::duration<double>(clock::now() - start).count(), first);
        session.after_pass(acc);
    }
    if (stats) {
        stats->passes = settings.spp - first;
        stats->seconds = std::chrono::duration<double>(clock::now() - start).count();
        std::nth_element(pass_seconds.begin(), pass_seconds.begin() + pass_seconds.size() / 2, pass_seconds.end());
        stats->median_pass_seconds = pass_seconds.empty() ? 0.0 : pass_seconds[pass_seconds.size() / 2];
    }
    if (stats) integrator->report(*stats);
    Image image = acc.mean_image(settings.aovs, settings.variance);
    if (settings.aovs) integrator->add_aov_channels(image, settings.spp - first);
    return image;
}

}  // namespace tessera
