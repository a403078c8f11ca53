// Launch tiling and launch-failure messages (host/opencl/launch.h): tile sizes follow the
// measured rate within the budget, images are the same bit for bit with any tiling, and
// a failed launch says which device, kernel and error, and why it likely happened.
#include <filesystem>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "opencl/device.h"
#include "opencl/launch.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "support/render_helpers.h"

namespace tessera {
namespace {

TEST(TileSizer, UntimedLaunchesRunWhole) {
    TileSizer whole(0.0, 0, 8);
    EXPECT_FALSE(whole.timed());
    EXPECT_EQ(whole.next(1000), 1000u);
    TileSizer fixed(0.1, 3, 8);  // a fixed size wins over the budget
    EXPECT_FALSE(fixed.timed());
    EXPECT_EQ(fixed.next(1000), 3u);
    EXPECT_EQ(fixed.next(2), 2u);
}

TEST(TileSizer, TilesFollowTheMeasuredRateWithinTheBudget) {
    TileSizer s(0.125, 0, 8);  // 125 ms (times below are exact binary fractions)
    EXPECT_TRUE(s.timed());
    EXPECT_EQ(s.next(1000), 8u);  // first tile: no rate yet
    EXPECT_EQ(s.next(5), 5u);
    EXPECT_FALSE(s.has_rate());   // enqueue_tiled waits for this first tile to time it
    s.record(8, 0.015625);        // 512 groups/s: 64 fit in the budget, growth capped at 4 × 8
    EXPECT_TRUE(s.has_rate());
    EXPECT_EQ(s.next(1000), 32u);
    s.record(32, 0.03125);        // 1024 groups/s: 128 fit, cap 128
    EXPECT_EQ(s.next(1000), 128u);
    s.record(128, 0.25);          // 512 groups/s: shrink to 64
    EXPECT_EQ(s.next(1000), 64u);
    EXPECT_EQ(s.next(50), 50u);
    s.record(64, 1.0);            // a slow tile (64 groups/s): 8 fit
    EXPECT_EQ(s.next(1000), 8u);
    s.record(8, 100.0);           // slower than one group per budget: still one group
    EXPECT_EQ(s.next(1000), 1u);
}

TEST(LaunchFailure, MessageNamesDeviceKernelErrorAndCauses) {
    LaunchFailure f;
    f.device = "Example GPU";
    f.kernel = "igi_surface_pass";
    f.error = CL_OUT_OF_RESOURCES;
    f.call = "clFinish";
    f.tile_items = 4096;
    f.launch_items = 262144;
    f.budget_ms = 100.0;
    f.private_bytes = 700;
    f.work_group = 64;
    f.buffer_bytes = 3ull << 20;
    f.global_mem = 8ull << 30;
    const std::string m = launch_failure_message(f);
    for (const char* part : {"igi_surface_pass", "Example GPU", "CL_OUT_OF_RESOURCES (-5)", "clFinish",
                             "4096 of 262144 work-items", "watchdog", "about 100 ms", "TESSERA_CL_LAUNCH_MS",
                             "700 bytes per work-item (CL_KERNEL_PRIVATE_MEM_SIZE)", "44800 per work-group of 64",
                             "3.0 MiB of the device's 8192.0 MiB", "--backend embree"})
        EXPECT_NE(m.find(part), std::string::npos) << "missing \"" << part << "\" in: " << m;
    f.budget_ms = 0.0;
    f.private_bytes = 0;
    const std::string m2 = launch_failure_message(f);
    EXPECT_NE(m2.find("not tiled"), std::string::npos) << m2;
    EXPECT_NE(m2.find("does not report"), std::string::npos) << m2;
}

// A launch queued without a wait fails where the queue is next waited for: the message
// names the first launch whose event failed (user events stand in for the tiles' events).
TEST(LaunchFailure, AFailureFoundLaterIsPutOnTheLaunchThatFailed) {
    const ClDeviceInfo dev = select_cl_device("");
    cl::Context ctx(dev.device);
    cl::UserEvent done(ctx), failed(ctx), later(ctx), running(ctx);
    done.setStatus(CL_COMPLETE);
    failed.setStatus(CL_OUT_OF_RESOURCES);
    later.setStatus(CL_OUT_OF_RESOURCES);
    EXPECT_EQ(failed_launch({{"igi_surface_pass", done}, {"igi_media_pass", failed}, {"igi_resolve", later}}),
              "igi_media_pass");
    EXPECT_EQ(failed_launch({{"igi_surface_pass", done}, {"igi_media_pass", running}}), "");
    EXPECT_EQ(failed_launch({}), "");
    running.setStatus(CL_COMPLETE);  // a user event must end before its context goes
}

TEST(LaunchFailure, ResourceErrorsAreRecognised) {
    for (int e : {CL_OUT_OF_RESOURCES, CL_MEM_OBJECT_ALLOCATION_FAILURE, CL_OUT_OF_HOST_MEMORY, CL_INVALID_COMMAND_QUEUE})
        EXPECT_TRUE(is_resource_error(e)) << e;
    EXPECT_FALSE(is_resource_error(CL_INVALID_KERNEL_ARGS));
    EXPECT_EQ(cl_error_name(CL_INVALID_COMMAND_QUEUE), "CL_INVALID_COMMAND_QUEUE");
}

// Same images with any tiling: whole launches, tiles of one work-group (every launch
// split at every work-group boundary, offsets up to the last one), and tiles sized from
// measured times under a 1 µs budget (after the first tile, one work-group each, timed).
// Work-item i's output depends only on i. Packet and per-ray kernels both.
std::unique_ptr<Backend> tiled(const SceneBuffers& b, const Scene& s, bool packets, double ms, uint32_t groups) {
    BackendOptions o{BackendKind::OpenCL, ""};
    o.cl_packets = packets;
    o.cl_launch_ms = ms;
    o.cl_tile_groups = groups;
    return make_backend(o, b, plan_effects(s));
}

class TiledImages : public ::testing::TestWithParam<Method> {};

TEST_P(TiledImages, EqualWholeLaunchImagesBitForBit) {
    const Scene scene =
        load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box-fog.json", make_data_path(std::nullopt));
    SceneBuffers buffers = make_scene_buffers(scene);
    const RenderSettings rs = test::packet_test_settings(GetParam());
    for (bool packets : {true, false}) {
        const Image whole = render_frame(*tiled(buffers, scene, packets, 0.0, 0), scene, buffers, rs);
        test::expect_images_identical(whole, render_frame(*tiled(buffers, scene, packets, 0.0, 1), scene, buffers, rs));
        test::expect_images_identical(whole, render_frame(*tiled(buffers, scene, packets, 1e-3, 0), scene, buffers, rs));
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, TiledImages, ::testing::Values(Method::Igi, Method::Ais, Method::Ic),
                         [](const auto& info) { return test::method_param_name(info.param); });

}  // namespace
}  // namespace tessera
