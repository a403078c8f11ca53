// `tessera view [SCENE] [options]`: the interactive viewer (docs/viewer.md). The window lives in
// a module loaded with dlopen (view/window_api.h); `--headless` runs the same frame loop
// (view/view_loop.h) with no window and no OpenGL at all.
#include <dlfcn.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "backend/backend.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/parameter_options.h"
#include "device/coincident_emitters.h"
#include "image/image_io.h"
#include "integrators/method.h"
#include "render/interrupt.h"
#include "render/parameters.h"
#include "render/renderer.h"
#include "render/sequence.h"
#include "scene/loader.h"
#include "util/error.h"
#include "util/input_limits.h"
#include "view/camera_path.h"
#include "view/frame_budget.h"
#include "view/input.h"
#include "view/view_loop.h"
#include "view/view_session.h"
#include "view/window_api.h"

#ifndef TESSERA_VIEW_WINDOW
#define TESSERA_VIEW_WINDOW 0
#endif

namespace tessera::cli {
namespace fs = std::filesystem;
using namespace tessera::view;
namespace {

// Bounds of the viewer's real options: far above any use (a 1000 fps budget is 1 ms a
// frame; 1e12 scene units per second crosses any float scene in a frame), low enough
// that what they feed (a frame time, a camera step) stays finite.
constexpr double kMaxTargetFps = 1000.0;
constexpr double kMaxSpeed = 1e12;

struct ViewArgs {
    std::string scene, backend = "opencl", device, method = "igi", components = "ss,id,pm,edge", data_dir;
    std::string frames, camera_path, input_script, frame_images, times, screenshot, screenshot_window, reference;
    std::string pareto;
    int screenshot_window_frame = 10;
    float exposure = 0.0f, speed = 0.0f;
    double target_fps = 0.0, min_scale = view::BudgetOptions{}.min_scale;
    bool headless = false, record = false, fixed_dt = false;
    RenderSettings settings;
};

// Runs the loop in the window module; exceptions of the frame loop are carried across it.
class CliWindowHost final : public WindowHost {
public:
    CliWindowHost(ViewSession& session, ViewLoop& loop, const ViewArgs& a) : session_(session), loop_(loop), args_(a) {}
    int width() const override { return session_.width(); }
    int height() const override { return session_.height(); }
    std::string title() const override {
        return "Tessera: " + (args_.scene.empty() ? default_scene_path().string() : args_.scene);
    }
    void input(const InputEvent& e) override { guard([&] { session_.handle(e); }); }
    void frame(double dt) override { guard([&] { loop_.step(dt); }); }
    bool done() const override { return error_ || loop_.done(); }
    bool idle() const override { return session_.idle() && !loop_.scripted(); }
    const std::vector<uint8_t>& pixels() override {
        session_.display(pixels_);
        return pixels_;
    }
    bool hud_visible() const override { return session_.hud_visible(); }
    std::vector<std::string> hud(double fps) override { return session_.hud_lines(fps); }
    int capture_frame() const override { return args_.screenshot_window.empty() ? -1 : args_.screenshot_window_frame; }
    void window_captured(const std::vector<uint8_t>& rgba, int w, int h) override {
        guard([&] {
            if (rgba.size() != size_t(w) * size_t(h) * 4u)
                throw RuntimeError("cannot write '" + args_.screenshot_window + "': the window's capture holds " +
                                   std::to_string(rgba.size()) + " bytes, not " + std::to_string(w) + "x" +
                                   std::to_string(h) + " RGBA pixels");
            write_png_rgba8(args_.screenshot_window, rgba.data(), w, h);
            std::printf("%s\n", args_.screenshot_window.c_str());
        });
    }
    void rethrow() const {
        if (error_) std::rethrow_exception(error_);
    }

private:
    template <class F>
    void guard(F&& f) {
        if (error_) return;
        try {
            f();
        } catch (...) {
            error_ = std::current_exception();
        }
    }
    ViewSession& session_;
    ViewLoop& loop_;
    const ViewArgs& args_;
    std::vector<uint8_t> pixels_;
    std::exception_ptr error_;
};

[[noreturn]] void no_window(const std::string& why) {
    throw RuntimeError("tessera view cannot open a window: " + why +
                       "; use `tessera view --headless` or `tessera render`");
}

// The window module's entry points, loaded before the scene so that a missing display
// or library costs one line and no work.
struct WindowModule {
    int (*probe)(char*, size_t) = nullptr;
    int (*run)(WindowHost*, char*, size_t) = nullptr;
};

WindowModule load_window_module() {
    if (!TESSERA_VIEW_WINDOW)
        no_window("this build has no viewer window (GLFW, Xlib, OpenGL or Dear ImGui were not found when it was configured)");
    const fs::path module = fs::read_symlink("/proc/self/exe").parent_path() / "libtessera_view_window.so";
    // The module stays loaded to the end: GLFW and Mesa may have registered exit handlers.
    void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) no_window(std::string("cannot load ") + module.string() + " (" + dlerror() + ")");
    auto abi = reinterpret_cast<int (*)()>(dlsym(handle, "tessera_view_window_abi"));
    WindowModule m;
    m.probe = reinterpret_cast<int (*)(char*, size_t)>(dlsym(handle, "tessera_view_window_probe"));
    m.run = reinterpret_cast<int (*)(WindowHost*, char*, size_t)>(dlsym(handle, "tessera_view_window_run"));
    if (!abi || !m.probe || !m.run || abi() != kWindowAbiVersion)
        no_window(module.string() + " is not this build's window module");
    char error[512] = {0};
    if (m.probe(error, sizeof error) != 0) no_window(error);
    return m;
}

// Runs the window's frame loop. Returns "" when it ended as asked (Esc, the window
// closed), or why the display went away mid-run (the run's frames are then still written
// before the error); throws when no window could be opened.
std::string run_window(const WindowModule& module, ViewSession& session, ViewLoop& loop, const ViewArgs& a) {
    CliWindowHost host(session, loop, a);
    char error[512] = {0};
    const int rc = module.run(&host, error, sizeof error);
    host.rethrow();
    if (rc == kWindowLostDisplay) return error;
    if (rc != 0) no_window(error);
    return "";
}

// The scene's name as a file name in bench/results/accuracy ("" when it cannot be one:
// a "/" in it, "." or ".."), so that a name never reaches outside that directory.
std::string result_file_stem(const Scene& scene) {
    const std::string& n = scene.name;
    return n.find('/') != std::string::npos || n == "." || n == ".." ? "" : n;
}

std::vector<BudgetPoint> load_pareto(const ViewArgs& a, const Scene& scene) {
    fs::path csv = a.pareto;
    if (csv.empty()) {
        const fs::path dir = fs::path(TESSERA_SOURCE_DIR) / "bench/results/accuracy";
        const std::string stem = result_file_stem(scene);
        csv = !stem.empty() && fs::exists(dir / (stem + ".csv")) ? dir / (stem + ".csv") : dir / "cornell-box.csv";
    }
    if (!fs::exists(csv)) throw InputError("--target-fps needs an accuracy sweep: " + csv.string() + " does not exist (--pareto FILE.csv)");
    // A method without rows (ic, tic, pt, direct) keeps its own settings: the budget then
    // changes only the resolution (docs/viewer.md §4).
    return read_pareto_front(csv, a.backend);
}

// The pixels of the sweep's images, from the JSON bench/accuracy writes beside the CSV
// (0 when there is none): the first moving frame's prediction scales the sweep's times by
// the window's pixels over these.
double pareto_pixels(const ViewArgs& a, const Scene& scene) {
    if (a.pareto.empty() && result_file_stem(scene).empty()) return 0.0;
    fs::path json = a.pareto.empty()
                        ? fs::path(TESSERA_SOURCE_DIR) / "bench/results/accuracy" / (result_file_stem(scene) + ".json")
                        : fs::path(a.pareto);
    json.replace_extension(".json");
    std::ifstream in(json);
    if (!in) return 0.0;
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        const double pixels = j.at("width").get<double>() * j.at("height").get<double>();
        return std::isfinite(pixels) && pixels > 0 ? pixels : 0.0;
    } catch (const std::exception&) {
        return 0.0;  // not the sweep's JSON: the first frame's measurement sets the cost instead
    }
}

