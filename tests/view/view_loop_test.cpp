// The frame loop shared by the window and --headless: a replayed path sets the camera of
// each frame (a repeated camera accumulates), scripted events arrive at their frames,
// and per-frame times, images and a recorded path are written.
#include "view/view_loop.h"

#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "render/sequence.h"
#include "scene/loader.h"
#include "support/scratch_dir.h"
#include "view/camera_control.h"

namespace tessera::view {
namespace {

class ViewLoopTest : public test::ScratchDirTest {
protected:
    Scene scene_ = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box.json",
                              make_data_path(std::nullopt));
    ViewOptions options() const {
        ViewOptions o;
        o.backend = {BackendKind::Embree, ""};
        o.settings.method = Method::Igi;
        o.settings.width = o.settings.height = 16;
        o.settings.spp = 100;
        o.screenshot = dir_ / "shot.exr";
        return o;
    }
};

TEST_F(ViewLoopTest, ReplaysAPathAccumulatingWhereTheCameraRests) {
    std::vector<PathFrame> path;
    for (int i = 0; i < 3; ++i) path.push_back({move_camera(scene_.camera, {1, 0, 0}, 0.01f * i), 0});
    for (int i = 0; i < 2; ++i) path.push_back(path.back());
    ViewSession session(scene_, options());
    LoopOptions lo;
    lo.path = path;
    lo.headless = true;
    lo.fixed_dt = true;
    lo.times = dir_ / "times.json";
    lo.frame_images = dir_;
    ViewLoop loop(session, lo);
    while (!loop.done()) loop.step(0.0);
    loop.finish(scene_.name);
    ASSERT_EQ(loop.times().size(), 5u);
    // Frame 0 starts the accumulation: the run's start, not a move.
    const bool moving[] = {false, true, true, false, false};
    // Frames 1 and 2 move 1% and keep frame 0's view points (ViewPointHistory), so the
    // first frame at rest starts over with the camera's own, as render has them.
    const uint32_t passes[] = {1, 1, 1, 1, 2};
    for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(loop.times()[i].report.moving, moving[i]) << i;
        EXPECT_EQ(loop.times()[i].report.passes, passes[i]) << i;
        EXPECT_TRUE(std::filesystem::exists(frame_output_path(dir_ / "frame.exr", i))) << i;
    }
    EXPECT_FALSE(camera_differs(session.camera(), path.back().camera));
    std::ifstream in(dir_ / "times.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["frames"].size(), 5u);
    EXPECT_EQ(j["moving_frames"].get<int>(), 2);
    EXPECT_GT(j["frames"][0]["ms"].get<double>(), 0.0);
    EXPECT_GT(j["frames"][0]["rays"].get<double>(), 0.0);
    EXPECT_TRUE(j["frames"][4]["stages_ms"].contains("surface"));
}

TEST_F(ViewLoopTest, ScriptedEventsArriveAtTheirFramesAndTheHeadlessRunStopsAfterThem) {
    ViewSession session(scene_, options());
    LoopOptions lo;
    lo.headless = true;
    lo.fixed_dt = true;
    lo.script = {{1, {InputEvent::Kind::Press, 'W'}}, {3, {InputEvent::Kind::Release, 'W'}},
                 {4, {InputEvent::Kind::Press, 'P'}}};
    lo.record = dir_ / "recorded.json";
    ViewLoop loop(session, lo);
    while (!loop.done()) loop.step(123.0);  // ignored: fixed 1/30 s steps
    loop.finish(scene_.name);
    EXPECT_EQ(loop.frame(), 5);
    const std::vector<PathFrame> recorded = read_camera_path(dir_ / "recorded.json");
    ASSERT_EQ(recorded.size(), 5u);
    EXPECT_FALSE(camera_differs(recorded[0].camera, scene_.camera));
    // Frames 1 and 2 move forward by speed / 30 each; 3 and 4 rest.
    const float step = default_speed(scene_) / 30.0f;
    EXPECT_NEAR(glm::length(recorded[2].camera.position - scene_.camera.position), 2 * step, 1e-5f);
    EXPECT_FALSE(camera_differs(recorded[3].camera, recorded[2].camera));
    // Frame 2's short step kept frame 1's view points: frame 3, the first at rest, starts
    // over (ViewPointHistory), frame 4 adds its second pass.
    EXPECT_EQ(loop.times()[4].report.passes, 2u);
    EXPECT_TRUE(std::filesystem::exists(dir_ / "shot.0000.exr"));  // the P key
    EXPECT_TRUE(std::filesystem::exists(dir_ / "shot.0000.png"));
}

// P before the first pass (frame 0) has no accumulation to write: the screenshot is taken
// once the frame's pass is in (it crashed the viewer), and holds that one pass.
TEST_F(ViewLoopTest, ScreenshotOnFrameZeroIsTakenAfterItsPass) {
    ViewSession session(scene_, options());
    LoopOptions lo;
    lo.headless = true;
    lo.fixed_dt = true;
    lo.script = {{0, {InputEvent::Kind::Press, 'P'}}};
    ViewLoop loop(session, lo);
    while (!loop.done()) loop.step(0.0);
    ASSERT_TRUE(std::filesystem::exists(dir_ / "shot.0000.exr"));
    EXPECT_TRUE(std::filesystem::exists(dir_ / "shot.0000.png"));
    EXPECT_FALSE(std::filesystem::exists(dir_ / "shot.0001.exr"));
    EXPECT_EQ(loop.times()[0].report.passes, 1u);
}

}  // namespace
}  // namespace tessera::view
