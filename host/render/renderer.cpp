#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include <memory>

#include "render/accumulator.h"
#include "render/checkpoint_session.h"
#include "device/frame.h"
#include "render/parameters.h"
#include "util/error.h"

namespace tessera {

TsFrame make_render_frame(const Camera& camera, int width, int height, const SceneBuffers& buffers,
                          const RenderSettings& settings) {
    TsFrame frame = make_frame(camera, width, height, settings.shadow_samples, settings.seed, buffers.light_count);
    frame.max_depth = settings.max_depth;
    frame.max_scatter = settings.max_scatter;
    frame.light_power = buffers.light_power;
    return frame;
}

Image render_frame(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                   const RenderSettings& settings, RenderStats* stats, const ProgressFn& progress,
                   const CheckpointOptions* checkpoint) {
    validate_settings(settings);
    const int w = settings.width > 0 ? settings.width : scene.camera.width;
    const int h = settings.height > 0 ? settings.height : scene.camera.height;
    TsFrame frame = make_render_frame(scene.camera, w, h, buffers, settings);
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
