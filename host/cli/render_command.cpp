// `tessera render [SCENE] [options]`: renders a scene to EXR (+ PNG preview).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>
#include <unistd.h>

#include "backend/backend.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/parameter_options.h"
#include "image/atomic_file.h"
#include "image/background_writer.h"
#include "image/image_io.h"
#include "render/checkpoint.h"
#include "render/checkpoint_session.h"
#include "render/cluster.h"
#include "device/coincident_emitters.h"
#include "device/effect_plan.h"
#include "integrators/method.h"
#include "render/interrupt.h"
#include "render/parameters.h"
#include "render/renderer.h"
#include "device/scene_buffers.h"
#include "render/sequence.h"
#include "scene/loader.h"
#include "util/error.h"
#include "util/input_limits.h"

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
    std::string method = "ais";  ///< the thesis's method: a user who names none gets global illumination
    std::string components = "ss,id,pm,edge";
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

// `v`, a float setting widened to double, as the decimal the float was given as: 0.3f
// is 0.30000001192092896 as a double, "0.3" as the shortest text that reads back as it.
double as_given(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<float>(v));
    return std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
}

// The settings of the method, by option name without "--" ("tile": 3, "no-filter":
// false): each parameter the method reads (parameter_applies), as a flag whether the
// option is in effect, --width and --height as rendered (the camera's where not given),
// values in effect (--ic-subsets 0 as the subsets it resolved to, resolve_ic_subsets).
nlohmann::json settings_json(const RenderSettings& given, int width, int height) {
    RenderSettings s = given;
    resolve_ic_subsets(s, width, height);
    nlohmann::json j = nlohmann::json::object();
    for (const Parameter& p : render_parameters()) {
        if (!parameter_applies(p, s.method)) continue;
        const std::string key = std::string(p.option).substr(2);
        const double v = parameter_value(p, s);
        if (is_flag(p))
            j[key] = (v != 0) != p.negated;
        else if (is_integer(p))
            j[key] = static_cast<long long>(v);
        else
            j[key] = std::visit([&](auto get) {
                using T = std::remove_reference_t<decltype(get(s))>;
                return std::is_same_v<T, float> ? as_given(v) : v;
            }, p.field);
    }
    j["width"] = width;
    j["height"] = height;
    return j;
}

// Timing of this run for the accuracy sweeps (bench/accuracy). A pass is one frame of a
// progressive method: reaching `spp` passes costs about spp x median_pass_seconds.
// `tracer` is the backend's description (device and traversal).
// `ranks`: the MPI ranks that rendered it (1 alone), which divide the passes between them.
void write_stats_json(const fs::path& path, const RenderArgs& a, const RenderSettings& s, const RenderStats& stats,
                      const std::string& tracer, int ranks, int width, int height) {
    const nlohmann::json j = {
        {"median_pass_seconds", stats.median_pass_seconds},
        {"passes", stats.passes},  // rendered by this run (excludes passes restored by --resume)
        {"seconds", stats.seconds},  // wall time of those passes, set-up excluded
        {"method", a.method},
        {"backend", a.backend},
        {"tracer", tracer},
        {"spp", s.spp},
        {"shadow_samples", s.shadow_samples},
        {"mpi_ranks", ranks},
        {"settings", settings_json(s, width, height)},
    };
    const std::string text = j.dump(2) + "\n";
    write_file_atomic(path, text.data(), text.size());
}

// The PNG preview written beside an EXR.
fs::path png_beside(const fs::path& exr) {
    fs::path png = exr;
    png.replace_extension(".png");
    return png;
}

// Every file the run writes, checkpoint included, with the names messages give them.
std::vector<OutputFile> outputs_of(const RenderArgs& a, const fs::path& out, const std::optional<FrameRange>& frames,
                                   int digits) {
    std::vector<OutputFile> files;
    if (frames) {
        for (int f = frames->first; f <= frames->last; ++f) {
            const fs::path exr = frame_output_path(out, f, digits);
            files.push_back({exr, "frame " + std::to_string(f) + " of --out"});
            files.push_back({png_beside(exr), "the PNG preview of frame " + std::to_string(f)});
        }
        return files;
    }
    files.push_back({out, "--out"});
    files.push_back({png_beside(out), "--out's PNG preview"});
    files.push_back({checkpoint_path_for(out), "--out's checkpoint"});
    if (!a.stats_json.empty()) files.push_back({a.stats_json, "--stats-json"});
    return files;
}

