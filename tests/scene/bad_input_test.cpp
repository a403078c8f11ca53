// Every kind of bad scene input throws InputError naming the file, key or setting.
#include <fstream>

#include "scene/scene_test_util.h"

namespace tessera {
namespace {

using test::fixture;
using test::load_error;

TEST(BadInput, MissingSceneFile) {
    const std::string e = load_error(fixture("no_such_scene.json"));
    EXPECT_CONTAINS(e, "no_such_scene.json");
    EXPECT_CONTAINS(e, "not found");
}

// Regression: positions overflowing a float after the object transform were accepted
// (bounds "inf"); the fuzzer's scene invariants (tests/fuzz) call such a scene broken.
TEST(BadInput, TransformOverflowNamesTheObject) {
    const std::string e = load_error(fixture("transform_overflow.json"));
    EXPECT_CONTAINS(e, "transform_overflow.json");
    EXPECT_CONTAINS(e, "objects[0]");
    EXPECT_CONTAINS(e, "overflows a float");
}

TEST(BadInput, LightCornerOverflowNamesTheLight) {
    const std::string e = load_error(fixture("light_overflow.json"));
    EXPECT_CONTAINS(e, "lights[0]");
    EXPECT_CONTAINS(e, "overflows a float");
}

TEST(BadInput, MalformedJsonNamesFileAndLine) {
    const std::string e = load_error(fixture("malformed.json"));
    EXPECT_CONTAINS(e, "malformed.json:3:");  // the missing comma is on line 3
    EXPECT_CONTAINS(e, "malformed JSON");
}

// An OBJ given as the scene file gets a hint (it was "malformed JSON ... '#'" alone), and
// a byte of invalid UTF-8 that the parser quotes is written \xNN, not sent to the terminal.
TEST(BadInput, MalformedJsonHintsAtAMeshAndShowsRawBytesEscaped) {
    const std::string mesh = load_error(fixture("quad.obj"));
    EXPECT_CONTAINS(mesh, "quad.obj:1:1: malformed JSON");
    EXPECT_CONTAINS(mesh, "quad.obj is a mesh file: a scene is a JSON file that names its meshes under \"objects\"");
    const auto dir = test::unique_temp_dir("tessera_utf8");
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "bad.json") << "{\"my\xff\": 1}";
    const std::string bytes = load_error(dir / "bad.json");
    EXPECT_CONTAINS(bytes, "\\xff");
    EXPECT_EQ(bytes.find('\xff'), std::string::npos) << bytes;
    EXPECT_EQ(bytes.find("mesh file"), std::string::npos) << bytes;
    std::filesystem::remove_all(dir);
}

TEST(BadInput, OutOfRangeFaceIndex) {
    const std::string e = load_error(fixture("bad_index.json"));
    EXPECT_CONTAINS(e, "bad_index.obj");
    EXPECT_CONTAINS(e, "out of range");
}

TEST(BadInput, NanVertexNamesObjAndLine) {
    const std::string e = load_error(fixture("nan_vertex.json"));
    EXPECT_CONTAINS(e, "nan_vertex.obj");
    EXPECT_CONTAINS(e, "nan_vertex.obj:3:");
}

TEST(BadInput, MissingMtlNamesTheMtl) {
    const std::string e = load_error(fixture("missing_mtl.json"));
    EXPECT_CONTAINS(e, "missing_mtl.obj");
    EXPECT_CONTAINS(e, "does_not_exist.mtl");
}

TEST(BadInput, MissingTextureNamesTheTexture) {
    const std::string e = load_error(fixture("missing_texture.json"));
    EXPECT_CONTAINS(e, "no_such_texture.png");
}

TEST(BadInput, SceneWithoutLights) {
    // quad.mtl defines an emissive material, but no face uses it.
    const std::string e = load_error(fixture("no_lights.json"));
    EXPECT_CONTAINS(e, "scene fixture-dark has no lights (no MTL Ke and no JSON light,");
}

TEST(BadInput, UnknownMaterialOverrideNamesTheKey) {
    const std::string e = load_error(fixture("unknown_material.json"));
    EXPECT_CONTAINS(e, "unknown_material.json");
    EXPECT_CONTAINS(e, "materials.no_such_material");
}

TEST(BadInput, MissingMeshListsDirectoriesTried) {
    DataPath data;
    data.roots = {fixture("no_root_a"), fixture("no_root_b")};
    const auto dir = test::unique_temp_dir("tessera_bad_mesh");
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "s.json") << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
                                         "objects": [{"mesh": "gone.obj"}]})";
    const std::string e = load_error(dir / "s.json", data);
    EXPECT_CONTAINS(e, "gone.obj");
    EXPECT_CONTAINS(e, "objects[0].mesh");
    EXPECT_CONTAINS(e, "no_root_a");
    EXPECT_CONTAINS(e, "no_root_b");
    EXPECT_CONTAINS(e, dir.string());
    std::filesystem::remove_all(dir);
}

