// The scene-input contract through `tessera render`: one bad input per layer (OBJ, MTL,
// texture, scene JSON, animation) exits non-zero with one message naming the file and the
// value, and writes no output file.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>

#include "scene/scene_test_util.h"
#include "support/scratch_dir.h"

namespace tessera {
namespace {

struct CliCase {
    const char* name;
    const char* scene;  ///< s.json; the mesh is m.obj beside it
    const char* obj;
    const char* mtl;    ///< m.mtl
    const char* file;   ///< the file the message must start with (relative to the folder)
    const char* value;  ///< the key/line and value it must name
};

class BadInputCli : public test::ScratchDirTest, public ::testing::WithParamInterface<CliCase> {};

constexpr const char* kScene = R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]}, "objects": [{"mesh": "m.obj"}]})";
constexpr const char* kObj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nusemtl m\nf 1 3 2\n";
constexpr const char* kMtl = "newmtl m\nKd 0.5 0.5 0.5\nKe 1 1 1\n";

TEST_P(BadInputCli, ExitsNonZeroNamesTheValueWritesNothing) {
    const CliCase& c = GetParam();
    std::ofstream(dir_ / "s.json") << c.scene;
    std::ofstream(dir_ / "m.obj") << c.obj;
    std::ofstream(dir_ / "m.mtl") << c.mtl;
    const auto out = dir_ / "out" / "img.exr";
    const std::string cmd = std::string(TESSERA_EXE) + " render " + (dir_ / "s.json").string() +
                            " --spp 1 --width 8 --height 8 --out " + out.string() + " 2>&1";
    FILE* p = ::popen(cmd.c_str(), "r");
    std::string output;
    std::array<char, 4096> buf;
    while (const size_t n = std::fread(buf.data(), 1, buf.size(), p)) output.append(buf.data(), n);
    const int status = ::pclose(p);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0) << output;
    EXPECT_CONTAINS(output, "tessera: error: " + (dir_ / c.file).string());
    EXPECT_CONTAINS(output, c.value);
    EXPECT_EQ(output.find('\n'), output.size() - 1) << "one line expected: " << output;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "out")) << "an output was created";
}

INSTANTIATE_TEST_SUITE_P(
    Cli, BadInputCli,
    ::testing::Values(
        CliCase{"ObjShortFace", kScene, "v 0 0 0\nv 1 0 0\nf 1 2\n", kMtl, "m.obj:3:", "'f 1 2'"},
        CliCase{"ObjZeroIndex", kScene, "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 0 1 2\n", kMtl, "m.obj:4:", "vertex index 0"},
        CliCase{"MtlKdNan", kScene, kObj, "newmtl m\nKd nan 0 0\n", "m.mtl:2:", "'nan'"},
        CliCase{"MtlKeInf", kScene, kObj, "newmtl m\nKe inf 1 1\n", "m.mtl:2:", "'inf'"},
        // Below the smallest normal float: the backends rendered 1e-40 as 0 and as 1e-40.
        CliCase{"MtlKeSubnormal", kScene, kObj, "newmtl m\nKe 1e-40 1 1\n", "m.mtl:2:",
                "'1e-40' is below the smallest normal float, 1.2e-38 (give 0)"},
        CliCase{"JsonEmissionSubnormal",
                R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]}, "objects": [{"mesh": "m.obj"}],
                    "materials": {"m": {"emission": [1e-40, 0, 1]}}})",
                kObj, kMtl, "s.json", "key 'materials.m.emission[0]' = 1e-40: number is below the smallest normal float"},
        CliCase{"Texture", kScene, kObj, "newmtl m\nKe 1 1 1\nmap_Kd gone.png\n", "gone.png", "not found"},
        CliCase{"JsonUnknownKey",
                R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]}, "objects": [{"mesh": "m.obj"}], "lightz": []})",
                kObj, kMtl, "s.json", "unknown key 'lightz'"},
        CliCase{"JsonDuplicateKey",
                R"({"camera": {"position": [0,1,3], "look_at": [0,0,0], "vfov": 30, "vfov": 60}, "objects": [{"mesh": "m.obj"}]})",
                kObj, kMtl, "s.json", "duplicate key 'camera.vfov'"},
        CliCase{"JsonSyntax", "{\"camera\": {]}", kObj, kMtl, "s.json:1:13:", "malformed JSON"},
        CliCase{"Animation",
                R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]}, "objects": [{"mesh": "m.obj"}],
                    "animation": {"frames": 3, "materials": {"m": [{"frame": 0, "emision": [1, 1, 1]}]}}})",
                kObj, kMtl, "s.json", "unknown key 'animation.materials.m[0].emision'"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace tessera
