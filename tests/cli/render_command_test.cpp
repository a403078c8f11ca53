// `tessera` as a user runs it: bad input gives one clear message naming the file or
// setting, a non-zero exit, and no output file; good input writes EXR and PNG.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "support/shell.h"
#include <nlohmann/json.hpp>

#include "image/image_io.h"
#include "support/scratch_dir.h"

namespace fs = std::filesystem;

namespace {

using tessera::test::CliResult;
using tessera::test::run_shell;
using tessera::test::run_tessera;

class RenderCli : public tessera::test::ScratchDirTest {
protected:

    // Renders `scene_args` and expects failure naming `needle`, and no image written.
    void expect_rejected(const std::string& scene_args, const std::string& needle,
                         const std::string& spp = "--spp 1") {
        const fs::path out = dir_ / "img.exr";
        CliResult r = run_tessera("render " + scene_args + " " + spp + " --width 8 --height 8 --out " + out.string());
        EXPECT_NE(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find("tessera: error:"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(needle), std::string::npos) << "message should name " << needle << ":\n" << r.output;
        EXPECT_FALSE(fs::exists(out));
        EXPECT_FALSE(fs::exists(dir_ / "img.png"));
    }

};

const std::string kData = TESSERA_TEST_DATA;

TEST_F(RenderCli, MissingSceneFile) { expect_rejected(kData + "/does-not-exist.json", "does-not-exist.json"); }
TEST_F(RenderCli, MalformedJson) { expect_rejected(kData + "/malformed.json", "malformed.json"); }
TEST_F(RenderCli, ObjIndexOutOfRange) { expect_rejected(kData + "/bad_index.json", "bad_index.obj"); }
TEST_F(RenderCli, ObjNanVertex) { expect_rejected(kData + "/nan_vertex.json", "nan_vertex.obj"); }
TEST_F(RenderCli, MissingMtl) { expect_rejected(kData + "/missing_mtl.json", ".mtl"); }
TEST_F(RenderCli, SceneWithoutLights) { expect_rejected(kData + "/no_lights.json", "no lights"); }
TEST_F(RenderCli, UnknownDevice) {
    expect_rejected(kData + "/light.json --device no-such-device-xyz", "no-such-device-xyz");
}
TEST_F(RenderCli, UnknownBackend) { expect_rejected(kData + "/light.json --backend vulkan", "--backend"); }
TEST_F(RenderCli, UnknownMethod) { expect_rejected(kData + "/light.json --method magic", "--method"); }
TEST_F(RenderCli, ZeroSpp) { expect_rejected(kData + "/light.json", "--spp", "--spp 0"); }
TEST_F(RenderCli, UnknownOption) { expect_rejected(kData + "/light.json --bogus", "--bogus"); }
// One side given alone scales the other; one scaled beyond the limit is refused before
// any work (no banner, no backend), naming the option.
TEST_F(RenderCli, AScaledSideOutOfRangeIsRefusedBeforeAnyWork) {
    const CliResult r = run_tessera("render " + kData + "/light.json --backend embree --height 16384 --out " +
                                    (dir_ / "img.exr").string());  // the camera is 64x32
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("tessera: error: --height 16384: at the camera's aspect ratio the --width would be "
                            "32768 px, above 16384; give --width too"),
              std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("triangles"), std::string::npos) << r.output;
}

// A misspelt option gets the closest one the command has, as a misspelt scene key does.
TEST_F(RenderCli, MisspeltOptionGetsASuggestion) {
    expect_rejected(kData + "/light.json --sppp 4", "--sppp; --sppp: did you mean --spp? (see --help)");
    expect_rejected(kData + "/light.json --shadow-sample=4", "--shadow-sample: did you mean --shadow-samples?");
    CliResult r = run_tessera("render " + kData + "/light.json --bogus-thing --width 8 --out " +
                              (dir_ / "img.exr").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(r.output.find("did you mean"), std::string::npos) << r.output;  // nothing close
}

TEST_F(RenderCli, UnwritableOutputKeepsNothingBehind) {
    CliResult r = run_tessera("render " + kData + "/light.json --spp 1 --width 8 --height 8 --backend embree --out " +
                        "/proc/tessera-no/img.exr");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("/proc/tessera-no"), std::string::npos) << r.output;
}

// A setting the method does not read renders as without it, with one note naming the
// option, the methods that read it and the method given; one it reads gets no note.
TEST_F(RenderCli, SettingsTheMethodIgnoresGetANote) {
    const std::string base = "render " + kData + "/light.json --spp 1 --width 8 --height 8 --backend embree --out ";
    const CliResult plain = run_tessera(base + (dir_ / "a.exr").string() + " --method pt");
    const CliResult noted = run_tessera(base + (dir_ / "b.exr").string() + " --method pt --tile 4 --ic-paths 9");
    ASSERT_EQ(plain.exit_code, 0) << plain.output;
    ASSERT_EQ(noted.exit_code, 0) << noted.output;
    EXPECT_NE(noted.output.find("tessera: note: --tile is read by igi, ais, ais-max, ic and tic; --method pt ignores it\n"),
              std::string::npos) << noted.output;
    EXPECT_NE(noted.output.find("tessera: note: --ic-paths is read by ic and tic; --method pt ignores it\n"),
              std::string::npos) << noted.output;
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "a.exr"), tessera::test::file_bytes(dir_ / "b.exr"));
    const CliResult read = run_tessera(base + (dir_ / "c.exr").string() + " --method igi --tile 4 --vpl-paths 2");
    ASSERT_EQ(read.exit_code, 0) << read.output;
    EXPECT_EQ(read.output.find("tessera: note: --"), std::string::npos) << read.output;  // (quad.mtl's Kd has one)
}

