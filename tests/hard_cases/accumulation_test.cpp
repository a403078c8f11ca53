// Hard case: long accumulation. 2,500+ passes (the seed thesis's reference rate) of a
// constant image must average to that constant to float precision.
#include <vector>

#include "hard_cases/hard_case.h"
#include "render/accumulator.h"

namespace tessera::test {
namespace {

// 0.1f is not a binary fraction: a float running sum of 3000 copies drifts (by ~1e-4
// relative); the double sums of the Accumulator must give back 0.1f exactly.
TEST(LongAccumulation, ThreeThousandPassesOfAConstantStayExact) {
    const int w = 4, h = 3;
    Accumulator acc(w, h);
    std::vector<float> pass(size_t(w) * h * TS_PASS_FLOATS);
    for (size_t p = 0; p < size_t(w) * h; ++p) {
        float* o = &pass[p * TS_PASS_FLOATS];
        float* L = o + TS_PASS_RADIANCE;
        L[0] = 0.1f; L[1] = 1e-7f; L[2] = 3.3333333f;
        for (int c = 0; c < 3; ++c) o[TS_PASS_ALBEDO + c] = 0.7f;
        for (int c = 0; c < 3; ++c) o[TS_PASS_NORMAL + c] = c == 1 ? 1.0f : 0.0f;
        o[TS_PASS_DEPTH] = 12345.678f;
    }
    float naive = 0.0f;
    for (int i = 0; i < 3000; ++i) {
        acc.add(pass);
        naive += 0.1f;
    }
    ASSERT_NE(naive / 3000.0f, 0.1f) << "the float sum was meant to drift";
    const Image img = acc.mean_image(true, true);
    for (const char* c : {"R", "G", "B", "Z", "albedo.R", "variance.R"}) {
        ASSERT_NE(img.find(c), nullptr) << c;
        ASSERT_EQ(img.find(c)->data.size(), size_t(w * h)) << c;
    }
    for (float v : img.find("R")->data) EXPECT_EQ(v, 0.1f);
    for (float v : img.find("G")->data) EXPECT_EQ(v, 1e-7f);
    for (float v : img.find("B")->data) EXPECT_EQ(v, 3.3333333f);
    for (float v : img.find("Z")->data) EXPECT_EQ(v, 12345.678f);
    for (float v : img.find("albedo.R")->data) EXPECT_EQ(v, 0.7f);
    // A constant has no variance; rounding may leave a tiny positive value, never a
    // negative or non-finite one.
    for (float v : img.find("variance.R")->data) {
        EXPECT_GE(v, 0.0f);
        EXPECT_LT(v, 1e-12f);
    }
}

class LongAccumulation : public HardCase {};

// End to end: a camera that sees only an emitter (Le = 0.1, black) renders 2,500 passes
// of exactly 0.1 per pixel, on every method and backend.
TEST_P(LongAccumulation, TwentyFiveHundredPassesOfAnEmitter) {
    Scene s;
    const uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(0.1f, 0.3f, 1e-3f));
    add_quad(s, {-10, -10, -1}, {20, 0, 0}, {0, 20, 0}, light);  // z = -1, facing +z
    s.camera.position = {0, 0, 0};
    s.camera.look_at = {0, 0, -1};
    s.camera.width = s.camera.height = 4;
    const Image img = render(s, 2500);
    for (const char* c : {"R", "G", "B"}) {
        ASSERT_NE(img.find(c), nullptr) << c;
        ASSERT_EQ(img.find(c)->data.size(), 16u) << c;
    }
    for (float v : img.find("R")->data) EXPECT_EQ(v, 0.1f);
    for (float v : img.find("G")->data) EXPECT_EQ(v, 0.3f);
    for (float v : img.find("B")->data) EXPECT_EQ(v, 1e-3f);
}

INSTANTIATE_TEST_SUITE_P(Methods, LongAccumulation, ::testing::ValuesIn(hard_case_params()), hard_case_name);

}  // namespace
}  // namespace tessera::test
