// What an animation pays per frame before its first pass (render_sequence and the
// viewer's build_backend): the pose (PosedFrames::at, as both pose), make_scene_buffers
// with and without the frame before's buffers (the mip chains taken from them, or
// remade), plan_effects and Backend::set_scene, on both backends, in one process.
// Medians over frames 1..--frames (frame 0 makes the backend), ms. Writes
// frame_setup_bench.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "backend/backend.h"
#include "bench/machine.h"
#include "device/effect_plan.h"
#include "scene/animation.h"
#include "scene/loader.h"
#include "scene/posed_frames.h"
#include "util/heap.h"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

struct Parts {
    std::vector<double> pose, fresh, from_earlier, plan, set_scene;
};

// Frames 0..frames of `rest` through one backend of `kind`, as render_sequence does; the
// fresh buffers are made and timed too but not given to the backend.
Parts time_frames(const Scene& rest, BackendKind kind, int frames) {
    Parts p;
    std::unique_ptr<SceneBuffers> buffers;
    std::unique_ptr<Backend> backend;
    const PosedFrames posed(rest);
    for (int frame = 0; frame <= frames; ++frame) {
        auto t0 = Clock::now();
        const Scene scene = posed.at(frame % rest.animation.frame_count);
        const double pose = ms_since(t0);
        t0 = Clock::now();
        const SceneBuffers fresh = make_scene_buffers(scene);
        const double fresh_ms = ms_since(t0);
        t0 = Clock::now();
        auto next = std::make_unique<SceneBuffers>(make_scene_buffers(scene, buffers.get()));
        const double earlier_ms = ms_since(t0);
        t0 = Clock::now();
        const EffectPlan plan = plan_effects(scene);
        const double plan_ms = ms_since(t0);
        t0 = Clock::now();
        give_scene(backend, {kind, ""}, *next, plan);
        const double set_ms = ms_since(t0);
        buffers = std::move(next);
        if (frame == 0) continue;
        p.pose.push_back(pose), p.fresh.push_back(fresh_ms), p.from_earlier.push_back(earlier_ms);
        p.plan.push_back(plan_ms), p.set_scene.push_back(set_ms);
    }
    return p;
}

}  // namespace

int main(int argc, char** argv) {
    keep_frame_memory();  // as the CLI: util/heap.h
    CLI::App app{"Tessera per-frame set-up of an animation (both backends)"};
    std::vector<std::string> scenes = {"scenes/cornell-box-animated.json", "scenes/sibenik-animated.json"};
    std::string out_dir = "bench/results";
    int frames = 8;
    app.add_option("--scene", scenes)->capture_default_str();
    app.add_option("--frames", frames, "frames after frame 0 to time")->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--out", out_dir)->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    std::string md = "# An animation's per-frame set-up, median of frames 1.." + std::to_string(frames) +
                     " (ms)\n\nMachine: " + bench::machine_description() +
                     ".\n\nbuffers: make_scene_buffers alone (fresh) and from the frame before's buffers (as "
                     "render_sequence and the viewer call it); set_scene: the backend's BVH build and upload.\n\n"
                     "| scene | triangles | backend | pose | buffers, fresh | buffers, from the frame before | "
                     "plan | set_scene |\n|---|---|---|---|---|---|---|---|\n";
    for (const std::string& path : scenes) {
        const Scene rest = load_scene(path, make_data_path(std::nullopt));
        if (!rest.animation.animated()) throw std::runtime_error(path + ": no animation");
        for (const BackendKind kind : {BackendKind::Embree, BackendKind::OpenCL}) {
            const Parts p = time_frames(rest, kind, frames);
            char row[400];
            std::snprintf(row, sizeof row, "| %s | %u | %s | %.2f | %.2f | %.2f | %.2f | %.2f |\n", rest.name.c_str(),
                          unsigned(rest.triangle_count()), kind == BackendKind::OpenCL ? "opencl" : "embree", median(p.pose),
                          median(p.fresh), median(p.from_earlier), median(p.plan), median(p.set_scene));
            md += row;
            std::fprintf(stderr, "%s", row);
        }
    }
    fs::create_directories(out_dir);
    std::ofstream(fs::path(out_dir) / "frame_setup_bench.md") << md;
    return 0;
}