// --ic-view-rays weighs the paths --ic-importance K > 1 chooses among: with K = 1 it
// changes nothing (the same bytes), and says so; with K > 1 it is read, without a note.
TEST_F(RenderCli, ViewRaysWithoutPathImportanceGetANote) {
    const std::string base = "render " + kData + "/light.json --spp 1 --width 8 --height 8 --backend embree --method ic "
                             "--ic-paths 8 --out ";
    const CliResult plain = run_tessera(base + (dir_ / "a.exr").string() + " --ic-importance 1");
    const CliResult noted = run_tessera(base + (dir_ / "b.exr").string() + " --ic-importance 1 --ic-view-rays 5");
    ASSERT_EQ(plain.exit_code, 0) << plain.output;
    ASSERT_EQ(noted.exit_code, 0) << noted.output;
    EXPECT_NE(noted.output.find("tessera: note: --ic-view-rays is read only with --ic-importance above 1"),
              std::string::npos) << noted.output;
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "a.exr"), tessera::test::file_bytes(dir_ / "b.exr"));
    const CliResult read = run_tessera(base + (dir_ / "c.exr").string() + " --ic-importance 2 --ic-view-rays 5");
    ASSERT_EQ(read.exit_code, 0) << read.output;
    EXPECT_EQ(read.output.find("--ic-view-rays is read only"), std::string::npos) << read.output;
}

// The medium's settings on a clear scene change nothing; each given one gets a note (they
// were taken without a word). On a foggy scene they are read, without a note.
TEST_F(RenderCli, MediumSettingsOnAClearSceneGetANote) {
    const std::string base = "render " + kData + "/light.json --spp 1 --width 8 --height 8 --backend embree --method igi";
    const CliResult plain = run_tessera(base + " --out " + (dir_ / "a.exr").string());
    const CliResult noted =
        run_tessera(base + " --out " + (dir_ / "b.exr").string() + " --uniform-march --march-steps 3 --single-scattering");
    ASSERT_EQ(plain.exit_code, 0) << plain.output;
    ASSERT_EQ(noted.exit_code, 0) << noted.output;
    for (const char* option : {"--uniform-march", "--march-steps", "--single-scattering"})
        EXPECT_NE(noted.output.find(std::string("tessera: note: ") + option + ": scene " + kData +
                                    "/light.json has no medium; it changes nothing\n"),
                  std::string::npos)
            << noted.output;
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "a.exr"), tessera::test::file_bytes(dir_ / "b.exr"));
    const CliResult fog = run_tessera("render " + std::string(TESSERA_SCENES_DIR) +
                                      "/cornell-box-fog.json --spp 1 --width 8 --height 8 --backend embree --method igi "
                                      "--uniform-march --out " + (dir_ / "c.exr").string());
    ASSERT_EQ(fog.exit_code, 0) << fog.output;
    EXPECT_EQ(fog.output.find("has no medium"), std::string::npos) << fog.output;
}