// The frames a headless run or a replayed path will write under --frame-images: none of
// their files may be a directory or other non-file, checked before frame 0 is written
// (check_outputs has checked frame 0 and the directory itself).
// The frames --frame-images writes: one per camera-path frame, per frame of a headless
// script, else (a window, ended by the user) only the first is known.
int frame_image_count(const LoopOptions& lo) {
    return !lo.path.empty()                     ? static_cast<int>(lo.path.size())
           : (lo.headless && !lo.script.empty()) ? lo.script.back().frame + 1
                                                 : 1;
}

// The end of the line for a run cut short (a signal, a lost display) after `frames`
// frames: what it wrote for them, "; written: times (t.json), frame images (dir)", or ""
// when it was asked for none of them (--times is written even for none; a path and
// frame images only for some).
std::string outputs_written(const ViewArgs& a, int frames) {
    std::string text;
    auto add = [&](const std::string& what, const std::string& path) {
        text += (text.empty() ? "; written: " : ", ") + what + " (" + path + ")";
    };
    if (!a.times.empty()) add("times", a.times);
    if (a.record && frames > 0) add("recorded path", a.camera_path);
    if (!a.frame_images.empty() && frames > 0) add("frame images", a.frame_images);
    return text;
}

void run_view(const ViewArgs& a, const CLI::App& cmd) {
    reject_empty_values(cmd);
    const fs::path scene_path = a.scene.empty() ? default_scene_path() : fs::path(a.scene);
    ViewOptions o;
    o.backend = {parse_backend_kind(a.backend), a.device};
    o.settings = a.settings;
    o.settings.method = parse_method(a.method);
    o.settings.igi.components = parse_components(a.components);
    validate_settings(o.settings);
    check_data_dir(a.data_dir);
    if (cmd.count("--device") && o.backend.kind != BackendKind::OpenCL)
        throw InputError("--device " + a.device + ": only --backend opencl uses a device");
    if (cmd.count("--min-scale") && !cmd.count("--target-fps"))
        throw InputError("--min-scale " + cmd.get_option("--min-scale")->as<std::string>() + ": is read only with --target-fps (the floor of its resolution scale)");
    if (cmd.count("--pareto") && !cmd.count("--target-fps"))
        throw InputError("--pareto " + a.pareto + ": is read only with --target-fps (the frame budget it feeds)");
    if (cmd.count("--screenshot-window-frame") && a.screenshot_window.empty())
        throw InputError("--screenshot-window-frame " + std::to_string(a.screenshot_window_frame) +
                         ": is read only with --screenshot-window (the frame after which it captures the window)");
    if (a.record && a.camera_path.empty()) throw InputError("--record needs --camera-path FILE.json to record into");
    if (a.record && a.headless) throw InputError("--record records a windowed session; it cannot be used with --headless");
    if (a.headless && !a.screenshot_window.empty())
        throw InputError("--screenshot-window " + a.screenshot_window +
                         ": a headless run has no window to capture (--frame-images writes its frames)");
    if (a.headless && a.camera_path.empty() && a.input_script.empty())
        throw InputError("--headless needs --camera-path or --input-script (there is no one to steer it)");
    WindowModule window;
    if (!a.headless) window = load_window_module();
    const DataPath data = make_data_path(a.data_dir.empty() ? std::nullopt : std::optional<fs::path>(a.data_dir));
    const Scene scene = load_scene(scene_path, data);
    (void)render_image_size(o.settings, scene.camera);  // a side scaled out of range fails here, before any work
    check_scene_options(o.settings, a.components, scene, scene_path, /*switches_methods=*/true);
    print_scene_notes(scene.notes);
    if (!a.frames.empty()) {
        const FrameRange r = parse_frame_range(a.frames, scene);
        o.first_frame = r.first, o.last_frame = r.last;
    }
    o.exposure = a.exposure;
    o.reference = a.reference;
    o.screenshot = a.screenshot.empty() ? default_output(scene, "-view.exr") : fs::path(a.screenshot);
    require_exr_name("--screenshot", o.screenshot);
    o.target_fps = a.target_fps;
    o.speed = a.speed;
    o.min_scale = a.min_scale;
    if (a.target_fps > 0) {
        o.pareto = load_pareto(a, scene);
        o.pareto_pixels = pareto_pixels(a, scene);
    }

    LoopOptions lo;
    lo.headless = a.headless;
    if (!a.input_script.empty()) lo.script = read_input_script(a.input_script);
    if (!a.camera_path.empty() && !a.record) {
        std::string recorded_on;
        lo.path = read_camera_path(a.camera_path, &recorded_on);
        // A path of another scene flies through that scene's space: likely the wrong file.
        if (!recorded_on.empty() && recorded_on != scene.name)
            std::fprintf(stderr, "tessera view: note: --camera-path %s was recorded on scene %s; this run's scene is "
                                 "%s\n", a.camera_path.c_str(), recorded_on.c_str(), scene.name.c_str());
    }
    for (const PathFrame& f : lo.path)
        if (f.frame < o.first_frame || f.frame > o.last_frame)
            throw InputError("--camera-path " + a.camera_path + ": animation frame " + std::to_string(f.frame) +
                             " is outside --frames " + std::to_string(o.first_frame) + ":" + std::to_string(o.last_frame));
    if (a.record) lo.record = a.camera_path;
    lo.frame_images = a.frame_images;
    lo.times = a.times;
    lo.fixed_dt = a.fixed_dt || !lo.script.empty() || !lo.path.empty();

    // Every output before the first ray (screenshots: the first one's files).
    const fs::path first_screenshot = frame_output_path(o.screenshot, 0);
    std::vector<OutputFile> files = {{first_screenshot, "--screenshot"},
                                     {fs::path(first_screenshot).replace_extension(".png"), "the PNG beside --screenshot"}};
    if (!a.times.empty()) files.push_back({a.times, "--times"});
    if (a.record) files.push_back({a.camera_path, "--camera-path (recording)"});
    if (!a.screenshot_window.empty()) files.push_back({a.screenshot_window, "--screenshot-window"});
    std::vector<fs::path> inputs = scene.inputs;
    for (const std::string& in : {a.reference, a.input_script, a.record ? std::string() : a.camera_path,
                                  a.pareto})
        if (!in.empty()) inputs.push_back(in);
    // Later screenshots (numbered on from 0001), and a window's frame images (not known
    // before), step over every file the run reads or writes otherwise, so they never
    // replace the reference or --times.
    for (const fs::path& in : inputs) o.reserved.push_back(same_file(in));
    for (size_t i = 2; i < files.size(); ++i) o.reserved.push_back(same_file(files[i].path));
    // As many digits as the last frame's (a window session's count is not known: 4).
    lo.frame_image_digits = frame_digits(frame_image_count(lo) - 1);
    if (!a.frame_images.empty())
        for (int i = 0, n = frame_image_count(lo); i < n; ++i)
            files.push_back({frame_output_path(fs::path(a.frame_images) / "frame.exr", i, lo.frame_image_digits),
                             "--frame-images (frame " + std::to_string(i) + ")"});
    check_outputs(files, inputs);
    check_output_directories(files);

    // Installed before the banner: a signal sent once the banner shows (a user's Ctrl-C, a
    // script waiting for it) ends the loop after its frame (ViewLoop::done), never the process.
    const InterruptScope interrupts;
    ViewSession session(scene, o);
    std::fprintf(stderr, "tessera view: %s, %zu triangles, %dx%d, %s on %s\n", scene.name.c_str(),
                 scene.triangle_count(), session.width(), session.height(), method_name(session.method()),
                 session.backend_description().c_str());
    if (session.stacked_emitters() > 0)
        std::fprintf(stderr, "tessera view: note: %s\n", stacked_emitters_text(session.stacked_emitters()).c_str());
    ViewLoop loop(session, lo);
    std::string lost_display;
    if (a.headless) {
        while (!loop.done()) loop.step(0.0);
    } else {
        for (const std::string& line : ViewSession::key_help()) std::fprintf(stderr, "  %s\n", line.c_str());
        lost_display = run_window(window, session, loop, a);
    }
    {
        const InterruptDeferral writing;  // --times and --record are written whole
        loop.finish(scene.name);
    }
    if (!lost_display.empty())
        throw RuntimeError(lost_display + " after " + std::to_string(loop.frame()) + " viewer frames" +
                           outputs_written(a, loop.frame()));
    if (interrupt_signal())
        throw Interrupted("interrupted after " + std::to_string(loop.frame()) + " viewer frames" +
                          outputs_written(a, loop.frame()));
}

}  // namespace

