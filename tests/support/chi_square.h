// Pearson's chi-square goodness-of-fit test for sample warps, as pbrt and Mitsuba test
// theirs: histogram the samples, integrate the claimed pdf over each bin for the
// expected counts, merge bins expecting fewer than 5, and reject at significance 1e-3.
#pragma once
#include <cmath>
#include <vector>

namespace tessera::test {

struct ChiSquareResult {
    double statistic = 0.0;
    int dof = 0;
    double z = 0.0;  ///< Wilson–Hilferty normal deviate of the statistic
    bool reject = true;
};

/// observed[i], expected[i]: counts per bin (expected need not be integers).
inline ChiSquareResult chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
    ChiSquareResult r;
    double pooled_o = 0.0, pooled_e = 0.0;
    int bins = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5.0) {
            pooled_o += observed[i];
            pooled_e += expected[i];
            continue;
        }
        r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++bins;
    }
    if (pooled_e >= 5.0) {
        r.statistic += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
        ++bins;
    } else if (pooled_o > 0.0 && pooled_e == 0.0) {
        r.statistic = INFINITY;  // samples where the pdf says none can be
    }
    r.dof = bins - 1;
    // Wilson & Hilferty (1931): (X/k)^(1/3) is close to normal with mean 1 - 2/(9k) and
    // variance 2/(9k); accurate for the k > 30 used here. z > 3.09 means p < 1e-3.
    const double k = r.dof;
    r.z = (std::cbrt(r.statistic / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
    r.reject = !(r.z < 3.09);
    return r;
}

}  // namespace tessera::test
