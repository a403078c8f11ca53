#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include <memory>
#include <optional>

#include "render/accumulator.h"
#include "render/checkpoint_session.h"
#include "render/cluster.h"
#include "render/pass_exchange.h"
#include "device/frame.h"
#include "render/parameters.h"
#include "util/error.h"

namespace tessera {

Image render_frame(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                   const RenderSettings& settings, RenderStats* stats, const ProgressFn& progress,
                   const CheckpointOptions* checkpoint, Cluster* cluster) {
    validate_settings(settings);
    const int w = settings.width > 0 ? settings.width : scene.camera.width;
    const int h = settings.height > 0 ? settings.height : scene.camera.height;
    TsFrame frame = make_frame(scene.camera, w, h, settings.shadow_samples, settings.seed, buffers.light_count);
    frame.max_depth = settings.max_depth;
    frame.max_scatter = settings.max_scatter;
    frame.light_power = buffers.light_power;
    const bool distributed = cluster && cluster->size() > 1;
    const bool lead = !distributed || cluster->rank() == 0;  // accumulates, checkpoints, reports
    Accumulator acc(lead ? w : 0, lead ? h : 0);
    CheckpointSession session(lead ? checkpoint : nullptr, scene, settings, w, h);
    uint32_t first = 0;
    std::unique_ptr<Integrator> integrator;
    auto set_up = [&] {
        first = session.restore(acc);
        integrator = make_integrator(backend, scene, buffers, settings);
    };
    if (distributed) {
        cluster->step(set_up);  // a checkpoint or integrator failing on any rank stops all
        first = cluster->broadcast(first);
        if (!lead) {
            run_worker(*cluster, *integrator, frame, first, settings.spp);
            return Image{};
        }
    } else {
        set_up();
    }
    std::optional<PassCollector> collector;
    if (distributed) collector.emplace(*cluster, size_t(w) * h * TS_PASS_FLOATS);
    std::vector<float> pass;
    std::vector<double> pass_seconds;  // of the passes rendered here
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    try {
        for (uint32_t i = first; i < settings.spp; ++i) {
            const auto t0 = clock::now();
            frame.pass = i;
            const int owner = distributed ? pass_owner(i, first, cluster->size()) : 0;
            if (owner == 0)
                integrator->render_pass(frame, pass);
            else if (!collector->receive(owner, i, pass))
                session.interrupt(acc);  // the owner got SIGINT/SIGTERM: save, as for our own
            acc.add(pass);
            if (owner == 0) pass_seconds.push_back(std::chrono::duration<double>(clock::now() - t0).count());
            if (progress)
                progress(i + 1, settings.spp, std::chrono::duration<double>(clock::now() - start).count(), first);
            session.after_pass(acc);
        }
    } catch (...) {
        if (collector) collector->stop(exit_code_of(std::current_exception()));
        throw;
    }
    if (collector) collector->stop(0);
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