// OBJ bodies that tinyobjloader accepts (or half-accepts) but the loader must reject.
class BadObjTest : public ::testing::TestWithParam<const char*> {};

TEST_P(BadObjTest, NamesTheObj) {
    const auto dir = test::unique_temp_dir("tessera_bad_obj");
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "broken.obj") << GetParam();
    std::ofstream(dir / "s.json") << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
        "objects": [{"mesh": "broken.obj"}],
        "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}]})";
    const std::string e = load_error(dir / "s.json");
    EXPECT_CONTAINS(e, "broken.obj");
    std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Obj, BadObjTest,
    ::testing::Values("v 0 0 0\nv 1 0 0\nv 0 0 1\nf -9 1 2\n",          // relative, before the start
                      "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 4\n",           // one past the end
                      "v 0 0 0\nv 1 0 0\nv 0 0 1\nvn 0 1 0\nf 1//1 2//2 3//1\n",  // normal index
                      "v 0 0 0\nv 1 0 0\nv 0 0 1\nvt 0 0\nf 1/1 2/5 3/1\n",       // texcoord index
                      "v 0 0 0\nv 1 0 inf\nv 0 0 1\nf 1 2 3\n",         // infinity
                      "v 0 0 0\nv 1 0 1e39\nv 0 0 1\nf 1 2 3\n",        // overflows a float
                      "v 0 0 0\nv 1 0 0\nv 0 0 1\nvt 0 0\nvt 4e44 1\nf 1/1 2/2 3/1\n",  // texcoord overflows
                      "v 0 0 0\nv 1 0 0\nv 0 0 1\nvt 0 -5e40\nf 1/1 2/1 3/1\n",        // texcoord -inf
                      "v 0 0 0\nv 1 0 0\nv 0 0 1\nusemtl nothing\nf 1 2 3\n",  // no MTL defines it
                      "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 0 1 2\n",           // OBJ indices start at 1
                      "# no faces\nv 0 0 0\n"));

// Scene files with one bad setting each; the quad mesh is referenced by absolute path.
struct BadKey {
    const char* json;  ///< body after "objects"; %M is replaced by the quad's path
    const char* key;   ///< the key path the message must name
};

class BadKeyTest : public ::testing::TestWithParam<BadKey> {};

TEST_P(BadKeyTest, NamesTheKey) {
    std::string body = GetParam().json;
    const std::string mesh = fixture("quad.obj").string();
    for (size_t at; (at = body.find("%M")) != std::string::npos;) body.replace(at, 2, mesh);
    const auto dir = test::unique_temp_dir("tessera_bad_key");
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "bad.json") << body;
    const std::string e = load_error(dir / "bad.json");
    EXPECT_CONTAINS(e, "bad.json");
    EXPECT_CONTAINS(e, GetParam().key);
    std::filesystem::remove_all(dir);
}

#define CAM_OK R"("camera": {"position": [0,1,3], "look_at": [0,0,0]})"
#define OBJ_OK R"("objects": [{"mesh": "%M"}])"
#define LIGHT_OK \
    R"("lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}])"

