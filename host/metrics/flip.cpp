#include "metrics/flip.h"

#include <nlohmann/json.hpp>

#include "metrics/external_tool.h"

namespace tessera::metrics {
namespace fs = std::filesystem;

FlipResult compute_flip(const fs::path& ref, const fs::path& test, const std::optional<fs::path>& map_png) {
    FlipResult r;
    const std::string python = env_or("TESSERA_PYTHON", "python3");
    const fs::path script = env_or("TESSERA_FLIP_SCRIPT", std::string(TESSERA_SOURCE_DIR) + "/bench/flip_metric.py");
    if (!fs::exists(script)) {
        r.reason = "script " + script.string() + " not found";
        return r;
    }
    std::vector<std::string> args = {python, script.string(), ref.string(), test.string()};
    if (map_png) args.insert(args.end(), {"--map", map_png->string()});
    const ToolRun run = run_tool(args);
    if (!run.started) {
        r.reason = "cannot run " + python + " (" + run.spawn_error + ")";
        return r;
    }
    if (run.exit_code != 0) {
        r.reason = (run.exit_code == 127 ? python + " not found" : last_line(run.err));
        if (r.reason.empty())
            r.reason = script.filename().string() + " exited with status " + std::to_string(run.exit_code);
        return r;
    }
    try {
        const auto j = nlohmann::json::parse(run.out);
        r.mean = j.at("mean").get<double>();
        r.pct_gt_0_1 = j.at("p_gt_0_1").get<double>();
        r.pct_gt_0_3 = j.at("p_gt_0_3").get<double>();
        r.implementation = j.value("implementation", "flip-evaluator");
        r.available = true;
    } catch (const std::exception& e) {
        r.reason = "unparsable output from " + script.filename().string() + ": " + e.what();
    }
    return r;
}

}  // namespace tessera::metrics
