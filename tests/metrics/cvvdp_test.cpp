// The cvvdp tool interface (host/metrics/cvvdp.h) with stand-in interpreters, so these run
// everywhere: which interpreter is chosen, the error when it cannot run or import
// pycvvdp, and the parsing of the script's JSON. The real metric's values are tested in
// tests/cli/compare_command_test.cpp (CompareCli.Cvvdp*), skipped where pycvvdp is missing.
#include <sys/stat.h>

#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "metrics/cvvdp.h"
#include "support/error_of.h"
#include "support/scoped_env.h"
#include "support/scratch_dir.h"
#include "util/error.h"

namespace fs = std::filesystem;
using tessera::test::error_of;
using namespace tessera;
using namespace tessera::metrics;

namespace {

class Cvvdp : public tessera::test::ScratchDirTest {
protected:
    // An executable /bin/sh script standing in for the Python interpreter.
    std::string fake_python(const std::string& name, const std::string& body) {
        const fs::path p = dir_ / name;
        std::ofstream(p) << "#!/bin/sh\n" << body << "\n";
        ::chmod(p.c_str(), 0755);
        return p.string();
    }
    CvvdpTool tool(const std::string& python) {
        const fs::path script = dir_ / "cvvdp_metric.py";
        std::ofstream(script) << "# stand-in: the fake interpreter does not read it\n";
        return {python, script};
    }
};

const char* const kJson =
    R"({"jod": 9.125, "p_ge_1jod": 12.5, "p_ge_2_44jod": 0.75, "d_mean": 0.0421, "d_max": 0.6, )"
    R"("width": 4, "height": 4, "implementation": "cvvdp 0.5.7, torch 2.9.0", )"
    R"("viewing": {"display_photometry": "standard_hdr_linear", "peak_cd_m2": 1500.0, )"
    R"("pixels_per_degree": 32.45, "reference_mean_luminance_cd_m2": 100.0}})";

}  // namespace

TEST_F(Cvvdp, InterpreterFromOptionThenEnvironmentThenPython3) {
    const tessera::test::ScopedEnv no_script("TESSERA_CVVDP_SCRIPT", nullptr);
    {
        const tessera::test::ScopedEnv none("TESSERA_CVVDP_PYTHON", nullptr);
        EXPECT_EQ(cvvdp_tool("").python, "python3");
        EXPECT_EQ(cvvdp_tool("").script, fs::path(TESSERA_SOURCE_DIR) / "bench/cvvdp_metric.py");
        EXPECT_TRUE(fs::exists(cvvdp_tool("").script));
    }
    const tessera::test::ScopedEnv venv("TESSERA_CVVDP_PYTHON", "/opt/venv/bin/python");
    EXPECT_EQ(cvvdp_tool("").python, "/opt/venv/bin/python");
    EXPECT_EQ(cvvdp_tool("/other/python").python, "/other/python");
}

TEST_F(Cvvdp, MissingInterpreterIsAnInputErrorNamingTheOption) {
    const std::string e = error_of([&] { check_cvvdp(tool("/nonexistent/python3"), "--cvvdp"); });
    EXPECT_EQ(e.rfind("--cvvdp: ColorVideoVDP is not available with /nonexistent/python3", 0), 0u) << e;
    EXPECT_NE(e.find("--cvvdp-python"), std::string::npos) << "says how to name another interpreter: " << e;
    EXPECT_THROW(check_cvvdp(tool("/nonexistent/python3"), "--cvvdp"), InputError);
}

TEST_F(Cvvdp, ImportFailureGivesTheScriptsReason) {
    const std::string py = fake_python("py", "echo \"cvvdp_metric: No module named 'pycvvdp' (install: ...)\" >&2; exit 3");
    const std::string e = error_of([&] { check_cvvdp(tool(py), "--cvvdp"); });
    EXPECT_NE(e.find("No module named 'pycvvdp'"), std::string::npos) << e;
    EXPECT_NE(e.find("--cvvdp: "), std::string::npos) << e;
}

TEST_F(Cvvdp, MissingScriptIsAnInputError) {
    const std::string e = error_of([&] { check_cvvdp({"python3", dir_ / "none.py"}, "--cvvdp"); });
    EXPECT_NE(e.find("--cvvdp: script " + (dir_ / "none.py").string() + " not found"), std::string::npos) << e;
}

TEST_F(Cvvdp, CheckReturnsTheReportedImplementation) {
    const std::string py = fake_python("py", "[ \"$2\" = --check ] || exit 9; echo 'cvvdp 0.5.7, torch 2.9.0'");
    EXPECT_EQ(check_cvvdp(tool(py), "--cvvdp"), "cvvdp 0.5.7, torch 2.9.0");
}

TEST_F(Cvvdp, ParsesTheScriptsJsonAndPassesTheHeatmapPath) {
    // The stand-in checks its arguments: script, reference, test, --heatmap PATH.
    const std::string py = fake_python(
        "py", "[ \"$2\" = ref.exr ] && [ \"$3\" = test.exr ] && [ \"$4\" = --heatmap ] && [ \"$5\" = map.png ] "
              "|| { echo \"bad arguments: $*\" >&2; exit 2; }\necho '" + std::string(kJson) + "'");
    const CvvdpResult r = compute_cvvdp(tool(py), "ref.exr", "test.exr", fs::path("map.png"));
    EXPECT_EQ(r.jod, 9.125);
    EXPECT_EQ(r.pct_ge_1jod, 12.5);
    EXPECT_EQ(r.pct_ge_2_44jod, 0.75);
    EXPECT_EQ(r.d_mean, 0.0421);
    EXPECT_EQ(r.ppd, 32.45);
    EXPECT_EQ(r.peak_cd_m2, 1500.0);
    EXPECT_EQ(r.mean_luminance, 100.0);
    EXPECT_EQ(r.display, "standard_hdr_linear");
    EXPECT_EQ(r.implementation, "cvvdp 0.5.7, torch 2.9.0");
}

TEST_F(Cvvdp, ScriptFailureAndBadOutputAreRuntimeErrors) {
    const std::string failing = fake_python("fail", "echo 'cvvdp_metric: b.exr: NaN or infinite values' >&2; exit 2");
    EXPECT_EQ(error_of([&] { compute_cvvdp(tool(failing), "a.exr", "b.exr"); }),
              "ColorVideoVDP failed: cvvdp_metric: b.exr: NaN or infinite values");
    EXPECT_THROW(compute_cvvdp(tool(failing), "a.exr", "b.exr"), RuntimeError);
    const std::string garbage = fake_python("garbage", "echo 'not json'");
    EXPECT_NE(error_of([&] { compute_cvvdp(tool(garbage), "a.exr", "b.exr"); }).find("unparsable output"),
              std::string::npos);
    const std::string partial = fake_python("partial", "echo '{\"jod\": 9.0}'");
    EXPECT_THROW(compute_cvvdp(tool(partial), "a.exr", "b.exr"), RuntimeError);
}
