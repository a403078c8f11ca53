// MTL materials, JSON overrides and textures.
#include <fstream>

#include "scene/scene_test_util.h"

namespace tessera {
namespace {

const Material& material_named(const Scene& s, const std::string& name) {
    for (const auto& m : s.materials)
        if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
}

TEST(Material, MtlValuesWithKdClamped) {
    const Scene s = load_scene(test::fixture("light.json"), DataPath{});
    const Material& grey = material_named(s, "grey");
    EXPECT_EQ(grey.albedo, glm::vec3(0.2f, 0.4f, 1.0f));  // Kd blue 1.7 clamped to 1
    EXPECT_EQ(grey.ior, 1.5f);
    EXPECT_EQ(grey.illum, 2);
    EXPECT_EQ(grey.texture, -1);
    // quad.obj gives each corner (x, 0, z) the texture coordinate (x, z), whichever
    // diagonal the triangulation picks.
    for (size_t c = 0; c < 6; ++c)
        EXPECT_EQ(s.uvs[c], glm::vec2(s.positions[c].x, s.positions[c].z));
}

TEST(Material, OverrideCanMakeAnMtlMaterialALight) {
    const Scene s = load_scene(test::fixture("override.json"), DataPath{});
    const Material& grey = material_named(s, "grey");
    EXPECT_EQ(grey.albedo, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(grey.emission, glm::vec3(2, 0, 0));
}

TEST(Material, TexturesDecodedAndDeduplicated) {
    const Scene s = load_scene(test::fixture("textured.json"), DataPath{});
    ASSERT_EQ(s.textures.size(), 1u);  // two materials, one file
    const Texture& t = s.textures[0];
    EXPECT_EQ(t.path.filename(), "checker.png");
    ASSERT_EQ(t.width, 2);
    ASSERT_EQ(t.height, 2);
    // Row 0 is the top of the image; R in the low byte.
    EXPECT_EQ(t.rgba8[0], 0xFF0000FFu);  // red
    EXPECT_EQ(t.rgba8[1], 0xFF00FF00u);  // green
    EXPECT_EQ(t.rgba8[2], 0xFFFF0000u);  // blue
    EXPECT_EQ(t.rgba8[3], 0x80FFFFFFu);  // white, alpha 128
    EXPECT_EQ(material_named(s, "a").texture, 0);
    EXPECT_EQ(material_named(s, "b").texture, 0);
}

TEST(Material, FacesWithoutUsemtlGetDefaultGrey) {
    // An OBJ with no mtllib and no usemtl, written to a temporary folder.
    const auto dir = test::unique_temp_dir("tessera_material_test");
    std::filesystem::create_directories(dir);
    {
        std::ofstream(dir / "plain.obj") << "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n";
        std::ofstream(dir / "plain.json")
            << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
                  "objects": [{"mesh": "plain.obj"}],
                  "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0],
                              "edge2": [0,0,1], "radiance": [1,1,1]}]})";
    }
    const Scene s = load_scene(dir / "plain.json", DataPath{});
    EXPECT_EQ(s.name, "plain");  // no "name" key: the file stem
    EXPECT_EQ(s.materials[s.material[0]].albedo, glm::vec3(0.5f));
    EXPECT_EQ(s.uvs[0], glm::vec2(0.0f));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera
