// Hard cases: the camera inside an object, and camera rays that miss everything.
#include "hard_cases/hard_case.h"

namespace tessera::test {
namespace {

class InsideAndMiss : public HardCase {};

// A closed box whose walls face outward (albedo 0.5, emitting 3 from their front =
// outer side), lit also by a light outside; the camera is inside. It sees only the
// walls' back faces, which neither emit (area lights emit from the front) nor receive
// light (none enters a closed box): black. (A method that treated the back as a front
// would see the box's emission instead; the check accepts nothing else.)
TEST_P(InsideAndMiss, CameraInsideAClosedBoxWithOutwardNormals) {
    Scene s;
    const uint32_t wall = add_material(s, glm::vec3(0.5f), glm::vec3(3.0f));
    const uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(10.0f));
    const glm::vec3 lo(-1, 0, -1), d(2, 2, 2);
    add_quad(s, lo, {d.x, 0, 0}, {0, 0, d.z}, wall);                     // floor, -y (out)
    add_quad(s, {lo.x, lo.y + d.y, lo.z}, {0, 0, d.z}, {d.x, 0, 0}, wall); // ceiling, +y
    add_quad(s, lo, {0, d.y, 0}, {d.x, 0, 0}, wall);                     // back, -z
    add_quad(s, {lo.x, lo.y, lo.z + d.z}, {d.x, 0, 0}, {0, d.y, 0}, wall); // front, +z
    add_quad(s, lo, {0, 0, d.z}, {0, d.y, 0}, wall);                     // left, -x
    add_quad(s, {lo.x + d.x, lo.y, lo.z}, {0, d.y, 0}, {0, 0, d.z}, wall); // right, +x
    add_quad(s, {-1, 4, -1}, {2, 0, 0}, {0, 0, 2}, light);               // above, facing down
    s.camera.position = {0.2f, 1.1f, 0.3f};
    s.camera.look_at = {-1, 0.2f, -1};
    s.camera.vfov_deg = 100.0f;
    s.camera.width = s.camera.height = 16;
    const Image img = render(s, 8);
    ASSERT_TRUE(all_finite(img));
    EXPECT_EQ(radiance_max(img), 0.0f);
    // Depth: every pixel hits a wall at a finite distance within the box's diagonal.
    for (float z : img.find("Z")->data) EXPECT_TRUE(z > 0.0f && z < 3.5f) << z;
}

// The camera looks away from a lit quad: every ray misses. Radiance 0, albedo and
// normal 0, depth +inf.
TEST_P(InsideAndMiss, RaysThatMissEverything) {
    Scene s;
    const uint32_t grey = add_material(s, glm::vec3(0.5f));
    const uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(5.0f));
    add_quad(s, {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, grey);
    add_quad(s, {-0.5f, 1, -0.5f}, {1, 0, 0}, {0, 0, 1}, light);
    s.camera.position = {0, 0.5f, 5};
    s.camera.look_at = {0, 0.5f, 10};
    s.camera.width = s.camera.height = 8;
    const Image img = render(s, 4);
    EXPECT_EQ(radiance_max(img), 0.0f);
    EXPECT_EQ(channel_max(img, "R"), 0.0f);
    for (const char* c : {"albedo.R", "N.X", "N.Y", "N.Z", "variance.R"})
        for (float v : img.find(c)->data) EXPECT_EQ(v, 0.0f) << c;
    for (float z : img.find("Z")->data) EXPECT_EQ(z, INFINITY);
}

INSTANTIATE_TEST_SUITE_P(Methods, InsideAndMiss, ::testing::ValuesIn(hard_case_params()), hard_case_name);

}  // namespace
}  // namespace tessera::test
