// IGI frame time at 512×512 on both backends, in one process: for each scene the median
// frame time over several frames, the time of each stage (VPL generation, surface kernel
// = SS + ID, media kernel = PM, filter + composite), rays per frame and rays per second.
// Writes igi_bench.json and igi_bench.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "backend/backend.h"
#include "bench/machine.h"
#include "bench/igi_timing.h"
#include "integrators/igi_frame.h"
#include "device/frame.h"
#include "scene/loader.h"
#include "util/heap.h"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

struct Row {
    std::string scene, backend;
    double frame_ms, vpl_ms, surface_ms, media_ms, filter_ms;
    double rays;  // per frame
};

Row measure(const Scene& scene, const SceneBuffers& b, BackendKind kind, const std::string& device, int size,
            int frames, bool pass_aovs) {
    auto be = make_backend({kind, device}, b, plan_effects(scene));
    const bench::IgiTiming t = bench::time_igi_frames(*be, scene, b, IgiSettings{}, size, frames, false, pass_aovs);
    return {scene.name, kind == BackendKind::OpenCL ? "opencl" : "embree", 1e3 * t.frame, 1e3 * t.vpl,
            1e3 * t.surface, 1e3 * t.media, 1e3 * t.filter, double(t.last.vpl_rays + t.last.pixel_rays)};
}

}  // namespace

int main(int argc, char** argv) {
    tessera::keep_frame_memory();
    CLI::App app{"Tessera IGI frame time (both backends)"};
    std::vector<std::string> scenes = bench::standard_scenes();
    std::string out_dir = "bench/results", device;
    int size = 512, frames = 3;
    app.add_option("--scene", scenes)->capture_default_str();
    app.add_option("--size", size)->capture_default_str();
    app.add_option("--frames", frames, "timed frames per scene and backend")->capture_default_str();
    app.add_option("--device", device);
    app.add_option("--out", out_dir)->capture_default_str();
    bool pass_aovs = false;
    app.add_flag("--pass-aovs", pass_aovs,
                 "read back the whole pass image (albedo, normal, depth too), as `render` does; default: the "
                 "radiance alone, as the viewer (IgiSettings::pass_aovs; only frames resolved on the device differ)");
    CLI11_PARSE(app, argc, argv);

    nlohmann::json j;
    j["size"] = size;
    j["frames"] = frames;
    const IgiSettings defaults;
    char clamp_c[32];
    std::snprintf(clamp_c, sizeof clamp_c, "%g", defaults.clamp_c);
    j["settings"] = "IgiSettings defaults: tile " + std::to_string(defaults.tile) + "x" + std::to_string(defaults.tile) +
                    ", " + std::to_string(defaults.paths_per_set) + " VPL paths per set, " +
                    std::to_string(defaults.set_shadow_samples) + " light samples per pixel, " +
                    std::to_string(defaults.march_steps) + " march steps, clamp c = " + clamp_c +
                    " (pass 0 of its decay), " +
                    (pass_aovs ? "the whole pass read back" : "a device-resolved frame's radiance alone read back");
    std::string md = "# IGI frame time, " + std::to_string(size) + "x" + std::to_string(size) + ", median of " +
                     std::to_string(frames) + " frames\n\nMachine: " + bench::machine_description() + ". " +
                     j["settings"].get<std::string>() +
                     ". Rays per frame count light-path, camera, shadow and VPL rays (the VPL count is the "
                     "set's average, an upper bound on traced VPL shadow rays).\n\n"
                     "| scene | backend | frame (ms) | fps | VPLs (ms) | SS+ID (ms) | PM (ms) | filter (ms) | "
                     "Mrays/frame | Mrays/s | OpenCL / Embree time |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string& path : scenes) {
        Scene scene = load_scene(path, make_data_path(std::nullopt));
        SceneBuffers b = make_scene_buffers(scene);
        Row cl = measure(scene, b, BackendKind::OpenCL, device, size, frames, pass_aovs);
        Row em = measure(scene, b, BackendKind::Embree, device, size, frames, pass_aovs);
        for (int k = 0; k < 2; ++k) {
            const Row& r = k == 0 ? cl : em;
            char buf[400];
            std::snprintf(buf, sizeof buf, "| %s | %s | %.0f | %.2f | %.1f | %.0f | %.0f | %.1f | %.1f | %.1f | %s |\n",
                          r.scene.c_str(), r.backend.c_str(), r.frame_ms, 1e3 / r.frame_ms, r.vpl_ms, r.surface_ms,
                          r.media_ms, r.filter_ms, r.rays * 1e-6, r.rays * 1e-3 / r.frame_ms,
                          k == 0 ? std::to_string(cl.frame_ms / em.frame_ms).substr(0, 4).c_str() : "");
            md += buf;
            j["rows"].push_back({{"scene", r.scene}, {"backend", r.backend}, {"frame_ms", r.frame_ms},
                                 {"vpl_ms", r.vpl_ms}, {"surface_ms", r.surface_ms}, {"media_ms", r.media_ms},
                                 {"filter_ms", r.filter_ms}, {"rays_per_frame", r.rays}});
            std::fprintf(stderr, "%-16s %-6s %7.0f ms/frame\n", r.scene.c_str(), r.backend.c_str(), r.frame_ms);
        }
    }
    fs::create_directories(out_dir);
    std::ofstream(fs::path(out_dir) / "igi_bench.json") << j.dump(2) << "\n";
    std::ofstream(fs::path(out_dir) / "igi_bench.md") << md;
    return 0;
}
