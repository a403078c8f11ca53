#include "metrics/cvvdp.h"

#include <vector>

#include <nlohmann/json.hpp>

#include "metrics/external_tool.h"
#include "util/error.h"

namespace tessera::metrics {
namespace fs = std::filesystem;
namespace {

const char* const kInstallHint =
    "install cvvdp in a venv (bench/README.md, 'Perceptual metric') and name its python with --cvvdp-python or "
    "TESSERA_CVVDP_PYTHON";

}  // namespace

CvvdpTool cvvdp_tool(const std::string& python_option) {
    return {python_option.empty() ? env_or("TESSERA_CVVDP_PYTHON", "python3") : python_option,
            env_or("TESSERA_CVVDP_SCRIPT", std::string(TESSERA_SOURCE_DIR) + "/bench/cvvdp_metric.py")};
}

std::string check_cvvdp(const CvvdpTool& tool, const std::string& option) {
    if (!fs::exists(tool.script))
        throw InputError(option + ": script " + tool.script.string() + " not found (TESSERA_CVVDP_SCRIPT)");
    const ToolRun run = run_tool({tool.python, tool.script.string(), "--check"});
    if (!run.started || run.exit_code != 0)
        throw InputError(option + ": ColorVideoVDP is not available with " + tool.python + ": " +
                         tool_failure(tool.python, tool.script, run) + "; " + kInstallHint);
    return last_line(run.out);
}

CvvdpResult compute_cvvdp(const CvvdpTool& tool, const fs::path& ref, const fs::path& test,
                          const std::optional<fs::path>& heatmap_png) {
    std::vector<std::string> args = {tool.python, tool.script.string(), ref.string(), test.string()};
    if (heatmap_png) args.insert(args.end(), {"--heatmap", heatmap_png->string()});
    const ToolRun run = run_tool(args);
    if (!run.started || run.exit_code != 0) throw RuntimeError("ColorVideoVDP failed: " + tool_failure(tool.python, tool.script, run));
    CvvdpResult r;
    try {
        const auto j = nlohmann::json::parse(run.out);
        r.jod = j.at("jod").get<double>();
        r.pct_ge_1jod = j.at("p_ge_1jod").get<double>();
        r.pct_ge_2_44jod = j.at("p_ge_2_44jod").get<double>();
        r.d_mean = j.at("d_mean").get<double>();
        const auto& v = j.at("viewing");
        r.ppd = v.at("pixels_per_degree").get<double>();
        r.peak_cd_m2 = v.at("peak_cd_m2").get<double>();
        r.mean_luminance = v.at("reference_mean_luminance_cd_m2").get<double>();
        r.display = v.at("display_photometry").get<std::string>();
        r.implementation = j.value("implementation", "cvvdp");
    } catch (const std::exception& e) {
        throw RuntimeError("ColorVideoVDP: unparsable output from " + tool.script.filename().string() + ": " +
                           e.what());
    }
    return r;
}

}  // namespace tessera::metrics
