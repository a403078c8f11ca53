// kernels/shared/medium.h compiled as C++: Beer–Lambert transmittance through the box
// (and without the slab test where a span lies in it),
// the free-flight distance distribution, the unbiasedness of the RGB weights (one segment,
// and a chromatic path's, with their bound), and
// equiangular distance sampling (its pdf and its finite densities), the distance
// sampling toward a line of ray lights, and the far roulette's importance.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "kernels/shared/medium.h"
#include "support/chi_square.h"

namespace tessera {
namespace {

using ts::make_float3;

ts::TsMedium slab(ts::float3 sigma_a, ts::float3 sigma_s) {
    float buf[TS_MEDIUM_FLOATS] = {sigma_a.x, sigma_a.y, sigma_a.z, sigma_s.x, sigma_s.y, sigma_s.z, 0.0f, 1.0f,
                                   -1.0f,     -5.0f,     -5.0f,     1.0f,      5.0f,      5.0f,      1.0f, 0.0f};
    return ts::ts_medium_load(buf);  // the slab -1 <= x <= 1 (5 units either way in y, z)
}

TEST(Medium, TransmittanceIsBeerLambertOverThePathInsideTheBox) {
    ts::TsMedium m = slab(make_float3(0.1f, 0.5f, 2.0f), make_float3(0.2f, 0.0f, 0.0f));
    // Along x through the 2-unit slab: exp(-sigma_t · 2), per channel.
    ts::float3 tr = ts::ts_medium_transmittance(&m, make_float3(-3, 0, 0), make_float3(1, 0, 0), 0.0f, 10.0f);
    EXPECT_NEAR(tr.x, std::exp(-0.3 * 2), 1e-6);
    EXPECT_NEAR(tr.y, std::exp(-0.5 * 2), 1e-6);
    EXPECT_NEAR(tr.z, std::exp(-2.0 * 2), 1e-6);
    // Unnormalised direction, segment ending half-way into the slab: 1 unit inside.
    tr = ts::ts_medium_transmittance(&m, make_float3(-3, 0, 0), make_float3(4, 0, 0), 0.0f, 0.75f);
    EXPECT_NEAR(tr.y, std::exp(-0.5), 1e-6);
    // At 60° to the slab normal the path inside is 2 / cos 60° = 4.
    tr = ts::ts_medium_transmittance(&m, make_float3(-2, -3, 0), make_float3(0.5f, std::sqrt(0.75f), 0), 0.0f, 100.0f);
    EXPECT_NEAR(tr.x, std::exp(-0.3 * 4), 1e-5);
    // A segment that misses the box sees no medium.
    tr = ts::ts_medium_transmittance(&m, make_float3(-3, 0, 0), make_float3(0, 1, 0), 0.0f, 100.0f);
    EXPECT_EQ(tr.x, 1.0f);
    // Very dense and very thin media stay finite and in [0, 1].
    ts::TsMedium dense = slab(make_float3(500, 500, 500), make_float3(0, 0, 0));
    ts::TsMedium thin = slab(make_float3(1e-6f, 1e-6f, 1e-6f), make_float3(0, 0, 0));
    EXPECT_EQ(ts::ts_medium_transmittance(&dense, make_float3(-3, 0, 0), make_float3(1, 0, 0), 0, 10).x, 0.0f);
    EXPECT_NEAR(ts::ts_medium_transmittance(&thin, make_float3(-3, 0, 0), make_float3(1, 0, 0), 0, 10).x,
                1.0 - 2e-6, 1e-7);
}

// ts_medium_misses_box: boxes apart from the medium's (beyond 1e-4 of the coordinates)
// are; boxes that overlap it, touch it or come within that margin are not, nor any box of
// a medium filling space or with a non-finite corner; without a medium every box is. And
// where it says apart, every segment between points of the box (ends offset as the
// shadow rays' are) has a transmittance of exactly 1.
TEST(Medium, BoxesApartFromTheMediumSeeNoMedium) {
    const ts::TsMedium m = slab(make_float3(0.1f, 0.1f, 0.1f), make_float3(0.5f, 0.5f, 0.5f));
    auto apart = [&](ts::float3 lo, ts::float3 hi, float scale = 0.0f) {
        return ts::ts_medium_misses_box(&m, lo, hi, scale) != 0;
    };
    EXPECT_TRUE(apart(make_float3(1.01f, -1, -1), make_float3(3, 1, 1)));     // beside the slab in x
    EXPECT_TRUE(apart(make_float3(-3, 5.1f, 0), make_float3(3, 6, 1)));       // above it in y
    EXPECT_FALSE(apart(make_float3(0.5f, -1, -1), make_float3(3, 1, 1)));     // overlapping
    EXPECT_FALSE(apart(make_float3(1.0f, -1, -1), make_float3(3, 1, 1)));     // touching
    EXPECT_FALSE(apart(make_float3(1.0002f, -1, -1), make_float3(3, 1, 1)));  // within 1e-4 · 5
    EXPECT_FALSE(apart(make_float3(1.01f, -1, -1), make_float3(3, 1, 1), 1000.0f));  // a larger pos_scale
    EXPECT_FALSE(apart(make_float3(NAN, -1, -1), make_float3(3, 1, 1)));
    EXPECT_FALSE(apart(make_float3(1.01f, -1, -1), make_float3(INFINITY, 1, 1)));
    ts::TsMedium everywhere = m;
    everywhere.bounded = 0;
    EXPECT_FALSE(ts::ts_medium_misses_box(&everywhere, make_float3(10, 10, 10), make_float3(11, 11, 11), 0.0f));
    ts::TsMedium none = m;
    none.present = 0;
    EXPECT_TRUE(ts::ts_medium_misses_box(&none, make_float3(-1, -1, -1), make_float3(1, 1, 1), 0.0f));

    // Segments between random points of a box just apart (by 1e-3 of the slab's size, at
    // sizes 1e-3 to 1e4; the margin is 6e-4 of it there) see transmittance 1.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float k : {1e-3f, 1.0f, 1e4f}) {
        float buf[TS_MEDIUM_FLOATS] = {0.1f, 0.1f, 0.1f, 0.5f / k, 0.5f / k, 0.5f / k, 0.0f, 1.0f,
                                       -k,   -5 * k, -5 * k, k,    5 * k,    5 * k,    1.0f, 0.0f};
        const ts::TsMedium mk = ts::ts_medium_load(buf);
        const ts::float3 lo = make_float3(k * (1.0f + 1e-3f), -6 * k, -6 * k), hi = make_float3(3 * k, 6 * k, 6 * k);
        ASSERT_TRUE(ts::ts_medium_misses_box(&mk, lo, hi, 6 * k)) << k;
        for (int i = 0; i < 2000; ++i) {
            const ts::float3 a = lo + (hi - lo) * make_float3(u(rng), u(rng), u(rng));
            const ts::float3 b = lo + (hi - lo) * make_float3(u(rng), u(rng), u(rng));
            const ts::TsRay r = ts::ts_shadow_ray(ts::ts_offset_ray_origin(a, make_float3(-1, 0, 0), 6 * k), b,
                                                  make_float3(-1, 0, 0), 6 * k);
            const ts::float3 tr = ts::ts_shadow_transmittance(&mk, r);
            ASSERT_EQ(tr.x, 1.0f) << k << " " << i;
        }
    }
}

// Shadow rays whose two ends lie in the box (drawn inside, on its faces, edges and
// corners, at sizes 1e-3 to 1e4 and 1e4 from the origin) keep their whole span: the
// transmittance without the slab test (ts_medium_span_transmittance) is the slab test's,
// bit for bit, wherever ts_medium_keeps_span says so, and it says so for all of them.
TEST(Medium, ASpanBetweenTwoPointsInTheBoxNeedsNoSlabTest) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float k : {1e-3f, 1.0f, 1e4f})
        for (float shift : {0.0f, 1e4f}) {
            float buf[TS_MEDIUM_FLOATS] = {0.1f / k,  0.2f / k,  0.3f / k,  0.5f / k,  1.0f / k,  2.0f / k,
                                           0.0f,      1.0f,      shift - k, shift - 2 * k, shift - 3 * k,
                                           shift + k, shift + 2 * k, shift + 3 * k, 1.0f, 0.0f};
            const ts::TsMedium m = ts::ts_medium_load(buf);
            // A coordinate in the box: a face's (1 in 4), else uniform within.
            auto coordinate = [&](float lo, float hi) {
                const float r = u(rng);
                return r < 0.125f ? lo : r < 0.25f ? hi : lo + (hi - lo) * u(rng);
            };
            auto point = [&] {
                return make_float3(coordinate(m.box_min.x, m.box_max.x), coordinate(m.box_min.y, m.box_max.y),
                                   coordinate(m.box_min.z, m.box_max.z));
            };
            for (int i = 0; i < 4000; ++i) {
                const ts::float3 o = point(), p = point();
                ASSERT_TRUE(ts::ts_medium_holds(&m, o) && ts::ts_medium_holds(&m, p));
                const ts::TsRay r = ts::ts_shadow_ray(o, p, make_float3(0, 0, 0), 0.0f);
                if (r.dir.x == 0.0f && r.dir.y == 0.0f && r.dir.z == 0.0f) continue;
                ASSERT_TRUE(ts::ts_medium_keeps_span(1, r.dir, r.tmin, r.tmax)) << k << " " << i;
                const ts::float3 slab_test = ts::ts_shadow_transmittance(&m, r);
                const ts::float3 span = ts::ts_medium_span_transmittance(&m, ts::length(r.dir), r.tmin, r.tmax);
                ASSERT_EQ(std::memcmp(&slab_test, &span, sizeof span), 0)
                    << k << " " << shift << " " << i << ": " << slab_test.x << " vs " << span.x;
            }
        }

    // Where it says no. A denormal component: 1/dir overflows, and with org on the box's
    // face the slab's entry is 0 · inf = NaN, which fmin drops for the exit (+inf): the
    // clip comes out empty (1) where the span would dim it.
    const ts::TsMedium m = slab(make_float3(0.1f, 0.1f, 0.1f), make_float3(0.5f, 0.5f, 0.5f));
    const ts::float3 org = make_float3(-1.0f, 0.0f, 0.0f), dir = make_float3(1e-40f, 0.5f, 0.0f);
    EXPECT_FALSE(ts::ts_medium_keeps_span(1, dir, 0.0f, 0.99999f));
    EXPECT_EQ(ts::ts_medium_transmittance(&m, org, dir, 0.0f, 0.99999f).x, 1.0f);
    EXPECT_LT(ts::ts_medium_span_transmittance(&m, ts::length(dir), 0.0f, 0.99999f).x, 1.0f);
    EXPECT_FALSE(ts::ts_medium_keeps_span(0, make_float3(1, 0, 0), 0.0f, 0.99999f));  // an end outside
    EXPECT_FALSE(ts::ts_medium_keeps_span(1, make_float3(1, 0, 0), 0.1f, 0.99999f));  // t0 > 0
    EXPECT_FALSE(ts::ts_medium_keeps_span(1, make_float3(1, 0, 0), 0.0f, 1.0f));      // t1 at the far end
    EXPECT_FALSE(ts::ts_medium_keeps_span(1, make_float3(INFINITY, 0, 0), 0.0f, 0.5f));
    // Above 2^126, 1/dir is a denormal, which flush-to-zero makes 0: the slab's 0 · inf.
    EXPECT_FALSE(ts::ts_medium_keeps_span(1, make_float3(1e38f, 0, 0), 0.0f, 0.5f));
    EXPECT_TRUE(ts::ts_medium_keeps_span(1, make_float3(8.5e37f, 0, 0), 0.0f, 0.5f));
    EXPECT_FALSE(ts::ts_medium_keeps_span(1, make_float3(NAN, 0, 0), 0.0f, 0.5f));
    EXPECT_TRUE(ts::ts_medium_keeps_span(1, make_float3(0, -1e-30f, 0), 0.0f, 0.5f));
    // What the box holds: its closed faces, not a NaN, everything for fog filling space.
    EXPECT_TRUE(ts::ts_medium_holds(&m, make_float3(1.0f, -5.0f, 5.0f)));
    EXPECT_FALSE(ts::ts_medium_holds(&m, make_float3(std::nextafter(1.0f, 2.0f), 0.0f, 0.0f)));
    EXPECT_FALSE(ts::ts_medium_holds(&m, make_float3(NAN, 0.0f, 0.0f)));
    ts::TsMedium everywhere = m;
    everywhere.bounded = 0;
    EXPECT_TRUE(ts::ts_medium_holds(&everywhere, make_float3(1e30f, 0.0f, 0.0f)));
    ts::TsMedium none = m;
    none.present = 0;
    EXPECT_FALSE(ts::ts_medium_holds(&none, make_float3(0.0f, 0.0f, 0.0f)));
}

