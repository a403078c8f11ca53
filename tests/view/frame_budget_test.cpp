// The frame-time budget: the Pareto front of the sweep's settings, and the choice of
// setting from measured frame times (hysteresis included).
#include "view/frame_budget.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "util/error.h"

namespace tessera::view {
namespace {

BudgetPoint point(uint32_t tile, double seconds, double relmse) {
    BudgetPoint p;
    p.method = "igi";
    p.tile = tile;
    p.seconds = seconds;
    p.relmse = relmse;
    return p;
}

TEST(FrameBudget, ParetoFrontKeepsOnlyPointsBetterThanEveryFasterOne) {
    const auto front = pareto_front({point(1, 0.030, 0.10), point(2, 0.010, 0.50), point(3, 0.020, 0.60),
                                     point(4, 0.040, 0.20), point(5, 0.020, 0.30)});
    ASSERT_EQ(front.size(), 3u);
    EXPECT_EQ(front[0].tile, 2u);  // 10 ms, 0.5
    EXPECT_EQ(front[1].tile, 5u);  // 20 ms, 0.3 (tile 3 is as fast and worse)
    EXPECT_EQ(front[2].tile, 1u);  // 30 ms, 0.1 (tile 4 is slower and worse)
}

TEST(FrameBudget, ChoosesTheBestSettingThatFitsTheMeasuredScale) {
    const std::vector<BudgetPoint> front = {point(8, 0.010, 0.5), point(4, 0.020, 0.3), point(2, 0.040, 0.2),
                                            point(1, 0.080, 0.1)};
    FrameBudget budget(0.050, front);
    EXPECT_EQ(budget.choice().tile, 2u);  // the sweep's own times: 40 ms fits 50 ms
    budget.observe(0.080);                // twice as slow here: scale 2, only 20 ms × 2 fits
    EXPECT_DOUBLE_EQ(budget.cost_factor(), 2.0);
    EXPECT_EQ(budget.choice().tile, 4u);
    budget.observe(0.020);  // 1x: scale 0.7·2 + 0.3·1 = 1.7; 40 ms × 1.7 = 68 ms does not fit
    EXPECT_NEAR(budget.cost_factor(), 1.7, 1e-12);
    EXPECT_EQ(budget.choice().tile, 4u);
    for (int i = 0; i < 20; ++i) budget.observe(0.010);  // scale → 0.5: 80 ms × 0.5 = 40 ms fits
    EXPECT_EQ(budget.choice().tile, 1u);
}

TEST(FrameBudget, SlowerSettingOnlyWithinNinetyPercentOfTheTarget) {
    FrameBudget budget(0.050, {point(4, 0.010, 0.3), point(2, 0.047, 0.2)});
    EXPECT_EQ(budget.choice().tile, 2u);
    budget.observe(0.0494);  // scale 1.05: 47 ms × 1.05 = 49.4 ms is over 90% of 50 ms
    EXPECT_EQ(budget.choice().tile, 2u);  // already chosen and fits: kept
    budget.observe(0.060);   // over budget: down to the fast setting
    EXPECT_EQ(budget.choice().tile, 4u);
    for (int i = 0; i < 30; ++i) budget.observe(0.010);  // scale → 1: 47 ms fits 50 ms but not 45 ms
    EXPECT_NEAR(budget.cost_factor(), 1.0, 1e-3);
    EXPECT_EQ(budget.choice().tile, 4u);
    for (int i = 0; i < 30; ++i) budget.observe(0.009);  // scale → 0.9: 42.3 ms is within 45 ms
    EXPECT_EQ(budget.choice().tile, 2u);
}

// A synthetic cost model of a moving frame: a fixed cost (VPL tracing, set-up) plus a cost
// per pixel, `per_pixel` times the sweep's time of the setting at the full window.
struct SyntheticCost {
    double fixed = 0.020, per_pixel = 10.0;
    double operator()(const FrameBudget& b) const {
        const double fraction = b.scale() * b.scale();
        return fixed + per_pixel * b.choice().seconds * fraction;
    }
};

// Runs `frames` frames of the model (with a deterministic +-`jitter` relative noise) and
// returns the measured times.
std::vector<double> run_frames(FrameBudget& budget, const SyntheticCost& cost, int frames, double jitter = 0.0) {
    std::vector<double> times;
    for (int f = 0; f < frames; ++f) {
        const double t = cost(budget) * (1.0 + jitter * ((f * 7919) % 11 - 5) / 5.0);
        times.push_back(t);
        budget.observe(t, budget.scale() * budget.scale());
    }
    return times;
}

const std::vector<BudgetPoint> kFront = {point(8, 0.010, 0.5), point(4, 0.020, 0.3), point(2, 0.040, 0.2)};

// Even the fastest setting takes 0.12 s at full resolution, the target is 0.05 s: the
// scale falls until a frame takes about the target, and stays there.
TEST(FrameBudget, ControllerConvergesOnTheScaleThatFitsTheTarget) {
    FrameBudget budget(0.050, kFront);  // the sweep's own times first: 40 ms fits
    const std::vector<double> t = run_frames(budget, SyntheticCost{}, 30);
    for (int f = 15; f < 30; ++f) {
        EXPECT_LE(t[f], 0.050 * 1.08) << f;  // within the dead band around the target
        EXPECT_GE(t[f], 0.050 * 0.90) << f;
    }
    EXPECT_EQ(budget.choice().tile, 8u);  // resolution is lowered only with the fastest setting
    // The fixed point: 0.02 + 0.1·s² = 0.05 → s ≈ 0.55; the model's scale is that within the dead band.
    EXPECT_GT(budget.scale(), std::sqrt((0.90 * 0.05 - 0.02) / 0.1) - 1e-9);
    EXPECT_LT(budget.scale(), std::sqrt((1.08 * 0.05 - 0.02) / 0.1) + 1e-9);
}

TEST(FrameBudget, ScaleHoldsStillUnderNoiseInsideTheDeadBand) {
    FrameBudget budget(0.050, kFront);
    run_frames(budget, SyntheticCost{}, 30);
    int changes = 0;
    double last = budget.scale();
    for (int f = 0; f < 60; ++f) {  // +-3% noise on every frame
        const double t = SyntheticCost{}(budget) * (1.0 + 0.03 * ((f * 7919) % 11 - 5) / 5.0);
        budget.observe(t, budget.scale() * budget.scale());
        if (budget.scale() != last) ++changes, last = budget.scale();
    }
    EXPECT_LE(changes, 3);  // +-3% stays inside the dead band
}

TEST(FrameBudget, ScaleNeverDropsBelowItsFloorAndSaysWhenTheTargetIsOutOfReach) {
    BudgetOptions options;
    options.min_scale = 0.25;
    FrameBudget budget(0.010, kFront, options);  // the fixed 20 ms alone misses 10 ms
    const std::vector<double> t = run_frames(budget, SyntheticCost{}, 40);
    EXPECT_DOUBLE_EQ(budget.scale(), 0.25);
    EXPECT_TRUE(budget.at_cheapest());
    for (double x : t) EXPECT_GE(x, 0.020);
    EXPECT_THROW(FrameBudget(0.01, kFront, BudgetOptions{0.0, 1.0}), std::invalid_argument);
    EXPECT_THROW(FrameBudget(0.01, kFront, BudgetOptions{0.25, 0.0}), std::invalid_argument);
}

TEST(FrameBudget, BackToFullResolutionAndBetterSettingsWhenFramesGetCheaper) {
    FrameBudget budget(0.050, kFront);
    run_frames(budget, SyntheticCost{}, 30);
    ASSERT_LT(budget.scale(), 1.0);
    SyntheticCost cheap;  // e.g. the camera turned to a simpler view
    cheap.fixed = 0.002, cheap.per_pixel = 0.5;
    const std::vector<double> t = run_frames(budget, cheap, 40);
    EXPECT_DOUBLE_EQ(budget.scale(), 1.0);
    EXPECT_EQ(budget.choice().tile, 2u);  // the best setting: 0.002 + 0.5·0.04 = 22 ms fits 50 ms
    for (double x : t) EXPECT_LE(x, 0.050);
}

// The first frame's prediction uses the initial cost factor (window pixels / sweep pixels).
TEST(FrameBudget, InitialCostFactorScalesTheSweepTimes) {
    FrameBudget budget(0.050, kFront, BudgetOptions{0.25, 16.0});  // a 512² window, a 128² sweep
    EXPECT_EQ(budget.choice().tile, 8u);
    EXPECT_NEAR(budget.scale(), std::sqrt(0.98 * 0.050 / (16 * 0.010)), 1e-12);
}

TEST(FrameBudget, ReadsTheCommittedSweepFront) {
    const auto csv = std::filesystem::path(TESSERA_SOURCE_DIR) / "bench/results/accuracy/cornell-box.csv";
    const std::vector<BudgetPoint> all = read_pareto_front(csv, "embree");
    ASSERT_FALSE(all.empty());
    for (const char* method : {"igi", "ais", "ais-max"}) {
        std::vector<BudgetPoint> one;
        for (const BudgetPoint& p : all)
            if (p.method == method) one.push_back(p);
        ASSERT_FALSE(one.empty()) << method;
        for (size_t i = 1; i < one.size(); ++i) {  // a front: slower points have lower error
            EXPECT_GE(one[i].seconds, one[i - 1].seconds);
            EXPECT_LT(one[i].relmse, one[i - 1].relmse);
        }
        for (const BudgetPoint& p : one) EXPECT_TRUE(p.tile >= 1 && p.tile <= 8 && p.vpl_paths > 0);
    }
}

// A row whose time or error is not a finite number (or a time <= 0) is refused naming the
// file and the values, not fed to the budget.
TEST(FrameBudget, NonFiniteSweepRowsAreRefused) {
    const auto dir = std::filesystem::temp_directory_path() / ("tessera-budget-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string head = "scene,backend,method,setting,spp,median_pass_s,relmse\n";
    const std::string setting = "\"tile=1,vpl-paths=8,shadow-samples=1\"";  // as the sweep writes one
    for (const auto& [time, err] : {std::pair{"nan", "0.1"}, std::pair{"0.01", "inf"}, std::pair{"0", "0.1"},
                                    std::pair{"-1", "0.1"}}) {
        const auto csv = dir / "sweep.csv";
        std::ofstream(csv) << head << "box,embree,igi," << setting << ",1," << time << "," << err << "\n";
        try {
            read_pareto_front(csv, "embree");
            ADD_FAILURE() << time << " " << err;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(csv.string()), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(std::string("median_pass_s ") + time), std::string::npos) << e.what();
        }
    }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera::view