INSTANTIATE_TEST_SUITE_P(
    Scene, BadKeyTest,
    ::testing::Values(
        BadKey{"{" OBJ_OK "}", "camera"},
        BadKey{"{" CAM_OK "}", "objects"},
        BadKey{"[1, 2]", "top level"},
        BadKey{R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "vfov": 180}, )" OBJ_OK "}",
               "camera.vfov"},
        BadKey{R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "vfov": 0}, )" OBJ_OK "}",
               "camera.vfov"},
        BadKey{R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "resolution": [0, 5]}, )" OBJ_OK "}",
               "camera.resolution"},
        BadKey{R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "resolution": [16385, 5]}, )" OBJ_OK "}",
               "camera.resolution"},
        BadKey{R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "resolution": [64.5, 5]}, )" OBJ_OK "}",
               "camera.resolution[0]"},
        BadKey{R"({"camera": {"position": [0,1e999,3], "look_at": [0,0,0]}, )" OBJ_OK "}",
               "camera.position[1]"},
        BadKey{R"({"camera": {"position": [0,1e39,3], "look_at": [0,0,0]}, )" OBJ_OK "}",
               "camera.position[1]"},
        BadKey{R"({"camera": {"position": [0,1], "look_at": [0,0,0]}, )" OBJ_OK "}", "camera.position"},
        BadKey{R"({"camera": {"position": "here", "look_at": [0,0,0]}, )" OBJ_OK "}", "camera.position"},
        BadKey{R"({"camera": {"position": [0,0,0], "look_at": [0,0,0]}, )" OBJ_OK "}", "look_at equals position"},
        BadKey{"{" CAM_OK R"(, "objects": {"mesh": "%M"}})", "objects"},
        BadKey{"{" CAM_OK R"(, "objects": []})", "objects"},
        BadKey{"{" CAM_OK R"(, "objects": [{"mesh": 3}]})", "objects[0].mesh"},
        BadKey{"{" CAM_OK R"(, "objects": [{"mesh": ""}]})", "objects[0].mesh' = \"\": must name an OBJ file"},
        // A NUL ends the path for the OS and the message for the terminal: the whole
        // string is refused, shown escaped.
        BadKey{"{" CAM_OK R"(, "objects": [{"mesh": "a\u0000b.obj"}]})",
               "objects[0].mesh' = \"a\\u0000b.obj\": must not contain a NUL character"},
        BadKey{"{" CAM_OK R"(, "objects": [{"mesh\u0000evil": "%M"}]})",
               "key \"mesh\\u0000evil\" in 'objects[0]': must not contain a NUL character"},
        BadKey{R"({"a\u0000": 1, )" CAM_OK ", " OBJ_OK "}", "key \"a\\u0000\" in the top level"},
        BadKey{"{" CAM_OK R"(, "objects": [{"mesh": "%M", "transform": {"scale": [1, 0, 1]}}], )" LIGHT_OK "}",
               "objects[0].transform.scale"},
        BadKey{"{" CAM_OK R"(, "objects": [{"mesh": "%M", "transform": {"rotate": [{"axis": [0,1,0]}]}}])"
               ", " LIGHT_OK "}",
               "objects[0].transform.rotate[0].degrees"},
        BadKey{"{" CAM_OK ", " OBJ_OK R"(, "lights": [{"type": "sphere"}]})", "lights[0].type"},
        BadKey{"{" CAM_OK ", " OBJ_OK
               R"(, "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [2,0,0], "radiance": [1,1,1]}]})",
               "lights[0]"},
        BadKey{"{" CAM_OK ", " OBJ_OK
               R"(, "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,-1,1]}]})",
               "lights[0].radiance"},
        BadKey{"{" CAM_OK ", " OBJ_OK ", " LIGHT_OK R"(, "materials": {"grey": {"albedo": [2, 0, 0]}}})",
               "materials.grey.albedo"},
        // Radiance above limits::kMaxRadiance (ic wrote Inf pixels at 1e36), as a light's and
        // as a material's emission.
        BadKey{"{" CAM_OK ", " OBJ_OK
               R"(, "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1.1e15,1]}]})",
               "lights[0].radiance"},
        BadKey{"{" CAM_OK ", " OBJ_OK ", " LIGHT_OK R"(, "materials": {"grey": {"emission": [1e36, 0, 0]}}})",
               "radiance components must be <= 1e+15"},
        // A medium whose optical depth over the scene passes limits::kMaxOpticalDepth
        // (sigma_s = 5e37 gave NaN pixels): the quad's diagonal with the light's is about 2.4.
        BadKey{"{" CAM_OK ", " OBJ_OK ", " LIGHT_OK R"(, "medium": {"sigma_a": [0,0,0], "sigma_s": [1,1e9,1]}})",
               "optical depth of"},
        BadKey{"{" CAM_OK ", " OBJ_OK ", " LIGHT_OK R"(, "medium": {"sigma_a": [3e38,0,0], "sigma_s": [3e38,0,0]}})",
               "sigma_a + sigma_s = 6e+38"},
        // Coordinates past limits::kMaxCoordinate (1e10): a scale of 1e30 overflowed the
        // emitters' areas with an error naming no key; a light at 3e38 lost its area in float
        // and was dropped without a word. The key is the transform's, or the light's.
        BadKey{"{" CAM_OK R"(, "objects": [{"mesh": "%M", "transform": {"scale": 1e30}}], )" LIGHT_OK "}",
               "objects[0].transform"},
        BadKey{"{" CAM_OK R"(, "objects": [{"mesh": "%M", "transform": {"translate": [0, -2e10, 0]}}], )" LIGHT_OK "}",
               "beyond the limit of ±1e+10 scene units"},
        BadKey{"{" CAM_OK ", " OBJ_OK
               R"(, "lights": [{"type": "quad", "corner": [3e38,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}]})",
               "lights[0]"}));

