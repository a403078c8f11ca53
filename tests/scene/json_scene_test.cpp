// The scene-JSON layer of the input contract (host/scene/json_scene.cpp,
// json_document.cpp, json_field.cpp): unknown keys (with a suggestion), duplicate keys,
// numbers that overflow, wrong types, values out of range and syntax errors are each
// rejected with the scene file, the key path and the value, before any mesh is used.
#include <fstream>

#include "scene/scene_test_util.h"
#include "support/data_files.h"
#include "support/scratch_dir.h"

namespace tessera {
namespace {

// The valid scene each case starts from: the quad fixture under one JSON light.
#define CAM R"("camera": {"position": [0,1,3], "look_at": [0,0,0]})"
#define OBJ R"("objects": [{"mesh": "%M"}])"
#define LIGHT R"("lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}])"

class SceneJson : public test::ScratchDirTest {
protected:
    // Writes `body` as bad.json, with %M replaced by the quad fixture's path.
    std::filesystem::path write(std::string body) {
        const std::string mesh = test::fixture("quad.obj").string();
        for (size_t at; (at = body.find("%M")) != std::string::npos;) body.replace(at, 2, mesh);
        std::ofstream(dir_ / "bad.json", std::ios::binary) << body;
        return dir_ / "bad.json";
    }
};

struct BadScene {
    const char* name;
    const char* json;
    const char* key;    ///< the key path (or file:line:column) the message must name
    const char* value;  ///< the offending value as shown
    const char* what;
};

class BadSceneJson : public SceneJson, public ::testing::WithParamInterface<BadScene> {};

TEST_P(BadSceneJson, NamesFileKeyAndValue) {
    const std::string e = test::load_error(write(GetParam().json));
    EXPECT_CONTAINS(e, (dir_ / "bad.json").string());
    EXPECT_CONTAINS(e, GetParam().key);
    EXPECT_CONTAINS(e, GetParam().value);
    EXPECT_CONTAINS(e, GetParam().what);
    // nlohmann::json's own wording must not reach the user.
    EXPECT_EQ(e.find("json.exception"), std::string::npos) << e;
    EXPECT_EQ(e.find("parse error at"), std::string::npos) << e;
}

INSTANTIATE_TEST_SUITE_P(
    Json, BadSceneJson,
    ::testing::Values(
        // Unknown keys, at every level, with the closest known key suggested.
        // The name is printed in logs: not empty, no terminal escapes.
        BadScene{"NameEmpty", R"({"name": "", )" CAM ", " OBJ ", " LIGHT "}", "key 'name'", "\"\"",
                 "must be a name to print"},
        BadScene{"NameWithAnEscape", R"({"name": "a\u001b[2Jb", )" CAM ", " OBJ ", " LIGHT "}", "key 'name'",
                 "u001b", "must be a name to print"},
        BadScene{"NameWithACsi", R"({"name": "a\u009bb", )" CAM ", " OBJ ", " LIGHT "}", "key 'name'",
                 "a\xc2\x9b" "b", "must be a name to print"},  // raw here; main() prints it as \u009b
        BadScene{"TopLevelLightz", "{" CAM ", " OBJ R"(, "lightz": []})", "unknown key 'lightz'", "[]",
                 "did you mean 'lights'?"},
        BadScene{"TopLevelMaterails", "{" CAM ", " OBJ ", " LIGHT R"(, "materails": {}})", "unknown key 'materails'",
                 "{}", "did you mean 'materials'?"},
        BadScene{"CameraFov", R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "fov": 45}, )" OBJ "}",
                 "unknown key 'camera.fov'", "= 45", "did you mean 'vfov'?"},
        BadScene{"CameraPositon", R"({"camera": {"positon": [0,1,3], "look_at": [0,0,0]}, )" OBJ "}",
                 "unknown key 'camera.positon'", "[0,1,3]", "did you mean 'position'?"},
        BadScene{"ObjectMeshh", "{" CAM R"(, "objects": [{"meshh": "%M"}]})", "unknown key 'objects[0].meshh'",
                 "quad.obj", "did you mean 'mesh'?"},
        BadScene{"TransformRotation", "{" CAM R"(, "objects": [{"mesh": "%M", "transform": {"rotation": []}}]})",
                 "unknown key 'objects[0].transform.rotation'", "[]", "did you mean 'rotate'?"},
        BadScene{"RotateAngle",
                 "{" CAM R"(, "objects": [{"mesh": "%M", "transform": {"rotate": [{"axis": [0,1,0], "angle": 5}]}}]})",
                 "unknown key 'objects[0].transform.rotate[0].angle'", "= 5", "known keys here: axis, degrees"},
        BadScene{"LightRadiannce", "{" CAM ", " OBJ R"(, "lights": [{"type": "quad", "corner": [0,2,0],
                 "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}, {"type": "quad", "corner": [0,2,0],
                 "edge1": [1,0,0], "edge2": [0,0,1], "radiannce": [1,1,1]}]})",
                 "unknown key 'lights[1].radiannce'", "[1,1,1]", "did you mean 'radiance'?"},
        BadScene{"OverrideAlbedoo", "{" CAM ", " OBJ ", " LIGHT R"(, "materials": {"grey": {"albedoo": [1,1,1]}}})",
                 "unknown key 'materials.grey.albedoo'", "[1,1,1]", "did you mean 'albedo'?"},
        BadScene{"MediumSigma", "{" CAM ", " OBJ ", " LIGHT R"(, "medium": {"sigma_a": [0,0,0], "sigma_s": [0,0,0],
                 "sigma_t": [1,1,1]}})", "unknown key 'medium.sigma_t'", "[1,1,1]", "did you mean 'sigma_"},
        BadScene{"MediumBoxMn", "{" CAM ", " OBJ ", " LIGHT R"(, "medium": {"sigma_a": [0,0,0], "sigma_s": [0,0,0],
                 "box": {"mn": [0,0,0], "max": [1,1,1]}}})", "unknown key 'medium.box.mn'", "[0,0,0]",
                 "did you mean 'min'?"},
        BadScene{"FarFromAnyKey", "{" CAM ", " OBJ R"(, "xyzzy_plugh": 1})", "unknown key 'xyzzy_plugh'", "= 1",
                 "known keys here: name, stands_in_for, camera"},
        // Duplicate keys (nlohmann::json would keep the last one).
        BadScene{"DuplicateTopLevel", "{" CAM ", " CAM ", " OBJ "}", "duplicate key 'camera'", "camera",
                 "may appear once"},
        BadScene{"DuplicateNested", "{" CAM ", " OBJ R"(, "lights": [{"type": "quad", "corner": [0,2,0],
                 "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1], "radiance": [9,9,9]}]})",
                 "duplicate key 'lights[0].radiance'", "radiance", "may appear once"},
        BadScene{"DuplicateComment", R"({"comment": "a", "comment": "b", )" CAM ", " OBJ "}",
                 "duplicate key 'comment'", "comment", "may appear once"},
        // Numbers: overflow of a double (the literal) and of a float, NaN-like values.
        BadScene{"LiteralOverflow", R"({"camera": {"position": [0,1e999,3], "look_at": [0,0,0]}, )" OBJ "}",
                 "key 'camera.position[1]'", "'1e999'", "overflows a double"},
        BadScene{"LiteralOverflowInObject", R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "vfov": -1e400}, )" OBJ "}",
                 "key 'camera.vfov'", "'-1e400'", "overflows a double"},
        BadScene{"FloatOverflow", R"({"camera": {"position": [0,1e39,3], "look_at": [0,0,0]}, )" OBJ "}",
                 "key 'camera.position[1]'", "= 1e+39", "not finite"},
        BadScene{"NanString", R"({"camera": {"position": [0,"NaN",3], "look_at": [0,0,0]}, )" OBJ "}",
                 "key 'camera.position[1]'", "\"NaN\"", "expected a number, got string"},
        BadScene{"ViewOverflow", R"({"camera": {"position": [0,0,3e38], "look_at": [0,0,-3e38]}, )" OBJ "}",
                 "key 'camera'", "3e+38", "look_at - position overflows a float"},
        BadScene{"UpParallel", R"({"camera": {"position": [0,1,3], "look_at": [0,1,0], "up": [0,0,2]}, )" OBJ "}",
                 "key 'camera'", "\"up\":[0,0,2]", "up is zero or parallel"},
        // 1e-7 rad off up: make_frame's basis would be round-off, so the loader refuses it
        // (it once passed the loader and stopped the render after its set-up).
        BadScene{"UpNearlyParallel", R"({"camera": {"position": [0.5,3,0.5], "look_at": [0.5,0,0.5000001]}, )" OBJ "}",
                 "key 'camera'", "0.5000001", "up is zero or parallel"},
        BadScene{"FarAboveLooksDown", R"({"camera": {"position": [0,2e18,3], "look_at": [0.5,0,0.5]}, )" OBJ "}",
                 "key 'camera'", "2e+18", "up is zero or parallel"},
        // Wrong types and ranges.
        BadScene{"VfovString", R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "vfov": "wide"}, )" OBJ "}",
                 "key 'camera.vfov'", "\"wide\"", "expected a number, got string"},
        BadScene{"VfovRange", R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "vfov": 180}, )" OBJ "}",
                 "key 'camera.vfov'", "= 180", "(0, 180)"},
        BadScene{"ResolutionHuge", R"({"camera": {"position": [0,1,3], "look_at": [0,0,0],
                 "resolution": [18446744073709551615, 5]}, )" OBJ "}",
                 "key 'camera.resolution[0]'", "18446744073709551615", "integer out of range"},
        BadScene{"ResolutionFloat", R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "resolution": [64.0, 5]}, )" OBJ "}",
                 "key 'camera.resolution[0]'", "64.0", "expected an integer"},
        BadScene{"NameNumber", R"({"name": 5, )" CAM ", " OBJ "}", "key 'name'", "= 5", "expected a string"},
        BadScene{"LightsObject", "{" CAM ", " OBJ R"(, "lights": {"type": "quad"}})", "key 'lights'", "quad",
                 "expected an array"},
        BadScene{"ScaleTiny", "{" CAM R"(, "objects": [{"mesh": "%M", "transform": {"scale": 1e-20}}]})",
                 "key 'objects[0].transform'", "1e-20", "determinant"},
        BadScene{"AxisOverflow",
                 "{" CAM R"(, "objects": [{"mesh": "%M", "transform": {"rotate": [{"axis": [3e38,3e38,3e38], "degrees": 5}]}}]})",
                 "key 'objects[0].transform.rotate[0].axis'", "3e+38", "overflows a float"},
        BadScene{"RadianceNegative", "{" CAM ", " OBJ R"(, "lights": [{"type": "quad", "corner": [0,2,0],
                 "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,-1,1]}]})", "key 'lights[0].radiance'", "[1,-1,1]",
                 ">= 0"},
        BadScene{"MediumG", "{" CAM ", " OBJ ", " LIGHT R"(, "medium": {"sigma_a": [0,0,0], "sigma_s": [1,1,1], "g": 1}})",
                 "key 'medium.g'", "= 1", "(-1, 1)"},
        // Syntax: file:line:column once, no library text.
        BadScene{"MissingComma", "{\n  \"camera\": {}\n  \"objects\": []\n}", "bad.json:3:",
                 "malformed JSON: syntax error", "unexpected string literal"},
        BadScene{"Empty", "", "bad.json:1:1: malformed JSON", "", "unexpected end of input"},
        BadScene{"TrailingGarbage", "{" CAM ", " OBJ "} x", "bad.json:1:", "malformed JSON", "expected end of input"},
        BadScene{"JsComment", "{// a comment\n" CAM ", " OBJ "}", "bad.json:1:2: malformed JSON", "", "invalid literal"},
        BadScene{"NotAnObject", "[1, 2]", "top level", "", "expected an object, got array"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST_F(SceneJson, SyntaxErrorGivesLineAndColumnOnce) {
    const std::string e = test::load_error(write("{\n  \"camera\": {}\n  \"objects\": []\n}"));
    const std::string file = (dir_ / "bad.json").string();
    ASSERT_EQ(e.rfind(file + ":3:", 0), 0u) << e;
    const std::string rest = e.substr(file.size());
    EXPECT_EQ(rest.find("line"), std::string::npos) << e;  // only the ":3:<column>:" form
    EXPECT_EQ(rest.find("byte"), std::string::npos) << e;
}

// Two OBJs that read one MTL file share its materials, and one OBJ named two ways is
// loaded once: the scene holds each material and each file once. A material of the same
// name but other values (another MTL) stays apart.
TEST_F(SceneJson, SharedMtlAndRespelledObjLoadOnce) {
    const std::string quad = test::read_bytes(test::fixture("quad.obj"));
    std::filesystem::copy_file(test::fixture("quad.mtl"), dir_ / "quad.mtl");
    std::ofstream(dir_ / "a.obj") << quad;
    std::ofstream(dir_ / "b.obj") << quad;
    std::ofstream(dir_ / "c.obj") << "mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nusemtl grey\nf 1 3 2\n";
    std::ofstream(dir_ / "c.mtl") << "newmtl grey\nKd 0.9 0.9 0.9\n";
    const Scene s = load_scene(write(R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
        "objects": [{"mesh": "a.obj"}, {"mesh": "b.obj"}, {"mesh": "./a.obj"}, {"mesh": "c.obj"}],
        "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}]})"),
                               DataPath{});
    // quad.mtl's grey and lamp once, c.mtl's grey, the JSON light.
    ASSERT_EQ(s.materials.size(), 4u);
    EXPECT_EQ(s.material[0], s.material[2]) << "a.obj and b.obj share quad.mtl's grey";
    EXPECT_EQ(s.material[0], s.material[4]) << "./a.obj is a.obj";
    EXPECT_NE(s.material[0], s.material[6]) << "c.mtl's grey is another material";
    // bad.json; a.obj and b.obj, each with quad.mtl; c.obj with c.mtl (./a.obj is a.obj).
    EXPECT_EQ(s.inputs.size(), 7u);
}

// Comment keys are allowed everywhere: "comment" and keys starting with '_', also among
// names (materials, animation tracks), with any value.
TEST_F(SceneJson, CommentKeysAreIgnored) {
    const Scene s = load_scene(write(R"({"comment": "top", "_version": 2,
        "camera": {"position": [0,1,3], "look_at": [0,0,0], "_why": "framing"},
        "objects": [{"mesh": "%M", "comment": {"any": ["value"]}, "transform": {"_": 0, "scale": 2}}],
        "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1], "_": 1}],
        "materials": {"comment": "overrides", "grey": {"albedo": [0.1, 0.2, 0.3], "_old": [1, 1, 1]}},
        "medium": {"sigma_a": [0,0,0], "sigma_s": [0,0,0], "comment": "none", "box": {"min": [0,0,0], "max": [1,1,1], "_": 1}},
        "animation": {"frames": 2, "comment": "x", "objects": {"_": 1}, "materials": {"comment": "x"},
                      "camera": [{"frame": 0, "_": 1}]}})"),
                               DataPath{});
    glm::vec3 top(0.0f);  // the quad, 0..1 in x and z, scaled by 2
    for (size_t v = 0; v < 6; ++v) top = glm::max(top, s.positions[v]);
    EXPECT_EQ(top, glm::vec3(2, 0, 2));
    bool found = false;
    for (const Material& m : s.materials)
        if (m.name == "grey") found = m.albedo == glm::vec3(0.1f, 0.2f, 0.3f);
    EXPECT_TRUE(found);
}

