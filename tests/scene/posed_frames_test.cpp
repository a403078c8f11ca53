// PosedFrames: an animation's frames posed with the rest scene's motion bounds and frame
// 0's clamp length found once equal scene_at_frame's, which finds them per call.
#include "scene/posed_frames.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "scene/animation.h"
#include "scene/loader.h"
#include "util/error.h"

namespace tessera {
namespace {

void expect_same_pose(const Scene& a, const Scene& b, int frame) {
    EXPECT_EQ(a.positions, b.positions) << "frame " << frame;
    EXPECT_EQ(a.normals, b.normals) << "frame " << frame;
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t m = 0; m < a.materials.size(); ++m) EXPECT_EQ(a.materials[m], b.materials[m]) << "frame " << frame;
    EXPECT_EQ(a.camera.position, b.camera.position) << "frame " << frame;
    EXPECT_EQ(a.camera.look_at, b.camera.look_at) << "frame " << frame;
    EXPECT_EQ(a.motion_bounds, b.motion_bounds) << "frame " << frame;
    EXPECT_EQ(a.clamp_length, b.clamp_length) << "frame " << frame;
}

TEST(PosedFrames, EveryFrameEqualsSceneAtFrame) {
    const Scene rest = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box-animated.json",
                                  make_data_path(std::nullopt));
    const PosedFrames frames(rest);
    for (int f = 0; f < rest.animation.frame_count; f += 7) expect_same_pose(frames.at(f), scene_at_frame(rest, f), f);
    const Scene last = frames.at(rest.animation.frame_count - 1);
    expect_same_pose(last, scene_at_frame(rest, rest.animation.frame_count - 1), rest.animation.frame_count - 1);
    // The object moves, so there is a D of frame 0's and a box it moves in.
    EXPECT_GT(last.clamp_length, 0.0f);
    EXPECT_FALSE(last.motion_bounds.empty());
    EXPECT_NE(last.positions, rest.positions);
}

TEST(PosedFrames, AStillSceneHasNoClampLengthAndRefusesFramesAsSceneAtFrame) {
    const Scene still = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box.json",
                                   make_data_path(std::nullopt));
    const PosedFrames frames(still);
    expect_same_pose(frames.at(0), scene_at_frame(still, 0), 0);
    EXPECT_EQ(frames.at(0).clamp_length, 0.0f);
    EXPECT_THROW(frames.at(1), InputError);
    EXPECT_THROW(frames.at(-1), InputError);
}

}  // namespace
}  // namespace tessera
