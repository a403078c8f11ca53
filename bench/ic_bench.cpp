// Instant caching over animations (docs/instant-caching.md): per frame of each animated scene, the frame
// time, the records (re)computed and the indirect rays traced, for igi, ais, ic and tic on
// both backends in one run; then the error of each method against per-frame path-traced
// references for a few frames. Writes ic_bench.{json,md}.
//
// Every frame is rendered as `tessera render --frames` renders it: pose, flatten, give the
// sequence's backend the frame's scene (Backend::set_scene: BVH build and upload,
// "set-up", reported apart; the first frame makes the backend), one pass (1 spp). tic
// keeps one cache across the frames; the others start from nothing each frame.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "backend/backend.h"
#include "bench/igi_timing.h"
#include "metrics/image_metrics.h"
#include "device/effect_plan.h"
#include "render/renderer.h"
#include "device/scene_buffers.h"
#include "integrators/factory.h"
#include "scene/loader.h"
#include "scene/posed_frames.h"
#include "util/heap.h"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

struct FrameResult {
    double seconds = 0, setup = 0;
    size_t records = 0, recomputed = 0;
    uint64_t rays = 0;
    Image image;
};

RenderSettings method_settings(Method m, int size) {
    RenderSettings s;
    s.method = m;
    s.spp = 1;
    s.width = s.height = size;
    s.variance = false;
    return s;
}

// Indirect rays of a pass: light-path rays plus the VPL shadow rays. Exact for ic/tic
// (rays actually traced); for igi/ais pixels × VPLs per set (+ extra AIS sets), an upper
// bound (VPLs a surface faces away from cost no ray).
uint64_t indirect_rays(Method m, const RenderStats& st, int size, uint32_t sets) {
    if (m == Method::Ic || m == Method::Tic) return st.ic.indirect_rays();
    const uint64_t per_set = st.igi.vpls / std::max<uint32_t>(1, sets);
    return st.igi.vpl_rays + per_set * (uint64_t(size) * size + st.igi.ais_items);
}

std::vector<FrameResult> run_sequence(const Scene& rest, Method m, BackendKind kind, const std::string& device,
                                      int size, int frames, bool keep_images) {
    RenderSettings s = method_settings(m, size);
    std::vector<FrameResult> out;
    std::unique_ptr<SceneBuffers> buffers;  // before the backend, which reads it
    std::unique_ptr<Backend> backend;
    const PosedFrames posed(rest);  // as render_sequence
    for (int f = 0; f < frames; ++f) {
        const auto t0 = std::chrono::steady_clock::now();
        const Scene scene = posed.at(f);
        auto next = std::make_unique<SceneBuffers>(make_scene_buffers(scene, buffers.get()));  // as render_sequence
        const EffectPlan plan = plan_effects(scene);
        give_scene(backend, {kind, device}, *next, plan);
        buffers = std::move(next);
        FrameResult r;
        r.setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        // tic: one cache for the sequence, with the igi settings it reads, as `render` makes it.
        if (m == Method::Tic && !s.ic_state) prepare_sequence(s, rest);
        RenderStats st;
        Image img = render_frame(*backend, scene, *buffers, s, &st);
        r.seconds = st.seconds;
        r.records = st.ic.records;
        r.recomputed = st.ic.created + st.ic.resummed;
        r.rays = indirect_rays(m, st, size, s.igi.tile * s.igi.tile);
        if (keep_images) r.image = std::move(img);
        out.push_back(std::move(r));
    }
    return out;
}

metrics::RgbImage rgb(const Image& img) { return metrics::rgb_for_metrics(img, "bench"); }

}  // namespace

