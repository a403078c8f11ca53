// `tessera render [SCENE] [options]`: renders a scene to EXR (+ PNG preview).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <unistd.h>

#include "backend/backend.h"
#include "cli/commands.h"
#include "cli/parameter_options.h"
#include "image/atomic_file.h"
#include "image/image_io.h"
#include "render/checkpoint.h"
#include "render/checkpoint_session.h"
#include "device/effect_plan.h"
#include "render/parameters.h"
#include "render/renderer.h"
#include "device/scene_buffers.h"
#include "render/sequence.h"
#include "scene/loader.h"
#include "util/error.h"

#include <nlohmann/json.hpp>

namespace tessera::cli {
namespace fs = std::filesystem;
namespace {

struct RenderArgs {
    std::string scene;
    std::string backend = "opencl";
    std::string device;
    std::string out;
    std::string data_dir;
    std::string method = "direct";
    std::string components = "ss,id,pm";
    std::string stats_json;
    std::string frames;  ///< --frames A:B, "" for one still image
    float exposure = 0.0f;
    bool resume = false;
    RenderSettings settings;
};

// `restored`: passes loaded from a checkpoint, not part of this run's rate.
void print_progress(uint32_t done, uint32_t total, double elapsed, uint32_t restored) {
    static const bool tty = ::isatty(STDERR_FILENO);
    const double rate = (done - restored) / std::max(elapsed, 1e-9);
    const double eta = (total - done) / std::max(rate, 1e-9);
    if (tty) {
        std::fprintf(stderr, "\r  %u/%u spp  %.1f spp/s  ETA %.0f s   ", done, total, rate, eta);
        if (done == total) std::fprintf(stderr, "\n");
    } else if (done == total || done % std::max(1u, total / 10) == 0) {
        std::fprintf(stderr, "  %u/%u spp, %.1f spp/s, ETA %.0f s\n", done, total, rate, eta);
    }
}

// Timing of this run for the accuracy sweeps (bench/accuracy). A pass is one frame of a
// progressive method: reaching `spp` passes costs about spp x median_pass_seconds.
void write_stats_json(const RenderArgs& a, const RenderSettings& s, const RenderStats& stats) {
    const nlohmann::json j = {
        {"median_pass_seconds", stats.median_pass_seconds},
        {"passes", stats.passes},  // rendered by this run (excludes passes restored by --resume)
        {"seconds", stats.seconds},  // wall time of those passes, set-up excluded
        {"method", a.method},
        {"backend", a.backend},
        {"spp", s.spp},
        {"shadow_samples", s.shadow_samples},
    };
    const std::string text = j.dump(2) + "\n";
    write_file_atomic(a.stats_json, text.data(), text.size());
}

void run_sequence(const RenderArgs& a, const Scene& scene, FrameRange frames, const fs::path& out,
                  const BackendOptions& bo, RenderSettings& settings) {
    std::fprintf(stderr, "tessera: %s, %zu triangles, frames %d..%d\n", scene.name.c_str(), scene.triangle_count(),
                 frames.first, frames.last);
    render_sequence(scene, frames, bo, settings, [&](int frame, const Image& img, const RenderStats& stats, double seconds) {
        const fs::path exr = frame_output_path(out, frame);
        fs::path png = exr;
        png.replace_extension(".png");
        write_exr(exr, img);
        write_png(png, img, a.exposure);
        std::fprintf(stderr, "tessera: frame %d: %.2f s (%u spp in %.2f s, the rest set-up)\n", frame, seconds,
                     stats.passes, stats.seconds);
        if (!stats.detail.empty()) std::fprintf(stderr, "  %s\n", stats.detail.c_str());
        std::printf("%s\n%s\n", exr.c_str(), png.c_str());
        std::fflush(stdout);
    }, print_progress);
}

void run_render(const RenderArgs& a) {
    const fs::path scene_path = a.scene.empty() ? default_scene_path() : fs::path(a.scene);
    const DataPath data = make_data_path(a.data_dir.empty() ? std::nullopt : std::optional<fs::path>(a.data_dir));
    BackendOptions bo{parse_backend_kind(a.backend), a.device};
    RenderSettings settings = a.settings;
    settings.method = parse_method(a.method);
    settings.igi.components = parse_components(a.components);
    validate_settings(settings);  // before the scene loads: a bad option fails at once
    if (!a.frames.empty() && a.resume)
        throw InputError("--frames cannot be combined with --resume (checkpoints hold one still frame)");
    if (settings.method == Method::Tic && a.resume)
        throw InputError("--method tic cannot be combined with --resume (a checkpoint does not hold the cache, so a "
                         "resumed render would differ from the uninterrupted one)");
    if (!a.frames.empty() && !a.stats_json.empty())
        throw InputError("--frames cannot be combined with --stats-json (it describes one still frame)");
    Scene scene = load_scene(scene_path, data);
    const fs::path out = a.out.empty() ? fs::path("out") / (scene.name + ".exr") : fs::path(a.out);
    if (out.extension() != ".exr") throw InputError("--out " + out.string() + ": must end in .exr");
    std::optional<FrameRange> frames;
    if (!a.frames.empty()) frames = parse_frame_range(a.frames, scene);
    if (!out.parent_path().empty()) {  // before rendering: checkpoints are written there too
        std::error_code ec;
        fs::create_directories(out.parent_path(), ec);
        if (ec) throw RuntimeError("cannot create output directory " + out.parent_path().string() + ": " + ec.message());
    }
    if (frames) return run_sequence(a, scene, *frames, out, bo, settings);
    // A still of an animated scene is its frame 0 (the rest pose with frame 0's keys).
    if (scene.animation.animated()) scene = scene_at_frame(scene, 0);
    const CheckpointOptions ckpt{checkpoint_path_for(out), bo.kind, a.resume};
    if (!a.resume && fs::exists(ckpt.path))
        std::fprintf(stderr, "tessera: note: %s exists; starting over (it will be replaced; --resume continues it)\n",
                     ckpt.path.c_str());

    const EffectPlan plan = plan_effects(scene);
    const SceneBuffers buffers = make_scene_buffers(scene);
    std::unique_ptr<Backend> backend = make_backend(bo, buffers, plan);
    std::fprintf(stderr, "tessera: %s, %zu triangles, %u lights, on %s\n", scene.name.c_str(),
                 scene.triangle_count(), buffers.light_count, backend->description().c_str());
    for (const auto& line : plan.describe()) std::fprintf(stderr, "  %s\n", line.c_str());

    RenderStats stats;
    Image img = render_frame(*backend, scene, buffers, settings, &stats, print_progress, &ckpt);
    fs::path png = out;
    png.replace_extension(".png");
    write_exr(out, img);
    write_png(png, img, a.exposure);
    std::error_code ec;
    fs::remove(ckpt.path, ec);  // the render is complete: its checkpoint is of no further use
    if (!stats.detail.empty()) std::fprintf(stderr, "tessera: %s\n", stats.detail.c_str());
    std::fprintf(stderr, "tessera: %u spp in %.2f s (median %.1f ms per pass)", stats.passes, stats.seconds,
                 1e3 * stats.median_pass_seconds);
    if (a.resume) std::fprintf(stderr, " after %u spp from the checkpoint", a.settings.spp - stats.passes);
    std::fprintf(stderr, "\n");
    if (!a.stats_json.empty()) write_stats_json(a, settings, stats);
    std::printf("%s\n%s\n", out.c_str(), png.c_str());
}

}  // namespace

void add_render_command(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene (default: the built-in Cornell box)");
    cmd->add_option("scene", args->scene, "Scene file (.json)");
    cmd->add_option("--backend", args->backend, "opencl or embree")->capture_default_str();
    cmd->add_option("--device", args->device, "OpenCL device: index or name substring (see `tessera devices`)");
    cmd->add_option("--method", args->method, "Rendering method: direct, pt, igi, ais, ais-max, ic or tic")
        ->capture_default_str();
    cmd->add_option("--components", args->components, "igi/ais: components to compute, e.g. ss,id,pm")
        ->capture_default_str();
    add_parameter_options(*cmd, args->settings);  // --spp, --tile, ...: render/parameters.cpp
    cmd->add_option("--out", args->out, "Output EXR (default out/<scene>.exr); a PNG preview is written beside it");
    cmd->add_option("--exposure", args->exposure, "PNG preview exposure in stops")->capture_default_str();
    cmd->add_flag("--resume", args->resume,
                  "Continue from the checkpoint beside --out (<out>.ckpt) left by an interrupted render");
    cmd->add_option("--frames", args->frames,
                    "Animated scene: render frames A..B (inclusive) to <out stem>.####.exr (+ .png)");
    cmd->add_option("--stats-json", args->stats_json,
                    "Write timing as JSON: {median_pass_seconds, passes, seconds, ...} (seconds exclude set-up)");
    cmd->add_option("--data-dir", args->data_dir, "Directory searched for scene data (before $TESSERA_DATA)");
    cmd->callback([args] { run_render(*args); });
}

}  // namespace tessera::cli