// The logs of transmittance that the 16-lane gathers take their exponentials of: each
// one's ts_exp3 is the transmittance bit for bit (rays through, into, out of and past the
// slab; a grey medium, one with two equal channels and a chromatic one), and
// ts_medium_exp_lanes gives ts_exp3 lane by lane, special values included. The
// exponential is within 1e-7 of double's.
TEST(Medium, LogTransmittanceOverLanesGivesTheTransmittanceBitForBit) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-4.0f, 4.0f);
    const ts::TsMedium grey = slab(make_float3(0.2f, 0.2f, 0.2f), make_float3(1.3f, 1.3f, 1.3f));
    const ts::TsMedium chromatic = slab(make_float3(0.1f, 0.5f, 2.0f), make_float3(0.2f, 3.0f, 0.0f));
    const ts::TsMedium two_equal = slab(make_float3(0.5f, 0.5f, 0.5f), make_float3(0.5f, 0.5f, 1.5f));
    int misses = 0;
    for (const ts::TsMedium* m : {&grey, &two_equal, &chromatic})
        for (int batch = 0; batch < 200; ++batch) {
            float x[3][TS_PACKET_LANES];
            ts::float3 want[TS_PACKET_LANES];
            for (int i = 0; i < TS_PACKET_LANES; ++i) {
                const ts::TsRay r = ts::ts_shadow_ray(make_float3(u(rng), u(rng), u(rng)),
                                                      make_float3(u(rng), u(rng), u(rng)), make_float3(0, 0, 0), 0.0f);
                want[i] = ts::ts_shadow_transmittance(m, r);
                const ts::float3 l = ts::ts_shadow_log_transmittance(m, r);
                const ts::float3 one = ts::ts_exp3(l);
                ASSERT_EQ(std::memcmp(&one, &want[i], sizeof one), 0) << batch << " " << i;
                misses += want[i].x == 1.0f;
                x[0][i] = l.x, x[1][i] = l.y, x[2][i] = l.z;
            }
            ts::ts_medium_exp_lanes(m, x);
            for (int i = 0; i < TS_PACKET_LANES; ++i) {
                const ts::float3 lanes = make_float3(x[0][i], x[1][i], x[2][i]);
                ASSERT_EQ(std::memcmp(&lanes, &want[i], sizeof lanes), 0) << batch << " " << i;
            }
        }
    EXPECT_GT(misses, 100);  // rays that miss the slab: log 0, exactly 1
    // Special values through the lanes, every row, with three exponentials per lane
    // (chromatic) and with one row's copied (grey).
    const float special[] = {0.0f, -0.0f, -1e-30f, -87.3f, -88.0f, -INFINITY, NAN, -1e4f, -0.5f, -20.0f};
    for (const ts::TsMedium* m : {&chromatic, &grey}) {
        float x[3][TS_PACKET_LANES] = {};
        for (int i = 0; i < 10; ++i) x[0][i] = x[1][i] = x[2][i] = special[i];
        ts::ts_medium_exp_lanes(m, x);
        for (int i = 0; i < 10; ++i) {
            const ts::float3 one = ts::ts_exp3(make_float3(special[i], special[i], special[i]));
            const ts::float3 lanes = make_float3(x[0][i], x[1][i], x[2][i]);
            EXPECT_EQ(std::memcmp(&one, &lanes, sizeof one), 0) << special[i];
            if (std::isfinite(special[i]) && special[i] > -87.0f) {
                EXPECT_NEAR(x[2][i], std::exp(double(special[i])), 1e-7 * std::exp(double(special[i])) + 1e-30);
            }
        }
        EXPECT_EQ(x[0][0], 1.0f);  // e^0 and e^-0: exactly 1 (a ray that misses the medium)
        EXPECT_EQ(x[1][1], 1.0f);
        EXPECT_EQ(x[2][5], 0.0f);
        EXPECT_TRUE(std::isnan(x[0][6]));
    }
}