// ic and tic read igi's VPL settings only for a medium's light: on a clear scene the image
// is the same to the bit, and a note says so; with fog there is no note.
TEST_F(RenderCli, VplSettingsOfIcOnAClearSceneGetANote) {
    const std::string base = "render --spp 1 --width 8 --height 8 --backend embree";
    for (const char* method : {"ic", "tic"}) {
        SCOPED_TRACE(method);
        const std::string m = std::string(" --method ") + method;
        const CliResult plain = run_tessera(base + m + " --out " + (dir_ / "a.exr").string());
        const CliResult noted =
            run_tessera(base + m + " --vpl-paths 8 --vpl-importance 2 --out " + (dir_ / "b.exr").string());
        ASSERT_EQ(plain.exit_code, 0) << plain.output;
        ASSERT_EQ(noted.exit_code, 0) << noted.output;
        for (const char* option : {"--vpl-paths", "--vpl-importance"})
            EXPECT_NE(noted.output.find(std::string("tessera: note: ") + option + ": --method " + method +
                                        " reads it only on a scene with a medium"),
                      std::string::npos)
                << noted.output;
        EXPECT_EQ(tessera::test::file_bytes(dir_ / "a.exr"), tessera::test::file_bytes(dir_ / "b.exr"));
        const CliResult fog = run_tessera("render " + std::string(TESSERA_SCENES_DIR) + "/cornell-box-fog.json" +
                                          " --spp 1 --width 8 --height 8 --backend embree" + m + " --vpl-paths 8 --out " +
                                          (dir_ / "c.exr").string());
        ASSERT_EQ(fog.exit_code, 0) << fog.output;
        EXPECT_EQ(fog.output.find("reads it only"), std::string::npos) << fog.output;
    }
}

// A medium of |g| > 0.9 with an igi-family method gets a note that these methods return
// only part of its multiple scattering (docs/igi.md §6); pt, and g = 0.9, get none.
TEST_F(RenderCli, APeakedPhaseFunctionGetsANoteWithTheIgiFamily) {
    const std::string scene = tessera::test::file_bytes(fs::path(TESSERA_SCENES_DIR) / "cornell-box-fog.json");
    auto with_g = [&](const std::string& g) {
        std::string text = scene;
        const size_t at = text.find("\"g\": 0.3");
        text.replace(at, 8, "\"g\": " + g);
        const size_t mesh = text.find("\"cornell-box.obj\"");
        text.replace(mesh, 17, "\"" + std::string(TESSERA_SCENES_DIR) + "/cornell-box.obj\"");
        const fs::path file = dir_ / ("g" + g + ".json");
        std::ofstream(file) << text;
        return file.string();
    };
    const std::string args = " --spp 1 --width 8 --height 8 --backend embree --out " + (dir_ / "x.exr").string();
    const CliResult ais = run_tessera("render " + with_g("-0.99") + args);
    ASSERT_EQ(ais.exit_code, 0) << ais.output;
    EXPECT_NE(ais.output.find("tessera: note: the medium's g = -0.99: --method ais returns only part of the multiple "
                              "scattering"),
              std::string::npos)
        << ais.output;
    for (const std::string& other : {"render " + with_g("0.99") + args + " --method pt",
                                     "render " + with_g("0.9") + args + " --method igi"}) {
        const CliResult r = run_tessera(other);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_EQ(r.output.find("tessera: note: the medium's g"), std::string::npos) << other << ": " << r.output;
    }
}

// `direct` renders a foggy scene as if clear (docs/path-tracing.md §6): a note says so; a
// clear scene, or another method on the foggy one, gets none.
TEST_F(RenderCli, DirectOnAFoggySceneGetsANote) {
    const std::string fog = std::string(TESSERA_SCENES_DIR) + "/cornell-box-fog.json";
    const std::string args = " --spp 1 --width 8 --height 8 --backend embree --out " + (dir_ / "d.exr").string();
    const std::string note = "tessera: note: --method direct ignores the scene's medium";
    const CliResult direct = run_tessera("render " + fog + args + " --method direct");
    ASSERT_EQ(direct.exit_code, 0) << direct.output;
    EXPECT_NE(direct.output.find(note), std::string::npos) << direct.output;
    for (const std::string& other : {"render " + fog + args + " --method igi", "render" + args + " --method direct"}) {
        const CliResult r = run_tessera(other);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_EQ(r.output.find(note), std::string::npos) << other << ": " << r.output;
    }
}

TEST_F(RenderCli, RendersExrAndPngOnBothBackends) {
    for (const char* backend : {"embree", "opencl"}) {
        const fs::path out = dir_ / (std::string(backend) + ".exr");
        CliResult r = run_tessera("render --spp 1 --width 16 --height 16 --backend " + std::string(backend) + " --out " +
                            out.string());
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_GT(fs::file_size(out), 0u);
        EXPECT_GT(fs::file_size(dir_ / (std::string(backend) + ".png")), 0u);
    }
}

// Without --out the image is named after the scene file, in out/ under the working
// directory: a copy of a scene renders to its own image, whatever its "name" key says.
TEST_F(RenderCli, DefaultOutputIsNamedAfterTheSceneFile) {
    std::ifstream in(std::string(TESSERA_SCENES_DIR) + "/cornell-box.json");
    std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The copy's meshes are found from its own directory: name them by absolute path.
    for (size_t at = 0; (at = json.find("\"cornell-box.obj\"", at)) != std::string::npos;)
        json.replace(at, 17, "\"" + std::string(TESSERA_SCENES_DIR) + "/cornell-box.obj\""), at += 17;
    // A name that reads like a path changes nothing: outputs are not made from it.
    const size_t name = json.find("\"cornell-box\"");
    ASSERT_NE(name, std::string::npos);
    json.replace(name, 13, "\"../../Cornell / box\"");
    std::ofstream(dir_ / "mybox.json") << json;
    const CliResult r = run_shell("cd " + dir_.string() + " && " + TESSERA_EXE +
                                  " render mybox.json --spp 1 --width 8 --height 8 --backend embree");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "mybox.exr")) << r.output;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "mybox.png")) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "cornell-box.exr")) << r.output;
    EXPECT_NE(r.output.find("tessera: ../../Cornell / box, 32 triangles"), std::string::npos) << r.output;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), {}), 2) << "mybox.json and out/ only";
}

TEST(InfoCli, ListsEffectsOfTheDefaultScene) {
    CliResult r = run_tessera("info");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("triangles:  32"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("medium (PM):          no"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("animation:"), std::string::npos) << r.output;
    // The default method (ais) builds igi.cl: the line names each method's programs.
    EXPECT_NE(r.output.find("OpenCL programs, built with -cl-std=CL1.2 (and the device's division option"),
              std::string::npos) << r.output;
    EXPECT_NE(r.output.find("igi, ais, ais-max: igi.cl, trace.cl;"), std::string::npos) << r.output;
}

// A $TESSERA_DATA that is not a directory is said (--data-dir of the same is an error);
// the run goes on, since a scene may not need it.
TEST(InfoCli, DataPathThatIsNotADirectoryIsSaid) {
    const CliResult r = run_tessera("info", "TESSERA_DATA=/no/such/tessera-data");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("tessera: note: TESSERA_DATA=/no/such/tessera-data is not a directory"), std::string::npos)
        << r.output;
}

