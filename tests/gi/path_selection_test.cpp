// The instant cache's paths kept for the view (gi/path_selection.h): each path kept with
// its probability and weighed by its inverse, and every part of the view keeping its
// share of paths to within one.
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "gi/light_paths.h"
#include "gi/path_selection.h"
#include "gi/vpl_importance.h"
#include "kernels/shared/vpl.h"

namespace tessera {
namespace {

// Candidates for select_paths: path j has j % 4 VPLs of flux 1 whose importance is
// skewed, all landing at `centre(j)` in the view (3 floats).
struct Candidates {
    std::vector<LightPath> paths;
    std::vector<float> importance, where;
    std::vector<double> p;  // path_keep_probabilities at K
};

template <class Centre>
Candidates make_candidates(uint32_t n, uint32_t k, Centre centre) {
    Candidates c;
    c.paths.resize(n);
    std::vector<float> path_importance;
    std::vector<uint32_t> counts;
    for (uint32_t j = 0; j < n; ++j) {
        c.paths[j].index = 1000 + j;
        double sum = 0.0;
        for (uint32_t v = 0; v < j % 4; ++v) {
            std::vector<float> vpl(TS_VPL_FLOATS, 0.0f);
            for (int ch = 0; ch < 3; ++ch) vpl[TS_VPL_FLUX + ch] = 1.0f;
            c.paths[j].vpls.insert(c.paths[j].vpls.end(), vpl.begin(), vpl.end());
            c.importance.push_back(float((j * 7919u + v) % 100) * float((j * 104729u) % 13));
            sum += c.importance.back();
            const std::array<float, 3> at = centre(j);
            c.where.insert(c.where.end(), at.begin(), at.end());
        }
        path_importance.push_back(float(sum));
        counts.push_back(j % 4);
    }
    c.p = path_keep_probabilities(path_importance, counts, k);
    return c;
}

std::array<float, 3> scattered(uint32_t j) {
    return {float((j * 37u) % 101), float((j * 53u) % 89), float((j * 71u) % 97)};
}

TEST(SelectPaths, KeepsTheFluxInExpectationWithTheirWeights) {
    // 5000 candidates in runs of 1000. A kept path carries weight 1/p on every VPL, so the
    // kept flux estimates the candidates' with variance at most Σ m_j² (1 − p_j)/p_j (m_j
    // its VPLs; a systematic sample's is lower): a 5σ bound. Each run keeps Σ p_j of it
    // to within one.
    const uint32_t k = 4, run = 1000;
    const Candidates c = make_candidates(5000, k, scattered);
    double total = 0.0, var_flux = 0.0;
    for (uint32_t j = 0; j < c.p.size(); ++j) {
        const double m = j % 4;
        total += m;
        var_flux += m * m * (1.0 - c.p[j]) / c.p[j];
    }
    std::vector<LightPath> copy = c.paths;
    const std::vector<LightPath> kept = select_paths(copy, c.importance, c.where, run, k, 0u);
    double flux = 0.0;
    int64_t last = -1;
    std::vector<int> per_run(5, 0);
    for (const LightPath& path : kept) {
        const uint32_t j = uint32_t(path.index - 1000);
        EXPECT_GT(int64_t(path.index), last) << "kept paths stay in candidate order";
        last = int64_t(path.index);
        ++per_run[j / run];
        EXPECT_FLOAT_EQ(path.weight, float(1.0 / c.p[j]));
        ASSERT_EQ(path.vpls.size(), c.paths[j].vpls.size());
        for (size_t v = 0; v < path.vpls.size(); v += TS_VPL_FLOATS) {
            EXPECT_EQ(path.vpls[v + TS_VPL_FLUX], path.weight) << "flux 1 times the weight";
            flux += path.vpls[v + TS_VPL_FLUX];
        }
    }
    EXPECT_NEAR(flux, total, 5.0 * std::sqrt(var_flux));
    for (uint32_t r = 0; r < 5; ++r) {
        double share = 0.0;
        for (uint32_t j = r * run; j < (r + 1) * run; ++j) share += c.p[j];
        EXPECT_LE(std::abs(per_run[r] - share), 1.0) << "run " << r;
    }
    // The same candidates and seed keep the same paths; another seed keeps others.
    copy = c.paths;
    const std::vector<LightPath> again = select_paths(copy, c.importance, c.where, run, k, 0u);
    ASSERT_EQ(again.size(), kept.size());
    for (size_t i = 0; i < kept.size(); ++i) EXPECT_EQ(again[i].index, kept[i].index);
    copy = c.paths;
    const std::vector<LightPath> other = select_paths(copy, c.importance, c.where, run, k, light_path_seed_mix(2));
    size_t same = 0;
    for (size_t i = 0; i < std::min(other.size(), kept.size()); ++i) same += other[i].index == kept[i].index;
    EXPECT_LT(same, kept.size() / 2);
}

TEST(SelectPaths, KeepsEachPathWithItsProbability) {
    // Over 4000 seeds, path j is kept a fraction of them within 5σ of p_j (binomial), so
    // the weight 1/p_j makes the estimate unbiased whatever the sort put before it.
    const uint32_t k = 4, n = 120, seeds = 4000;
    const Candidates c = make_candidates(n, k, scattered);
    std::vector<int> kept_for(n, 0);
    for (uint32_t s = 0; s < seeds; ++s) {
        std::vector<LightPath> copy = c.paths;
        for (const LightPath& path : select_paths(copy, c.importance, c.where, 60, k, light_path_seed_mix(s)))
            ++kept_for[path.index - 1000];
    }
    for (uint32_t j = 0; j < n; ++j) {
        const double sd = std::sqrt(c.p[j] * (1.0 - c.p[j]) / seeds);
        EXPECT_NEAR(double(kept_for[j]) / seeds, c.p[j], 5.0 * sd + 1e-12) << "path " << j;
    }
}

TEST(SelectPaths, EveryPartOfTheViewKeepsItsShare) {
    // Two rooms: odd paths land at z in [0, 40], even ones at z in [60, 100], interleaved
    // in candidate order. Sorted by their Morton keys (z is the top bit) the near room's
    // paths come first, so over every seed the count kept there is its Σ p_j to within
    // one; independent decisions would leave it its binomial spread (sd > 3 here).
    const uint32_t k = 4, n = 2000;
    const Candidates c = make_candidates(n, k, [](uint32_t j) {
        return std::array<float, 3>{float((j * 37u) % 101), float((j * 53u) % 89),
                                    float(j % 2 ? (j * 71u) % 41 : 60 + (j * 71u) % 41)};
    });
    // Paths of no importance (no VPLs, or VPLs that light no view point) have no place in
    // the view: they sort last, after the far room's.
    const std::vector<uint64_t> keys = path_view_keys(c.paths, c.importance, c.where);
    for (uint32_t j = 4; j < n; j += 4) EXPECT_EQ(keys[j], UINT64_MAX) << "a path without VPLs has no place";
    EXPECT_THROW(path_view_keys(c.paths, c.importance, {}), std::invalid_argument);
    auto in_near_room = [&](uint32_t j) { return j % 2 == 1 && keys[j] != UINT64_MAX; };
    double share = 0.0, binomial = 0.0;
    for (uint32_t j = 0; j < n; ++j)
        if (in_near_room(j)) share += c.p[j], binomial += c.p[j] * (1.0 - c.p[j]);
    ASSERT_GT(std::sqrt(binomial), 3.0);
    for (uint32_t s = 0; s < 200; ++s) {
        std::vector<LightPath> copy = c.paths;
        int near = 0;
        for (const LightPath& path : select_paths(copy, c.importance, c.where, n, k, light_path_seed_mix(s)))
            near += in_near_room(uint32_t(path.index - 1000));
        ASSERT_LE(std::abs(near - share), 1.0) << "seed " << s;
    }
}

}  // namespace
}  // namespace tessera