TEST(Medium, FarImportanceIsOneWithinTheMarginAndFallsAsTheSquareBeyond) {
    ts::TsFarRegion r;
    r.lo = make_float3(-1.0f, -1.0f, -1.0f);
    r.hi = make_float3(1.0f, 1.0f, 1.0f);
    r.margin = 2.0f;
    EXPECT_EQ(ts::ts_far_importance(&r, make_float3(0.0f, 0.0f, 0.0f)), 1.0f);
    EXPECT_EQ(ts::ts_far_importance(&r, make_float3(3.0f, 0.0f, 0.0f)), 1.0f);  // 2 from the box
    EXPECT_FLOAT_EQ(ts::ts_far_importance(&r, make_float3(5.0f, 0.0f, 0.0f)), 0.25f);  // (2 / 4)²
    EXPECT_FLOAT_EQ(ts::ts_far_importance(&r, make_float3(-4.0f, 5.0f, 1.0f)), 0.16f);  // (3, 4, 0) out: (2 / 5)²
    const float nan = std::nanf("");
    EXPECT_EQ(ts::ts_far_importance(&r, make_float3(nan, 0.0f, 0.0f)), 1.0f);
    EXPECT_EQ(ts::ts_far_importance(&r, make_float3(3e10f, 0.0f, 0.0f)), 0.0f);  // past 1e10 margins: ends
    r.margin = 0.0f;  // no region: a zeroed frame or light-path table
    EXPECT_EQ(ts::ts_far_importance(&r, make_float3(1e30f, -1e30f, 0.0f)), 1.0f);
}

