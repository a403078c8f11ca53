#include "metrics/hdrvdp.h"

#include <nlohmann/json.hpp>

#include "metrics/external_tool.h"
#include "util/error.h"

namespace tessera::metrics {
namespace fs = std::filesystem;

HdrvdpTool hdrvdp_tool() {
    return {"python3", env_or("TESSERA_HDRVDP_SCRIPT", std::string(TESSERA_SOURCE_DIR) + "/bench/hdrvdp_metric.py")};
}

std::string check_hdrvdp(const HdrvdpTool& tool, const std::string& option) {
    if (!fs::exists(tool.script))
        throw InputError(option + ": script " + tool.script.string() + " not found (TESSERA_HDRVDP_SCRIPT)");
    const ToolRun run = run_tool({tool.python, tool.script.string(), "--check"});
    if (!run.started || run.exit_code != 0)
        throw InputError(option + ": HDR-VDP-3 is not available: " + tool_failure(tool.python, tool.script, run) +
                         " (bench/README.md, 'Perceptual metric')");
    return last_line(run.out);
}

HdrvdpResult compute_hdrvdp(const HdrvdpTool& tool, const fs::path& ref, const fs::path& test) {
    const ToolRun run = run_tool({tool.python, tool.script.string(), ref.string(), test.string()});
    if (!run.started || run.exit_code != 0)
        throw RuntimeError("HDR-VDP-3 failed: " + tool_failure(tool.python, tool.script, run));
    HdrvdpResult r;
    try {
        const auto j = nlohmann::json::parse(last_line(run.out));
        r.pct_p_ge_75 = j.at("p_ge_75").get<double>();
        r.pct_p_ge_95 = j.at("p_ge_95").get<double>();
        r.q_jod = j.at("q_jod").get<double>();
        r.ppd = j.at("pixels_per_degree").get<double>();
        r.implementation = j.value("implementation", "hdrvdp-3");
    } catch (const std::exception& e) {
        throw RuntimeError("HDR-VDP-3: unparsable output from " + tool.script.filename().string() + ": " + e.what());
    }
    return r;
}

}  // namespace tessera::metrics
