// `tessera compare REF.exr TEST.exr [--map FILE.png] [--flip-map FILE.png] [--cvvdp [--cvvdp-map FILE.png]]
// [--json]`: error metrics of a test image against a reference (metrics/image_metrics.h,
// metrics/flip.h, metrics/cvvdp.h).
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/option_checks.h"
#include "image/atomic_file.h"
#include "image/fatal_signal_cleanup.h"
#include "image/image_io.h"
#include "metrics/cvvdp.h"
#include "metrics/hdrvdp.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::cli {
namespace fs = std::filesystem;
namespace {

struct CompareArgs {
    std::string ref, test, map, flip_map, cvvdp_map, cvvdp_python;
    float exposure = 0.0f;
    bool json = false;
    bool no_flip = false;
    bool cvvdp = false;
    bool hdrvdp = false;
};

// Before reading the images: the error maps can be written, the metric options are sane,
// and a requested ColorVideoVDP or HDR-VDP-3 can run (the checks throw naming the option).
void check_compare_options(const CompareArgs& a, const CLI::App& cmd) {
    reject_empty_values(cmd);
    if (a.cvvdp) metrics::check_cvvdp(metrics::cvvdp_tool(a.cvvdp_python), "--cvvdp");
    if (a.hdrvdp) metrics::check_hdrvdp(metrics::hdrvdp_tool(), "--hdrvdp");
    if (a.no_flip && !a.flip_map.empty())
        throw InputError("--flip-map " + a.flip_map + ": FLIP writes it, and --no-flip skips FLIP");
    std::vector<OutputFile> maps;
    if (!a.map.empty()) maps.push_back({a.map, "--map"});
    if (!a.flip_map.empty()) maps.push_back({a.flip_map, "--flip-map"});
    if (!a.cvvdp_map.empty()) maps.push_back({a.cvvdp_map, "--cvvdp-map"});
    check_outputs(maps, {});
    for (const OutputFile& m : maps)
        if (m.path.extension() != ".png" && m.path.extension() != ".PNG")
            throw InputError(m.role + " " + m.path.string() + ": the map is written as PNG; name it .png");
    // equivalent() with an error code: libstdc++ 13 and later report an error, not
    // false, when a map does not exist yet.
    std::error_code ec;
    for (const auto& [image, role] : {std::pair{a.ref, "reference"}, std::pair{a.test, "test"}})
        for (const OutputFile& m : maps)
            if (fs::exists(image) && fs::equivalent(image, m.path, ec))
                throw InputError(m.role + " " + m.path.string() + ": is the " + role + " image");
    check_output_directories(maps);
}

// The two images cover the same pixels: the same size and the same data window origin
// (pixel (x, y) of one is pixel (x, y) of the other), and the reference is radiance (>= 0).
void check_comparable(const Image& ref, const Image& test, const CompareArgs& a) {
    if (ref.x0 != test.x0 || ref.y0 != test.y0)
        throw InputError("image data windows differ: " + a.ref + " starts at pixel (" + std::to_string(ref.x0) + ", " +
                         std::to_string(ref.y0) + "), " + a.test + " at (" + std::to_string(test.x0) + ", " +
                         std::to_string(test.y0) + "); they do not cover the same pixels");
    for (const char* name : {"R", "G", "B"})
        if (const ImageChannel* c = ref.find(name))
            for (size_t i = 0; i < c->data.size(); ++i)
                if (c->data[i] < 0.0f)
                    throw InputError("reference " + a.ref + ": negative value " + std::to_string(c->data[i]) +
                                     " in channel " + name + " at pixel (" +
                                     std::to_string(ref.x0 + int(i % size_t(ref.width))) + ", " +
                                     std::to_string(ref.y0 + int(i / size_t(ref.width))) +
                                     "); a reference is radiance, which is >= 0");
}

void run_compare(const CompareArgs& a, const CLI::App& cmd) {
    // Ctrl-C during a metric tool's minutes (HDR-VDP under Octave) leaves neither the maps'
    // temporaries nor the tools' output files behind.
    const TemporariesRemovedOnSignal on_signal;
    check_compare_options(a, cmd);
    const Image ref_image = read_exr(a.ref), test_image = read_exr(a.test);
    const metrics::RgbImage ref = metrics::rgb_for_metrics(ref_image, a.ref);
    const metrics::RgbImage test = metrics::rgb_for_metrics(test_image, a.test);
    metrics::check_same_size(ref, a.ref, test, a.test);
    check_comparable(ref_image, test_image, a);

    const double rel = metrics::rel_mse(ref, test);
    const double rmse = metrics::rmse(ref, test);
    const double psnr = metrics::psnr_tonemapped(ref, test, a.exposure);
    // The maps land together at the end, or none does (a failing run writes nothing): each
    // is written to a temporary beside it, the missing directories made at that write.
    CommitGroup maps;
    const auto map_temp = [&maps](const std::string& target) -> std::optional<fs::path> {
        if (target.empty()) return std::nullopt;
        return maps.add(target);
    };
    // A tool's message about the temporary it filled names the map asked for instead.
    metrics::FlipResult flip;
    std::optional<metrics::CvvdpResult> cvvdp;
    maps.naming_targets([&] {
        if (a.no_flip)
            flip.reason = "disabled by --no-flip";
        else
            flip = metrics::compute_flip(a.ref, a.test, map_temp(a.flip_map));
        flip.reason = maps.shown(flip.reason);
        // Without --flip-map an unavailable FLIP is reported in the output; a map asked for
        // and not written fails the run.
        if (!flip.available && !a.flip_map.empty())
            throw RuntimeError("--flip-map " + a.flip_map + ": not written: FLIP did not run (" + flip.reason + ")");
        if (!a.map.empty())
            maps.write(a.map, [&](const fs::path& temp) {
                metrics::write_error_map_png(temp, ref.width, ref.height, metrics::rel_se_map(ref, test));
            });
        if (a.cvvdp)
            cvvdp = metrics::compute_cvvdp(metrics::cvvdp_tool(a.cvvdp_python), a.ref, a.test, map_temp(a.cvvdp_map));
    });
    std::optional<metrics::HdrvdpResult> hdrvdp;
    if (a.hdrvdp) hdrvdp = metrics::compute_hdrvdp(metrics::hdrvdp_tool(), a.ref, a.test);
    {
        const SignalsHeld whole;  // all the maps land, or none: a signal waits for the commit
        maps.commit();
    }

    if (a.json) {
        nlohmann::json j = {
            {"reference", a.ref},
            {"test", a.test},
            {"width", ref.width},
            {"height", ref.height},
            {"relmse", rel},
            {"rmse", rmse},
            // JSON has no infinity: identical tone-mapped images give null here.
            {"psnr_db", std::isinf(psnr) ? nlohmann::json(nullptr) : nlohmann::json(psnr)},
            {"psnr_tonemap", "clamp(x*2^exposure,0,1) then sRGB OETF, peak 1"},
            {"exposure", a.exposure},
            {"flip", flip.available ? nlohmann::json{{"mean", flip.mean},
                                                     {"p_gt_0_1", flip.pct_gt_0_1},
                                                     {"p_gt_0_3", flip.pct_gt_0_3},
                                                     {"implementation", flip.implementation}}
                                    : nlohmann::json{{"unavailable", flip.reason}}},
            {"cvvdp", cvvdp ? nlohmann::json{{"jod", cvvdp->jod},
                                             {"p_ge_1jod", cvvdp->pct_ge_1jod},
                                             {"p_ge_2_44jod", cvvdp->pct_ge_2_44jod},
                                             {"d_mean", cvvdp->d_mean},
                                             {"pixels_per_degree", cvvdp->ppd},
                                             {"peak_cd_m2", cvvdp->peak_cd_m2},
                                             {"reference_mean_luminance_cd_m2", cvvdp->mean_luminance},
                                             {"display", cvvdp->display},
                                             {"implementation", cvvdp->implementation}}
                            : nlohmann::json{{"unavailable", "not requested (--cvvdp)"}}},
            {"hdrvdp", hdrvdp ? nlohmann::json{{"p_ge_75", hdrvdp->pct_p_ge_75},
                                               {"p_ge_95", hdrvdp->pct_p_ge_95},
                                               {"q_jod", hdrvdp->q_jod},
                                               {"pixels_per_degree", hdrvdp->ppd},
                                               {"implementation", hdrvdp->implementation}}
                              : nlohmann::json{{"unavailable", "not requested (--hdrvdp)"}}},
        };
        std::printf("%s\n", j.dump(2).c_str());
        return;
    }
    std::printf("reference  %s (%dx%d)\ntest       %s\n", a.ref.c_str(), ref.width, ref.height, a.test.c_str());
    std::printf("relMSE     %.6g   (mean of (t-r)^2/(r^2+0.01) over pixels and RGB)\n", rel);
    std::printf("RMSE       %.6g   (linear radiance)\n", rmse);
    if (std::isinf(psnr))
        std::printf("PSNR       inf dB (identical after tone mapping)\n");
    else
        std::printf("PSNR       %.3f dB (clamp(x*2^%g) then sRGB, peak 1)\n", psnr, a.exposure);
    if (flip.available)
        std::printf("FLIP       mean %.6f, %.3f%% of pixels > 0.1, %.3f%% > 0.3 (HDR-FLIP, %s)\n", flip.mean,
                    flip.pct_gt_0_1, flip.pct_gt_0_3, flip.implementation.c_str());
    else
        std::printf("FLIP       unavailable: %s\n", flip.reason.c_str());
    if (cvvdp)
        std::printf("cvvdp      %.4f JOD, %.3f%% of pixels >= 1 JOD, %.3f%% >= 2.44 JOD (ColorVideoVDP, %s; %s display, "
                    "peak %g cd/m^2, %g pixels/degree, reference mean %g cd/m^2)\n",
                    cvvdp->jod, cvvdp->pct_ge_1jod, cvvdp->pct_ge_2_44jod, cvvdp->implementation.c_str(),
                    cvvdp->display.c_str(), cvvdp->peak_cd_m2, cvvdp->ppd, cvvdp->mean_luminance);
    if (hdrvdp)
        std::printf("HDR-VDP-3  %.3f%% of pixels P >= 75%%, %.3f%% P >= 95%%, Q %.4f JOD (%s; %g pixels/degree, "
                    "reference mean 100 cd/m^2)\n",
                    hdrvdp->pct_p_ge_75, hdrvdp->pct_p_ge_95, hdrvdp->q_jod, hdrvdp->implementation.c_str(),
                    hdrvdp->ppd);
}

}  // namespace