TEST(Medium, FreeFlightDistancesAreExponential) {
    // Grey medium: all channels share sigma_t = 0.7, so t ~ Exp(0.7). Fifty bins of equal
    // probability under that law, on an (effectively) infinite segment.
    ts::TsMedium m = slab(make_float3(0.2f, 0.2f, 0.2f), make_float3(0.5f, 0.5f, 0.5f));
    const int bins = 50, n = 200000;
    std::vector<double> observed(bins, 0.0), expected(bins, double(n) / bins);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < n; ++i) {
        ts::float3 w;
        int scattered;
        ts::TsSpectralMis sm = ts::ts_spectral_mis_start();
        float t = ts::ts_medium_sample_distance(&m, 1e30f, u(rng), u(rng), &sm, &w, &scattered);
        ASSERT_TRUE(scattered);
        double cdf = 1.0 - std::exp(-0.7 * t);
        observed[std::min(bins - 1, int(cdf * bins))] += 1.0;
        ASSERT_NEAR(w.x, 0.5 / 0.7, 1e-5);  // sigma_s / sigma_t: the single-scattering albedo
    }
    auto r = test::chi_square(observed, expected);
    EXPECT_FALSE(r.reject) << "chi2 " << r.statistic << " dof " << r.dof << " z " << r.z;
}

