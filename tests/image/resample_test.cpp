// Bilinear resizing for the viewer's reduced-resolution moving frames.
#include "image/resample.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

namespace tessera {
namespace {

Image ramp(int w, int h) {  // value = source x coordinate of the pixel centre
    Image img;
    img.width = w, img.height = h;
    img.channels.push_back({"R", std::vector<float>(size_t(w) * h)});
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.channels[0].data[size_t(y) * w + x] = float(x);
    return img;
}

TEST(ResizeBilinear, SameSizeIsTheIdentity) {
    const Image src = ramp(7, 5);
    const Image out = resize_bilinear(src, 7, 5);
    EXPECT_EQ(out.channels[0].data, src.channels[0].data);
}

// Pixel centres aligned: output pixel x of a 2x upsample sits at source x/2 - 0.25, so a
// linear ramp stays linear (exactly, away from the clamped border).
TEST(ResizeBilinear, UpsamplingALinearRampIsLinear) {
    const Image out = resize_bilinear(ramp(8, 4), 16, 8);
    ASSERT_EQ(out.width, 16);
    ASSERT_EQ(out.channels[0].data.size(), 128u);
    for (int y = 0; y < 8; ++y)
        for (int x = 1; x < 15; ++x) EXPECT_NEAR(out.channels[0].data[y * 16 + x], (x + 0.5) / 2 - 0.5, 1e-6);
    EXPECT_FLOAT_EQ(out.channels[0].data[0], 0.0f);   // clamped at the border
    EXPECT_FLOAT_EQ(out.channels[0].data[15], 7.0f);
}

TEST(ResizeBilinear, AMissedPixelsInfiniteDepthMakesNoNaN) {
    Image src = ramp(2, 1);
    src.channels[0].name = "Z";
    src.channels[0].data[1] = std::numeric_limits<float>::infinity();
    const Image out = resize_bilinear(src, 4, 1);
    for (float v : out.channels[0].data) EXPECT_FALSE(std::isnan(v));
    EXPECT_FLOAT_EQ(out.channels[0].data[0], 0.0f);
    EXPECT_TRUE(std::isinf(out.channels[0].data[3]));
}

TEST(ResizeBilinear, RefusesEmptySizes) {
    EXPECT_THROW(resize_bilinear(ramp(2, 2), 0, 2), std::invalid_argument);
    EXPECT_THROW(resize_bilinear(Image{}, 2, 2), std::invalid_argument);
}

}  // namespace
}  // namespace tessera
