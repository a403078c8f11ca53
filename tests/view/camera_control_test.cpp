// The viewer's first-person controls: analytic moves and turns, the pitch limit, and the
// camera JSON reading back as the same floats.
#include "view/camera_control.h"

#include <cmath>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace tessera::view {
namespace {

Camera looking_down_z() {
    Camera c;
    c.position = {1.0f, 2.0f, 3.0f};
    c.look_at = {1.0f, 2.0f, 1.0f};  // forward −z, look distance 2
    c.up = {0.0f, 1.0f, 0.0f};
    return c;
}

void expect_near(glm::vec3 a, glm::vec3 b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(CameraControl, MovesAlongItsOwnAxes) {
    const Camera c = looking_down_z();  // right = forward × up = (−z) × y = +x
    expect_near(move_camera(c, {0, 0, 1}, 0.5f).position, {1.0f, 2.0f, 2.5f});
    expect_near(move_camera(c, {1, 0, 0}, 0.5f).position, {1.5f, 2.0f, 3.0f});
    expect_near(move_camera(c, {0, -1, 0}, 0.5f).position, {1.0f, 1.5f, 3.0f});
    const Camera moved = move_camera(c, {1, 1, 1}, 2.0f);
    expect_near(moved.look_at - moved.position, c.look_at - c.position);  // look_at moves along
}

TEST(CameraControl, YawTurnsAboutUpKeepingTheLookDistance) {
    const Camera c = looking_down_z();
    const Camera left = turn_camera(c, glm::half_pi<float>(), 0.0f);  // −z turned 90° left about +y: −x
    expect_near(left.look_at, {-1.0f, 2.0f, 3.0f});
    expect_near(left.position, c.position);
    EXPECT_NEAR(glm::length(left.look_at - left.position), 2.0f, 1e-5f);
}

TEST(CameraControl, PitchStopsOneDegreeFromUp) {
    const Camera c = looking_down_z();
    const Camera up = turn_camera(c, 0.0f, 3.0f);  // asks for 172°: limited to 89° above the horizon
    const glm::vec3 f = glm::normalize(up.look_at - up.position);
    EXPECT_NEAR(std::acos(f.y), glm::radians(1.0f), 1e-4f);
    const Camera small = turn_camera(c, 0.0f, 0.1f);
    EXPECT_NEAR(std::asin(glm::normalize(small.look_at - small.position).y), 0.1f, 1e-5f);
}

TEST(CameraControl, DiffersOnlyWhenTheViewChanges) {
    Camera a = looking_down_z(), b = a;
    b.width = 7;  // the resolution is not part of the view
    EXPECT_FALSE(camera_differs(a, b));
    b.vfov_deg += 1.0f;
    EXPECT_TRUE(camera_differs(a, b));
    EXPECT_TRUE(camera_differs(a, move_camera(a, {0, 0, 1}, 1e-3f)));
}

TEST(CameraControl, JsonReadsBackAsTheSameFloats) {
    Camera c = turn_camera(move_camera(looking_down_z(), {0.3f, 0.1f, 0.7f}, 0.123456f), 0.37f, -0.21f);
    c.vfov_deg = 39.3077f;
    const nlohmann::json j = nlohmann::json::parse("{" + camera_json(c) + "}")["camera"];
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(j["position"][i].get<float>(), c.position[i]);
        EXPECT_EQ(j["look_at"][i].get<float>(), c.look_at[i]);
        EXPECT_EQ(j["up"][i].get<float>(), c.up[i]);
    }
    EXPECT_EQ(j["vfov"].get<float>(), c.vfov_deg);
    EXPECT_EQ(j["resolution"][0].get<int>(), c.width);
}

}  // namespace
}  // namespace tessera::view