// Stops a run interrupted by a signal that no checkpoint session saw (set-up, sequences).
void stop_if_interrupted(const std::string& when) {
    if (interrupt_signal())
        throw Interrupted("interrupted " + when + "; no checkpoint written (nothing of this run is saved)");
}

// Option combinations and values the settings table does not check, before any work.
void check_render_options(const RenderArgs& a, const CLI::App& cmd, const BackendOptions& bo) {
    check_data_dir(a.data_dir);
    if (cmd.count("--device") && bo.kind != BackendKind::OpenCL)
        throw InputError("--device " + a.device + ": only --backend opencl uses a device (this run has --backend " +
                         a.backend + ")");
    if (!a.frames.empty() && a.resume)
        throw InputError("--frames cannot be combined with --resume (checkpoints hold one still frame)");
    if (!a.frames.empty() && !a.stats_json.empty())
        throw InputError("--frames cannot be combined with --stats-json (it describes one still frame)");
    if (!a.frames.empty() && cmd.count("--checkpoint-interval"))
        throw InputError("--frames cannot be combined with --checkpoint-interval (a sequence keeps no checkpoint)");
}

// A setting the method does not read is left as given, with a note: it changes nothing
// (a script may pass one set of options to every method), but a user who expected it to
// should hear so.
void note_ignored_parameters(const CLI::App& cmd, Method method, const std::string& method_text) {
    for (const Parameter& p : render_parameters())
        if (cmd.count(p.option) && !parameter_applies(p, method))
            std::fprintf(stderr, "tessera: note: %s is read by %s; --method %s ignores it\n", p.option,
                         parameter_scope_text(p), method_text.c_str());
}

// --ic-view-rays weighs the candidate paths --ic-importance K > 1 chooses among; with
// K = 1 every path is kept and no view ray is traced (docs/instant-caching.md §2).
void note_view_rays_without_importance(const CLI::App& cmd, const RenderSettings& s) {
    if (cmd.count("--ic-view-rays") && (s.method == Method::Ic || s.method == Method::Tic) && s.ic.path_importance == 1)
        std::fprintf(stderr, "tessera: note: --ic-view-rays is read only with --ic-importance above 1 (it weighs the "
                             "candidate paths a view keeps); --ic-importance 1 keeps every path, so it changes nothing\n");
}

// The medium's settings on a scene without one: a note, as for a setting the method does
// not read (the same script may render foggy and clear scenes).
void note_medium_options(const CLI::App& cmd, const EffectPlan& plan, const fs::path& scene_path, Method method) {
    if (plan.medium) return;
    for (const char* option : {"--max-scatter", "--march-steps", "--single-scattering", "--point-medium-vpls",
                               "--uniform-march", "--ais-pm-trigger", "--ais-pm-cov"})
        if (cmd.count(option))
            std::fprintf(stderr, "tessera: note: %s: scene %s has no medium; it changes nothing\n", option,
                         scene_path.string().c_str());
    // ic and tic trace igi's VPL sets only for a medium's light: the cache's records
    // gather from VPLs of their own paths (--ic-paths).
    if (method == Method::Ic || method == Method::Tic)
        for (const char* option : {"--vpl-paths", "--vpl-importance"})
            if (cmd.count(option))
                std::fprintf(stderr, "tessera: note: %s: --method %s reads it only on a scene with a medium, and "
                                     "scene %s has none; it changes nothing (--ic-paths sets the cache's light paths)\n",
                             option, method_info(method).name, scene_path.string().c_str());
}

