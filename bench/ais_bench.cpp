// Adaptive Interleaved Sampling against A-MAX and IGI, laid out like the seed thesis's
// Tables 5.1 (frames per second per component: ID, SS, PM, FULL under A and A-MAX, and
// FULL under IGI) and 5.2 (speedups A vs A-MAX per component, A vs IGI for FULL), for the
// standard scenes in the seed's row order (bench::standard_scenes) on both backends in one
// run, with the seed's Average rows (the mean over the scenes that have a value). Medians
// over frames; writes ais_bench.{json,md}.
// All methods at the same settings (tile 3×3, 32 VPL paths per set, 4 light samples per
// pixel, 8 march steps), plus full-rate IGI: tile 1 with the samples of all 9 sets at
// every pixel (the seed's IGI, slower than its A-MAX). Equal-error comparisons against
// the cheapest IGI come from bench/accuracy.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
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

std::string num(double v, const char* spec = "%.2f") {
    char buf[32];
    std::snprintf(buf, sizeof buf, spec, v);
    return buf;
}

// IGI without interleaving that takes, at every pixel, the samples of all n² sets of `s`:
// n²× the light paths, light samples and march steps at tile 1. Same sample counts as a
// pixel AIS refines to every set, so its error is at most A's (measured in bench/accuracy).
// bench/ais_bound's full_rate is the same mapping for `tessera render` options.
IgiSettings full_rate(IgiSettings s) {
    const uint32_t sets = s.tile * s.tile;
    s.tile = 1;
    s.paths_per_set *= sets;
    s.set_shadow_samples *= sets;
    s.march_steps *= sets;
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    tessera::keep_frame_memory();
    CLI::App app{"Tessera AIS vs A-MAX vs IGI frame rates (Tables 5.1/5.2 layout)"};
    std::vector<std::string> scenes = bench::standard_scenes();
    std::string out_dir = "bench/results", device;
    int size = 512, frames = 3;
    app.add_option("--scene", scenes)->capture_default_str();
    app.add_option("--size", size)->capture_default_str();
    app.add_option("--frames", frames)->capture_default_str();
    app.add_option("--device", device);
    app.add_option("--out", out_dir)->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    const std::vector<std::pair<std::string, uint32_t>> comps = {
        {"ID", TS_COMPONENT_ID}, {"SS", TS_COMPONENT_SS}, {"PM", TS_COMPONENT_PM}, {"FULL", 7u}};
    nlohmann::json j;
    j["size"] = size;
    j["frames"] = frames;
    std::string t51 = "| scene | backend | ID A | ID A-MAX | SS A | SS A-MAX | PM A | PM A-MAX | FULL A | FULL A-MAX | "
                      "FULL IGI | FULL IGI full-rate |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::string t52 = "| scene | backend | ID A vs A-MAX | SS A vs A-MAX | PM A vs A-MAX | FULL A vs A-MAX | "
                      "FULL A vs IGI | FULL A vs IGI full-rate |\n|---|---|---|---|---|---|---|---|\n";
    std::string t_adapt = "| scene | backend | A: adaptive ms | A: extra sets / pixel | A-MAX: adaptive ms | "
                          "A-MAX: extra sets / pixel | A-MAX / A (adaptive time) | flagged SS / ID / PM % |\n"
                          "|---|---|---|---|---|---|---|---|\n";
    // Per backend and column, the values of every scene that has one: the Average rows
    // (as in the seed, the mean over the scenes with a value, e.g. PM over the fog scenes).
    std::map<std::string, std::map<std::string, std::vector<double>>> fps_of, speedup_of;
    // The tables with their Average rows, written after every scene so that a run stopped
    // early (a lent GPU's time limit) leaves the scenes it finished.
    auto write_tables = [&]() {
        // Average rows, per backend: columns in table order, "-" where no scene has a value.
        auto average_row = [&](const std::string& bname, auto& values, const std::vector<std::string>& keys,
                               nlohmann::json& out) {
            std::string row = "| Average | " + bname;
            for (const std::string& k : keys) {
                const std::vector<double>& v = values[bname][k];
                if (v.empty()) {
                    row += " | -";
                    continue;
                }
                double sum = 0;
                for (double x : v) sum += x;
                out[k] = sum / double(v.size());
                row += " | " + num(sum / double(v.size()));
            }
            return row + " |\n";
        };
        std::string a51 = t51, a52 = t52;
        for (const std::string bname : {"opencl", "embree"}) {
            a51 += average_row(bname, fps_of,
                               {"ID A", "ID A-MAX", "SS A", "SS A-MAX", "PM A", "PM A-MAX", "FULL A", "FULL A-MAX",
                                "FULL IGI", "FULL IGI full-rate"},
                               j["average"]["fps"][bname]);
            a52 += average_row(bname, speedup_of,
                               {"ID A vs ID A-MAX", "SS A vs SS A-MAX", "PM A vs PM A-MAX", "FULL A vs FULL A-MAX",
                                "FULL A vs FULL IGI", "FULL A vs FULL IGI full-rate"},
                               j["average"]["speedup"][bname]);
        }
        fs::create_directories(out_dir);
        std::ofstream(fs::path(out_dir) / "ais_bench.json") << j.dump(2) << "\n";
        std::ofstream(fs::path(out_dir) / "ais_bench.md")
            << "# AIS vs A-MAX vs IGI, " << size << "x" << size << ", median of " << frames << " frames\n\n"
            << "Machine: " << bench::machine_description() << ". All at tile 3x3, 32 VPL paths per set, 4 light samples per pixel, "
               "8 march steps; ID/SS/PM render that component alone, FULL all the scene calls for. FULL IGI "
               "is IGI at those same settings, i.e. the base pass AIS refines: A costs more than it by "
               "construction, and its error is lower. FULL IGI full-rate is IGI without interleaving taking the "
               "samples of all 9 sets at every pixel (tile 1, 288 paths, 36 light samples, 72 march steps): the "
               "seed's IGI (its IGI runs slower than its A-MAX, which only a non-interleaved IGI can), whose "
               "error is at most A's. The fair comparison, against the cheapest IGI configuration that reaches "
               "A's error, is bench/results/accuracy/report.md, Tables 2 and 2b.\n\n"
            << "## Frames per second (layout of the seed's Table 5.1)\n\n" << a51
            << "\n## Speedups (layout of the seed's Table 5.2)\n\n" << a52
            << "\n## The adaptive pass alone (FULL; guidance, schedule, extra sets)\n\n"
               "The part of the frame where A and A-MAX differ: both share the base pass, the filter and the "
               "composite. Extra sets per pixel: (pixel, set) evaluations over the image's pixels.\n\n"
            << t_adapt;
    };
    for (const std::string& path : scenes) {
        Scene scene = load_scene(path, make_data_path(std::nullopt));
        SceneBuffers b = make_scene_buffers(scene);
        const bool medium = plan_effects(scene).medium;
        for (BackendKind kind : {BackendKind::OpenCL, BackendKind::Embree}) {
            auto be = make_backend({kind, device}, b, plan_effects(scene));
            const std::string bname = kind == BackendKind::OpenCL ? "opencl" : "embree";
            std::map<std::string, double> f;
            std::map<AisMode, bench::IgiTiming> full;
            for (const auto& [cname, bits] : comps) {
                if (cname == "PM" && !medium) continue;
                for (AisMode mode : {AisMode::A, AisMode::AMax}) {
                    IgiSettings is;
                    is.components = bits;
                    is.ais_mode = mode;
                    const bench::IgiTiming t = bench::time_igi_frames(*be, scene, b, is, size, frames, true);
                    f[cname + (mode == AisMode::A ? " A" : " A-MAX")] = 1.0 / t.frame;
                    if (cname == "FULL") full[mode] = t;
                }
            }
            f["FULL IGI"] = 1.0 / bench::time_igi_frames(*be, scene, b, IgiSettings{}, size, frames).frame;
            f["FULL IGI full-rate"] = 1.0 / bench::time_igi_frames(*be, scene, b, full_rate(IgiSettings{}), size,
                                                                   frames).frame;
            const double pixels = double(size) * size;
            const auto& ta = full[AisMode::A];
            const auto& tm = full[AisMode::AMax];
            t_adapt += "| " + scene.name + " | " + bname + " | " + num(1e3 * ta.ais, "%.1f") + " | " +
                       num(ta.last.ais_items / pixels) + " | " + num(1e3 * tm.ais, "%.1f") + " | " +
                       num(tm.last.ais_items / pixels) + " | " + num(tm.ais / ta.ais) + " | " +
                       num(100 * ta.last.flagged[kAisSS], "%.1f") + " / " + num(100 * ta.last.flagged[kAisID], "%.1f") +
                       " / " + num(100 * ta.last.flagged[kAisPM], "%.1f") + " |\n";
            j["adaptive"][scene.name][bname] = {{"A_ms", 1e3 * ta.ais}, {"A_items", ta.last.ais_items},
                                                {"AMAX_ms", 1e3 * tm.ais}, {"AMAX_items", tm.last.ais_items}};
            auto cell = [&](const std::string& k) {
                if (!f.count(k)) return std::string("-");
                fps_of[bname][k].push_back(f[k]);
                return num(f[k]);
            };
            auto ratio = [&](const std::string& a, const std::string& b2) {
                if (!f.count(a) || !f.count(b2)) return std::string("-");
                speedup_of[bname][a + " vs " + b2].push_back(f[a] / f[b2]);
                return num(f[a] / f[b2]);
            };
            t51 += "| " + scene.name + " | " + bname;
            for (const char* k : {"ID A", "ID A-MAX", "SS A", "SS A-MAX", "PM A", "PM A-MAX", "FULL A", "FULL A-MAX",
                                  "FULL IGI", "FULL IGI full-rate"})
                t51 += " | " + cell(k);
            t51 += " |\n";
            t52 += "| " + scene.name + " | " + bname + " | " + ratio("ID A", "ID A-MAX") + " | " +
                   ratio("SS A", "SS A-MAX") + " | " + ratio("PM A", "PM A-MAX") + " | " +
                   ratio("FULL A", "FULL A-MAX") + " | " + ratio("FULL A", "FULL IGI") + " | " +
                   ratio("FULL A", "FULL IGI full-rate") + " |\n";
            j["fps"][scene.name][bname] = f;
            std::fprintf(stderr, "%-16s %-6s FULL: A %.2f, A-MAX %.2f, IGI %.2f, IGI full-rate %.2f fps\n",
                         scene.name.c_str(), bname.c_str(), f["FULL A"], f["FULL A-MAX"], f["FULL IGI"],
                         f["FULL IGI full-rate"]);
        }
        write_tables();
    }
    return 0;
}
