// Hard case: extreme values. Emission 2^49 and 1e15 (the loader's limit) with albedo 0.99; very dense (optical depth
// 1e3) and very thin (1e-6) media; Henyey–Greenstein g = ±0.999.
#include "hard_cases/hard_case.h"
#include "kernels/shared/layout_igi.h"
#include "util/input_limits.h"

namespace tessera::test {
namespace {

class ExtremeValues : public HardCase {};

// Emission scaled up to the largest the scene loader accepts (limits::kMaxRadiance, 1e15:
// beyond about 1e36 ic wrote Inf), in a box of albedo 0.99.
//
// 2^49 (5.6e14, the largest power of two within the limit): scaling every emitter by 2^k
// scales every float the estimators form from it by exactly 2^k (no rounding changes while
// nothing overflows or falls to a denormal), so every decision is the same and every pixel
// is exactly 2^k times the unscaled one: any overflow, absolute epsilon or clamp that does
// not scale with the emission shows as a pixel off.
//
// 1e15 itself (not a power of two): the flux of every VPL and path rounds otherwise than at
// 1, so an estimator's discrete choices may differ. ic and tic keep each VPL with a
// probability from its importance, in steps of 1/64, by one systematic draw
// (host/gi/vpl_importance.cpp: keep_probabilities, systematic_sample): an importance that
// rounds across a step, or a running sum across the draw's point, flips a choice. At 1e15
// (also 5e14, 2e15 and 7e9; not 1e14 or 7e14) one flips on Embree and about 50 pixels move
// by up to 1.4e-3 (measured at 16 passes; with --ic-importance 1, no selection, none
// move). Every other method holds a few ulps per vertex (< 1e-4 relative after 128
// vertices; measured < 3e-7).
// 4 passes: the scaling is exact or not at any count, and ic/tic, whose passes each
// gather from ~100-bounce paths (albedo 0.99), cost 4x less than at 16.
constexpr uint32_t kScalingSpp = 4;

TEST_P(ExtremeValues, EmissionScalesLinearlyUpToTheLimit) {
    const Scene one = closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.99f), glm::vec3(1.0f), 0.3f);
    const Image a = render(one, kScalingSpp);
    ASSERT_TRUE(all_finite(a));
    const auto& ra = a.find("G")->data;
    {
        const int k = int(std::floor(std::log2(double(limits::kMaxRadiance))));
        Scene big = one;
        big.materials[1].emission = glm::vec3(std::ldexp(1.0f, k));
        const Image b = render(big, kScalingSpp);
        const auto& rb = b.find("G")->data;
        size_t off = 0, first = ra.size();
        for (size_t i = 0; i < ra.size(); ++i)
            if (rb[i] != std::ldexp(ra[i], k)) first = std::min(first, i), ++off;
        EXPECT_EQ(off, 0u) << "2^" << k << ": first pixel off: " << first;
    }
    const double scale = double(limits::kMaxRadiance);
    Scene big = one;
    big.materials[1].emission = glm::vec3(limits::kMaxRadiance);
    const Image b = render(big, kScalingSpp);
    ASSERT_TRUE(all_finite(b));
    const bool selects = method().method == Method::Ic || method().method == Method::Tic;
    const double tolerance = selects ? 3e-3 : 1e-4;
    const auto& rb = b.find("G")->data;
    for (size_t i = 0; i < ra.size(); ++i)
        EXPECT_NEAR(rb[i], scale * double(ra[i]), tolerance * scale * double(ra[i]) + 1e-30) << "pixel " << i;
    EXPECT_NEAR(radiance_mean(b) / radiance_mean(a), scale, scale * 1e-5);
    EXPECT_LE(radiance_max(b), radiance_bound(method().transport, scale, 0.99));
    for (const char* c : {"variance.R", "variance.G", "variance.B"})
        EXPECT_TRUE(std::isfinite(channel_max(b, c)));
}

// The furnace (pt_test.cpp): every wall emits 1 and reflects 0.5, a purely scattering
// medium fills the box; the radiance is Le / (1 - rho) = 2 everywhere.
Scene furnace_with_medium(float sigma_s, float g) {
    Scene s = closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(1.0f), 0.3f);
    s.positions.resize(s.positions.size() - 6);
    s.normals.resize(s.normals.size() - 6);
    s.uvs.resize(s.uvs.size() - 6);
    s.material.resize(s.material.size() - 2);
    s.materials[0].emission = glm::vec3(1.0f);
    s.camera.width = s.camera.height = 16;
    s.has_medium = true;
    s.medium.sigma_s = glm::vec3(sigma_s);
    s.medium.g = g;
    return s;
}

