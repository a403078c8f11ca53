// bench/accuracy_report's equal-error arithmetic on synthetic rows, through Python: the
// speedup at a target is the ratio of the times the two Pareto fronts need to reach it
// (log-log interpolation), and the full-rate IGI comparator holds igi's tile-1 rows only.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "bench/igi_timing.h"
#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;
using tessera::test::shell_status;

namespace {

// Loads bench/accuracy_report (a script without a .py name) as the module `r`.
constexpr const char* kLoadReport = R"PY(import importlib.machinery, importlib.util, sys
loader = importlib.machinery.SourceFileLoader("accuracy_report", sys.argv[1])
spec = importlib.util.spec_from_loader("accuracy_report", loader)
r = importlib.util.module_from_spec(spec)
loader.exec_module(r)
)PY";

class AccuracyReport : public tessera::test::ScratchDirTest {
protected:
    /// Runs kLoadReport + `body` with python3 (sys.argv[2]: a report path in the scratch
    /// directory) and returns its exit status; log() holds what it printed.
    int run_python(const std::string& body) {
        const fs::path py = dir_ / "check.py";
        std::ofstream(py) << kLoadReport << body;
        const std::string report = std::string(TESSERA_SOURCE_DIR) + "/bench/accuracy_report";
        return shell_status("python3 " + py.string() + " " + report + " " + (dir_ / "report.md").string() + " > " +
                            log_path().string() + " 2>&1");
    }
    std::string log() const {
        std::ifstream in(log_path());
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

private:
    fs::path log_path() const { return dir_ / "log.txt"; }
};

}  // namespace

TEST_F(AccuracyReport, EqualErrorSpeedupsAndTheFullRateIgiComparator) {
    // Fronts: A reaches relMSE 0.1 in 1 s and 0.01 in 10 s; igi tile 3 reaches them in 2 s
    // and 20 s; igi tile 1 in 8 s and 80 s (plus a dominated tile-1 point). Log-log lines
    // through each pair, so at every target in [0.01, 0.1] A vs igi = 2, A vs igi-t1 = 8.
    const std::string script = R"PY(
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
    EXPECT_EQ(run_python(script), 0) << log();
}

// The report's rows: the standard scenes in the seed's row order (the same list as the C++
// benchmarks' bench::standard_scenes), others after them by name, and an Average row that
// is the mean over the scenes with a value.
TEST_F(AccuracyReport, SeedRowOrderAndAverage) {
    std::string cpp_names;
    for (const std::string& path : tessera::bench::standard_scenes())
        cpp_names += "'" + fs::path(path).stem().string() + "', ";
    const std::string script = R"PY(
import standard_scenes
assert standard_scenes.STANDARD_SCENES == [)PY" + cpp_names + R"PY(], standard_scenes.STANDARD_SCENES
names = ["zeta", "sibenik", "office-fog", "alpha", "cornell-box", "deskar", "shirley6"]
got = sorted(names, key=r.row_order)
assert got == ["cornell-box", "deskar", "sibenik", "shirley6", "office-fog", "alpha", "zeta"], got
assert r.mean_or_none([1.0, None, 3.0]) == 2.0
assert r.mean_or_none([None, None]) is None
print("ok")
)PY";
    EXPECT_EQ(run_python(script), 0) << log();
}

