// The `pt` method against analytic values, on both backends.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "integrators/factory.h"
#include "integrators/integrator.h"
#include "kernels/shared/layout_pass.h"
#include "support/render_helpers.h"
#include "support/single_scatter.h"
#include "support/test_scenes.h"

namespace tessera {
namespace {

const char* backend_name(const ::testing::TestParamInfo<BackendKind>& info) {
    return info.param == BackendKind::Embree ? "Embree" : "OpenCL";
}

// A closed box whose walls all emit Le and reflect with albedo rho: in equilibrium the
// radiance is Le / (1 - rho) everywhere and in every direction, with or without a
// non-absorbing medium inside (scattering only redistributes a uniform radiance field).
Scene furnace(float rho, float le) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(rho), glm::vec3(1.0f), 0.3f);
    s.positions.resize(s.positions.size() - 6);  // drop the ceiling light: walls emit instead
    s.normals.resize(s.normals.size() - 6);
    s.uvs.resize(s.uvs.size() - 6);
    s.material.resize(s.material.size() - 2);
    s.materials[0].emission = glm::vec3(le);
    s.camera.width = s.camera.height = 16;
    return s;
}

class PtFurnace : public ::testing::TestWithParam<BackendKind> {};

void expect_furnace(BackendKind kind, const Scene& s, uint32_t spp) {
    RenderSettings rs;
    rs.method = Method::PathTrace;
    rs.spp = spp;
    Image img = test::render_with(kind, s, rs);
    ASSERT_TRUE(test::all_finite(img));
    // 256 pixels: the relative standard error of the image mean is about 0.1% here
    // (measured), so 0.5% is a five-sigma bound.
    for (const char* c : {"R", "G", "B"}) EXPECT_NEAR(test::channel_mean(img, c), 2.0, 0.01);
}

TEST_P(PtFurnace, EmptyEnclosure) { expect_furnace(GetParam(), furnace(0.5f, 1.0f), 256); }

TEST_P(PtFurnace, EnclosureWithScatteringMedium) {
    Scene s = furnace(0.5f, 1.0f);
    s.has_medium = true;
    s.medium.sigma_s = glm::vec3(0.8f);  // grey (RGB weights exactly 1); optical depth 1.6 across the box
    s.medium.g = 0.4f;
    expect_furnace(GetParam(), s, 256);
}

// A dense medium that scatters without absorbing (σs 10: 20 mean free paths across the
// box) ends no path by roulette: light random-walks ~(extent / mean free path)² events to
// the walls. The default depth must let it (128 vertices rendered 1.89, 1,024 2.018; at σs
// 30, 1.36 and 1.97). The noise is larger than the empty furnace's (16 spp: a standard
// error of ~0.6% measured), so 3% is five sigma.
TEST_P(PtFurnace, DenseScatteringMediumAtTheDefaultDepth) {
    Scene s = furnace(0.5f, 1.0f);
    s.has_medium = true;
    s.medium.sigma_s = glm::vec3(10.0f);
    s.medium.g = 0.3f;
    RenderSettings rs;
    rs.method = Method::PathTrace;
    rs.spp = 16;
    Image img = test::render_with(GetParam(), s, rs);
    ASSERT_TRUE(test::all_finite(img));
    for (const char* c : {"R", "G", "B"}) EXPECT_NEAR(test::channel_mean(img, c), 2.0, 0.06) << c;
}