// Meshes and the scene file's quad lights are counted apart (Sibenik's one mesh and four
// lights were "objects: 5"), and mirrors and dielectrics are named among the materials.
TEST_F(RenderCli, InfoCountsMeshesLightsAndSpecularMaterials) {
    fs::copy_file(fs::path(TESSERA_SCENES_DIR) / "cube.obj", dir_ / "cube.obj");
    std::ofstream(dir_ / "cube.mtl") << "newmtl cube\nKd 0.5 0.5 0.5\nKs 1 1 1\nNi 1.5\nillum 7\n";
    std::ofstream(dir_ / "scene.json") << R"({
      "camera": {"position": [0, 2, 3], "look_at": [0, 0, 0]},
      "objects": [{"mesh": "cube.obj"}],
      "lights": [{"type": "quad", "corner": [-1, 3, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "radiance": [1, 1, 1]},
                 {"type": "quad", "corner": [-1, 4, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "radiance": [1, 1, 1]}]
    })";
    const CliResult r = run_tessera("info " + (dir_ / "scene.json").string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("objects:    1 and 2 quad lights of the scene file\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(0 mirror, 1 dielectric)"), std::string::npos) << r.output;
}

TEST(InfoCli, DescribesAnAnimation) {
    CliResult r = run_tessera("info " + std::string(TESSERA_SCENES_DIR) + "/cornell-box-animated.json");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("objects:    2"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("animation:  30 frames; tracks: 1 objects, 2 materials"), std::string::npos) << r.output;
}

// What a scene calls for over its whole animation: a light dark in the rest pose and lit
// by a key later is a light. One OBJ named by two spellings is loaded once.
TEST_F(RenderCli, InfoCountsLightsOfTheAnimationAndEachFileOnce) {
    for (const char* f : {"textured.obj", "textured.mtl", "checker.png"})
        fs::copy_file(fs::path(kData) / f, dir_ / f);
    std::ofstream(dir_ / "scene.json") << R"({
      "camera": {"position": [0, 2, 3], "look_at": [0, 0, 0]},
      "objects": [{"mesh": "textured.obj"}, {"mesh": "./textured.obj", "transform": {"translate": [0, 0, 2]}}],
      "lights": [{"type": "quad", "corner": [0, 5, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1],
                  "radiance": [0, 0, 0]}],
      "animation": {"frames": 4, "materials": {"json-light-0": [{"frame": 0, "emission": [0, 0, 0]},
                                                        {"frame": 3, "emission": [20, 20, 20]}]}}
    })";
    const CliResult r = run_tessera("info " + (dir_ / "scene.json").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("area lights (SS):     yes"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("indirect diffuse (ID): yes"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(", textures: 1\n"), std::string::npos) << r.output;
    const CliResult once = run_tessera("info " + std::string(kData) + "/textured.json");
    const auto materials = [](const std::string& out) { return out.substr(out.find("materials:"), 16); };
    EXPECT_EQ(materials(r.output), materials(once.output)) << r.output << once.output;
}

// Likewise a surface black at rest and coloured by a later key reflects: info said "no
// reflecting surface" while frame 2 has indirect light.
TEST_F(RenderCli, InfoCountsSurfacesTheAnimationColours) {
    std::ofstream(dir_ / "floor.mtl") << "newmtl black\nKd 0 0 0\n";
    std::ofstream(dir_ / "floor.obj") << "mtllib floor.mtl\nusemtl black\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n"
                                         "f 1 4 3\nf 1 3 2\n";
    std::ofstream(dir_ / "scene.json") << R"({
      "camera": {"position": [0, 2, 3], "look_at": [0, 0, 0]},
      "objects": [{"mesh": "floor.obj"}],
      "lights": [{"type": "quad", "corner": [0, 1, 0], "edge1": [0.2, 0, 0], "edge2": [0, 0, 0.2],
                  "radiance": [5, 5, 5]}],
      "animation": {"frames": 3, "materials": {"black": [{"frame": 0, "albedo": [0, 0, 0]},
                                                      {"frame": 2, "albedo": [0.5, 0.5, 0.5]}]}}
    })";
    const CliResult r = run_tessera("info " + (dir_ / "scene.json").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("indirect diffuse (ID): yes"), std::string::npos) << r.output;
}