int main(int argc, char** argv) {
    tessera::keep_frame_memory();
    CLI::App app{"Tessera instant caching over animations: igi, ais, ic, tic per frame, both backends"};
    std::vector<std::string> scenes = {std::string(TESSERA_SCENES_DIR) + "/cornell-box-animated.json",
                                       std::string(TESSERA_SCENES_DIR) + "/sibenik-animated.json"};
    std::string out_dir = "bench/results", device;
    int size = 512, frames = 30, error_size = 256, ref_spp = 1024;
    std::vector<int> error_frames = {0, 15, 29};
    app.add_option("--scene", scenes)->capture_default_str();
    app.add_option("--size", size)->capture_default_str();
    app.add_option("--frames", frames, "frames 0..N-1 of each animation")->capture_default_str();
    app.add_option("--error-frames", error_frames)->delimiter(',')->capture_default_str();
    app.add_option("--error-size", error_size)->capture_default_str();
    app.add_option("--ref-spp", ref_spp, "pt samples per pixel of the per-frame references")->capture_default_str();
    app.add_option("--device", device);
    app.add_option("--out", out_dir)->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    const std::vector<Method> methods = {Method::Igi, Method::Ais, Method::Ic, Method::Tic};
    nlohmann::json j;
    j["size"] = size;
    std::string md = "## Per frame at " + std::to_string(size) + "x" + std::to_string(size) +
                     " (medians over frames 1.., frame 0 apart; 1 spp)\n\n"
                     "| scene | backend | method | frame 0 s | median s | fps | set-up s | records | "
                     "recomputed/frame | indirect rays/frame |\n|---|---|---|---|---|---|---|---|---|---|\n";
    std::string err = "## Error against per-frame pt references (" + std::to_string(error_size) + "x" +
                      std::to_string(error_size) + ", pt " + std::to_string(ref_spp) +
                      " spp, Embree; relMSE)\n\n| scene | frame | igi | ais | ic | tic |\n|---|---|---|---|---|---|\n";
    for (const std::string& path : scenes) {
        Scene rest;
        try {
            rest = load_scene(path, make_data_path(std::nullopt));
        } catch (const std::exception& e) {
            std::fprintf(stderr, "skipping %s: %s\n", path.c_str(), e.what());
            continue;
        }
        const int n = std::min(frames, std::max(1, rest.animation.frame_count));
        for (BackendKind kind : {BackendKind::OpenCL, BackendKind::Embree}) {
            const char* bname = kind == BackendKind::OpenCL ? "opencl" : "embree";
            for (Method m : methods) {
                const auto res = run_sequence(rest, m, kind, device, size, n, false);
                std::vector<double> secs, setup, rec, rays;
                for (size_t f = 1; f < res.size(); ++f) {
                    secs.push_back(res[f].seconds), setup.push_back(res[f].setup);
                    rec.push_back(double(res[f].recomputed)), rays.push_back(double(res[f].rays));
                }
                if (secs.empty()) secs = {res[0].seconds}, setup = {res[0].setup}, rec = {0}, rays = {0};
                const double med = bench::median(secs);
                char line[400];
                std::snprintf(line, sizeof line, "| %s | %s | %s | %.3f | %.3f | %.2f | %.3f | %zu | %.0f | %.3g |\n",
                              rest.name.c_str(), bname, method_name(m), res[0].seconds, med, 1.0 / med,
                              bench::median(setup), res.back().records, bench::median(rec), bench::median(rays));
                md += line;
                std::fputs(line, stderr);
                nlohmann::json& e = j["frames"][rest.name][bname][method_name(m)];
                for (const FrameResult& r : res)
                    e.push_back({{"seconds", r.seconds}, {"setup", r.setup}, {"records", r.records},
                                 {"recomputed", r.recomputed}, {"indirect_rays", r.rays}});
            }
        }
        // Error: each method's frames against pt references of the same frames. tic runs
        // its whole sequence up to each error frame, so its cache is the updated one.
        const int last = *std::max_element(error_frames.begin(), error_frames.end());
        if (last >= n) continue;
        std::vector<std::vector<FrameResult>> runs;
        for (Method m : methods) runs.push_back(run_sequence(rest, m, BackendKind::Embree, device, error_size, last + 1, true));
        for (int f : error_frames) {
            const Scene scene = scene_at_frame(rest, f);
            const SceneBuffers buffers = make_scene_buffers(scene);
            auto be = make_backend({BackendKind::Embree, ""}, buffers, plan_effects(scene));
            RenderSettings ps = method_settings(Method::PathTrace, error_size);
            ps.spp = static_cast<uint32_t>(ref_spp);
            const metrics::RgbImage ref = rgb(render_frame(*be, scene, buffers, ps));
            std::string row = "| " + rest.name + " | " + std::to_string(f);
            for (size_t k = 0; k < methods.size(); ++k) {
                const double e = metrics::rel_mse(ref, rgb(runs[k][f].image));
                char cell[32];
                std::snprintf(cell, sizeof cell, " | %.4g", e);
                row += cell;
                j["error"][rest.name][std::to_string(f)][method_name(methods[k])] = e;
            }
            err += row + " |\n";
            std::fputs((row + " |\n").c_str(), stderr);
        }
    }
    fs::create_directories(out_dir);
    std::ofstream(fs::path(out_dir) / "ic_bench.json") << j.dump(2) << "\n";
    std::ofstream(fs::path(out_dir) / "ic_bench.md")
        << "# ic_bench: " << std::thread::hardware_concurrency() << " hardware threads; analysis in README.md\n\n"
        << md << "\n" << err;
    return 0;
}