// A nesting bomb (tens of thousands of levels) stops at limits::kJsonDepth with the file
// and where it was; 64 levels of legitimate nesting still parse (then fail as a scene).
TEST_F(SceneJson, DeepNestingIsRejectedAtTheLimit) {
    std::string objects;
    for (int i = 0; i < 50000; ++i) objects += "{\"a\":";
    for (const std::string& bomb : {std::string(50000, '['), objects}) {
        const std::string e = test::load_error(write(bomb));
        EXPECT_CONTAINS(e, (dir_ / "bad.json").string());
        EXPECT_CONTAINS(e, "nested deeper than 64 levels");
    }
    EXPECT_CONTAINS(test::load_error(write(objects)), "key 'a.a.a.a");
    const std::string at_limit = std::string(64, '[') + std::string(64, ']');
    const std::string e = test::load_error(write(at_limit));
    EXPECT_EQ(e.find("nested deeper"), std::string::npos) << e;
    EXPECT_CONTAINS(e, "expected an object");
}

TEST_F(SceneJson, SceneFileThatIsADirectory) {
    std::filesystem::create_directories(dir_ / "dir.json");
    const std::string e = test::load_error(dir_ / "dir.json");
    EXPECT_CONTAINS(e, (dir_ / "dir.json").string() + ": scene file is a directory");
}