// A strongly forward or backward scattering medium with an igi-family method: a note, as
// these methods return only part of its multiple scattering (docs/igi.md §6, "Limit").
void note_peaked_phase(const RenderSettings& s, const Scene& scene, const EffectPlan& plan) {
    if (!igi_family(s.method) || !plan.medium || !(std::fabs(scene.medium.g) > 0.9f)) return;
    std::fprintf(stderr,
                 "tessera: note: the medium's g = %g: --method %s returns only part of the multiple scattering of "
                 "a medium this peaked (about 2/3 of pt's radiance at |g| = 0.99 in the foggy Cornell box; "
                 "docs/igi.md §6); --method pt is unbiased\n",
                 double(scene.medium.g), method_info(s.method).name);
}

// `direct` on a scene with a medium: a note, as it renders the scene as if clear
// (docs/path-tracing.md §6) and nothing else in the image says so.
void note_direct_without_medium(const RenderSettings& s, const EffectPlan& plan) {
    if (s.method != Method::Direct || !plan.medium) return;
    std::fprintf(stderr,
                 "tessera: note: --method direct ignores the scene's medium (no fog, no transmittance; "
                 "docs/path-tracing.md §6); pt, igi, ais, ais-max, ic and tic render it\n");
}

void run_sequence(const RenderArgs& a, const Scene& scene, FrameRange frames, const fs::path& out,
                  const BackendOptions& bo, RenderSettings& settings) {
    std::fprintf(stderr, "tessera: %s, %zu triangles, frames %d..%d\n", scene.name.c_str(), scene.triangle_count(),
                 frames.first, frames.last);
    {  // said once, of the first frame (animation moves objects, rarely onto each other)
        const Scene first = scene_at_frame(scene, frames.first);
        std::vector<glm::vec3> positions = first.positions;
        if (const size_t n = separate_coincident_emitters(first, positions).stacked)
            std::fprintf(stderr, "tessera: note: %s\n", stacked_emitters_text(n).c_str());
    }
    // A failing sequence writes no frame (every frame is renamed into place at the end). An
    // interrupted one (a signal) keeps the frames it finished, as a still render keeps its
    // checkpoint: they are complete, and --frames from the next one continues the animation.
    CommitGroup outputs;
    // Frame N's files are written while frame N+1 renders; declared after `outputs`, whose
    // temporaries its writes fill, so that a failing run's write in flight ends first.
    BackgroundWriter writes;
    std::string written;
    int frame_now = frames.first;
    auto stop_keeping_finished = [&](const std::string& when) {
        if (!interrupt_signal()) return;
        const std::string rest = "--frames " + std::to_string(frame_now) + ":" + std::to_string(frames.last);
        if (frame_now == frames.first)
            throw Interrupted("interrupted " + when + "; no frame finished, none written (" + rest +
                              " renders a sequence from the start; it keeps no checkpoint)");
        {
            const InterruptDeferral defer;
            writes.wait();  // the last finished frame's files
            outputs.commit();
        }
        std::fputs(written.c_str(), stdout);
        throw Interrupted("interrupted " + when + "; frames " + std::to_string(frames.first) + ".." +
                          std::to_string(frame_now - 1) + " are written, continue with " + rest +
                          (method_info(settings.method).temporal ? " (tic's cache then starts afresh)" : ""));
    };
    auto progress = [&](uint32_t done, uint32_t total, double elapsed, uint32_t restored) {
        print_progress(done, total, elapsed, restored);
        writes.check();  // a failed write of the frame before stops the run now, not at the frame's end
        if (done < total)
            stop_keeping_finished("in frame " + std::to_string(frame_now) + " after " + std::to_string(done) + " of " +
                                  std::to_string(total) + " spp");
    };
    render_sequence(scene, frames, bo, settings, [&](int frame, const Image& img, const RenderStats& stats, double seconds) {
        const fs::path exr = frame_output_path(out, frame, frame_number_digits(scene));
        const fs::path png = png_beside(exr);
        // A further signal waits for the write: the handler's clean-up would otherwise race
        // it for the temporaries (image/fatal_signal_cleanup.h).
        writes.start([&outputs, exr, png, exposure = a.exposure, image = img] {
            const InterruptDeferral defer;
            outputs.write(exr, [&](const fs::path& t) { write_exr(t, image); });
            outputs.write(png, [&](const fs::path& t) { write_png(t, image, exposure); });
        });
        std::fprintf(stderr, "tessera: frame %d: %.1f ms (%u spp in %.1f ms, the rest set-up)\n", frame, 1e3 * seconds,
                     stats.passes, 1e3 * stats.seconds);
        if (!stats.detail.empty()) std::fprintf(stderr, "  %s\n", stats.detail.c_str());
        written += exr.string() + "\n" + png.string() + "\n";
        frame_now = frame + 1;
        if (frame < frames.last) stop_keeping_finished("after frame " + std::to_string(frame));
    }, progress);
    {
        const InterruptDeferral defer;
        writes.wait();
        outputs.commit();
    }
    if (interrupt_signal())
        std::fprintf(stderr, "tessera: interrupted after the last pass: every frame is complete and written\n");
    std::fputs(written.c_str(), stdout);
}

