// render/renderer.h's image size: --width and --height override the scene camera's; one
// given alone scales the other so the picture keeps the camera's aspect ratio.
#include "render/renderer.h"

#include <gtest/gtest.h>

#include "util/error.h"

namespace tessera {
namespace {

ImageSize size_for(int width, int height, int camera_width, int camera_height) {
    RenderSettings s;
    s.width = width, s.height = height;
    Camera c;
    c.width = camera_width, c.height = camera_height;
    return render_image_size(s, c);
}

TEST(RenderImageSize, OneSideGivenKeepsTheCamerasAspectRatio) {
    const auto expect = [](ImageSize got, int w, int h) {
        EXPECT_EQ(got.width, w);
        EXPECT_EQ(got.height, h);
    };
    expect(size_for(0, 0, 640, 360), 640, 360);    // neither: the camera's
    expect(size_for(320, 200, 640, 360), 320, 200);  // both: as given, whatever the aspect
    expect(size_for(64, 0, 512, 512), 64, 64);
    expect(size_for(320, 0, 640, 360), 320, 180);
    expect(size_for(0, 90, 640, 360), 160, 90);
    expect(size_for(101, 0, 640, 360), 101, 57);     // 56.8 rounds to 57
    expect(size_for(1, 0, 640, 360), 1, 1);          // never 0
}

TEST(RenderImageSize, AScaledSideAboveTheLimitNamesTheOption) {
    try {
        size_for(0, 16384, 4096, 1024);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "--height 16384: at the camera's aspect ratio the --width would be 65536 px, above 16384; "
                               "give --width too");
    }
}

}  // namespace
}  // namespace tessera