TEST(Medium, ChromaticPathWeightsAreUnbiasedAndBounded) {
    // A path through six segments of length 0.4 in a strongly chromatic medium, each
    // passed or scattered (the direction does not matter in a homogeneous medium), one
    // channel drawing every distance (path-level MIS over the channels, TsSpectralMis).
    // Every channel's weight after segment j must have mean m_c^j, m_c = Tr_c(L) +
    // a_c (1 − Tr_c(L)) the segment's integral (a_c the single-scattering albedo); and be at
    // most 3 times the product of the channel's albedos over the scattering events
    // (f_c / mean_c(p_c) ≤ 3 f_c / p_c, which is a_c or 1 per segment). With
    // one channel drawn per segment and each segment divided by its own channel mean
    // (unbiased too), weights reached 285 over these six segments, and a foggy frame's red
    // came out 10% dark at 32 light paths a set (docs/path-tracing.md §4).
    const ts::float3 sa = make_float3(0.05f, 0.05f, 0.05f), ss = make_float3(5.0f, 0.5f, 0.05f);
    ts::TsMedium m = slab(sa, ss);
    const float len = 0.4f;
    const int n = 200000, segments = 6;
    const float st[3] = {sa.x + ss.x, sa.y + ss.y, sa.z + ss.z}, s[3] = {ss.x, ss.y, ss.z};
    double sum[segments][3] = {}, sum2[segments][3] = {}, largest = 0.0;
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    auto u = [&] { return std::min(uni(rng), 0x1.fffffep-1f); };  // [0, 1) whatever the library
    for (int i = 0; i < n; ++i) {
        ts::TsSpectralMis sm = ts::ts_spectral_mis_start();
        ts::float3 alpha = make_float3(1.0f, 1.0f, 1.0f);
        double albedos[3] = {1.0, 1.0, 1.0};  // the product of each channel's albedos so far
        for (int j = 0; j < segments; ++j) {
            ts::float3 w;
            int scattered;
            const float uc = u(), ud = u();
            ts::ts_medium_sample_distance(&m, len, uc, ud, &sm, &w, &scattered);
            alpha = alpha * w;
            const double a[3] = {alpha.x, alpha.y, alpha.z};
            for (int c = 0; c < 3; ++c) {
                if (scattered) albedos[c] *= double(s[c]) / st[c];
                sum[j][c] += a[c];
                sum2[j][c] += a[c] * a[c];
                largest = std::max(largest, a[c] / (3.0 * albedos[c]));
            }
        }
    }
    EXPECT_LE(largest, 1.0 + 1e-5) << "a weight over 3 times its channel's albedos";
    for (int c = 0; c < 3; ++c) {
        const double tr = std::exp(-st[c] * len), seg = tr + s[c] / st[c] * (1.0 - tr);
        for (int j = 0; j < segments; ++j) {
            const double mean = sum[j][c] / n, sd = std::sqrt(std::max(0.0, sum2[j][c] / n - mean * mean));
            // 5 standard errors of the mean: a one-in-a-million miss per comparison.
            EXPECT_NEAR(mean, std::pow(seg, j + 1), 5.0 * sd / std::sqrt(double(n)) + 1e-6)
                << "channel " << c << ", segment " << j;
        }
    }
}

