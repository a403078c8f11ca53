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
    write_camera_path(dir_ / "p.json", frames);
    const std::vector<PathFrame> back = read_camera_path(dir_ / "p.json");
    ASSERT_EQ(back.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(back[i].camera.position, frames[i].camera.position);
        EXPECT_EQ(back[i].camera.look_at, frames[i].camera.look_at);
        EXPECT_EQ(back[i].camera.up, frames[i].camera.up);
        EXPECT_EQ(back[i].camera.vfov_deg, frames[i].camera.vfov_deg);
        EXPECT_EQ(back[i].frame, i);
    }
}

TEST_F(CameraPath, RejectsBadEntriesNamingThem) {
    const std::string ok = R"({"position": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "vfov": 40})";
    EXPECT_CONTAINS(error_of(R"({"cameras": []})"), "non-empty");
    EXPECT_CONTAINS(error_of(R"({"cameras": [)" + ok + R"(, {"position": [0,0], "look_at": [0,0,-1], "up": [0,1,0], "vfov": 40}]})"),
                    "cameras[1]: \"position\"");
    EXPECT_CONTAINS(error_of(R"({"cameras": [{"position": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "vfov": 180}]})"),
                    "\"vfov\"");
    EXPECT_CONTAINS(error_of(R"({"cameras": [{"position": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "vfov": 40, "frame": -2}]})"),
                    "\"frame\"");
    EXPECT_EQ(error_of(R"({"cameras": [)" + ok + "]}"), "");
}

}  // namespace
}  // namespace tessera::view
