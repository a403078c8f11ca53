// Frame ranges and output names of `tessera render --frames`, and render_sequence.
#include "render/sequence.h"

#include <vector>

#include <gtest/gtest.h>

#include "scene/animation.h"
#include "scene/scene_test_util.h"
#include "support/render_helpers.h"

namespace tessera {
namespace {

Scene with_frames(int n) {
    Scene s;
    s.name = "seq";
    s.animation.frame_count = n;
    return s;
}

std::string range_error(const std::string& text, const Scene& scene) {
    try {
        parse_frame_range(text, scene);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Sequence, ParsesFrameRanges) {
    const FrameRange r = parse_frame_range("3:7", with_frames(30));
    EXPECT_EQ(r.first, 3);
    EXPECT_EQ(r.last, 7);
    EXPECT_EQ(parse_frame_range("29:29", with_frames(30)).first, 29);
    EXPECT_EQ(parse_frame_range("0:0", with_frames(0)).last, 0);  // a still
}

TEST(Sequence, RejectsBadFrameRanges) {
    for (const char* bad : {"", "3", "3:", ":3", "a:b", "-1:2", "1:2:3", "1.5:2", " 1:2"})
        EXPECT_CONTAINS(range_error(bad, with_frames(30)), "--frames");
    EXPECT_CONTAINS(range_error("5:4", with_frames(30)), "before the first");
    EXPECT_CONTAINS(range_error("0:30", with_frames(30)), "frames 0..29");
    EXPECT_CONTAINS(range_error("0:1", with_frames(0)), "no animation");
}

TEST(Sequence, FrameOutputPath) {
    EXPECT_EQ(frame_output_path("out/box.exr", 7), std::filesystem::path("out/box.0007.exr"));
    EXPECT_EQ(frame_output_path("a.b/c.d.exr", 123), std::filesystem::path("a.b/c.d.0123.exr"));
    EXPECT_EQ(frame_output_path("box.exr", 12345), std::filesystem::path("box.12345.exr"));
    EXPECT_EQ(frame_output_path("box.exr", 9999, 5), std::filesystem::path("box.09999.exr"));
}

// A scene of more than 10,000 frames numbers every frame with as many digits as its last,
// so that the names sort in frame order (.9999 sorted after .10000); 4 digits otherwise.
TEST(Sequence, FrameNumbersHaveTheLastFramesDigits) {
    EXPECT_EQ(frame_number_digits(with_frames(0)), 4);
    EXPECT_EQ(frame_number_digits(with_frames(30)), 4);
    EXPECT_EQ(frame_number_digits(with_frames(10000)), 4);  // frames 0..9999
    EXPECT_EQ(frame_number_digits(with_frames(10001)), 5);
    EXPECT_EQ(frame_number_digits(with_frames(100000)), 5);
    EXPECT_EQ(frame_digits(-1), 4);  // no frames (a window session's unknown count)
    EXPECT_EQ(frame_digits(123456), 6);
}

TEST(Sequence, RendersEachFrameInOrder) {
    const Scene rest = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box-animated.json",
                                  make_data_path(std::nullopt));
    RenderSettings settings;
    settings.width = 8;
    settings.height = 8;
    settings.spp = 1;
    std::vector<int> frames;
    render_sequence(rest, {2, 4}, BackendOptions{BackendKind::Embree, ""}, settings,
                    [&](int frame, const Image& img, const RenderStats& stats, double seconds) {
                        frames.push_back(frame);
                        EXPECT_EQ(img.width, 8);
                        EXPECT_EQ(stats.passes, 1u);
                        EXPECT_GE(seconds, stats.seconds);
                    });
    EXPECT_EQ(frames, (std::vector<int>{2, 3, 4}));
}

// The sequence's one backend (Backend::set_scene per frame) renders each frame as a
// backend made for that frame alone does, bit for bit.
TEST(Sequence, FramesEqualRendersOnAFreshBackend) {
    const Scene rest = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box-animated.json",
                                  make_data_path(std::nullopt));
    RenderSettings settings;
    settings.method = Method::Igi;
    settings.width = settings.height = 16;
    settings.spp = 1;
    settings.igi.paths_per_set = 4;
    for (BackendKind kind : {BackendKind::OpenCL, BackendKind::Embree}) {
        int checked = 0;
        render_sequence(rest, {3, 5}, BackendOptions{kind, ""}, settings,
                        [&](int frame, const Image& img, const RenderStats&, double) {
                            const Image fresh = test::render_with(kind, scene_at_frame(rest, frame), settings);
                            const auto& a = img.find("R")->data;
                            const auto& b = fresh.find("R")->data;
                            EXPECT_EQ(a, b) << "frame " << frame;
                            checked += a.size() == 256 && test::channel_mean(fresh, "R") > 0.0;
                        });
        EXPECT_EQ(checked, 3);
    }
}

// --no-clamp-compensation reaches tic's cache, made once for the sequence
// (prepare_sequence) before any frame: a sequence's first frame is the frame rendered
// alone, whose cache is made with the frame, with and without the compensation.
TEST(Sequence, TicFirstFrameEqualsTheFrameAloneWithAndWithoutClampCompensation) {
    const Scene rest = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box-animated.json",
                                  make_data_path(std::nullopt));
    RenderSettings settings;
    settings.method = Method::Tic;
    settings.width = settings.height = 16;
    settings.spp = 1;
    settings.igi.paths_per_set = 4;
    settings.ic.paths = 16;
    std::vector<double> means;
    for (bool compensation : {true, false}) {
        settings.igi.clamp_compensation = compensation;
        int checked = 0;
        render_sequence(rest, {2, 2}, BackendOptions{BackendKind::Embree, ""}, settings,
                        [&](int frame, const Image& img, const RenderStats&, double) {
                            const Image alone =
                                test::render_with(BackendKind::Embree, scene_at_frame(rest, frame), settings);
                            EXPECT_EQ(img.find("R")->data, alone.find("R")->data) << "compensation " << compensation;
                            means.push_back(test::channel_mean(img, "R"));
                            ++checked;
                        });
        EXPECT_EQ(checked, 1);
    }
    // The compensation adds light: the two settings differ, so the test tells them apart.
    ASSERT_EQ(means.size(), 2u);
    EXPECT_GT(means[0], means[1]);
}

}  // namespace
}  // namespace tessera