// The limits' boundaries load: radiance 1e15, a medium of optical depth just under 1e9,
// coordinates of 1e10.
TEST(BadInput, RadianceAndOpticalDepthAtTheLimitsLoad) {
    const auto dir = test::unique_temp_dir("tessera_limits");
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "ok.json") << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
        "objects": [{"mesh": ")" << fixture("quad.obj").string() << R"("}],
        "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1e15,0,1]}],
        "medium": {"sigma_a": [0,0,0], "sigma_s": [1e8,0,0]}})";
    const Scene s = load_scene(dir / "ok.json", DataPath{});
    EXPECT_EQ(s.medium.sigma_s.x, 1e8f);
    // Coordinates at limits::kMaxCoordinate load (the quad moved to 1e10, the light too).
    std::ofstream(dir / "far.json") << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
        "objects": [{"mesh": ")" << fixture("quad.obj").string() << R"(", "transform": {"translate": [0, 0, -9.9e9]}}],
        "lights": [{"type": "quad", "corner": [0,2,-1e10], "edge1": [1e3,0,0], "edge2": [0,0,1e3], "radiance": [1,1,1]}]})";
    EXPECT_EQ(load_scene(dir / "far.json", DataPath{}).triangle_count(), 4u);
    std::filesystem::remove_all(dir);
}

// A scene whose only emitter has zero area has no lights (the light list drops it).
TEST(BadInput, SceneWhoseOnlyEmitterHasZeroAreaHasNoLights) {
    const auto dir = test::unique_temp_dir("tessera_zero_area_light");
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "l.mtl") << "newmtl w\nKd .5 .5 .5\nnewmtl l\nKe 10 10 10\n";
    std::ofstream(dir / "l.obj") << "mtllib l.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 2 2\n"
                                    "usemtl w\nf 1 2 3\nusemtl l\nf 4 4 4\n";
    std::ofstream(dir / "s.json") << R"({"camera": {"position": [0.3,0.3,-2], "look_at": [0.3,0.3,0]},
                                         "objects": [{"mesh": "l.obj"}]})";
    const std::string e = load_error(dir / "s.json");
    EXPECT_CONTAINS(e, "s.json");
    EXPECT_CONTAINS(e, "has no lights");
    EXPECT_CONTAINS(e, "only emitters of zero area");
    std::filesystem::remove_all(dir);
}

// An MTL Kd above 1 is clamped to 1 (documented), and now said: one note naming the MTL,
// its line, the material and the values as written; a Kd within [0, 1] gets none.
TEST(BadInput, AKdAboveOneIsClampedWithANote) {
    const auto dir = test::unique_temp_dir("tessera_kd_note");
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "k.mtl") << "newmtl ok\nKd .5 .5 .5\nnewmtl hot\nKd 5 0.5 0.4\nnewmtl l\nKe 10 10 10\n";
    std::ofstream(dir / "k.obj") << "mtllib k.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\n"
                                    "usemtl ok\nf 1 2 3\nusemtl hot\nf 4 5 6\nusemtl l\nf 3 2 1\n";
    std::ofstream(dir / "s.json") << R"({"camera": {"position": [0.3,0.3,-2], "look_at": [0.3,0.3,0]},
                                         "objects": [{"mesh": "k.obj"}]})";
    const Scene s = load_scene(dir / "s.json", DataPath{});
    ASSERT_EQ(s.notes.size(), 1u);
    EXPECT_CONTAINS(s.notes[0], "k.mtl:3: material 'hot': Kd 5 0.5 0.4 clamped to 1 per channel");
    bool clamped = false;
    for (const Material& m : s.materials) clamped |= m.name == "hot" && m.albedo == glm::vec3(1.0f, 0.5f, 0.4f);
    EXPECT_TRUE(clamped);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera
