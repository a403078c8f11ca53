// The stand-in scenes of scenes/generate/standins.py (scenes/README.md): each loads with the lights
// it is built with, inside its room, `tessera info` lists the effects it calls for, a small
// IGI render agrees across backends, and the generator reproduces the committed files (and
// the build's generated mesh) byte for byte.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/loader.h"
#include "support/render_helpers.h"
#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;

namespace tessera {
namespace {

struct Standin {
    const char* name;
    uint32_t json_lights;  ///< quad lights the generator writes (each two triangles)
    bool medium;
};

// The seed's row order (Tables 5.1-5.3), stand-ins only.
constexpr Standin kStandins[] = {
    {"deskar", 2, false},     {"subdivided", 1, false}, {"desk", 2, false},
    {"office", 4, false},     {"conference", 5, false}, {"shirley6", 1, false},
    {"subdivided-fog", 1, true}, {"office-fog", 4, true}, {"shirley6-fog", 1, true},
};

fs::path scene_file(const Standin& s) { return fs::path(TESSERA_SCENES_DIR) / (std::string(s.name) + ".json"); }

std::string run_capture(const std::string& cmd) {
    FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
    std::string out;
    std::array<char, 4096> buf;
    while (size_t n = std::fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
    ::pclose(p);
    return out;
}

class StandinScene : public ::testing::TestWithParam<Standin> {};

TEST_P(StandinScene, LoadsWithItsLightsAndCameraInsideTheRoom) {
    const Standin& st = GetParam();
    const Scene s = load_scene(scene_file(st), make_data_path(std::nullopt));
    EXPECT_EQ(s.name, st.name);
    const auto doc = nlohmann::json::parse(tessera::test::file_bytes(scene_file(st)));
    ASSERT_TRUE(doc.contains("stands_in_for"));
    EXPECT_GT(doc["stands_in_for"].get<std::string>().size(), 20u);
    EXPECT_EQ(s.has_medium, st.medium);
    // Every scene is a closed room (its walls are the outermost geometry): the camera and
    // every light lie strictly inside the bounds of the non-emitting triangles.
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    uint32_t emitting = 0;
    for (size_t t = 0; t < s.triangle_count(); ++t) {
        if (s.materials[s.material[t]].emission != glm::vec3(0.0f)) {
            ++emitting;
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            lo = glm::min(lo, s.positions[3 * t + k]);
            hi = glm::max(hi, s.positions[3 * t + k]);
        }
    }
    EXPECT_EQ(emitting, 2 * st.json_lights);
    for (size_t t = 0; t < s.triangle_count(); ++t) {
        if (s.materials[s.material[t]].emission == glm::vec3(0.0f)) continue;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = s.positions[3 * t + k];
            EXPECT_TRUE(glm::all(glm::greaterThan(p, lo)) && glm::all(glm::lessThan(p, hi))) << "light triangle " << t;
        }
    }
    const glm::vec3 c = s.camera.position;
    EXPECT_TRUE(glm::all(glm::greaterThan(c, lo)) && glm::all(glm::lessThan(c, hi)));
    if (std::string(st.name).rfind("subdivided", 0) == 0) {
        // The seed's Subdivided holds a high-polygon object: the knot is 27 rings x 4
        // sides x 2 control triangles, 4^5 after five Loop steps.
        ASSERT_EQ(s.objects.size(), 3u);  // room, knot, the JSON light
        EXPECT_EQ(s.objects[1].triangle_count, 216u * 1024u);
        EXPECT_GE(s.objects[1].triangle_count, 200000u);
    }
}

TEST_P(StandinScene, InfoListsTheEffectsItCallsFor) {
    const Standin& st = GetParam();
    const std::string out = run_capture(std::string(TESSERA_EXE) + " info " + scene_file(st).string());
    EXPECT_NE(out.find("area lights (SS):     yes"), std::string::npos) << out;
    EXPECT_NE(out.find("indirect diffuse (ID): yes"), std::string::npos) << out;
    EXPECT_NE(out.find(st.medium ? "medium (PM):          yes" : "medium (PM):          no"), std::string::npos)
        << out;
    EXPECT_NE(out.find("lights:     " + std::to_string(2 * st.json_lights) + " emissive triangles"), std::string::npos)
        << out;
}

TEST_P(StandinScene, IgiBackendsAgree) {
    Scene s = load_scene(scene_file(GetParam()), make_data_path(std::nullopt));
    RenderSettings rs;
    rs.method = Method::Igi;
    rs.width = rs.height = 32;
    rs.spp = 1;
    // With a medium, IGI's ray march (the PM component) is not sample-for-sample equal
    // across backends: on office-fog (and on cornell-box-fog and sibenik-fog, not stand-ins)
    // 2-43% of pixel channels differ by more than 1e-3 at 32x32, 1 spp, while the relMSE
    // between backends stays 1e-4 to 1e-7 of the seed-to-seed relMSE (PM alone on
    // office-fog: RMSE 0.008 between backends, 0.76 between seeds). So for those scenes
    // only the relMSE bound applies; the surface components match pixel for pixel.
    test::expect_backends_agree(s, rs, /*count_differing_pixels=*/!GetParam().medium);
}

INSTANTIATE_TEST_SUITE_P(Standins, StandinScene, ::testing::ValuesIn(kStandins),
                         [](const auto& info) {
                             std::string n = info.param.name;
                             for (char& ch : n)
                                 if (ch == '-') ch = '_';
                             return n;
                         });

class StandinGenerator : public test::ScratchDirTest {};

// Regenerates every stand-in file into a scratch folder: each must equal, byte for byte,
// the committed file of that path under scenes/ (the small ones) or the file the build
// generated (the knot), so the generator is deterministic and the committed files are
// its current output. Also no committed file under scenes/standins/ is left unwritten.
TEST_F(StandinGenerator, ReproducesTheCommittedAndBuiltFiles) {
    const fs::path scenes(TESSERA_SCENES_DIR);
    ASSERT_EQ(test::shell_status("python3 " + (scenes / "generate" / "standins.py").string() + " --what all --out " +
                                 dir_.string()),
              0);
    size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) {
        if (!e.is_regular_file()) continue;
        const fs::path rel = fs::relative(e.path(), dir_);
        ++files;
        ASSERT_TRUE(fs::exists(scenes / rel)) << rel;
        EXPECT_TRUE(tessera::test::file_bytes(e.path()) == tessera::test::file_bytes(scenes / rel)) << rel << " differs from the generator's output";
    }
    EXPECT_EQ(files, 9u + 12u + 2u);  // scene JSON, standins/ OBJ + MTL, generated/ OBJ + MTL
    for (const auto& e : fs::directory_iterator(scenes / "standins"))
        EXPECT_TRUE(fs::exists(dir_ / "standins" / e.path().filename())) << e.path() << " is not generated";
}

}  // namespace
}  // namespace tessera
