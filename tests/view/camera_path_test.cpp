// Camera paths (--camera-path): written paths read back as the same floats; bad files
// give one message naming the file and entry.
#include "view/camera_path.h"

#include <fstream>

#include <gtest/gtest.h>

#include "scene/scene_test_util.h"
#include "support/scratch_dir.h"
#include "util/error.h"

namespace tessera::view {
namespace {

class CameraPath : public test::ScratchDirTest {
protected:
    std::string error_of(const std::string& text) {
        const auto p = dir_ / "path.json";
        std::ofstream(p) << text;
        try {
            read_camera_path(p);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }
};

TEST_F(CameraPath, RoundTripsExactly) {
    std::vector<PathFrame> frames(3);
    for (int i = 0; i < 3; ++i) {
        frames[i].camera.position = {0.1f * i + 1e-7f, 1.0f / 3.0f, -0.8f};
        frames[i].camera.look_at = {0.278f, 0.273f + i, 2.0f / 7.0f};
        frames[i].camera.up = {0.0f, 1.0f, 1e-3f};
        frames[i].camera.vfov_deg = 39.3077f;
        frames[i].frame = i;
    }
    write_camera_path(dir_ / "p.json", frames, "cornell \"box\"");
    std::string scene = "stale";
    const std::vector<PathFrame> back = read_camera_path(dir_ / "p.json", &scene);
    EXPECT_EQ(scene, "cornell \"box\"");  // the scene it was recorded on, escaped and back
    write_camera_path(dir_ / "q.json", frames);
    read_camera_path(dir_ / "q.json", &scene);
    EXPECT_EQ(scene, "");  // none recorded
    ASSERT_EQ(back.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(back[i].camera.position, frames[i].camera.position);
        EXPECT_EQ(back[i].camera.look_at, frames[i].camera.look_at);
        EXPECT_EQ(back[i].camera.up, frames[i].camera.up);
        EXPECT_EQ(back[i].camera.vfov_deg, frames[i].camera.vfov_deg);
        EXPECT_EQ(back[i].frame, i);
    }
}

// Each bad file: the message names the file, the entry's key path and the reason.
TEST_F(CameraPath, RejectsBadEntriesNamingThem) {
    const std::string ok = R"({"position": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "vfov": 40)";
    struct Case {
        std::string text, key, reason;
    };
    const std::vector<Case> cases = {
        {R"({"cameras": []})", "'cameras'", "at least one camera"},
        {R"({"cameras": [)" + ok + R"(}, {"position": [0,0], "look_at": [0,0,-1], "up": [0,1,0], "vfov": 40}]})",
         "'cameras[1].position'", "3 numbers"},
        {R"({"cameras": [)" + ok + R"(, "vfov": 180}]})", "duplicate key 'cameras[0].vfov'", "once"},
        {R"({"cameras": [{"position": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "vfov": 180}]})",
         "'cameras[0].vfov' = 180", "(0, 180)"},
        {R"({"cameras": [)" + ok + R"(, "frame": -2}]})", "'cameras[0].frame' = -2", "0..999999"},
        {R"({"cameras": [)" + ok + R"(, "frame": 4294967296}]})", "'cameras[0].frame' = 4294967296", "out of range"},
        {R"({"cameras": [)" + ok + R"(, "frame": 1.5}]})", "'cameras[0].frame' = 1.5", "integer"},
        {R"({"cameras": [)" + ok + R"(, "fov": 30}]})", "'cameras[0].fov'", "did you mean 'vfov'"},
        {R"({"cameras": [)" + ok + R"(, "positon": [0,0,0]}]})", "'cameras[0].positon'", "did you mean 'position'"},
        {R"({"cameras": [)" + ok + "}], \"speed\": 2}", "'speed'", "known keys here: scene, cameras"},
        {R"({"scene": 3, "cameras": [)" + ok + "}]}", "'scene' = 3", "string"},
        // The third camera is degenerate: found before anything renders.
        {R"({"cameras": [)" + ok + "}, " + ok + R"(}, {"position": [0,0,0], "look_at": [0,1,0], "up": [0,1,0], "vfov": 40}]})",
         "'cameras[2]'", "parallel"},
        {R"({"cameras": [{"position": [0,0,0], "look_at": [0,0,-1], "up": [0,0,0], "vfov": 40}]})", "'cameras[0]'",
         "zero"},
        {R"({"cameras": [{"position": [0,3,0], "look_at": [0,0,1e-7], "up": [0,1,0], "vfov": 40}]})", "'cameras[0]'",
         "parallel"},
        {R"({"cameras": [{"position": [1,2,3], "look_at": [1,2,3], "up": [0,1,0], "vfov": 40}]})", "'cameras[0]'",
         "equals position"},
        {R"({"cameras": [{"position": [0,0,1e39], "look_at": [0,0,-1], "up": [0,1,0], "vfov": 40}]})",
         "'cameras[0].position[2]'", "float"},
        {"{\"cameras\": [", "path.json:1:", "malformed JSON"},
        {std::string(100, '[') + std::string(100, ']'), "path.json", "nested deeper than 64"},
    };
    for (const Case& c : cases) {
        const std::string e = error_of(c.text);
        EXPECT_CONTAINS(e, "--camera-path ");
        EXPECT_CONTAINS(e, "path.json");
        EXPECT_CONTAINS(e, c.key);
        EXPECT_CONTAINS(e, c.reason);
    }
    EXPECT_EQ(error_of(R"({"cameras": [)" + ok + "}]}"), "");
}

// A path that is a directory or missing: the file and what is wrong, not a stream error.
TEST_F(CameraPath, DirectoryOrMissingFileIsNamed) {
    for (const auto& [p, reason] : {std::pair{dir_, "is a directory"}, std::pair{dir_ / "none.json", "not found"}}) {
        try {
            read_camera_path(p);
            ADD_FAILURE() << p;
        } catch (const InputError& e) {
            EXPECT_CONTAINS(e.what(), "--camera-path " + p.string());
            EXPECT_CONTAINS(e.what(), reason);
        }
    }
}

}  // namespace
}  // namespace tessera::view
