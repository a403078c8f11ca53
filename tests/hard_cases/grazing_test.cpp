// Hard case: grazing angles. Camera rays meet a floor at 89.9°–90° from its normal, and
// the only light is a distant quad 0.1° above the floor's horizon (light rays at 89.9°).
#include "hard_cases/hard_case.h"

namespace tessera::test {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr float kRho = 0.8f, kLe = 1e8f;
constexpr double kLightDist = 1e7, kLightHalf = 1e4, kElev = 0.1 * kDeg;

Scene grazing() {
    Scene s;
    s.name = "grazing";
    const uint32_t floor = add_material(s, glm::vec3(kRho));
    const uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(kLe));
    const float w = 2e5f;
    add_quad(s, {-w, 0, -w}, {0, 0, 2 * w}, {2 * w, 0, 0}, floor);  // y = 0, +y
    // The light, centred 1e7 away along +x at elevation 0.1°, facing the origin.
    const glm::dvec3 c(kLightDist * std::cos(kElev), kLightDist * std::sin(kElev), 0.0);
    const glm::dvec3 n = -glm::normalize(c);
    const glm::dvec3 e1 = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), n)) * (2 * kLightHalf);  // in the x-y plane
    const glm::dvec3 e2 = glm::dvec3(0, 0, 2 * kLightHalf);
    // cross(e1, e2) = cross(cross(z, n), z) = n: the front faces the origin.
    add_quad(s, glm::vec3(c - 0.5 * e1 - 0.5 * e2), glm::vec3(e1), glm::vec3(e2), light);
    // Camera 1 above the floor looking along -z, 0.1° below the horizon, 0.2° field of
    // view: the bottom row meets the floor at 0.2° (89.8° from the normal), the top row
    // runs parallel to it.
    s.camera.position = {0, 1, 0};
    s.camera.look_at = {0.0f, float(1.0 - std::tan(kElev)), -1.0f};
    s.camera.vfov_deg = 0.2f;
    s.camera.width = s.camera.height = 16;
    return s;
}

// Irradiance at the origin from the light by quadrature (the floor points the camera
// sees lie within 1e5 of it, where the light's elevation changes by < 1e-4 relative).
double expected_radiance() {
    const Scene s = grazing();
    const glm::dvec3 p0(s.positions[6]), e1 = glm::dvec3(s.positions[7]) - p0, e2 = glm::dvec3(s.positions[11]) - p0;
    const glm::dvec3 n = glm::normalize(glm::cross(e1, e2));
    const int k = 200;
    double e = 0.0;
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
            const glm::dvec3 y = p0 + e1 * ((i + 0.5) / k) + e2 * ((j + 0.5) / k);
            const double d2 = glm::dot(y, y);
            const glm::dvec3 w = y / std::sqrt(d2);
            e += w.y * -glm::dot(n, w) / d2;
        }
    e *= glm::length(glm::cross(e1, e2)) / (k * k);
    return kRho / M_PI * kLe * e;  // L = rho/π · E
}

class Grazing : public HardCase {};

TEST_P(Grazing, NearlyParallelCameraAndLightRays) {
    const Image img = render(grazing(), 64);
    ASSERT_TRUE(all_finite(img));
    const double expected = expected_radiance();
    ASSERT_GT(expected, 0.05);
    const auto& R = img.find("R")->data;
    const auto& V = img.find("variance.R")->data;
    const auto& Z = img.find("Z")->data;
    // Rows 8..15 point 0.1°–0.2° below the horizon: they hit the floor within 573 units
    // on every pass. Each must match rho/π E within 5 standard errors plus 1%; above them
    // (partly sky) no pixel may exceed it by more than that.
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const size_t i = size_t(y) * 16 + x;
            const double tol = 5.0 * std::sqrt(V[i]) + 0.01 * expected;
            EXPECT_LE(R[i], expected + tol) << "pixel " << x << "," << y;
            if (y < 8) continue;
            EXPECT_TRUE(std::isfinite(Z[i]) && Z[i] > 200.0f && Z[i] < 600.0f) << Z[i];
            EXPECT_NEAR(R[i], expected, tol) << "pixel " << x << "," << y;
            sum += R[i];
            ++n;
        }
    EXPECT_NEAR(sum / n, expected, 0.01 * expected);
}

INSTANTIATE_TEST_SUITE_P(Methods, Grazing, ::testing::ValuesIn(hard_case_params()), hard_case_name);

}  // namespace
}  // namespace tessera::test
