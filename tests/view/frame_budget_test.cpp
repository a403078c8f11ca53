// The frame-time budget: the Pareto front of the sweep's settings, and the choice of
// setting from measured frame times (hysteresis included).
#include "view/frame_budget.h"

#include <unistd.h>

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
    EXPECT_DOUBLE_EQ(budget.scale(), 2.0);
    EXPECT_EQ(budget.choice().tile, 4u);
    budget.observe(0.020);  // 1x: scale 0.7·2 + 0.3·1 = 1.7; 40 ms × 1.7 = 68 ms does not fit
    EXPECT_NEAR(budget.scale(), 1.7, 1e-12);
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
    EXPECT_NEAR(budget.scale(), 1.0, 1e-3);
    EXPECT_EQ(budget.choice().tile, 4u);
    for (int i = 0; i < 30; ++i) budget.observe(0.009);  // scale → 0.9: 42.3 ms is within 45 ms
    EXPECT_EQ(budget.choice().tile, 2u);
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
