// Backend::launch_count and launch_count_into (host/backend/backend.h): item kernels over
// work items 0..count-1 without a list, on both backends. Count 0 launches nothing (and
// keeps a placeholder input), a pixel kernel or a uint input is refused, and a launch over
// a tile's rows gives the kernel's per-row output (KernelId::EdgeSegmentCounts over known
// counts). Each launch's time is there to ask (kernel_seconds).
#include <memory>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/layout_igi.h"
#include "support/render_helpers.h"

namespace tessera {
namespace {

class LaunchCount : public ::testing::TestWithParam<BackendKind> {};

TEST_P(LaunchCount, CountsTilesWithoutAListAndRefusesWhatItCannotRun) {
    const Scene scene = test::cornell_box();
    SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = make_backend(BackendOptions{GetParam(), ""}, buffers, plan_effects(scene));
    TsFrame f{};
    f.width = 20;  // 2 × 2 tiles of 16, three of them partial: 64 segments, 18 of them empty
    f.height = 18;
    f.igi_tile = 3;
    // Pixel (x, y) takes (x + y) % 3 samples: per segment (row y % 16 of tile t), the sums
    // over its pixels.
    std::vector<float> counts(size_t(f.width) * f.height);
    uint32_t expected[64][2] = {};
    for (uint32_t y = 0; y < f.height; ++y)
        for (uint32_t x = 0; x < f.width; ++x) {
            const uint32_t n = (x + y) % 3, s = ((y / 16) * 2 + x / 16) * 16 + y % 16;
            counts[size_t(y) * f.width + x] = float(n);
            expected[s][0] += n;
            expected[s][1] += n > 0;
        }
    backend->set_input(KernelInput::EdgeCounts, counts);
    std::vector<float> out;
    backend->launch_count(KernelId::EdgeSegmentCounts, f, 64, out);
    ASSERT_EQ(out.size(), 64u * TS_EDGE_SEGMENT_FLOATS);
    for (int s = 0; s < 64; ++s) {
        EXPECT_EQ(out[s * TS_EDGE_SEGMENT_FLOATS + TS_EDGE_SEGMENT_SAMPLES], float(expected[s][0])) << s;
        EXPECT_EQ(out[s * TS_EDGE_SEGMENT_FLOATS + TS_EDGE_SEGMENT_FLAGGED], float(expected[s][1])) << s;
    }
    EXPECT_EQ(backend->dispatch_count(KernelId::EdgeSegmentCounts), 1u);

    backend->launch_count(KernelId::EdgeSegmentCounts, f, 0, out);
    EXPECT_TRUE(out.empty());
    backend->launch_count_into(KernelId::EdgeCompactSample, f, 0, KernelInput::EdgeSamples);
    std::vector<float> kept;
    backend->read_input(KernelInput::EdgeSamples, kept);
    EXPECT_EQ(kept, std::vector<float>(1, 0.0f));  // the placeholder
    EXPECT_EQ(backend->dispatch_count(KernelId::EdgeSegmentCounts), 1u);
    EXPECT_EQ(backend->dispatch_count(KernelId::EdgeCompactSample), 0u);

    EXPECT_THROW(backend->launch_count(KernelId::EdgeSchedule, f, 4, out), std::logic_error);
    EXPECT_THROW(backend->launch_count_into(KernelId::EdgeSchedule, f, 4, KernelInput::EdgeCounts), std::logic_error);
    EXPECT_THROW(backend->launch_count_into(KernelId::EdgeSegmentCounts, f, 4, KernelInput::EdgeSegmentOffsets),
                 std::logic_error);
}

// Backend::kernel_seconds: a launch kept where the kernels run (queued without a host wait
// on OpenCL) gives the same output as one read back, and its time once it has run (the
// device's timestamps on OpenCL, waited for); a call that launches nothing leaves 0.
TEST_P(LaunchCount, KernelSecondsTimeTheLastLaunchEvenWhenQueuedWithoutAWait) {
    const Scene scene = test::cornell_box();
    SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = make_backend(BackendOptions{GetParam(), ""}, buffers, plan_effects(scene));
    TsFrame f{};
    f.width = 512;  // 32 × 32 tiles of 16 pixels, 16 segments each
    f.height = 512;
    f.igi_tile = 3;
    std::vector<float> counts(size_t(f.width) * f.height);
    for (size_t p = 0; p < counts.size(); ++p) counts[p] = float(p % 5);
    backend->set_input(KernelInput::EdgeCounts, counts);
    const size_t segments = 32 * 32 * 16;
    EXPECT_EQ(backend->kernel_seconds(KernelId::EdgeSegmentCounts), 0.0);  // none yet
    std::vector<float> read_back, kept;
    backend->launch_count(KernelId::EdgeSegmentCounts, f, segments, read_back);
    EXPECT_GT(backend->kernel_seconds(KernelId::EdgeSegmentCounts), 0.0);
    backend->launch_count_into(KernelId::EdgeSegmentCounts, f, segments, KernelInput::EdgeSamples);
    const double seconds = backend->kernel_seconds(KernelId::EdgeSegmentCounts);
    EXPECT_GT(seconds, 0.0);
    EXPECT_LT(seconds, 60.0);
    backend->read_input(KernelInput::EdgeSamples, kept);
    EXPECT_EQ(kept, read_back);
    backend->launch_count(KernelId::EdgeSegmentCounts, f, 0, read_back);
    EXPECT_EQ(backend->kernel_seconds(KernelId::EdgeSegmentCounts), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Backends, LaunchCount, ::testing::Values(BackendKind::OpenCL, BackendKind::Embree),
                         [](const auto& info) { return info.param == BackendKind::OpenCL ? "OpenCL" : "Embree"; });

}  // namespace
}  // namespace tessera
