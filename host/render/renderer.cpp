#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <memory>
#include <optional>
#include <string>

#include "render/accumulator.h"
#include "render/checkpoint.h"
#include "render/checkpoint_session.h"
#include "render/cluster.h"
#include "render/pass_exchange.h"
#include "device/frame.h"
#include "gi/instant_cache.h"
#include "render/parameters.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera {
namespace {

// What a distributed render's ranks must agree on for their passes to fit together: the
// checkpoint identity (scene file and data, method, seed, shadow samples, depths, size,
// backend, the method's other settings) but the scene's path, which may differ between
// machines, plus --spp.
uint64_t render_fingerprint(const Scene& scene, const RenderSettings& settings, int w, int h, BackendKind backend) {
    const RunIdentity id = make_run_identity(scene, settings, w, h, backend);
    const std::string key = std::to_string(id.scene_file_hash) + " " + std::to_string(id.scene_data_hash) + " " +
                            id.method + " " + std::to_string(id.seed) + " " + std::to_string(id.shadow_samples) + " " +
                            std::to_string(id.max_depth) + " " + std::to_string(id.max_scatter) + " " +
                            std::to_string(id.width) + " " + std::to_string(id.height) + " " + id.backend + " " +
                            std::to_string(settings.spp) + " " + id.method_settings;
    return fnv1a64(key.data(), key.size());
}

}  // namespace

IntegratorSettings integrator_settings(const RenderSettings& settings, int width, int height) {
    RenderSettings resolved = settings;
    resolve_ic_subsets(resolved, width, height);
    IntegratorSettings s = resolved;
    s.igi.component_aovs = s.igi.component_aovs || settings.aovs;
    return s;
}

ImageSize render_image_size(const RenderSettings& settings, const Camera& camera) {
    ImageSize size{settings.width > 0 ? settings.width : camera.width,
                   settings.height > 0 ? settings.height : camera.height};
    // One side given: the other keeps the camera's aspect ratio, so the picture is scaled,
    // not cropped (the camera keeps its vertical field of view).
    const auto scaled = [](int given, int to, int from, const char* option, const char* other) {
        const long long side = std::max(1LL, std::llround(double(given) * to / from));
        if (side > limits::kImageSide)
            throw InputError(std::string(option) + " " + std::to_string(given) + ": at the camera's aspect ratio the " +
                             other + " would be " + std::to_string(side) + " px, above " +
                             std::to_string(limits::kImageSide) + "; give " + other + " too");
        return int(side);
    };
    if (settings.width > 0 && settings.height <= 0)
        size.height = scaled(settings.width, camera.height, camera.width, "--width", "--height");
    else if (settings.height > 0 && settings.width <= 0)
        size.width = scaled(settings.height, camera.width, camera.height, "--height", "--width");
    return size;
}

void resolve_ic_subsets(RenderSettings& settings, int width, int height) {
    if (settings.ic.subsets == 0)
        settings.ic.subsets = ic_subsets_for(settings.spp, uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0)));
}

TsFrame make_render_frame(const Camera& camera, int width, int height, const SceneBuffers& buffers,
                          const RenderSettings& settings) {
    TsFrame frame = make_frame(camera, width, height, settings.shadow_samples, settings.seed, buffers.light_count);
    frame.max_depth = settings.max_depth;
    frame.max_scatter = settings.max_scatter;
    frame.light_power = buffers.light_power;
    if (!settings.texture_filter) frame.pixel_cone = 0.0f;
    // pt's far roulette around the surfaces and the camera: a camera path's first
    // vertices lie near the camera, however far it stands from the scene.
    const SceneBounds& b = buffers.bounds;
    set_far_region(frame, far_region_of(glm::min(b.lo, camera.position), glm::max(b.hi, camera.position)));
    return frame;
}

Image render_frame(Backend& backend, const Scene& scene, const SceneBuffers& buffers,
                   const RenderSettings& settings, RenderStats* stats, const ProgressFn& progress,
                   const CheckpointOptions* checkpoint, Cluster* cluster) {
    validate_settings(settings);
    const auto [w, h] = render_image_size(settings, scene.camera);
    TsFrame frame = make_render_frame(scene.camera, w, h, buffers, settings);
    const bool distributed = cluster && cluster->size() > 1;
    const bool lead = !distributed || cluster->rank() == 0;  // accumulates, checkpoints, reports
    Accumulator acc(lead ? w : 0, lead ? h : 0);
    CheckpointSession session(lead ? checkpoint : nullptr, scene, settings, w, h);
    uint32_t first = 0;
    std::unique_ptr<Integrator> integrator;
    auto set_up = [&] {
        first = session.restore(acc);
        IntegratorSettings is = integrator_settings(settings, w, h);
        // The pass's albedo, normal and depth come back only where something reads them:
        // the image's AOVs, a checkpoint (a run resumed with --aov needs every pass's),
        // and MPI's passes, which are whole.
        is.igi.pass_aovs = settings.aovs || checkpoint != nullptr || distributed;
        integrator = make_integrator(backend, scene, buffers, is);
        session.keep_method_sums(integrator->aov_sums());
    };
    if (distributed) {
        uint64_t mine = 0;
        cluster->step([&] {  // a checkpoint or integrator failing on any rank stops all
            set_up();
            mine = render_fingerprint(scene, settings, w, h, checkpoint ? checkpoint->backend : BackendKind::OpenCL);
        });
        first = cluster->broadcast(first);
        const uint64_t lead_fingerprint =
            uint64_t(cluster->broadcast(uint32_t(mine >> 32))) << 32 | cluster->broadcast(uint32_t(mine));
        cluster->step([&] {
            if (mine != lead_fingerprint)
                throw InputError("its scene file, scene data or settings differ from rank 0's (every rank must "
                                 "render the same scene data with the same --method, --spp, --seed, "
                                 "--shadow-samples, --max-depth, --max-scatter, --width, --height, --backend "
                                 "and the method's other settings)");
        });
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
    // Programs compiled at their first launch are set-up, not pass time (--stats-json's
    // seconds exclude set-up): a cold OpenCL cache put seconds into pass 0.
    const double build_before = backend.program_build_seconds();
    try {
        for (uint32_t i = first; i < settings.spp; ++i) {
            const auto t0 = clock::now();
            const double build_t0 = backend.program_build_seconds();
            frame.pass = i;
            const int owner = distributed ? pass_owner(i, first, cluster->size()) : 0;
            if (owner == 0)
                integrator->render_pass(frame, pass);
            else if (!collector->receive(owner, i, pass))
                session.interrupt(acc);  // the owner got SIGINT/SIGTERM: save, as for our own
            acc.add(pass);
            if (owner == 0)
                pass_seconds.push_back(std::chrono::duration<double>(clock::now() - t0).count() -
                                       (backend.program_build_seconds() - build_t0));
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
        stats->seconds = std::chrono::duration<double>(clock::now() - start).count() -
                         (backend.program_build_seconds() - build_before);
        std::nth_element(pass_seconds.begin(), pass_seconds.begin() + pass_seconds.size() / 2, pass_seconds.end());
        stats->median_pass_seconds = pass_seconds.empty() ? 0.0 : pass_seconds[pass_seconds.size() / 2];
    }
    if (stats) integrator->report(*stats);
    Image image = acc.mean_image(settings.aovs, settings.variance);
    // The method's sums hold every pass: a resumed render's were restored with the rest.
    if (settings.aovs) integrator->add_aov_channels(image, settings.spp);
    return image;
}

}  // namespace tessera
