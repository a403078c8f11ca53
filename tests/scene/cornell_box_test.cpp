// The shipped scenes/cornell-box.json (our own OBJ from the published Cornell data).
#include <algorithm>
#include <cmath>
#include <utility>

#include "scene/scene_test_util.h"

namespace tessera {
namespace {

class CornellBox : public ::testing::Test {
protected:
    static void SetUpTestSuite() { scene_ = new Scene(load_scene(default_scene_path(), DataPath{})); }
    static void TearDownTestSuite() { delete scene_; }
    static Scene* scene_;
};
Scene* CornellBox::scene_ = nullptr;

TEST_F(CornellBox, DefaultScenePathIsTheShippedBox) {
    EXPECT_EQ(default_scene_path().filename(), "cornell-box.json");
    EXPECT_TRUE(std::filesystem::exists(default_scene_path()));
}

TEST_F(CornellBox, TriangleCountAndParallelArrays) {
    const Scene& s = *scene_;
    EXPECT_EQ(s.name, "cornell-box");
    // 5 walls + 5 faces per block x 2 + the light = 16 quads.
    ASSERT_EQ(s.triangle_count(), 32u);
    EXPECT_EQ(s.positions.size(), 96u);
    EXPECT_EQ(s.normals.size(), 96u);
    EXPECT_EQ(s.uvs.size(), 96u);
    EXPECT_TRUE(s.textures.empty());
}

TEST_F(CornellBox, BoundsInMetres) {
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const auto& p : scene_->positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    EXPECT_NEAR(lo.x, 0.0f, 1e-6f);
    EXPECT_NEAR(lo.y, 0.0f, 1e-6f);
    EXPECT_NEAR(lo.z, 0.0f, 1e-6f);
    EXPECT_NEAR(hi.x, 0.556f, 1e-6f);
    EXPECT_NEAR(hi.y, 0.5488f, 1e-6f);
    EXPECT_NEAR(hi.z, 0.5592f, 1e-6f);
}

TEST_F(CornellBox, NormalsAreUnitAndFinite) {
    for (const auto& n : scene_->normals) {
        ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    }
}

TEST_F(CornellBox, LightFacesDownJustBelowTheCeiling) {
    const Scene& s = *scene_;
    size_t emissive = 0;
    for (size_t i = 0; i < s.triangle_count(); ++i) {
        const Material& m = s.materials[s.material[i]];
        if (m.emission == glm::vec3(0.0f)) continue;
        ++emissive;
        EXPECT_EQ(m.name, "light");
        EXPECT_EQ(m.emission, glm::vec3(17, 12, 4));
        const glm::vec3 ng = test::geometric_normal(s, i);
        EXPECT_NEAR(ng.y, -1.0f, 1e-5f);
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = s.positions[3 * i + k];
            EXPECT_NEAR(p.y, 0.5487f, 1e-6f);
            EXPECT_TRUE(p.x >= 0.213f - 1e-6f && p.x <= 0.343f + 1e-6f);
            EXPECT_TRUE(p.z >= 0.227f - 1e-6f && p.z <= 0.332f + 1e-6f);
        }
    }
    EXPECT_EQ(emissive, 2u);
}

TEST_F(CornellBox, WallsFaceIntoTheRoom) {
    // The red and green walls are identified by material; their front side must face
    // the box centre.
    const Scene& s = *scene_;
    const glm::vec3 centre(0.278f, 0.274f, 0.280f);
    int walls = 0;
    for (size_t i = 0; i < s.triangle_count(); ++i) {
        const std::string& name = s.materials[s.material[i]].name;
        if (name != "red" && name != "green") continue;
        ++walls;
        const glm::vec3 p = s.positions[3 * i];
        EXPECT_GT(glm::dot(test::geometric_normal(s, i), centre - p), 0.0f) << name;
    }
    EXPECT_GE(walls, 4) << "two triangles or more per coloured wall";
}

TEST_F(CornellBox, CameraMatchesPublishedSetup) {
    const Camera& c = scene_->camera;
    EXPECT_EQ(c.position, glm::vec3(0.278f, 0.273f, -0.8f));
    EXPECT_NEAR(c.vfov_deg, 2.0 * std::atan(0.0125 / 0.035) * 180.0 / M_PI, 1e-3);
    EXPECT_EQ(c.width, 512);
    EXPECT_EQ(c.height, 512);
}

TEST_F(CornellBox, MtlReflectances) {
    const std::pair<const char*, glm::vec3> expected[] = {{"red", glm::vec3(0.63f, 0.065f, 0.05f)},
                                                          {"green", glm::vec3(0.14f, 0.45f, 0.091f)},
                                                          {"white", glm::vec3(0.725f, 0.71f, 0.68f)}};
    for (const auto& [name, albedo] : expected) {
        const auto m = std::find_if(scene_->materials.begin(), scene_->materials.end(),
                                    [&](const auto& x) { return x.name == name; });
        ASSERT_NE(m, scene_->materials.end()) << "no material " << name;
        EXPECT_EQ(m->albedo, albedo) << name;
    }
}

}  // namespace
}  // namespace tessera
