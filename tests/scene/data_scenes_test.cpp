// Scenes that use the shared data path (skipped when the data is not installed).
#include <cmath>

#include "scene/scene_test_util.h"

namespace tessera {
namespace {

bool data_has(const std::string& rel) {
    for (const auto& root : make_data_path(std::nullopt).roots)
        if (std::filesystem::exists(root / rel)) return true;
    return false;
}

TEST(DataScenes, Sibenik) {
    if (!data_has("sibenik/sibenik.obj")) GTEST_SKIP() << "sibenik/sibenik.obj not on the data path";
    const Scene s = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "sibenik.json",
                               make_data_path(std::nullopt));
    EXPECT_EQ(s.name, "sibenik");
    ASSERT_EQ(s.triangle_count(), 73564u + 4u * 2u);  // mesh + 4 JSON quad lights
    size_t emissive = 0;
    for (size_t i = 0; i < s.triangle_count(); ++i) {
        if (s.materials[s.material[i]].emission == glm::vec3(0.0f)) continue;
        ++emissive;
        EXPECT_NEAR(test::geometric_normal(s, i).y, -1.0f, 1e-5f);  // lights face down
    }
    EXPECT_EQ(emissive, 8u);
    ASSERT_GE(s.textures.size(), 3u);  // kamen, KAMEN-stup, mramor6x6
    for (const auto& t : s.textures) {
        EXPECT_GT(t.width, 0);
        EXPECT_GT(t.height, 0);
        EXPECT_EQ(t.rgba8.size(), size_t(t.width) * size_t(t.height));
    }
    for (const auto& n : s.normals) {
        ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
        ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
    }
}

TEST(DataScenes, CornellOriginal) {
    if (!data_has("cornell-box/CornellBox-Original.obj"))
        GTEST_SKIP() << "cornell-box/CornellBox-Original.obj not on the data path";
    const Scene s = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-original.json",
                               make_data_path(std::nullopt));
    ASSERT_EQ(s.triangle_count(), 36u);
    size_t emissive = 0;
    for (size_t i = 0; i < s.triangle_count(); ++i) {
        const Material& m = s.materials[s.material[i]];
        if (m.emission == glm::vec3(0.0f)) continue;
        ++emissive;
        EXPECT_EQ(m.name, "light");
        EXPECT_EQ(m.emission, glm::vec3(17, 12, 4));
        EXPECT_NEAR(test::geometric_normal(s, i).y, -1.0f, 1e-5f);
    }
    EXPECT_EQ(emissive, 2u);
}

}  // namespace
}  // namespace tessera