// A distance sampler on [a, b] against its pdf: fifty bins whose expected counts are the
// pdf integrated over each bin (Simpson, 64 panels), 200,000 samples from `seed`, so a
// sampler and a pdf that disagree fail the chi-square test; the pdf must integrate to one.
template <class Sample, class Pdf>
void expect_samples_follow_pdf(Sample sample, Pdf pdf, float a, float b, unsigned seed) {
    const int bins = 50, n = 200000;
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    const double width = (b - a) / bins;
    double total = 0.0;
    for (int k = 0; k < bins; ++k) {
        const int panels = 64;
        const double h = width / panels;
        double s = 0.0;
        for (int j = 0; j <= panels; ++j) {
            const double t = a + k * width + j * h;
            const double c = (j == 0 || j == panels) ? 1.0 : (j % 2 ? 4.0 : 2.0);
            s += c * pdf(float(t));
        }
        expected[k] = s * h / 3.0 * n;
        total += expected[k];
    }
    EXPECT_NEAR(total / n, 1.0, 1e-4) << "the pdf integrates to one over [a, b]";
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < n; ++i) {
        const float t = sample(u(rng));
        ASSERT_TRUE(t >= a && t <= b) << t;
        observed[std::min(bins - 1, int((t - a) / width))] += 1.0;
    }
    auto r = test::chi_square(observed, expected);
    EXPECT_FALSE(r.reject) << "chi2 " << r.statistic << " dof " << r.dof << " z " << r.z;
}

