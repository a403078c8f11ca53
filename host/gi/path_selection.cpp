#include "gi/path_selection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "gi/vpl_importance.h"
#include "kernels/shared/rng.h"
#include "kernels/shared/vpl.h"
#include "util/morton.h"

namespace tessera {
namespace {

// Seed of the instant cache's path decisions ("icpk"), apart from the VPL decisions.
constexpr uint32_t kPathKeepSeed = 0x6963706bu;
constexpr int kKeyBits = 21;  // an axis: three fit in a 64-bit key
constexpr double kKeyCells = double((1u << kKeyBits) - 1u);

}  // namespace

std::vector<uint64_t> path_view_keys(const std::vector<LightPath>& candidates, const std::vector<float>& importance,
                                     const std::vector<float>& where) {
    const size_t n = candidates.size();
    if (where.size() != 3 * importance.size())
        throw std::invalid_argument("path_view_keys: 3 floats of `where` a VPL, " + std::to_string(where.size()) +
                                    " for " + std::to_string(importance.size()) + " VPLs");
    std::vector<std::array<double, 3>> centre(n, {0.0, 0.0, 0.0});
    std::vector<bool> has(n, false);
    std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (size_t j = 0, i = 0; j < n; ++j) {
        double sum = 0.0;
        for (size_t v = candidates[j].vpls.size() / TS_VPL_FLOATS; v > 0; --v, ++i) {
            const double f = importance.at(i);
            const float* at = &where[3 * i];
            if (!(f > 0.0) || !std::isfinite(f) || !std::isfinite(at[0]) || !std::isfinite(at[1]) ||
                !std::isfinite(at[2]))
                continue;  // no place in the view (a medium VPL, or one that lights no point)
            sum += f;
            for (int a = 0; a < 3; ++a) centre[j][a] += f * at[a];
        }
        if (!(sum > 0.0) || !std::isfinite(sum)) continue;
        has[j] = true;
        for (int a = 0; a < 3; ++a) {
            centre[j][a] /= sum;
            lo[a] = std::min(lo[a], centre[j][a]), hi[a] = std::max(hi[a], centre[j][a]);
        }
    }
    std::vector<uint64_t> key(n, UINT64_MAX);
    for (size_t j = 0; j < n; ++j) {
        if (!has[j]) continue;
        uint32_t cell[3];
        for (int a = 0; a < 3; ++a) {
            const double t = hi[a] > lo[a] ? (centre[j][a] - lo[a]) / (hi[a] - lo[a]) : 0.0;
            cell[a] = static_cast<uint32_t>(std::clamp(t, 0.0, 1.0) * kKeyCells);
        }
        key[j] = morton3(cell[0], cell[1], cell[2]);
    }
    return key;
}

std::vector<LightPath> select_paths(std::vector<LightPath>& candidates, const std::vector<float>& importance,
                                    const std::vector<float>& where, size_t run, uint32_t oversampling,
                                    uint32_t seed_mix) {
    const size_t n = candidates.size();
    std::vector<float> path_importance(n, 0.0f);
    std::vector<uint32_t> counts(n, 0u);
    for (size_t j = 0, i = 0; j < n; ++j) {
        double sum = 0.0;
        counts[j] = static_cast<uint32_t>(candidates[j].vpls.size() / TS_VPL_FLOATS);
        for (uint32_t v = counts[j]; v > 0; --v) sum += importance.at(i++);
        path_importance[j] = static_cast<float>(sum);
    }
    const std::vector<double> p = path_keep_probabilities(path_importance, counts, oversampling);
    const std::vector<uint64_t> key = path_view_keys(candidates, importance, where);
    std::vector<bool> keep(n, false);
    run = std::max<size_t>(run, 1);
    for (size_t begin = 0; begin < n; begin += run) {
        const size_t end = std::min(n, begin + run);
        std::vector<size_t> order(end - begin);
        std::iota(order.begin(), order.end(), begin);
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key[a] < key[b]; });
        std::vector<double> q(order.size());
        for (size_t t = 0; t < order.size(); ++t) q[t] = p[order[t]];
        // Keyed by the whole 64-bit index: runs of passes 2^32 candidates apart differ.
        const uint64_t first = candidates[begin].index;
        ts::TsRng rng = ts::ts_rng_seed(kPathKeepSeed ^ seed_mix, static_cast<uint32_t>(first),
                                        static_cast<uint32_t>(first >> 32));
        const std::vector<bool> kept = systematic_sample(q, ts::ts_rng_next(&rng));
        for (size_t t = 0; t < order.size(); ++t) keep[order[t]] = kept[t];
    }
    std::vector<LightPath> out;
    for (size_t j = 0; j < n; ++j) {
        if (!keep[j]) continue;
        LightPath path = std::move(candidates[j]);
        // In float, as trace_light_paths applies a weight: a re-traced path (same scene)
        // leaves the same bits.
        path.weight = static_cast<float>(1.0 / p[j]);
        for (size_t v = 0; v < path.vpls.size(); v += TS_VPL_FLOATS)
            for (int c = 0; c < 3; ++c) path.vpls[v + TS_VPL_FLUX + c] *= path.weight;
        out.push_back(std::move(path));
    }
    return out;
}

}  // namespace tessera
