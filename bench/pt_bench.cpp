// Path-tracing throughput: samples (camera paths) per second of `pt` on both backends,
// for the Cornell box and Sibenik, in one process. Writes pt_bench.json and pt_bench.md.
// Each figure is the median over passes (one pass = 1 spp for every pixel).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/info.h>

#include "backend/backend.h"
#include "bench/machine.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "util/heap.h"

using namespace tessera;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
    tessera::keep_frame_memory();
    CLI::App app{"Tessera path-tracing throughput (pt, both backends)"};
    std::vector<std::string> scenes = {std::string(TESSERA_SCENES_DIR) + "/cornell-box.json",
                                       std::string(TESSERA_SCENES_DIR) + "/sibenik.json"};
    std::string out_dir = "bench/results", device;
    int size = 256, passes = 9;
    app.add_option("--scene", scenes, "scene files")->capture_default_str();
    app.add_option("--size", size, "image width and height")->capture_default_str();
    app.add_option("--passes", passes, "passes (spp) timed per backend")->capture_default_str();
    app.add_option("--device", device, "OpenCL device");
    app.add_option("--out", out_dir)->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    nlohmann::json j;
    j["threads"] = tbb::info::default_concurrency();
    j["size"] = size;
    j["passes"] = passes;
    std::string rows;
    for (const std::string& path : scenes) {
        Scene scene = load_scene(path, make_data_path(std::nullopt));
        SceneBuffers b = make_scene_buffers(scene);
        EffectPlan plan = plan_effects(scene);
        RenderSettings rs;
        rs.method = Method::PathTrace;
        rs.width = rs.height = size;
        rs.spp = static_cast<uint32_t>(passes);
        double sps[2] = {};
        std::string names[2];
        for (int k = 0; k < 2; ++k) {
            auto be = make_backend({k == 0 ? BackendKind::OpenCL : BackendKind::Embree, device}, b, plan);
            names[k] = be->description();
            RenderSettings warm = rs;
            warm.spp = 1;
            render_frame(*be, scene, b, warm);  // builds or loads the OpenCL program
            RenderStats st;
            render_frame(*be, scene, b, rs, &st);
            sps[k] = double(size) * size / st.median_pass_seconds;
        }
        std::fprintf(stderr, "%-12s OpenCL %.3g  Embree %.3g samples/s  ratio %.2f\n", scene.name.c_str(), sps[0],
                     sps[1], sps[0] / sps[1]);
        j["scenes"][scene.name] = {{"triangles", scene.triangle_count()}, {"opencl_samples_per_s", sps[0]},
                                   {"embree_samples_per_s", sps[1]}, {"opencl_over_embree", sps[0] / sps[1]}};
        j["opencl"] = names[0];
        j["embree"] = names[1];
        char buf[256];
        std::snprintf(buf, sizeof buf, "| %s | %zu | %.3g | %.3g | %.2f |\n", scene.name.c_str(),
                      scene.triangle_count(), sps[0], sps[1], sps[0] / sps[1]);
        rows += buf;
    }
    fs::create_directories(out_dir);
    std::ofstream(fs::path(out_dir) / "pt_bench.json") << j.dump(2) << "\n";
    std::ofstream(fs::path(out_dir) / "pt_bench.md")
        << "# `pt` throughput, " << size << "x" << size << ", median of " << passes << " passes\n\n"
        << "Machine: " << bench::machine_description() << "; OpenCL: " << j["opencl"].get<std::string>()
        << ". A sample is one camera path (with next-event estimation at every vertex).\n\n"
        << "| scene | triangles | OpenCL (samples/s) | Embree (samples/s) | OpenCL / Embree |\n|---|---|---|---|---|\n"
        << rows;
    return 0;
}