TEST(Medium, EquiangularDistancesFollowTheirPdf) {
    // ts_equiangular_sample against ts_equiangular_pdf (expect_samples_follow_pdf): a lost
    // D or a wrong angle range fails. A point 0.3 off the ray, its
    // projection inside the segment [0.5, 6]: a sharp peak, the case the method is for.
    const ts::float3 org = make_float3(0, 0, 0), dir = make_float3(0, 0, 1), p = make_float3(0.3f, 0, 2);
    const float a = 0.5f, b = 6.0f;
    ts::TsEquiangular e = ts::ts_equiangular_angles(ts::ts_equiangular_setup(org, dir, b, p, 0.0f), a, b);
    EXPECT_NEAR(e.delta, 2.0f, 1e-6f);
    EXPECT_NEAR(e.D, 0.3f, 1e-6f);
    expect_samples_follow_pdf([&](float v) { return ts::ts_equiangular_sample(&e, a, b, v); },
                              [&](float t) { return ts::ts_equiangular_pdf(&e, t); }, a, b, 21);
}

TEST(Medium, LineDistancesFollowTheirPdf) {
    // ts_line_sample against ts_line_pdf (the camera side of a ray light's link;
    // expect_samples_follow_pdf), for a line passing 0.2 from the ray at t = 2.5 at 60°, a
    // sharp 1/D(t) peak, and for a nearly parallel line (the uniform fallback).
    const ts::float3 org = make_float3(0, 0, 0), dir = make_float3(0, 0, 1);
    const float a = 0.5f, b = 6.0f;
    struct Line {
        ts::float3 p, w;
        float tc, h;
    };
    const float c60 = 0.5f, s60 = std::sqrt(3.0f) / 2.0f;
    for (const Line& line : {Line{make_float3(0.2f, 0, 2.5f), make_float3(0, s60, c60), 2.5f, 0.2f},
                             Line{make_float3(0.7f, 0, 1.0f), make_float3(0, 0, 1), 0.0f, 0.7f}}) {
        ts::TsLineSampler ls = ts::ts_line_sampler(org, dir, a, b, line.p, line.w);
        if (!ls.uniform) {
            EXPECT_NEAR(ls.tc, line.tc, 1e-5f);
            EXPECT_NEAR(ls.h, line.h, 1e-5f);
            EXPECT_NEAR(ls.a, s60, 1e-6f);
        }
        expect_samples_follow_pdf([&](float v) { return ts::ts_line_sample(&ls, a, b, v); },
                                  [&](float t) { return ts::ts_line_pdf(&ls, t); }, a, b, 23);
    }
    // Lines that cross (h = 0) keep finite samples and densities (the rounding floor).
    ts::TsLineSampler cross = ts::ts_line_sampler(org, dir, a, b, make_float3(0, 0, 3), make_float3(1, 0, 0));
    EXPECT_GT(cross.h, 0.0f);
    for (float v : {0.0f, 0.3f, 0.5f, 0.999f}) {
        const float t = ts::ts_line_sample(&cross, a, b, v);
        const float pdf = ts::ts_line_pdf(&cross, t);
        EXPECT_TRUE(std::isfinite(t) && std::isfinite(pdf) && pdf > 0.0f) << v << " " << t << " " << pdf;
    }
}