void add_compare_command(CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "Error of a test image against a reference (compare REF.exr TEST.exr): relMSE, RMSE, PSNR, HDR-FLIP (mean, % > 0.1, % > 0.3)");
    cmd->add_option("reference", args->ref, "Reference EXR (R, G, B channels)")->required();
    cmd->add_option("test", args->test, "Test EXR, same size")->required();
    cmd->add_option("--map", args->map, "Write the per-pixel relative squared error as a false-colour PNG "
                                        "(log scale, black 1e-4 to white 1)");
    cmd->add_option("--flip-map", args->flip_map, "Write the FLIP error map (magma) as PNG");
    cmd->add_option("--exposure", args->exposure, "Exposure in stops before the PSNR tone map")
        ->capture_default_str()
        ->check(finite_number_in("--exposure", -limits::kExposureStops, limits::kExposureStops, false));
    cmd->add_flag("--json", args->json, "Print the metrics as JSON");
    cmd->add_flag("--no-flip", args->no_flip, "Skip FLIP (no Python subprocess)");
    CLI::Option* cvvdp = cmd->add_flag(
        "--cvvdp", args->cvvdp,
        "Also run ColorVideoVDP (bench/cvvdp_metric.py; needs pycvvdp): JOD and % of pixels >= 1 / 2.44 JOD, "
        "32.45 pixels/degree, reference mean 100 cd/m^2 on a 1500 cd/m^2 HDR display");
    cmd->add_option("--cvvdp-map", args->cvvdp_map, "Write cvvdp's distortion map (threshold colours) as PNG")
        ->needs(cvvdp);
    cmd->add_option("--cvvdp-python", args->cvvdp_python,
                    "Python interpreter that imports pycvvdp (default $TESSERA_CVVDP_PYTHON, else python3)")
        ->needs(cvvdp);
    cmd->add_flag("--hdrvdp", args->hdrvdp,
                  "Also run HDR-VDP-3 (bench/hdrvdp_metric.py; needs GNU Octave with its statistics and image "
                  "packages): % of pixels with P >= 75% / 95% of a visible difference and Q_JOD, 32.45 "
                  "pixels/degree, reference mean 100 cd/m^2 (the seed's Table 5.3 figures)");
    cmd->callback([args, cmd] { run_compare(*args, *cmd); });
}

}  // namespace tessera::cli
