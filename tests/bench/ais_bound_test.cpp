// bench/ais_bound end to end on a tiny render (Cornell box, 32x32, Embree, tile 3, 2
// passes): the full-rate comparator is tile 1 with 9x the samples, and the stored bounds
// and A's equal-error speedups are the formulas of the script's docstring applied to the
// stored errors and times, against IGI's line and against a given IGI front.
#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;
using tessera::test::shell_status;

namespace {

class AisBound : public tessera::test::ScratchDirTest {};

}  // namespace

TEST_F(AisBound, TinyCornellRowFollowsItsFormulas) {
    const std::string src = TESSERA_SOURCE_DIR;
    const fs::path out = dir_ / "out", log = dir_ / "log.txt";
    // An IGI front on one log-log line, relMSE = t^-2 from (1 s, 1) to (100 s, 1e-4), so the
    // front reaches error e at t = e^-1/2; measured against the reference the run renders.
    const fs::path front = dir_ / "front.json";
    const fs::path ref = dir_ / "work" / "cornell-box" / "reference_pt_256spp_32x32.exr";
    std::ofstream(front) << nlohmann::json{
        {"scene", "cornell-box"}, {"width", 32}, {"height", 32}, {"date", "test"}, {"reference", {{"path", ref.string()}}},
        {"rows", {{{"method", "igi"}, {"backend", "embree"}, {"time_s", 1.0}, {"relmse", 1.0}},
                  {{"method", "igi"}, {"backend", "embree"}, {"time_s", 100.0}, {"relmse", 1e-4}}}}};
    const std::string cmd = "python3 " + src + "/bench/ais_bound --tessera " + TESSERA_EXE + " --scenes " + src +
                            "/scenes/cornell-box.json --width 32 --height 32 --backends embree --tiles 3 --passes 2" +
                            " --reference-spp 256 --no-flip --front " + front.string() + " --out " + out.string() +
                            " --work-dir " + (dir_ / "work").string() + " > " + log.string() + " 2>&1";
    ASSERT_EQ(shell_status(cmd), 0) << std::ifstream(log).rdbuf();
    const nlohmann::json docs = nlohmann::json::parse(std::ifstream(out / "ais_bound.json"));
    ASSERT_EQ(docs.size(), 1u);
    ASSERT_EQ(docs[0]["rows"].size(), 1u);
    const auto& r = docs[0]["rows"][0];
    EXPECT_EQ(r["passes"], 2);
    EXPECT_EQ(r["full_rate_setting"]["tile"], 1);
    EXPECT_EQ(r["full_rate_setting"]["vpl-paths"], 72) << "9 sets x 8 paths";
    EXPECT_EQ(r["full_rate_setting"]["shadow-samples"], 36) << "9 sets x 4 light samples";
    const auto& e = r["error"];
    const auto& t = r["time_s"];
    for (const char* n : {"igi", "igi2", "full", "ais", "amax"}) {
        EXPECT_GT(e[n]["relmse"].get<double>(), 0.0) << n;
        EXPECT_GT(t[n].get<double>(), 0.0) << n;
    }
    // The bound and A's speedup from the stored numbers (s from k and 2k passes of igi).
    const double s = std::log(e["igi"]["relmse"].get<double>() / e["igi2"]["relmse"].get<double>()) /
                     std::log(t["igi2"].get<double>() / t["igi"].get<double>());
    EXPECT_NEAR(r["relmse"]["slope"].get<double>(), s, 1e-9);
    const double lim = std::min({e["full"]["relmse"].get<double>(), e["ais"]["relmse"].get<double>(),
                                 e["amax"]["relmse"].get<double>()});
    if (s > 0) {
        EXPECT_NEAR(r["relmse"]["bound"].get<double>(), std::pow(e["igi"]["relmse"].get<double>() / lim, 1 / s), 1e-9);
        EXPECT_NEAR(r["relmse"]["ais_vs_igi"].get<double>(),
                    t["igi"].get<double>() * std::pow(e["igi"]["relmse"].get<double>() / e["ais"]["relmse"].get<double>(),
                                                      1 / s) / t["ais"].get<double>(),
                    1e-9);
    } else {  // no convergence rate to extrapolate with: the script writes no bound
        EXPECT_TRUE(r["relmse"]["bound"].is_null()) << s;
        EXPECT_TRUE(r["relmse"]["ais_vs_igi"].is_null()) << s;
    }
    EXPECT_NEAR(r["relmse"]["bound_vs_front"].get<double>(), std::pow(lim, -0.5) / t["igi"].get<double>(), 1e-9);
    EXPECT_NEAR(r["relmse"]["ais_vs_front"].get<double>(),
                std::pow(e["ais"]["relmse"].get<double>(), -0.5) / t["ais"].get<double>(), 1e-9);
    EXPECT_NEAR(r["ais_vs_full_rate"].get<double>(), t["full"].get<double>() / t["ais"].get<double>(), 1e-12);
    std::ifstream md(out / "ais_bound.md");
    std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("t3 p8 l4 x2"), std::string::npos) << text;
}
