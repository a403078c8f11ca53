// Object transforms: scale, rotations, translation; mirrors keep the front side.
#include "scene/scene_test_util.h"

namespace tessera {
namespace {

// Corners of the unit quad fixture after the transformed.json transform, computed by
// hand: (x, 0, z) -> scale (2x, 0, 3z) -> 90 deg about +y (x' = z, z' = -x)
// -> (3z, 0, -2x) -> + (10, 20, 30).
glm::vec3 by_hand(float x, float z) { return {10.0f + 3.0f * z, 20.0f, 30.0f - 2.0f * x}; }

bool contains(const std::vector<glm::vec3>& pts, glm::vec3 q) {
    for (const auto& p : pts)
        if (glm::length(p - q) < 1e-5f) return true;
    return false;
}

TEST(Transform, ScaleRotateTranslateLandsWhereComputedByHand) {
    const Scene s = load_scene(test::fixture("transformed.json"), DataPath{});
    ASSERT_EQ(s.triangle_count(), 4u);  // the quad (2) + the JSON light (2)
    const std::vector<glm::vec3> quad(s.positions.begin(), s.positions.begin() + 6);
    for (const auto& p : quad) {
        EXPECT_TRUE(contains({by_hand(0, 0), by_hand(1, 0), by_hand(1, 1), by_hand(0, 1)}, p))
            << p.x << " " << p.y << " " << p.z;
    }
    for (const auto& corner : {by_hand(0, 0), by_hand(1, 0), by_hand(1, 1), by_hand(0, 1)})
        EXPECT_TRUE(contains(quad, corner));
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_NEAR(test::geometric_normal(s, i).y, 1.0f, 1e-5f);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.normals[3 * i + k].y, 1.0f, 1e-5f);
    }
}

TEST(Transform, NegativeScaleKeepsTheFrontSide) {
    const Scene s = load_scene(test::fixture("negative_scale.json"), DataPath{});
    ASSERT_EQ(s.triangle_count(), 4u);
    for (size_t i = 0; i < 2; ++i) {
        // Mirrored in x: the quad covers x in [-1, 0] and still faces +y.
        for (int k = 0; k < 3; ++k) {
            EXPECT_LE(s.positions[3 * i + k].x, 0.0f);
            EXPECT_GE(s.positions[3 * i + k].x, -1.0f);
            EXPECT_NEAR(s.normals[3 * i + k].y, 1.0f, 1e-5f);
        }
        EXPECT_NEAR(test::geometric_normal(s, i).y, 1.0f, 1e-5f);
    }
}

TEST(Transform, QuadLightFacesCrossOfItsEdges) {
    const Scene s = load_scene(test::fixture("light.json"), DataPath{});
    ASSERT_EQ(s.triangle_count(), 4u);
    for (size_t i = 2; i < 4; ++i) {
        // cross((1,0,0), (0,0,1)) = (0,-1,0): the light at y = 2 shines down.
        EXPECT_NEAR(test::geometric_normal(s, i).y, -1.0f, 1e-6f);
        const Material& m = s.materials[s.material[i]];
        EXPECT_EQ(m.emission, glm::vec3(4, 3, 2));
        EXPECT_EQ(m.albedo, glm::vec3(0.0f));
        for (int k = 0; k < 3; ++k) EXPECT_EQ(s.positions[3 * i + k].y, 2.0f);
    }
    EXPECT_EQ(s.camera.width, 64);
    EXPECT_EQ(s.camera.height, 32);
    EXPECT_EQ(s.camera.vfov_deg, 45.0f);
}

}  // namespace
}  // namespace tessera