void add_view_command(CLI::App& app) {
    auto args = std::make_shared<ViewArgs>();
    args->settings.spp = 1024;  // the viewer accumulates until it holds this many passes
    CLI::App* cmd = app.add_subcommand("view", "Interactive viewer: fly through a scene with progressive refinement");
    cmd->add_option("scene", args->scene, "Scene file (.json); default " + default_scene_path().string());
    cmd->add_option("--backend", args->backend, "opencl or embree")->capture_default_str();
    cmd->add_option("--device", args->device, "OpenCL device: index or name substring (see `tessera devices`)");
    cmd->add_option("--method", args->method, "Starting method: " + method_names() +
                                                  " (M/N switch); default igi, the lightest to move in (render's is ais)")
        ->capture_default_str();
    cmd->add_option("--components", args->components, "igi/ais: starting components (1/2/3/4 toggle)")
        ->capture_default_str();
    add_parameter_options(*cmd, args->settings, true);  // --spp is the passes accumulated at rest
    cmd->add_option("--exposure", args->exposure, "Display and PNG exposure in stops ([ and ] change it)")
        ->capture_default_str()
        ->check(finite_number_in("--exposure", -limits::kExposureStops, limits::kExposureStops, false));
    cmd->add_option("--frames", args->frames, "Animated scene: the frames A:B that T plays");
    cmd->add_flag("--headless", args->headless, "No window: run --camera-path / --input-script and report frame times");
    cmd->add_option("--camera-path", args->camera_path, "Fly-through JSON to replay (or to record with --record)");
    cmd->add_flag("--record", args->record, "Record the session's camera, one entry per frame, into --camera-path");
    cmd->add_option("--input-script", args->input_script, "JSON of key/mouse events by frame, for tests and demos");
    cmd->add_flag("--fixed-dt", args->fixed_dt, "Move by 1/30 s per frame instead of wall time (on with a script or path)");
    cmd->add_option("--frame-images", args->frame_images, "Directory: write every frame's accumulation as frame.####.exr");
    cmd->add_option("--times", args->times, "Write per-frame times (ms, stages, rays, passes) as JSON");
    cmd->add_option("--screenshot", args->screenshot,
                    "Screenshot key P writes FILE.####.exr (+ .png); default out/<scene file's name>-view.exr");
    cmd->add_option("--screenshot-window", args->screenshot_window, "Write the window with its HUD as PNG");
    cmd->add_option("--screenshot-window-frame", args->screenshot_window_frame, "Frame after which --screenshot-window is taken")
        ->capture_default_str()
        ->transform(integer_in("--screenshot-window-frame", 0, limits::kViewFrames - 1));
    cmd->add_option("--reference", args->reference, "Reference EXR of the same size: error AOV and relMSE in the HUD");
    cmd->add_option("--target-fps", args->target_fps,
                    "Moving-camera frame budget: pick tile, VPL paths and light samples from the accuracy sweep's Pareto front, "
                    "and below full resolution when even the fastest misses")
        ->check(finite_number_in("--target-fps", 0, kMaxTargetFps, true));
    cmd->add_option("--min-scale", args->min_scale, "Floor of --target-fps's per-axis resolution scale")
        ->capture_default_str()
        ->check(finite_number_in("--min-scale", 0, 1, true));
    cmd->add_option("--pareto", args->pareto, "Accuracy sweep CSV for --target-fps (default bench/results/accuracy/<scene>.csv)");
    cmd->add_option("--speed", args->speed, "Movement speed, scene units per second (default: a tenth of the scene diagonal)")
        ->check(finite_number_in("--speed", 0, kMaxSpeed, true));
    cmd->add_option("--data-dir", args->data_dir, "Directory searched for scene data (before $TESSERA_DATA)");
    cmd->callback([args, cmd] { run_view(*args, *cmd); });
}

}  // namespace tessera::cli