TEST(DevicesCli, ListsPocl) {
    CliResult r = run_tessera("devices");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("[0]"), std::string::npos) << r.output;
}

// A name substring: devices of one name (identical GPUs) take the first; a substring of
// different devices' names is refused, listing them (it took the lowest index unsaid).
TEST_F(RenderCli, DeviceNameOfSeveralDevices) {
    const std::string render = "render --backend opencl --spp 1 --width 8 --height 8 --method direct --out " +
                               (dir_ / "d.exr").string();
    CliResult twins = run_tessera("devices", "POCL_DEVICES='pthread pthread'");
    if (twins.output.find("[1]") == std::string::npos) GTEST_SKIP() << "PoCL offers no second device here";
    CliResult r = run_tessera(render + " --device pthread", "POCL_DEVICES='pthread pthread'");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    CliResult mixed = run_tessera("devices", "POCL_DEVICES='pthread basic'");
    if (mixed.output.find("basic") == std::string::npos) GTEST_SKIP() << "PoCL has no basic device here";
    r = run_tessera(render + " --device portable", "POCL_DEVICES='pthread basic'");
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("--device portable: names 2 OpenCL devices ("), std::string::npos) << r.output;
}

// A device that is not there: one line naming it and listing those that are.
TEST(DevicesCli, UnknownDeviceIsOneLineListingTheDevices) {
    CliResult r = run_tessera("render --backend opencl --device no-such-device --spp 1 --width 8 --height 8");
    EXPECT_EQ(r.exit_code, 1) << r.output;
    const std::string start = "tessera: error: --device no-such-device: no such OpenCL device; available: [0] ";
    const size_t at = r.output.find(start);
    ASSERT_NE(at, std::string::npos) << r.output;
    const size_t end = r.output.find('\n', at);
    EXPECT_NE(r.output.substr(at, end - at).find(" (or use --backend embree)"), std::string::npos) << r.output;
}

}  // namespace

