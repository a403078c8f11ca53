// bench/accuracy_report's equal-error arithmetic on synthetic rows, through Python: the
// speedup at a target is the ratio of the times the two Pareto fronts need to reach it
// (log-log interpolation), and the full-rate IGI comparator holds igi's tile-1 rows only.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "bench/igi_timing.h"
#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;
using tessera::test::shell_status;

namespace {

class AccuracyReport : public tessera::test::ScratchDirTest {};

}  // namespace

TEST_F(AccuracyReport, EqualErrorSpeedupsAndTheFullRateIgiComparator) {
    // Fronts: A reaches relMSE 0.1 in 1 s and 0.01 in 10 s; igi tile 3 reaches them in 2 s
    // and 20 s; igi tile 1 in 8 s and 80 s (plus a dominated tile-1 point). Log-log lines
    // through each pair, so at every target in [0.01, 0.1] A vs igi = 2, A vs igi-t1 = 8.
    const std::string script = R"PY(
import importlib.machinery, importlib.util, sys
loader = importlib.machinery.SourceFileLoader("accuracy_report", sys.argv[1])
spec = importlib.util.spec_from_loader("accuracy_report", loader)
r = importlib.util.module_from_spec(spec)
loader.exec_module(r)
def row(m, setting, t, e):
    return {"method": m, "backend": "embree", "setting": setting, "spp": 1, "time_s": t, "relmse": e}
rows = [row("ais", "tile=3", 1.0, 0.1), row("ais", "tile=3", 10.0, 0.01),
        row("igi", "tile=3", 2.0, 0.1), row("igi", "tile=3", 20.0, 0.01),
        row("igi", "tile=1", 8.0, 0.1), row("igi", "tile=1", 80.0, 0.01), row("igi", "tile=1", 90.0, 0.05)]
full = [x for x in r.with_full_rate_igi(rows) if x["method"] == r.FULL_RATE_IGI]
assert sorted(x["time_s"] for x in full) == [8.0, 80.0, 90.0], full
rows = r.with_full_rate_igi(rows)
for b, want in (("igi", 2.0), (r.FULL_RATE_IGI, 8.0)):
    rng = r.speedup_range(rows, "ais", b, "embree", "relmse")
    assert len(rng) == 5, rng
    assert abs(rng[0][0] - 0.1) < 1e-12 and abs(rng[-1][0] - 0.01) < 1e-12, rng
    for target, s, la, lb in rng:
        assert abs(s - want) < 1e-9, (b, target, s)
    assert rng[0][2] == "t3 x1", rng
print("ok")
)PY";
    const fs::path py = dir_ / "check.py", log = dir_ / "log.txt";
    std::ofstream(py) << script;
    const std::string report = std::string(TESSERA_SOURCE_DIR) + "/bench/accuracy_report";
    EXPECT_EQ(shell_status("python3 " + py.string() + " " + report + " > " + log.string() + " 2>&1"), 0)
        << std::ifstream(log).rdbuf();
}

// The report's rows: the standard scenes in the seed's row order (the same list as the C++
// benchmarks' bench::standard_scenes), others after them by name, and an Average row that
// is the mean over the scenes with a value.
TEST_F(AccuracyReport, SeedRowOrderAndAverage) {
    std::string cpp_names;
    for (const std::string& path : tessera::bench::standard_scenes())
        cpp_names += "'" + fs::path(path).stem().string() + "', ";
    const std::string script = R"PY(
import importlib.machinery, importlib.util, sys
loader = importlib.machinery.SourceFileLoader("accuracy_report", sys.argv[1])
spec = importlib.util.spec_from_loader("accuracy_report", loader)
r = importlib.util.module_from_spec(spec)
loader.exec_module(r)
import standard_scenes
assert standard_scenes.STANDARD_SCENES == [)PY" + cpp_names + R"PY(], standard_scenes.STANDARD_SCENES
names = ["zeta", "sibenik", "office-fog", "alpha", "cornell-box", "deskar", "shirley6"]
got = sorted(names, key=r.row_order)
assert got == ["cornell-box", "deskar", "sibenik", "shirley6", "office-fog", "alpha", "zeta"], got
assert r.mean_or_none([1.0, None, 3.0]) == 2.0
assert r.mean_or_none([None, None]) is None
print("ok")
)PY";
    const fs::path py = dir_ / "order.py", log = dir_ / "log.txt";
    std::ofstream(py) << script;
    const std::string report = std::string(TESSERA_SOURCE_DIR) + "/bench/accuracy_report";
    EXPECT_EQ(shell_status("python3 " + py.string() + " " + report + " > " + log.string() + " 2>&1"), 0)
        << std::ifstream(log).rdbuf();
}