// The report's text where a sweep is partial or merged: no broken table without comparable
// pairs, every run a --merge kept named with its machine and load (a load above the core
// count warned about, and only then), variants labelled by the option they change, Table
// 3b's reason said once; and the plots' colours tell every method apart.
TEST_F(AccuracyReport, PartialAndMergedSweepsReadRight) {
    const std::string script = R"PY(
from pathlib import Path
out = Path(sys.argv[2])
def row(m, spp, t, e):
    return {"method": m, "backend": "embree", "setting": "-", "spp": spp, "time_s": t, "relmse": e, "psnr_db": 20.0}
def doc(scene, methods, rows, **extra):
    return {"scene": scene, "width": 32, "height": 32, "frames_timed": 3, "machine": "2-core Test CPU",
            "date": "2026-11-30T10:00:00", "reference": {"kind": "file", "path": "ref.exr"},
            "cvvdp": {"unavailable": "not requested (bench/accuracy --cvvdp)"},
            "methods": {m: {"operating": {"spp": 1}, "note": ""} for m in methods}, "rows": rows, **extra}
def report(*docs):
    r.report(list(docs), None, out)
    return out.read_text()

# pt alone on one backend: no pair, so one line each for Tables 2 and 2b, not an empty table.
md = report(doc("box", ["pt"], [row("pt", 1, 1.0, 0.1), row("pt", 4, 4.0, 0.03)]))
assert "| scene |  |" not in md and "\n|---|\n" not in md, md
assert "No comparable pair in these sweeps" in md, md
assert "None of its pairs (ais vs igi" in md, md
assert "Not measured: not requested (bench/accuracy --cvvdp; bench/results" in md, md
assert "--cvvdp) (bench" not in md, md
# An old file (no "runs", no load recorded): one run, from its header.
assert "Measured in one run:\n  - 2026-11-30T10:00:00 on 2-core Test CPU: pt (embree)" in md, md

# ais against pt is a pair; ais-nocomp is labelled by its option, not as old defaults.
rows = [row("pt", 1, 1.0, 0.1), row("pt", 4, 4.0, 0.03), row("ais", 1, 0.5, 0.1), row("ais", 4, 2.0, 0.03),
        row("ais-nocomp", 1, 0.5, 0.11), row("ais-nocomp", 4, 2.0, 0.033)]
runs = [{"date": "2026-11-26T04:06:29", "machine": "2-core New", "cores": 2, "load_average_1min": [0.87, 1.5],
         "frames_timed": 3, "methods": ["ais", "ais-nocomp"], "backends": ["embree"]},
        {"date": "2026-11-23T19:43:17", "machine": "2-core Old", "cores": 2, "load_average_1min": [2.78, 1.86],
         "frames_timed": 9, "methods": ["pt"], "backends": ["embree"]}]
md = report(doc("box", ["pt", "ais", "ais-nocomp"], rows, runs=runs))
assert "| ais vs pt (embree) |" in md, md
assert "2.00 [" in md, md  # ais reaches each error in half pt's time
assert "ais against ais-nocomp (ais --no-clamp-compensation): `box_ais_clamp_compensation.png`" in md, md
assert "old defaults" not in md, md
assert "Measured in 2 runs:" in md, md
assert "  - 2026-11-26T04:06:29 on 2-core New; 1-min load average 0.87 before, 1.5 after: ais, ais-nocomp (embree)" in md, md
assert ("  - 2026-11-23T19:43:17 (rows kept by `bench/accuracy --merge`) on 2-core Old; 1-min load average 2.78 "
        "before, 1.86 after (above its 2 cores") in md, md
assert "median of 9 passes: pt (embree)" in md, md
assert md.count("above its") == 1, md
assert "compares times measured on different dates and loads" in md, md
# Without a core count (a --machine text of another form) nothing is claimed about the load.
old = doc("box", ["pt"], [row("pt", 1, 1.0, 0.1)], machine="my laptop")
old["reference"]["load_average_1min"] = [5.0, 6.0]
md = report(old)
assert "1-min load average 5.0 before, 6.0 after: pt (embree)" in md and "above its" not in md, md
old["machine"] = "2-core Test CPU"
assert "(above its 2 cores" in report(old)

# Plot titles name each run that measured the plotted methods, and only those.
sub = r.runs_subtitle({"runs": runs}, rows[2:])
assert sub == "2026-11-26 04:06 2-core New, load 0.87/1.5: ais, ais-nocomp", sub
# Every method of the sweep has a colour of its own; pt is black, and no method is grey
# (the Pareto front's colour).
import accuracy_methods
styles = r.method_styles(set(accuracy_methods.METHODS))
colours = [c for c, _ in styles.values()]
assert len(set(colours)) == len(accuracy_methods.METHODS), styles
assert styles["pt"][0] == "black" and not any(c in ("#7f7f7f", "0.5", "grey", "gray") for c in colours), styles
print("ok")
)PY";
    EXPECT_EQ(run_python(script), 0) << log();
}
