// bench/accuracy and bench/accuracy_report end to end on a tiny sweep (Cornell box, 32x32,
// both backends, few settings): the outputs parse, times are consistent, and the pt error
// falls monotonically as spp grows against a reference rendered at far higher spp.
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;
using tessera::test::python_imports;
using tessera::test::shell_status;

namespace {

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> out;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, sep);) out.push_back(f);
    if (!line.empty() && line.back() == sep) out.emplace_back();
    return out;
}

class AccuracySweep : public tessera::test::ScratchDirTest {};

}  // namespace

TEST_F(AccuracySweep, TinyCornellSweepParsesAndPtErrorFalls) {
    const std::string src = TESSERA_SOURCE_DIR;
    const fs::path out = dir_ / "out", log = dir_ / "log.txt";
    const std::string cmd = "python3 " + src + "/bench/accuracy --tessera " + TESSERA_EXE + " --scenes " + src +
                            "/scenes/cornell-box.json --width 32 --height 32 --frames 3 --reference-spp 4096" +
                            " --methods pt direct --grid pt:spp=1,4,16,64 --grid direct:spp=1,16" +
                            " --grid direct:shadow-samples=1 --out-dir " + out.string() + " --work-dir " +
                            (dir_ / "work").string() + " --cvvdp --cvvdp-python /nonexistent/python3 > " +
                            log.string() + " 2>&1";
    ASSERT_EQ(shell_status(cmd), 0) << std::ifstream(log).rdbuf();

    std::ifstream jf(out / "cornell-box.json");
    ASSERT_TRUE(jf) << "no JSON written";
    const nlohmann::json doc = nlohmann::json::parse(jf);
    EXPECT_EQ(doc["width"], 32);
    EXPECT_EQ(doc["reference"]["spp"], 4096);
    EXPECT_EQ(doc["reference"]["kind"], "rendered by bench/accuracy");
    // --cvvdp with an interpreter that cannot run: the sweep goes on, the reason is recorded.
    EXPECT_NE(doc["cvvdp"]["unavailable"].get<std::string>().find("/nonexistent/python3"), std::string::npos)
        << doc["cvvdp"].dump();
    EXPECT_TRUE(doc["rows"][0]["cvvdp_jod"].is_null());
    const auto& rows = doc["rows"];
    ASSERT_EQ(rows.size(), 2u * (4 + 2)) << "2 backends x (4 pt + 2 direct settings)";
    // Provenance: one run, what it measured, where and under what load.
    ASSERT_EQ(doc["runs"].size(), 1u) << doc["runs"].dump();
    EXPECT_EQ(doc["runs"][0]["methods"], nlohmann::json::array({"pt", "direct"}));
    EXPECT_EQ(doc["runs"][0]["backends"], nlohmann::json::array({"opencl", "embree"}));
    EXPECT_EQ(doc["runs"][0]["date"], doc["date"]);
    EXPECT_GT(doc["runs"][0]["cores"].get<int>(), 0);
    EXPECT_EQ(doc["runs"][0]["load_average_1min"].size(), 2u);

    // CSV: header plus one line per row, same relMSE values as the JSON.
    std::ifstream cf(out / "cornell-box.csv");
    std::string line;
    ASSERT_TRUE(std::getline(cf, line));
    const auto header = split(line, ',');
    std::map<std::string, size_t> col;
    for (size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
    ASSERT_TRUE(col.count("relmse") && col.count("time_s") && col.count("flip_mean") && col.count("cvvdp_jod"));
    size_t n = 0;
    while (std::getline(cf, line)) {
        const auto f = split(line, ',');
        ASSERT_EQ(f.size(), header.size()) << line;
        EXPECT_NEAR(std::stod(f[col["relmse"]]), rows[n]["relmse"].get<double>(), 1e-12);
        ++n;
    }
    EXPECT_EQ(n, rows.size());

    const bool have_flip = rows[0]["flip_mean"].is_number();
    for (const std::string backend : {"opencl", "embree"}) {
        std::vector<nlohmann::json> pt;
        double direct_best = 1e30;
        for (const auto& r : rows) {
            EXPECT_GT(r["median_pass_s"].get<double>(), 0.0);
            EXPECT_NEAR(r["time_s"].get<double>(), r["spp"].get<int>() * r["median_pass_s"].get<double>(), 1e-12);
            EXPECT_TRUE(std::isfinite(r["relmse"].get<double>()));
            if (r["backend"] != backend) continue;
            if (r["method"] == "pt") pt.push_back(r);
            if (r["method"] == "direct") direct_best = std::min(direct_best, r["relmse"].get<double>());
        }
        ASSERT_EQ(pt.size(), 4u);
        for (size_t i = 1; i < pt.size(); ++i) {
            EXPECT_GT(pt[i]["spp"].get<int>(), pt[i - 1]["spp"].get<int>());
            // relMSE of an unbiased estimator falls ~1/spp: x4 spp must at least halve it.
            EXPECT_LT(pt[i]["relmse"].get<double>(), 0.5 * pt[i - 1]["relmse"].get<double>()) << backend << " " << i;
            EXPECT_GT(pt[i]["psnr_db"].get<double>(), pt[i - 1]["psnr_db"].get<double>());
            if (have_flip) {
                EXPECT_LT(pt[i]["flip_mean"].get<double>(), pt[i - 1]["flip_mean"].get<double>());
            }
        }
        // direct lacks indirect light: its error floors well above pt at 64 spp.
        EXPECT_GT(direct_best, 3.0 * pt.back()["relmse"].get<double>()) << backend;
    }

    // The report reads those files and writes the tables (and the plot if matplotlib exists).
    const bool mpl = python_imports("matplotlib");
    ASSERT_EQ(shell_status("python3 " + src + "/bench/accuracy_report --dir " + out.string() + (mpl ? "" : " --no-plots") +
                  " > " + log.string() + " 2>&1"),
              0)
        << std::ifstream(log).rdbuf();
    std::stringstream md;
    md << std::ifstream(out / "report.md").rdbuf();
    EXPECT_NE(md.str().find("## Table 1: frames per second"), std::string::npos);
    EXPECT_NE(md.str().find("| cornell-box |"), std::string::npos);
    if (mpl) {
        EXPECT_TRUE(fs::exists(out / "cornell-box.png"));
    }
    EXPECT_NE(md.str().find("## Table 2b"), std::string::npos);
    // pt and direct only: none of Table 2b's pairs, said in one line rather than an empty section.
    EXPECT_NE(md.str().find("None of its pairs (ais vs igi"), std::string::npos) << md.str();
    EXPECT_NE(md.str().find("Measured in one run:"), std::string::npos) << md.str();
    EXPECT_NE(md.str().find("## Table 3b: ColorVideoVDP"), std::string::npos);
    EXPECT_NE(md.str().find("Not measured: cannot run /nonexistent/python3"), std::string::npos) << md.str();

    // --merge re-sweeps one method and keeps the others' rows (same reference) ...
    const std::string base = "python3 " + src + "/bench/accuracy --tessera " + TESSERA_EXE + " --scenes " + src +
                             "/scenes/cornell-box.json --width 32 --height 32 --frames 3 --methods direct" +
                             " --grid direct:spp=4 --grid direct:shadow-samples=1 --merge --out-dir " +
                             out.string() + " --work-dir " + (dir_ / "work").string();
    ASSERT_EQ(shell_status(base + " --reference-spp 4096 > " + log.string() + " 2>&1"), 0) << std::ifstream(log).rdbuf();
    const nlohmann::json merged = nlohmann::json::parse(std::ifstream(out / "cornell-box.json"));
    size_t pt_rows = 0, direct_rows = 0;
    for (const auto& r : merged["rows"]) {
        pt_rows += r["method"] == "pt";
        direct_rows += r["method"] == "direct";
        if (r["method"] == "direct") {
            EXPECT_EQ(r["spp"], 4);
        }
    }
    EXPECT_EQ(pt_rows, 8u) << "pt kept from the first sweep";
    EXPECT_EQ(direct_rows, 2u) << "direct replaced by the new sweep";
    EXPECT_TRUE(merged["methods"].contains("pt"));
    // The kept rows' run stays on record beside the new one, narrowed to what it still holds.
    ASSERT_EQ(merged["runs"].size(), 2u) << merged["runs"].dump();
    EXPECT_EQ(merged["runs"][0]["methods"], nlohmann::json::array({"direct"}));
    EXPECT_EQ(merged["runs"][1]["methods"], nlohmann::json::array({"pt"}));
    EXPECT_EQ(merged["runs"][1]["date"], doc["date"]) << "the first sweep's run";
    ASSERT_EQ(shell_status("python3 " + src + "/bench/accuracy_report --no-plots --dir " + out.string() + " > " +
                           log.string() + " 2>&1"),
              0)
        << std::ifstream(log).rdbuf();
    std::stringstream merged_md;
    merged_md << std::ifstream(out / "report.md").rdbuf();
    EXPECT_NE(merged_md.str().find("Measured in 2 runs:"), std::string::npos) << merged_md.str();
    EXPECT_NE(merged_md.str().find("(rows kept by `bench/accuracy --merge`)"), std::string::npos) << merged_md.str();
    // ... and refuses to mix errors measured against another reference.
    EXPECT_NE(shell_status(base + " --reference-spp 64 > " + log.string() + " 2>&1"), 0);
    std::stringstream err;
    err << std::ifstream(log).rdbuf();
    EXPECT_NE(err.str().find("another reference"), std::string::npos) << err.str();
}

// Mistakes in the command line fail at once, exit status 2, with one line naming the option
// and value: not inside tessera after the reference has been rendered.
TEST_F(AccuracySweep, MistakesFailBeforeRendering) {
    const std::string src = TESSERA_SOURCE_DIR;
    const fs::path work = dir_ / "work";
    const std::string base = "python3 " + src + "/bench/accuracy --tessera " + TESSERA_EXE + " --scenes " + src +
                             "/scenes/cornell-box.json --width 32 --height 32 --out-dir " + (dir_ / "out").string() +
                             " --work-dir " + work.string() + " ";
    const std::pair<std::string, std::string> cases[] = {
        {"--methods pt --grid pt:sp=1,2", "--grid pt:sp=1,2: sp is neither a setting of pt (spp)"},
        {"--methods pt --grid pt:spp=0,2", "--grid pt:spp=0,2: spp values must be whole numbers of at least 1"},
        {"--backends cuda", "invalid choice: 'cuda'"},
        {"--frames 0", "--frames 0: must be at least 1"},
    };
    for (const auto& [words, message] : cases) {
        const auto r = tessera::test::run_shell(base + words);
        EXPECT_EQ(r.exit_code, 2) << words << "\n" << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << words << "\n" << r.output;
        EXPECT_FALSE(fs::exists(work)) << words << ": the sweep started (its work directory exists)";
    }
    // An option of tessera render that no method sweeps is a valid new axis: the grid passes
    // its check (made first) and the next mistake is the one reported.
    const auto ok = tessera::test::run_shell(base + "--methods pt --grid pt:max-depth=1,2 --frames -1");
    EXPECT_NE(ok.output.find("--frames -1: must be at least 1"), std::string::npos) << ok.output;
    EXPECT_EQ(ok.output.find("error: --grid"), std::string::npos) << ok.output;
}