TEST_P(ExtremeValues, HenyeyGreensteinNearPlusMinusOne) {
    for (float g : {0.4f, 0.999f, -0.999f}) {
        const Image img = render(furnace_with_medium(0.8f, g), 32);
        ASSERT_TRUE(all_finite(img)) << "g " << g;
        // Every method sees radiance 2 in every direction in the furnace, whatever the
        // medium does (a method that ignores media: the walls' 1 + 0.5 · 2); 256 pixels
        // x 32 spp give a standard error < 1% (measured 0.1–0.2% at 128 spp, so about
        // twice that here): 3% is generous. At g = 0.4 it also tells multiple scattering
        // from single (igi --single-scattering renders 0.61) and from none.
        if (method().peaked_phase_limit && std::abs(g) > 0.9f) {  // finite (above) and within the bound
            EXPECT_LE(radiance_max(img), radiance_bound(method().transport, 1.0, 0.5)) << "g " << g;
            continue;
        }
        const double expected = method().transport == Transport::Direct ? 1.0 + 0.5 * 1.0 : 2.0;
        // (The furnace is the extremal case of the energy bound: its radiance equals it,
        // so a per-pixel bound check would only test the noise.)
        EXPECT_NEAR(radiance_mean(img), expected, 0.03 * expected) << "g " << g;
    }
}

TEST(ExtremeValuesRayLights, HenyeyGreensteinNearPlusMinusOne) {
    // The ray lights' links are unclamped (docs/igi.md §6): with g = ±0.999 both phase
    // values of a link peak near 1e5 when the ray light runs along the camera ray. In the
    // furnace every pixel must stay finite and within the energy bound (radiance 2 there,
    // the bound's extremal case), on both backends, for igi and ais. (The igi family's
    // mean is ~0.64-0.79 here with point VPLs and ray lights alike, measured, and 0.80 /
    // 1.15 without the geometry clamp: the links cannot carry the phase function's spike,
    // HardCaseMethod::peaked_phase_limit, so only the bound is asked.)
    for (BackendKind kind : kHardCaseBackends)
        for (Method m : {Method::Igi, Method::Ais})
            for (float g : {0.999f, -0.999f}) {
                RenderSettings rs;
                rs.method = m;
                rs.spp = 32;
                rs.aovs = true;
                rs.igi.ray_lights = true;
                const Image img = render_with(kind, furnace_with_medium(0.8f, g), rs);
                ASSERT_TRUE(all_finite(img)) << method_name(m) << " g " << g;
                std::printf("  %s %s g %.3f: mean %.4f, max %.4f\n", kind == BackendKind::Embree ? "Embree" : "OpenCL",
                            method_name(m), g, radiance_mean(img), radiance_max(img));
                EXPECT_GT(radiance_mean(img), 0.0);
                EXPECT_LE(radiance_max(img), radiance_bound(Transport::Global, 1.0, 0.5)) << method_name(m) << " g " << g;
            }
}

// A lit closed box (albedo 0.5, Le 4) filled with a medium of single-scattering albedo
// 0.5 whose optical depth across the box is 1e3 (sigma_t = 500 per unit) or 1e-6.
TEST_P(ExtremeValues, DenseAndThinMedia) {
    const Scene base = closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(4.0f), 0.4f);
    const Image vacuum = render(base, 16, 1);
    for (float sigma : {250.0f, 2.5e-7f}) {
        Scene s = base;
        s.has_medium = true;
        s.medium.sigma_a = glm::vec3(sigma);
        s.medium.sigma_s = glm::vec3(sigma);
        const Image img = render(s, 16, 1);
        ASSERT_TRUE(all_finite(img)) << "sigma " << sigma;
        EXPECT_LE(radiance_max(img), radiance_bound(method().transport, 4.0, 0.5)) << "sigma " << sigma;
        EXPECT_GE(channel_max(img, "R"), 0.0f);
        const double se = std::hypot(radiance_mean_stderr(img), radiance_mean_stderr(vacuum));
        if (!method().media || sigma < 1.0f) {
            // A method that ignores media, or an optical depth of 1e-6 (a 1e-6 change):
            // the vacuum image within noise (4 standard errors of the difference).
            EXPECT_NEAR(radiance_mean(img), radiance_mean(vacuum), 4.0 * se + 1e-5) << "sigma " << sigma;
        } else {
            // Optical depth 1 within 2e-3 of the camera: nothing beyond the first few
            // mean free paths is seen. The camera sits 0.02 from the front wall, so what
            // it sees is medium lit by light that crossed ~1 unit (e^-500): black, and
            // the front wall's own radiance attenuated. Allow e^-1 of the vacuum mean.
            EXPECT_LT(radiance_mean(img), 0.37 * radiance_mean(vacuum)) << "sigma " << sigma;
        }
    }
}