// Every scene the project ships loads (no unknown keys, no duplicates). A scene may fail
// only for want of a data-path file that is absent on this machine.
TEST(ShippedScenes, AllLoad) {
    const DataPath data = make_data_path(std::nullopt);
    const char* data_files[] = {"sibenik/sibenik.obj", "cornell-box/CornellBox-Original.obj"};
    int loaded = 0, scenes = 0;
    for (const auto* dir : {TESSERA_SCENES_DIR, TESSERA_SCENES_DIR "/../bench/scenes"}) {
        for (const auto& entry : std::filesystem::directory_iterator(dir)) {
            if (entry.path().extension() != ".json") continue;
            ++scenes;
            try {
                load_scene(entry.path(), data);
                ++loaded;
            } catch (const InputError& e) {
                bool absent = false;
                for (const char* f : data_files)
                    absent |= std::string(e.what()).find(f) != std::string::npos && !test::on_data_path(data, f);
                if (!absent) ADD_FAILURE() << entry.path() << ": " << e.what();
            }
        }
    }
    EXPECT_GE(scenes, 15) << "the shipped scene files were not found";
    if (test::on_data_path(data, data_files[0]) && test::on_data_path(data, data_files[1])) {
        EXPECT_EQ(loaded, scenes);
    }
}

}  // namespace
}  // namespace tessera
