// Hard case: an emitter touching the surfaces it lights. The back wall of an open box
// is the light; it meets the floor, the ceiling and both side walls at concave corners,
// where the distance between a shaded point and the light goes to zero (contact
// shadows and the 1/d² of light sampling).
#include "hard_cases/hard_case.h"

namespace tessera::test {
namespace {

constexpr float kLe = 1.0f, kRho = 0.8f;

// Box [-1,1] x [0,2] x [0,2], open at z = 2 (the camera side); the back wall z = 0
// emits kLe toward +z and is black, the other four walls reflect kRho.
Scene contact_corner() {
    Scene s;
    s.name = "contact-corner";
    const uint32_t wall = add_material(s, glm::vec3(kRho));
    const uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(kLe));
    add_quad(s, {-1, 0, 0}, {0, 0, 2}, {2, 0, 0}, wall);   // floor y = 0, +y
    add_quad(s, {-1, 2, 0}, {2, 0, 0}, {0, 0, 2}, wall);   // ceiling y = 2, -y
    add_quad(s, {-1, 0, 0}, {0, 2, 0}, {0, 0, 2}, wall);   // left x = -1, +x
    add_quad(s, {1, 0, 0}, {0, 0, 2}, {0, 2, 0}, wall);    // right x = 1, -x
    add_quad(s, {-1, 0, 0}, {2, 0, 0}, {0, 2, 0}, light);  // back z = 0, +z: the light
    // Looking into the lower-left corner where floor, left wall and light meet.
    s.camera.position = {0.2f, 0.9f, 1.9f};
    s.camera.look_at = {-1.0f, 0.0f, 0.0f};
    s.camera.vfov_deg = 30.0f;
    s.camera.width = s.camera.height = 32;
    return s;
}

class Contact : public HardCase {};

TEST_P(Contact, CornerWhereTheLightMeetsTheWallsStaysBounded) {
    const Scene s = contact_corner();
    const Image img = render(s, 64);
    ASSERT_TRUE(all_finite(img));
    const double bound = radiance_bound(method().transport, kLe, kRho);
    const float mx = radiance_max(img);
    RecordProperty("max_over_bound", std::to_string(mx / bound));
    EXPECT_LE(mx, bound) << "firefly: a pixel mean exceeds the energy bound";
    // The light fills the middle of the view: pixels on it are kLe (its albedo is 0).
    EXPECT_GE(mx, 0.99f * kLe) << "the emitter in view is dark";
}

INSTANTIATE_TEST_SUITE_P(Methods, Contact, ::testing::ValuesIn(hard_case_params()), hard_case_name);

}  // namespace
}  // namespace tessera::test
