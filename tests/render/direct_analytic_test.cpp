// The `direct` method against closed-form irradiance, on both backends.
#include <cmath>

#include <gtest/gtest.h>

#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace tessera {
namespace {

// View factor from a differential area to a parallel a × b rectangle at height h whose
// corner lies straight above it (Howell, "A Catalog of Radiation Heat Transfer
// Configuration Factors", B-3).
double corner_view_factor(double a, double b, double h) {
    const double A = a / h, B = b / h;
    const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
    return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * M_PI);
}

// A Lambertian plane (albedo rho) under a square emitter of half-size a at height h,
// radiance Le, seen straight down near the point under the emitter's centre. Reflected
// radiance: L = rho/pi · E = rho · Le · F with F = 4 · F_corner(a, a, h).
class PlaneUnderLight : public ::testing::TestWithParam<BackendKind> {};

TEST_P(PlaneUnderLight, MatchesClosedFormIrradiance) {
    const float rho = 0.5f, le = 2.0f, a = 1.0f, h = 1.0f;
    Scene s;
    s.name = "plane";
    const uint32_t floor = test::add_material(s, glm::vec3(rho));
    const uint32_t light = test::add_material(s, glm::vec3(0.0f), glm::vec3(le));
    test::add_quad(s, {-50, 0, -50}, {0, 0, 100}, {100, 0, 0}, floor);             // faces +y
    test::add_quad(s, {-a, h, -a}, {2 * a, 0, 0}, {0, 0, 2 * a}, light);           // faces -y
    s.camera.position = {0, 0.5f * h, 0};
    s.camera.look_at = {0, 0, 0};
    s.camera.up = {0, 0, 1};
    s.camera.vfov_deg = 0.5f;  // pixels see within 0.003 of the centre: F varies by < 1e-5
    s.camera.width = s.camera.height = 16;
    RenderSettings rs;
    rs.spp = 16;
    rs.shadow_samples = 64;
    Image img = test::render_with(GetParam(), s, rs);
    ASSERT_TRUE(test::all_finite(img));
    const double expected = rho * le * 4.0 * corner_view_factor(a, a, h);
    // 256 pixels × 16 passes × 64 stratified samples: the standard error of the mean is
    // far below 0.1% (measured spread of single pixels: ~1%), so 1% is a real bound.
    for (const char* c : {"R", "G", "B"}) EXPECT_NEAR(test::channel_mean(img, c), expected, 0.01 * expected);
    for (float v : img.find("R")->data) EXPECT_NEAR(v, expected, 0.05 * expected);
}

// `direct` follows a mirror to the diffuse surface behind it: a lit floor seen in a
// vertical mirror of reflectance 0.8 is 0.8 times the same floor seen from the mirror
// image of the camera without the mirror (an image flipped left to right, so their means
// agree). The mirror stands clear of the light's way to the floor it shows. Before
// `direct` followed specular surfaces it shaded the mirror itself (Kd 0): black.
TEST_P(PlaneUnderLight, SeenInAMirrorIsTheMirrorImageTimesItsReflectance) {
    const float rho = 0.5f, le = 2.0f, ks = 0.8f;
    auto scene = [&](bool mirror) {
        Scene s;
        s.name = mirror ? "mirror" : "mirror-image";
        const uint32_t floor = test::add_material(s, glm::vec3(rho));
        const uint32_t light = test::add_material(s, glm::vec3(0.0f), glm::vec3(le));
        test::add_quad(s, {-50, 0, -50}, {0, 0, 100}, {100, 0, 0}, floor);  // faces +y
        test::add_quad(s, {-1, 1, -1}, {2, 0, 0}, {0, 0, 2}, light);        // faces -y
        if (mirror) {
            const uint32_t m = test::add_material(s, glm::vec3(0.0f));
            s.materials[m].specular = glm::vec3(ks);
            s.materials[m].illum = 3;
            test::add_quad(s, {4, 0, -3}, {0, 0, 6}, {0, 3, 0}, m);  // x = 4, faces -x
        }
        // Through the mirror at x = 4 the camera at (3, 2, 0) sees what (5, 2, 0) sees.
        s.camera.position = {mirror ? 3.0f : 5.0f, 2.0f, 0.0f};
        s.camera.look_at = {4, 1, 0};
        s.camera.up = {0, 1, 0};
        s.camera.vfov_deg = 10.0f;  // the view stays inside the mirror
        s.camera.width = s.camera.height = 16;
        return s;
    };
    RenderSettings rs;
    rs.spp = 16;
    rs.shadow_samples = 64;
    const Image seen = test::render_with(GetParam(), scene(true), rs);
    const Image image = test::render_with(GetParam(), scene(false), rs);
    ASSERT_TRUE(test::all_finite(seen));
    // As above, the estimate's standard error is far below 0.1%; the two means differ by
    // the floor's radiance gradient over the flipped pixels' jitter, well below 1%.
    for (const char* c : {"R", "G", "B"}) {
        const double expected = ks * test::channel_mean(image, c);
        ASSERT_GT(expected, 0.01);
        EXPECT_NEAR(test::channel_mean(seen, c), expected, 0.01 * expected) << c;
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, PlaneUnderLight, ::testing::Values(BackendKind::Embree, BackendKind::OpenCL),
                         [](const auto& info) { return info.param == BackendKind::Embree ? "Embree" : "OpenCL"; });

}  // namespace
}  // namespace tessera
