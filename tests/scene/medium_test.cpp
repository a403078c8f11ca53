// The "medium" block of scene files.
#include <fstream>

#include <gtest/gtest.h>

#include "scene/loader.h"
#include "scene_test_util.h"

namespace tessera {
namespace {

// Writes a scene with the light fixture's geometry plus `medium_json`, returns its path.
std::filesystem::path scene_with_medium(const std::string& dir_tag, const std::string& medium_json) {
    const auto dir = test::unique_temp_dir(dir_tag);
    std::filesystem::create_directories(dir);
    const auto path = dir / "m.json";
    std::ofstream(path) << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
        "objects": [{"mesh": ")" << test::fixture("quad.obj").string() << R"("}],
        "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}],
        "medium": )" << medium_json << "}";
    return path;
}

TEST(MediumBlock, ReadsCoefficientsAndBox) {
    const auto p = scene_with_medium("tessera_medium_ok", R"({"sigma_a": [0.1, 0.2, 0.3], "sigma_s": [1, 2, 3],
        "g": -0.4, "box": {"min": [-1, -2, -3], "max": [1, 2, 3]}})");
    Scene s = load_scene(p, DataPath{});
    EXPECT_TRUE(s.has_medium);
    EXPECT_EQ(s.medium.sigma_a, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(s.medium.sigma_s, glm::vec3(1, 2, 3));
    EXPECT_FLOAT_EQ(s.medium.g, -0.4f);
    EXPECT_TRUE(s.medium.bounded);
    EXPECT_EQ(s.medium.box_max, glm::vec3(1, 2, 3));
    std::filesystem::remove_all(p.parent_path());
}

TEST(MediumBlock, RejectsBadValuesNamingTheKey) {
    const std::pair<const char*, const char*> cases[] = {
        {R"({"sigma_a": [0,0,0], "sigma_s": [1,1,1], "g": 1.0})", "medium.g"},
        {R"({"sigma_a": [-1,0,0], "sigma_s": [1,1,1]})", "medium.sigma_a"},
        {R"({"sigma_a": [0,0,0]})", "sigma_s"},
        {R"({"sigma_a": [0,0,0], "sigma_s": [1,1,1], "box": {"min": [1,0,0], "max": [0,1,1]}})", "medium.box"},
    };
    for (const auto& [json, key] : cases) {
        const auto p = scene_with_medium("tessera_medium_bad", json);
        EXPECT_CONTAINS(test::load_error(p), key);
        std::filesystem::remove_all(p.parent_path());
    }
}

}  // namespace
}  // namespace tessera