// --stats-json: the timing the accuracy sweeps read (bench/accuracy). No --method: the
// record names the default, ais.
TEST_F(RenderCli, StatsJson) {
    const fs::path out = dir_ / "img.exr", stats = dir_ / "stats.json";
    CliResult r = run_tessera("render " + kData + "/light.json --spp 3 --width 8 --backend embree --tile 2 --no-filter "
                              "--out " + out.string() + " --stats-json " + stats.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::ifstream f(stats);
    ASSERT_TRUE(f) << r.output;
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_EQ(j["passes"], 3);
    EXPECT_EQ(j["spp"], 3);
    EXPECT_EQ(j["method"], "ais");
    EXPECT_EQ(j["backend"], "embree");
    EXPECT_EQ(j["mpi_ranks"], 1);
    EXPECT_EQ(j["tracer"].get<std::string>().substr(0, 7), "embree ") << j["tracer"];  // Backend::description()
    EXPECT_GT(j["median_pass_seconds"].get<double>(), 0.0);
    EXPECT_LE(j["median_pass_seconds"].get<double>(), j["seconds"].get<double>());
    // Every option ais reads, as in effect; the size as rendered; none that ais ignores.
    const nlohmann::json& set = j["settings"];
    EXPECT_EQ(set["tile"], 2);
    EXPECT_EQ(set["no-filter"], true);
    EXPECT_EQ(set["vpl-paths"], 32);
    EXPECT_EQ(set["aov"], false);
    EXPECT_EQ(set["seed"], 1);
    EXPECT_EQ(set["width"], 8);
    EXPECT_EQ(set["height"], 4);  // the camera's 64x32 scaled to --width 8
    EXPECT_FALSE(set.contains("max-scatter")) << set;  // pt only
    EXPECT_FALSE(set.contains("ic-paths")) << set;     // ic and tic only
    EXPECT_EQ(set["clamp"].dump(), "0.1") << set;      // the float as given, not 0.10000000149011612
}

// ic's settings as in effect: --ic-subsets 0 is the subsets it resolved to (2 below 16 spp,
// docs/instant-caching.md §2b), the log's "in each of 2 subsets"; floats as given.
TEST_F(RenderCli, StatsJsonShowsTheIcSettingsInEffect) {
    const fs::path stats = dir_ / "stats.json";
    const CliResult r = run_tessera("render " + kData + "/light.json --method ic --spp 4 --width 16 --height 16 "
                                    "--backend embree --ic-error 0.3 --out " + (dir_ / "img.exr").string() +
                                    " --stats-json " + stats.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("in each of 2 subsets"), std::string::npos) << r.output;
    std::ifstream f(stats);
    const nlohmann::json set = nlohmann::json::parse(f)["settings"];
    EXPECT_EQ(set["ic-subsets"], 2) << set;
    EXPECT_EQ(set["ic-error"].dump(), "0.3") << set;
}

// --frames: one EXR + PNG per frame, the frame number before the extension.
TEST_F(RenderCli, FramesWritesOneFilePerFrame) {
    const std::string scene = std::string(TESSERA_SCENES_DIR) + "/cornell-box-animated.json";
    CliResult r = run_tessera("render " + scene + " --frames 0:1 --spp 1 --width 16 --height 16 --backend embree --out " +
                              (dir_ / "seq.exr").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* name : {"seq.0000.exr", "seq.0000.png", "seq.0001.exr", "seq.0001.png"})
        EXPECT_TRUE(fs::exists(dir_ / name)) << name << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "seq.exr"));
    EXPECT_FALSE(fs::exists(dir_ / "seq.0002.exr"));
    EXPECT_NE(r.output.find("frame 1:"), std::string::npos) << r.output;
    const tessera::Image img = tessera::read_exr(dir_ / "seq.0001.exr");
    EXPECT_EQ(img.width, 16);
}

// The Cornell box's mesh loaded twice: its light is listed twice, and info, a still, a
// sequence and the viewer each say so once.
TEST_F(RenderCli, ALightListedTwiceIsSaidEverywhere) {
    const std::string obj = std::string(TESSERA_SCENES_DIR) + "/cornell-box.obj";
    const fs::path scene = dir_ / "twice.json";
    std::ofstream(scene) << R"({"camera": {"position": [0.278, 0.273, -0.8], "look_at": [0.278, 0.273, 0]},
        "objects": [{"mesh": ")" << obj << R"(", "transform": {"scale": 0.001}},
                    {"mesh": ")" << obj << R"(", "transform": {"scale": 0.001}}]})";
    const std::string note = "4 emissive triangles lie on another light facing the same way";
    const std::string small = " --width 8 --height 8 --spp 1 --method direct --backend embree";
    const fs::path quit = dir_ / "quit.json";
    std::ofstream(quit) << R"({"events": [{"frame": 1, "quit": true}]})";
    for (const std::string& args :
         {"info " + scene.string(), "render " + scene.string() + small + " --out " + (dir_ / "a.exr").string(),
          "render " + scene.string() + small + " --frames 0:0 --out " + (dir_ / "b.exr").string(),
          "view " + scene.string() + small + " --headless --input-script " + quit.string()}) {
        const CliResult r = run_tessera(args);
        EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(note), std::string::npos) << args << "\n" << r.output;
        EXPECT_EQ(r.output.find(note), r.output.rfind(note)) << "said once: " << args;
    }
}