// With at most N scattering vertices a path counts the walls' emission after up to N
// reflections: L = Le (1 + rho + ... + rho^N) = Le (1 - rho^(N+1)) / (1 - rho), 1.5, 1.75
// and 1.875 for N = 1, 2, 3 at rho = 1/2. The last vertex's light samples keep their MIS
// weight, so its continuation must still find the emitters: without it N = 1, 2, 3 gave 1.16, 1.58, 1.79.
TEST_P(PtFurnace, DepthLimitCountsEveryPathUpToIt) {
    const Scene s = furnace(0.5f, 1.0f);
    for (uint32_t n : {1u, 2u, 3u}) {
        RenderSettings rs;
        rs.method = Method::PathTrace;
        rs.spp = 256;
        rs.max_depth = n;
        const Image img = test::render_with(GetParam(), s, rs);
        const double expected = (1.0 - std::pow(0.5, n + 1)) / 0.5;
        // The noise is below the full furnace's (fewer, unrouletted vertices): 0.5% is
        // five sigma there.
        for (const char* c : {"R", "G", "B"})
            EXPECT_NEAR(test::channel_mean(img, c), expected, 0.005 * expected) << "max_depth " << n << " " << c;
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, PtFurnace, ::testing::Values(BackendKind::Embree, BackendKind::OpenCL),
                         backend_name);

class PtMedium : public ::testing::TestWithParam<BackendKind> {};

// An emitting wall (Le = 1, black) seen through a purely absorbing slab of thickness d:
// L = exp(-sigma_a d) per channel (Beer–Lambert).
TEST_P(PtMedium, AbsorbingSlabAttenuatesAnEmitter) {
    Scene s;
    s.name = "slab";
    const uint32_t wall = test::add_material(s, glm::vec3(0.0f), glm::vec3(1.0f));
    test::add_quad(s, {-20, -20, 5}, {0, 40, 0}, {40, 0, 0}, wall);  // z = 5, facing -z
    s.camera.position = {0, 0, 0};
    s.camera.look_at = {0, 0, 1};
    s.camera.vfov_deg = 5.0f;
    s.camera.width = s.camera.height = 16;
    s.has_medium = true;
    s.medium.sigma_a = glm::vec3(0.1f, 0.5f, 1.5f);
    s.medium.bounded = true;
    s.medium.box_min = {-30, -30, 1};
    s.medium.box_max = {30, 30, 3};  // thickness 2 along the view axis
    RenderSettings rs;
    rs.method = Method::PathTrace;
    rs.spp = 256;
    Image img = test::render_with(GetParam(), s, rs);
    // One sample passes the slab with probability mean_c Tr_c = 0.41, weighted Tr/0.41,
    // so 65,536 samples give a relative standard error of 0.47% in every channel; 2% is
    // four sigma. Camera rays deviate from the axis by < 2.5°: the path is < 0.1% longer.
    const char* ch[] = {"R", "G", "B"};
    const float sa[] = {0.1f, 0.5f, 1.5f};
    for (int c = 0; c < 3; ++c) {
        const double expected = std::exp(-2.0 * sa[c]);
        EXPECT_NEAR(test::channel_mean(img, ch[c]), expected, 0.02 * expected) << ch[c];
    }
}

TEST_P(PtMedium, SingleScatteringMatchesQuadrature) {
    RenderSettings rs;
    rs.method = Method::PathTrace;
    rs.max_scatter = 1;
    rs.spp = 4096;
    Image img = test::render_with(GetParam(), test::single_scatter_scene(), rs);
    ASSERT_TRUE(test::all_finite(img));
    const char* ch[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        const double expected = test::single_scatter_reference(c);
        // 64 pixels × 4096 spp: measured relative standard error of the mean 0.17%, and
        // the render came within 0.05% of the quadrature; 1% is a six-sigma bound.
        EXPECT_NEAR(test::channel_mean(img, ch[c]), expected, 0.01 * expected) << ch[c];
    }
}

// The far roulette (shared/medium.h, ts_far_importance) ends camera paths that walk away
// into a medium that scatters without absorbing, one scene size past the surfaces and the
// camera; without it they ran to the depth cap (8,192 vertices: an open Cornell box in
// such fog took 90x the time of a 64-vertex cap). It is unbiased, so the image is the one
// without it. An open box (its back wall removed) in such a medium filling space, both at
// a 128-vertex cap: the mean of 256 passes' differences, paired by pass (they share their
// numbers up to a path's first far roulette), lies within five of its standard errors of
// 0 (measured -1.6), and the roulette did act (the passes differ). A far roulette that
// did not divide the survivors' weight by their survival read -5.5 standard errors.
TEST_P(PtMedium, FarRouletteKeepsTheImageOfAnOpenMedium) {
    Scene s = test::open_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(4.0f), 0.4f);
    s.camera.width = s.camera.height = 16;
    s.has_medium = true;
    s.medium.sigma_s = glm::vec3(1.0f);
    s.medium.g = 0.5f;
    RenderSettings rs;
    rs.method = Method::PathTrace;
    rs.max_depth = 128;
    const SceneBuffers b = make_scene_buffers(s);
    auto backend = make_backend(BackendOptions{GetParam(), ""}, b, plan_effects(s));
    auto integrator = make_integrator(*backend, s, b, rs);
    const int passes = 256;
    std::vector<double> diff;
    double mean_with = 0.0;
    for (int pass = 0; pass < passes; ++pass) {
        TsFrame f = make_render_frame(s.camera, 16, 16, b, rs);
        f.pass = uint32_t(pass);
        ASSERT_GT(f.far_margin, 0.0f);
        double sums[2] = {0.0, 0.0};
        for (int off = 0; off < 2; ++off) {
            if (off) f.far_margin = 0.0f;
            std::vector<float> out;
            integrator->render_pass(f, out);
            for (size_t p = 0; p < out.size() / TS_PASS_FLOATS; ++p)
                for (int c = 0; c < 3; ++c) sums[off] += out[p * TS_PASS_FLOATS + TS_PASS_RADIANCE + c];
        }
        ASSERT_TRUE(std::isfinite(sums[0]));
        diff.push_back((sums[0] - sums[1]) / (3.0 * 256.0));
        mean_with += sums[0] / (3.0 * 256.0 * passes);
    }
    double mean = 0.0, var = 0.0;
    for (double d : diff) mean += d / passes;
    for (double d : diff) var += (d - mean) * (d - mean) / (passes - 1);
    const double se = std::sqrt(var / passes);
    std::printf("  mean radiance %.5f, with - without the far roulette %.5f (standard error %.5f)\n", mean_with, mean,
                se);
    EXPECT_GT(se, 0.0) << "the far roulette never acted";
    EXPECT_LT(std::fabs(mean), 5.0 * se + 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Backends, PtMedium, ::testing::Values(BackendKind::Embree, BackendKind::OpenCL),
                         backend_name);

}  // namespace
}  // namespace tessera
