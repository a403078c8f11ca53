// relMSE, RMSE and PSNR (host/metrics/image_metrics.h) against values computed by hand.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "metrics/image_metrics.h"
#include "util/error.h"

using namespace tessera;
using namespace tessera::metrics;

namespace {

RgbImage constant(int w, int h, float v) { return RgbImage{w, h, std::vector<float>(3 * w * h, v)}; }

Image make_image(int w, int h, float v, bool with_b = true) {
    Image img{w, h, {{"R", {}}, {"G", {}}}};
    if (with_b) img.channels.push_back({"B", {}});
    for (auto& c : img.channels) c.data.assign(w * h, v);
    return img;
}

}  // namespace

TEST(ImageMetrics, IdenticalImagesHaveZeroErrorAndInfinitePsnr) {
    RgbImage a = constant(4, 3, 0.3f);
    a.rgb[5] = 7.0f;
    EXPECT_EQ(rel_mse(a, a), 0.0);
    EXPECT_EQ(rmse(a, a), 0.0);
    EXPECT_EQ(psnr_tonemapped(a, a), std::numeric_limits<double>::infinity());
}

TEST(ImageMetrics, KnownPerturbation) {
    // Reference 0.25 everywhere, test 0.5 in half the pixels (2 of 4), unchanged elsewhere.
    RgbImage ref = constant(2, 2, 0.25f), test = ref;
    for (int i = 0; i < 6; ++i) test.rgb[i] = 0.5f;
    // Changed pixels: (0.25)^2 / (0.0625 + 0.01) = 0.0625 / 0.0725; half the pixels changed.
    EXPECT_NEAR(rel_mse(ref, test), 0.5 * 0.0625 / 0.0725, 1e-12);
    EXPECT_NEAR(rmse(ref, test), std::sqrt(0.5 * 0.0625), 1e-12);
    // sRGB OETF: 1.055 * 0.25^(1/2.4) - 0.055 = 0.537099, 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357;
    // MSE = 0.5 * 0.198258^2 = 0.0196532; PSNR = 10 log10(1 / 0.0196532) = 17.0657 dB.
    EXPECT_NEAR(tone_map_srgb(0.25), 0.537099, 1e-6);
    EXPECT_NEAR(tone_map_srgb(0.5), 0.735357, 1e-6);
    EXPECT_NEAR(psnr_tonemapped(ref, test), 17.0657, 1e-3);
    // Exposure +1 stop maps 0.5 to 1 and 0.25 to 0.5: MSE = 0.5 * (1 - 0.735357)^2, PSNR 14.5571 dB.
    EXPECT_NEAR(psnr_tonemapped(ref, test, 1.0), 14.5571, 1e-3);
}

TEST(ImageMetrics, RelMseEpsilonGuardsBlackReferencePixels) {
    // r = 0, t = 0.1: 0.01 / (0 + 0.01) = 1.
    EXPECT_NEAR(rel_mse(constant(3, 1, 0.0f), constant(3, 1, 0.1f)), 1.0, 1e-6);
}

TEST(ImageMetrics, ToneMapClampsAndIsLinearNearBlack) {
    EXPECT_EQ(tone_map_srgb(-1.0), 0.0);
    EXPECT_EQ(tone_map_srgb(5.0), 1.0);
    EXPECT_NEAR(tone_map_srgb(0.001), 0.01292, 1e-9);
}

TEST(ImageMetrics, RejectsNanInfAndMissingChannels) {
    Image img = make_image(2, 2, 1.0f);
    img.channels[1].data[3] = std::nanf("");
    try {
        rgb_for_metrics(img, "test.exr");
        FAIL() << "NaN accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("test.exr"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("(1, 1)"), std::string::npos) << e.what();
    }
    img.channels[1].data[3] = std::numeric_limits<float>::infinity();
    EXPECT_THROW(rgb_for_metrics(img, "test.exr"), InputError);
    try {
        rgb_for_metrics(make_image(2, 2, 1.0f, false), "nob.exr");
        FAIL() << "missing B accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("nob.exr: no 'B' channel"), std::string::npos) << e.what();
    }
}

TEST(ImageMetrics, RejectsMismatchedSizes) {
    try {
        check_same_size(constant(2, 2, 0.f), "a.exr", constant(3, 2, 0.f), "b.exr");
        FAIL() << "size mismatch accepted";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("a.exr is 2x2"), std::string::npos) << m;
        EXPECT_NE(m.find("b.exr is 3x2"), std::string::npos) << m;
    }
    EXPECT_THROW(rel_mse(constant(2, 2, 0.f), constant(3, 2, 0.f)), InputError);
}