// A distributed render (mpirun -n N, N > 1; docs/distributed.md) renders one still
// frame, and only what depends on nothing but the seed, the pixel and the pass index.
void check_distributed_options(const RenderArgs& a, const RenderSettings& s, const Cluster& cluster) {
    if (cluster.size() == 1) return;
    const std::string job = "a distributed render (" + std::to_string(cluster.size()) + " MPI ranks)";
    const MethodInfo& m = method_info(s.method);
    if (m.temporal)
        throw InputError("--method " + a.method + ": " + job + " cannot split its passes: its state (tic: the "
                         "instant cache) carries over from one pass to the next (--method ic rebuilds it per pass)");
    if (s.aovs && m.own_aovs)
        throw InputError("--aov with --method " + a.method + ": " + job + " cannot write them: the method's own AOV "
                         "channels are sums kept by one process (render AOVs without mpirun, or use direct or pt)");
    if (!a.frames.empty()) throw InputError("--frames " + a.frames + ": " + job + " renders one still frame");
}

void run_render(const RenderArgs& a, const CLI::App& cmd) {
    const InterruptScope interrupts;  // from the start: a signal during set-up is reported, not fatal
    Cluster& cluster = world_cluster();
    const bool lead = cluster.rank() == 0;  // the rank that writes files and reports
    fs::path scene_path, out;
    BackendOptions bo;
    RenderSettings settings = a.settings;
    Scene scene;
    std::optional<FrameRange> frames;
    std::optional<CheckpointOptions> ckpt;
    EffectPlan plan;
    SceneBuffers buffers;
    std::unique_ptr<Backend> backend;
    // Set-up: every rank does it; a failure on any rank stops them all with one message
    // from rank 0 naming that rank (Cluster::step; alone, the exception as it is).
    cluster.step([&] {
        reject_empty_values(cmd);
        scene_path = a.scene.empty() ? default_scene_path() : fs::path(a.scene);
        bo = BackendOptions{parse_backend_kind(a.backend), a.device};
        settings.method = parse_method(a.method);
        settings.igi.components = parse_components(a.components);
        if (cmd.count("--components") && !igi_family(settings.method))
            throw InputError("--components " + a.components + ": --method " + a.method +
                             " has no components (they select what igi, ais, ais-max, ic and tic compute)");
        if (cmd.count("--components") && (settings.igi.components & TS_COMPONENT_EDGE) &&
            !method_info(settings.method).adaptive)
            throw InputError("--components " + a.components + ": edge samples are an AIS component (--method ais or "
                             "ais-max), not --method " + a.method);
        validate_settings(settings);  // before the scene loads: a bad option fails at once
        if (lead) note_ignored_parameters(cmd, settings.method, a.method);
        if (lead) note_view_rays_without_importance(cmd, settings);
        check_render_options(a, cmd, bo);
        check_distributed_options(a, settings, cluster);
        if (method_info(settings.method).temporal && a.resume)
            throw InputError("--method " + a.method + " cannot be combined with --resume (a checkpoint does not hold "
                             "its state, tic's cache, so a resumed render would differ from the uninterrupted one)");
        // A note, not an error, as for the settings a method does not read: a script may pass
        // one set of options to every method (bench/accuracy does).
        if (lead && method_info(settings.method).temporal && cmd.count("--checkpoint-interval"))
            std::fprintf(stderr, "tessera: note: --checkpoint-interval: --method %s keeps no checkpoint (one would not "
                         "hold its state, tic's cache, so it could not be resumed); ignored\n", a.method.c_str());
        const DataPath data = make_data_path(a.data_dir.empty() ? std::nullopt : std::optional<fs::path>(a.data_dir));
        scene = load_scene(scene_path, data);
        (void)render_image_size(settings, scene.camera);  // a side scaled out of range fails here, before any work
        out = a.out.empty() ? default_output(scene, ".exr") : fs::path(a.out);
        require_exr_name("--out", out);
        if (!a.frames.empty()) frames = parse_frame_range(a.frames, scene);
        check_scene_options(settings, a.components, scene, scene_path);
        if (lead) {
            const EffectPlan scene_plan = plan_effects(scene);
            note_medium_options(cmd, scene_plan, scene_path, settings.method);
            note_peaked_phase(settings, scene, scene_plan);
            note_direct_without_medium(settings, scene_plan);
        }
        if (lead) print_scene_notes(scene.notes);
        // Before the scene's banner; rank 0 alone reads the checkpoint (render_frame).
        if (lead && a.resume) {
            require_checkpoint(checkpoint_path_for(out));
            check_checkpoint_file(checkpoint_path_for(out));  // a truncated or foreign file fails before the set-up
        }
        if (lead) {  // only rank 0 writes
            // Every output before the first ray: a run that cannot write its results does no work.
            const std::vector<OutputFile> files = outputs_of(a, out, frames, frame_number_digits(scene));
            check_outputs(files, scene.inputs);
            stop_if_interrupted("while loading the scene");
            check_output_directories(files);  // checkpoints are written there during the render too
        }
    });
    if (frames) return run_sequence(a, scene, *frames, out, bo, settings);
    cluster.step([&] {
        // A still of an animated scene is its frame 0 (the rest pose with frame 0's keys).
        if (scene.animation.animated()) scene = scene_at_frame(scene, 0);
        // tic keeps none: a checkpoint would not hold its cache, and --resume is refused.
        if (!method_info(settings.method).temporal) ckpt = CheckpointOptions{checkpoint_path_for(out), bo.kind, a.resume};
        // An interrupted render's passes are kept until the user says what to do with them:
        // a run of the same command without --resume would replace them at its first
        // checkpoint. Refused, not a note (a note scrolls by; hours of passes are gone).
        if (lead && ckpt && !a.resume && fs::exists(ckpt->path))
            throw InputError("--out " + out.string() + ": the checkpoint of an interrupted render is beside it, " +
                             ckpt->path.string() + ": continue it with --resume, or remove it to start over");
        plan = plan_effects(scene);
        buffers = make_scene_buffers(scene);
        backend = make_backend(bo, buffers, plan);
        if (lead) {
            std::fprintf(stderr, "tessera: %s, %zu triangles, %u lights, on %s", scene.name.c_str(),
                         scene.triangle_count(), buffers.light_count, backend->description().c_str());
            if (cluster.size() > 1) std::fprintf(stderr, ", %d MPI ranks", cluster.size());
            std::fprintf(stderr, "\n");
            for (const auto& line : plan.describe()) std::fprintf(stderr, "  %s\n", line.c_str());
            if (buffers.stacked_emitters > 0)
                std::fprintf(stderr, "tessera: note: %s\n", stacked_emitters_text(buffers.stacked_emitters).c_str());
        }
        stop_if_interrupted("before the first pass");
    });

    RenderStats stats;
    // Without a checkpoint session (tic) a signal is seen here, after the pass it ended.
    const ProgressFn progress = ckpt ? ProgressFn(print_progress)
                                     : [&a](uint32_t done, uint32_t total, double elapsed, uint32_t restored) {
                                           print_progress(done, total, elapsed, restored);
                                           if (done < total)
                                               stop_if_interrupted("after " + std::to_string(done) + " of " +
                                                                   std::to_string(total) + " spp (" + a.method + " keeps no checkpoint)");
                                       };
    Image img = render_frame(*backend, scene, buffers, settings, &stats, progress, ckpt ? &*ckpt : nullptr, &cluster);
    if (!lead) return;
    const fs::path png = png_beside(out);
    std::error_code ec;
    try {
        CommitGroup outputs;  // all of them or none
        outputs.write(out, [&](const fs::path& t) { write_exr(t, img); });
        outputs.write(png, [&](const fs::path& t) { write_png(t, img, a.exposure); });
        if (!a.stats_json.empty())
            outputs.write(a.stats_json, [&](const fs::path& t) {
                write_stats_json(t, a, settings, stats, backend->description(), cluster.size(), img.width, img.height);
            });
        const InterruptDeferral defer;
        outputs.commit();
    } catch (const RuntimeError& e) {
        // A periodic (or the resumed) checkpoint outlives the failed write: said, since the
        // next run of the command is refused beside it.
        if (ckpt && fs::exists(ckpt->path, ec))
            throw RuntimeError(std::string(e.what()) + "; the render's checkpoint " + ckpt->path.string() +
                               " is kept (the passes to its last save): once the outputs can be written, add --resume");
        throw;
    }
    if (ckpt) fs::remove(ckpt->path, ec);  // the render is complete: its checkpoint is of no further use
    if (!stats.detail.empty()) std::fprintf(stderr, "tessera: %s\n", stats.detail.c_str());
    std::fprintf(stderr, "tessera: %u spp in %.2f s (median %.1f ms per pass)", stats.passes, stats.seconds,
                 1e3 * stats.median_pass_seconds);
    if (a.resume) std::fprintf(stderr, " after %u spp from the checkpoint", a.settings.spp - stats.passes);
    std::fprintf(stderr, "\n");
    if (interrupt_signal())
        std::fprintf(stderr, "tessera: interrupted after the last pass: the render is complete and its outputs "
                             "are written (no checkpoint needed)\n");
    std::printf("%s\n%s\n", out.c_str(), png.c_str());
}

}  // namespace

