// Texture filtering at camera hits (TsFrame::pixel_cone, kernels/shared/geometry.h
// ts_surface_cone, material.h ts_texture_lookup): a minified one-texel checker reads as
// its mean, grey, instead of aliasing to black and white; pt (the reference) is unchanged.
#include <cmath>

#include <gtest/gtest.h>

#include "kernels/shared/srgb_table.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace tessera {
namespace {

struct AlbedoStats {
    double mean = 0, max_dev = 0, sd = 0;
};

AlbedoStats albedo_stats(const Image& img, double centre) {
    AlbedoStats a;
    const auto& r = img.find("albedo.R")->data;
    for (float v : r) a.mean += v;
    a.mean /= r.size();
    for (float v : r) {
        a.max_dev = std::max(a.max_dev, std::abs(v - centre));
        a.sd += (v - a.mean) * (v - a.mean);
    }
    a.sd = std::sqrt(a.sd / r.size());
    return a;
}

RenderSettings albedo_settings(Method m) {
    RenderSettings rs;
    rs.method = m;
    rs.spp = 1;
    rs.aovs = true;
    rs.igi.paths_per_set = 4;
    return rs;
}

class TextureFilter : public ::testing::TestWithParam<BackendKind> {};

TEST_P(TextureFilter, MinifiedCheckerReadsAsItsMean) {
    const Scene scene = test::checker_floor();
    const double grey = ts::ts_srgb_table[188];  // the checker's level-3 value (texture_mips_test)
    for (Method m : {Method::Direct, Method::Igi}) {
        const AlbedoStats on = albedo_stats(test::render_with(GetParam(), scene, albedo_settings(m)), grey);
        // Every pixel spans >= 7 texels (more toward the corners), so it reads level 2 or
        // coarser, all exactly grey: only float rounding of the trilinear blend remains.
        EXPECT_LT(on.max_dev, 1e-5) << method_name(m);
        RenderSettings rs = albedo_settings(m);
        rs.texture_filter = false;
        const AlbedoStats off = albedo_stats(test::render_with(GetParam(), scene, rs), grey);
        // At level 0 the checker aliases: a bilinear read at a uniform sub-texel position
        // (ax, ay) gives 0.5 ± 0.5·(1 − 2ax)(1 − 2ay), whose standard deviation is
        // 0.5 · (1/√3)² = 1/6; over 1024 pixels the sample value is within ±0.02 of it.
        EXPECT_NEAR(off.sd, 1.0 / 6.0, 0.02) << method_name(m);
        EXPECT_NEAR(off.mean, 0.5, 0.03) << method_name(m);
    }
}

TEST_P(TextureFilter, PathTracerIgnoresIt) {
    const Scene scene = test::checker_floor();
    RenderSettings rs = albedo_settings(Method::PathTrace);
    const Image on = test::render_with(GetParam(), scene, rs);
    rs.texture_filter = false;
    test::expect_images_identical(on, test::render_with(GetParam(), scene, rs));
}

INSTANTIATE_TEST_SUITE_P(Backends, TextureFilter, ::testing::Values(BackendKind::Embree, BackendKind::OpenCL),
                         [](const auto& info) {
                             return std::string(info.param == BackendKind::Embree ? "Embree" : "OpenCL");
                         });

}  // namespace
}  // namespace tessera