TEST(Medium, EquiangularStaysFiniteForAPointOnTheRay) {
    // A light or VPL exactly on the camera ray's line (D = 0) would give 0/0 angles and an
    // infinite density at its projection: the rounding floor keeps D > 0, so samples and
    // densities stay finite; d_min widens the density to the given distance (the VPL
    // clamp's radius in shared/igi_march.h).
    const ts::float3 org = make_float3(0, 0, 0), dir = make_float3(0, 0, 1), p = make_float3(0, 0, 3);
    ts::TsEquiangular e = ts::ts_equiangular_angles(ts::ts_equiangular_setup(org, dir, 10.0f, p, 0.0f), 0.0f, 10.0f);
    EXPECT_GT(e.D, 0.0f);
    for (float u : {0.0f, 0.25f, 0.5f, 0.75f, 0.999f}) {
        const float t = ts::ts_equiangular_sample(&e, 0.0f, 10.0f, u);
        EXPECT_TRUE(std::isfinite(t) && t >= 0.0f && t <= 10.0f) << u << " " << t;
        const float pdf = ts::ts_equiangular_pdf(&e, t);
        EXPECT_TRUE(std::isfinite(pdf) && pdf > 0.0f) << u << " " << pdf;
    }
    ts::TsEquiangular wide =
        ts::ts_equiangular_angles(ts::ts_equiangular_setup(org, dir, 10.0f, p, 0.5f), 0.0f, 10.0f);
    EXPECT_EQ(wide.D, 0.5f);
    // The peak density of a Cauchy law of scale D truncated to [0, 10] around 3: about
    // 1 / (pi D), here 1 / ((atan(14) + atan(6)) · 0.5).
    EXPECT_NEAR(ts::ts_equiangular_pdf(&wide, 3.0f), 1.0 / ((std::atan(14.0) + std::atan(6.0)) * 0.5), 1e-5);
}

TEST(Medium, RgbWeightsAreUnbiased) {
    // Channels with different sigma_t: E[pass weight] = Tr_c(len) and
    // E[scatter weight] = sigma_s,c (1 - Tr_c(len)) / sigma_t,c for every channel c.
    const ts::float3 sa = make_float3(0.1f, 0.6f, 2.0f), ss = make_float3(0.1f, 0.4f, 1.0f);
    ts::TsMedium m = slab(sa, ss);
    const float len = 1.5f;
    const int n = 400000;
    double pass[3] = {}, scat[3] = {};
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < n; ++i) {
        ts::float3 w;
        int scattered;
        ts::TsSpectralMis sm = ts::ts_spectral_mis_start();
        ts::ts_medium_sample_distance(&m, len, u(rng), u(rng), &sm, &w, &scattered);
        double* acc = scattered ? scat : pass;
        acc[0] += w.x;
        acc[1] += w.y;
        acc[2] += w.z;
    }
    const float st[3] = {sa.x + ss.x, sa.y + ss.y, sa.z + ss.z}, s[3] = {ss.x, ss.y, ss.z};
    for (int c = 0; c < 3; ++c) {
        const double tr = std::exp(-st[c] * len);
        EXPECT_NEAR(pass[c] / n, tr, 0.01 * tr + 2e-3) << "channel " << c;
        const double sc = s[c] * (1.0 - tr) / st[c];
        EXPECT_NEAR(scat[c] / n, sc, 0.01 * sc + 2e-3) << "channel " << c;
    }
}

}  // namespace
}  // namespace tessera