TEST_F(RenderCli, BadFrames) {
    const std::string scene = std::string(TESSERA_SCENES_DIR) + "/cornell-box-animated.json";
    expect_rejected(scene + " --frames 0-1", "--frames");
    expect_rejected(scene + " --frames 2:1", "--frames");
    expect_rejected(scene + " --frames 0:30", "--frames");
    expect_rejected(kData + "/light.json --frames 0:1", "--frames");
    expect_rejected(scene + " --frames 0:1 --resume", "--resume");
    expect_rejected(scene + " --frames 0:1 --stats-json " + (dir_ / "s.json").string(), "--stats-json");
    // A sequence keeps no checkpoint: an interval given for one was ignored without a word.
    expect_rejected(scene + " --frames 0:1 --checkpoint-interval 5",
                    "--frames cannot be combined with --checkpoint-interval");
}

TEST_F(RenderCli, TicSequenceLogsTheCacheAndRefusesResume) {
    const std::string scene = std::string(TESSERA_SCENES_DIR) + "/cornell-box-animated.json";
    CliResult r = run_tessera("render " + scene + " --method tic --frames 0:1 --spp 1 --width 16 --height 16 "
                              "--ic-paths 16 --backend embree --out " + (dir_ / "tic.exr").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir_ / "tic.0001.exr"));
    EXPECT_NE(r.output.find("tic: a 0.30, 16 paths"), std::string::npos) << r.output;
    expect_rejected("--method tic --resume", "--resume");
    expect_rejected("--method ic --ic-error 0", "--ic-error");
    expect_rejected("--method ic --ic-paths 0", "--ic-paths");
}

namespace tessera {
namespace {

class IgiCli : public tessera::test::ScratchDirTest {};

TEST_F(IgiCli, AovWritesEachComponentBeforeAndAfterFiltering) {
    const fs::path out = dir_ / "igi.exr";
    auto r = run_tessera("render --method igi --aov --spp 1 --width 24 --height 24 --backend embree --out " +
                         out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("igi: tile 3x3"), std::string::npos) << r.output;
    Image img = read_exr(out);
    for (const char* c : {"SS.R", "SS_filtered.G", "ID.B", "ID_filtered.R", "albedo.R", "N.X", "Z"})
        EXPECT_NE(img.find(c), nullptr) << c;
    EXPECT_EQ(img.find("PM.R"), nullptr) << "no medium, so no PM component";
    // The composite is emission + albedo × (filtered SS + filtered ID) where no medium.
    const auto &R = img.find("R")->data, &a = img.find("albedo.R")->data;
    const auto &ss = img.find("SS_filtered.R")->data, &id = img.find("ID_filtered.R")->data;
    const size_t centre = 12 * 24 + 12;  // the back wall
    EXPECT_NEAR(R[centre], a[centre] * (ss[centre] + id[centre]), 1e-4f * R[centre]);
}

}  // namespace
}  // namespace tessera

namespace {

// A log reader that leaves (`tessera render ... 2>&1 | head -c 1`) does not end the render:
// SIGPIPE killed it at its next line, with no image, no checkpoint and the frame's
// temporaries left. The render finishes, writes its image and exits 0.
TEST_F(RenderCli, AReaderThatLeavesDoesNotEndTheRender) {
    const fs::path out = dir_ / "img.exr";
    const CliResult r = run_shell("{ " + std::string(TESSERA_EXE) + " render " + kData +
                                  "/light.json --backend embree --spp 4 --width 8 --height 8 --out " + out.string() +
                                  " 2>&1; echo $? > " + (dir_ / "rc").string() + "; } | head -c 1");
    std::ifstream rc(dir_ / "rc");
    int status = -1;
    rc >> status;
    EXPECT_EQ(status, 0) << r.output;
    EXPECT_TRUE(fs::exists(out));
    EXPECT_TRUE(fs::exists(dir_ / "img.png"));
    for (const auto& e : fs::directory_iterator(dir_))
        EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}

}  // namespace
