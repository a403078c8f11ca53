// The HDR-VDP-3 tool interface (host/metrics/hdrvdp.h) with stand-in scripts, so these run
// everywhere: the script's location, the error when it cannot run or reports a missing
// Octave, and the parsing of its JSON line. The real metric's values are tested in
// tests/cli/compare_command_test.cpp (CompareCli.Hdrvdp*), skipped where Octave is missing.
#include <fstream>

#include <gtest/gtest.h>

#include "metrics/hdrvdp.h"
#include "support/error_of.h"
#include "support/scoped_env.h"
#include "support/scratch_dir.h"
#include "util/error.h"

namespace fs = std::filesystem;
using tessera::test::error_of;
using namespace tessera;
using namespace tessera::metrics;

namespace {

class Hdrvdp : public tessera::test::ScratchDirTest {
protected:
    // A Python script standing in for bench/hdrvdp_metric.py.
    HdrvdpTool stand_in(const std::string& body) {
        const fs::path p = dir_ / "hdrvdp_metric.py";
        std::ofstream(p) << "import sys\n" << body << "\n";
        return {"python3", p};
    }
};

}  // namespace

TEST_F(Hdrvdp, ScriptFromEnvironmentElseTheSourceTree) {
    {
        const tessera::test::ScopedEnv none("TESSERA_HDRVDP_SCRIPT", nullptr);
        EXPECT_EQ(hdrvdp_tool().script, fs::path(TESSERA_SOURCE_DIR) / "bench/hdrvdp_metric.py");
        EXPECT_EQ(hdrvdp_tool().python, "python3");
    }
    const tessera::test::ScopedEnv set("TESSERA_HDRVDP_SCRIPT", "/x/y.py");
    EXPECT_EQ(hdrvdp_tool().script, fs::path("/x/y.py"));
}

TEST_F(Hdrvdp, MissingScriptOrOctaveIsAnInputErrorNamingTheOption) {
    std::string e = error_of([&] { check_hdrvdp({"python3", dir_ / "none.py"}, "--hdrvdp"); });
    EXPECT_NE(e.find("--hdrvdp: script " + (dir_ / "none.py").string() + " not found"), std::string::npos) << e;
    const HdrvdpTool tool = stand_in("print('hdrvdp_metric: octave-cli not found', file=sys.stderr); sys.exit(3)");
    e = error_of([&] { check_hdrvdp(tool, "--hdrvdp"); });
    EXPECT_NE(e.find("--hdrvdp: HDR-VDP-3 is not available: hdrvdp_metric: octave-cli not found"), std::string::npos)
        << e;
    EXPECT_THROW(check_hdrvdp(tool, "--hdrvdp"), InputError);
}

TEST_F(Hdrvdp, ParsesTheLastLineAndPassesBothPaths) {
    // The stand-in echoes its arguments into the implementation field, so the test sees
    // that the reference comes first, as the script expects.
    const HdrvdpTool tool = stand_in(
        "import json\n"
        "print('Octave says something first')\n"
        "print(json.dumps({'p_ge_75': 12.5, 'p_ge_95': 0.25, 'q_jod': 8.75, 'pixels_per_degree': 32.45, "
        "'implementation': ' '.join(sys.argv[1:])}))");
    const HdrvdpResult r = compute_hdrvdp(tool, "ref.exr", "test.exr");
    EXPECT_EQ(r.pct_p_ge_75, 12.5);
    EXPECT_EQ(r.pct_p_ge_95, 0.25);
    EXPECT_EQ(r.q_jod, 8.75);
    EXPECT_EQ(r.ppd, 32.45);
    EXPECT_EQ(r.implementation, "ref.exr test.exr");
}

TEST_F(Hdrvdp, ScriptFailureAndBadOutputAreRuntimeErrors) {
    std::string e = error_of([&] {
        compute_hdrvdp(stand_in("print('hdrvdp_metric: a.exr: NaN or infinite values', file=sys.stderr); sys.exit(2)"),
                       "a.exr", "b.exr");
    });
    EXPECT_NE(e.find("HDR-VDP-3 failed: hdrvdp_metric: a.exr: NaN or infinite values"), std::string::npos) << e;
    e = error_of([&] { compute_hdrvdp(stand_in("print('{\"p_ge_75\": 1}')"), "a.exr", "b.exr"); });
    EXPECT_NE(e.find("HDR-VDP-3: unparsable output from hdrvdp_metric.py"), std::string::npos) << e;
    EXPECT_THROW(compute_hdrvdp(stand_in("print('not json')"), "a.exr", "b.exr"), RuntimeError);
}