// A medium box far larger than the scene (1e9 units) renders as the medium filling space
// does (pt alike). The box's back wall is left out, so camera rays and light paths escape
// through the hole into the fog. The igi family spread its escaped camera rays' march
// steps and its escaped light paths' ray lights over the 1e9 units: 33% dark here. Now
// both end at the medium's reach (ts_medium_reach). The two differ in their samples (a
// path may wander past where the unbounded march ends), so the means are compared:
// within 3% (measured within 0.4% at 8 spp on every method and backend).
TEST_P(ExtremeValues, AHugeMediumBoxRendersAsAMediumFillingSpace) {
    Scene filling = open_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(4.0f), 0.4f);
    filling.has_medium = true;
    filling.medium.sigma_a = glm::vec3(0.0f);
    filling.medium.g = 0.5f;
    // A reach of 20 units; the second without red scattering, which must not lift the
    // cut for green and blue (a channel that sees forever but scatters nothing).
    for (glm::vec3 sigma_s : {glm::vec3(1.0f), glm::vec3(0.0f, 1.0f, 1.0f)}) {
        filling.medium.sigma_s = sigma_s;
        Scene huge = filling;
        huge.medium.bounded = true;
        huge.medium.box_min = glm::vec3(-1e9f);
        huge.medium.box_max = glm::vec3(1e9f);
        const Image a = render(filling, 8), b = render(huge, 8);
        ASSERT_TRUE(all_finite(b));
        std::printf("  means (sigma_s.r %g): filling %.5f, box 1e9 %.5f\n", sigma_s.x, radiance_mean(a),
                    radiance_mean(b));
        EXPECT_NEAR(radiance_mean(b), radiance_mean(a), 0.03 * radiance_mean(a)) << "sigma_s.r " << sigma_s.x;
    }
}

// The camera segment's transmittance runs to the surface, not to the medium's reach: with
// green and blue dense and scattering (reach 20 mean free paths: 1 unit) and red thin and
// only absorbing, red's transmittance over the box's 2 units is e^-1, and the march ended
// at the reach gave e^-0.5 (the back wall 1.6x too bright in red). Red, lit by SS alone
// through links whose transmittance is exact, must be the image of a medium where no
// channel scatters (reach without end; there the march is not even run: PM is the
// transmittance alone). Measured equal to 1e-6 on every method and backend.
TEST_P(ExtremeValues, TransmittanceRunsPastTheReachOfOtherChannels) {
    if (!igi_family(method().method)) GTEST_SKIP() << "the igi family's march only";
    Scene s = closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(4.0f), 0.4f);
    s.has_medium = true;
    s.medium.sigma_a = glm::vec3(0.5f, 0.0f, 0.0f);
    RenderSettings rs = settings(2);
    rs.igi.components = TS_COMPONENT_SS | TS_COMPONENT_PM;
    double red[2];
    for (int scatter = 0; scatter < 2; ++scatter) {
        s.medium.sigma_s = scatter ? glm::vec3(0.0f, 20.0f, 20.0f) : glm::vec3(0.0f, 0.0f, 0.0f);
        const Image img = render_with(backend(), s, rs);
        ASSERT_TRUE(all_finite(img));
        red[scatter] = channel_mean(img, "R");
    }
    std::printf("  red mean: nothing scatters %.6f, green and blue scatter %.6f\n", red[0], red[1]);
    EXPECT_NEAR(red[1], red[0], 1e-3 * red[0]);
}

INSTANTIATE_TEST_SUITE_P(Methods, ExtremeValues, ::testing::ValuesIn(hard_case_params()), hard_case_name);

}  // namespace
}  // namespace tessera::test