void add_render_command(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene (default: the Cornell box of the source tree this binary was built from)");
    cmd->add_option("scene", args->scene, "Scene file (.json); default " + default_scene_path().string());
    cmd->add_option("--backend", args->backend, "opencl or embree")->capture_default_str();
    cmd->add_option("--device", args->device, "OpenCL device: index or name substring (see `tessera devices`)");
    cmd->add_option("--method", args->method, "Rendering method: " + method_names())
        ->capture_default_str();
    cmd->add_option("--components", args->components, "igi/ais: components to compute, e.g. ss,id,pm (ais: also edge)")
        ->capture_default_str();
    add_parameter_options(*cmd, args->settings);  // --spp, --tile, ...: render/parameters.cpp
    cmd->add_option("--out", args->out, "Output EXR (default out/<scene file's name>.exr, e.g. out/box.exr for box.json); a PNG preview is written beside it");
    cmd->add_option("--exposure", args->exposure, "PNG preview exposure in stops")
        ->capture_default_str()
        ->check(finite_number_in("--exposure", -limits::kExposureStops, limits::kExposureStops, false));
    cmd->add_flag("--resume", args->resume,
                  "Continue from the checkpoint beside --out (<out>.ckpt) left by an interrupted render");
    cmd->add_option("--frames", args->frames,
                    "Animated scene: render frames A:B (A to B inclusive) to <out stem>.####.exr (+ .png)");
    cmd->add_option("--stats-json", args->stats_json,
                    "Write timing as JSON: {median_pass_seconds, passes, seconds, ..., settings} (seconds exclude set-up; settings: "
                    "the value of every option the method reads)");
    cmd->add_option("--data-dir", args->data_dir, "Directory searched for scene data (before $TESSERA_DATA)");
    cmd->callback([args, cmd] { run_render(*args, *cmd); });
}

}  // namespace tessera::cli
