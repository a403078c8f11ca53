// What the viewer pays at every camera move before the pass starts (ViewSession::restart):
// make_integrator and make_render_frame, for igi and ais on both backends, in one process.
// The median over --restarts restarts per scene, method and backend, in ms; no pass is
// rendered. Writes restart_bench.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "backend/backend.h"
#include "bench/machine.h"
#include "device/effect_plan.h"
#include "integrators/factory.h"
#include "render/renderer.h"
#include "scene/loader.h"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

// Median of `restarts` set-ups of `method` at size × size, ms.
double median_restart_ms(Backend& backend, const Scene& scene, const SceneBuffers& b, Method method, int size,
                         int restarts) {
    RenderSettings rs;
    rs.method = method;
    rs.width = rs.height = size;
    const IntegratorSettings is = integrator_settings(rs, size, size);
    std::vector<double> ms;
    for (int i = 0; i < restarts; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        const auto integrator = make_integrator(backend, scene, b, is);
        const TsFrame frame = make_render_frame(scene.camera, size, size, b, rs);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        (void)frame;
    }
    std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
    return ms[ms.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Tessera viewer restart cost (both backends)"};
    std::vector<std::string> scenes = {"scenes/cornell-box.json", "scenes/conference.json", "scenes/sibenik.json"};
    std::string out_dir = "bench/results";
    int size = 512, restarts = 20;
    app.add_option("--scene", scenes)->capture_default_str();
    app.add_option("--size", size)->capture_default_str();
    app.add_option("--restarts", restarts)->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--out", out_dir)->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    std::string md = "# Viewer restart: make_integrator + make_render_frame, " + std::to_string(size) + "x" +
                     std::to_string(size) + ", median of " + std::to_string(restarts) +
                     " restarts (ms)\n\nMachine: " + bench::machine_description() +
                     ".\n\n| scene | triangles | backend | igi | ais |\n|---|---|---|---|---|\n";
    for (const std::string& path : scenes) {
        const Scene scene = load_scene(path, make_data_path(std::nullopt));
        const SceneBuffers b = make_scene_buffers(scene);
        for (const BackendKind kind : {BackendKind::Embree, BackendKind::OpenCL}) {
            auto backend = make_backend({kind, ""}, b, plan_effects(scene));
            const double igi = median_restart_ms(*backend, scene, b, Method::Igi, size, restarts);
            const double ais = median_restart_ms(*backend, scene, b, Method::Ais, size, restarts);
            char row[300];
            std::snprintf(row, sizeof row, "| %s | %u | %s | %.3f | %.3f |\n", scene.name.c_str(), b.triangle_count,
                          kind == BackendKind::OpenCL ? "opencl" : "embree", igi, ais);
            md += row;
            std::fprintf(stderr, "%s", row);
        }
    }
    fs::create_directories(out_dir);
    std::ofstream(fs::path(out_dir) / "restart_bench.md") << md;
    return 0;
}
