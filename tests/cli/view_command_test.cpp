// `tessera view` as a user runs it. Headless (no window, no OpenGL): a fly-through writes
// per-frame times and images, and the screenshot key's EXR equals `tessera render` with
// the same camera, method, seed and passes. Windowed, under Xvfb with Mesa's software
// OpenGL (skipped when this build has no window module or Xvfb is missing): the same
// screenshot and fly-through checks through the window, keys sent by an input script and
// by xdotool, and a window without a display fails with one line suggesting render.
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <stb_image.h>
#include <nlohmann/json.hpp>

#include "image/image_io.h"
#include "render/sequence.h"
#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;

namespace {

using tessera::Image;
using tessera::test::CliResult;
using tessera::test::run_shell;
using tessera::test::run_tessera;

const std::string kScenes = TESSERA_SCENES_DIR;

// Equal within float rounding (the viewer runs render's code, so bit for bit in practice),
// and not black.
void expect_same_image(const fs::path& a_path, const fs::path& b_path) {
    const Image a = tessera::read_exr(a_path), b = tessera::read_exr(b_path);
    double peak = 0;
    for (const char* c : {"R", "G", "B"}) {
        const auto* x = a.find(c);
        const auto* y = b.find(c);
        ASSERT_TRUE(x && y) << c;
        ASSERT_EQ(x->data.size(), y->data.size());
        for (size_t i = 0; i < x->data.size(); ++i) {
            ASSERT_NEAR(x->data[i], y->data[i], 1e-6f * std::max(1.0f, std::fabs(y->data[i])))
                << a_path << " vs " << b_path << " " << c << " pixel " << i;
            peak = std::max(peak, double(y->data[i]));
        }
    }
    EXPECT_GT(peak, 0.0);
}

// Two cameras moving right, then the last one three more times (at rest).
std::string fly_through() {
    std::string cams;
    for (int i = 0; i < 5; ++i) {
        const double x = 0.278 + 0.01 * std::min(i, 1);
        cams += std::string(i ? "," : "") + "{\"position\": [" + std::to_string(x) + ", 0.273, -0.8], \"look_at\": [" +
                std::to_string(x) + ", 0.273, 0.0], \"up\": [0, 1, 0], \"vfov\": 39.3077}";
    }
    return "{\"cameras\": [" + cams + "]}";
}

// The window tests run in the normal suite. Under AddressSanitizer (the CI's second,
// sanitized suite) they skip: they would check Mesa's llvmpipe, LLVM and Xlib as much as
// our module, and that combination has not been validated under ASan.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

bool window_tests_possible() {
    return !kSanitized && fs::exists(fs::path(TESSERA_EXE).parent_path() / "libtessera_view_window.so") &&
           tessera::test::shell_status("command -v Xvfb >/dev/null") == 0;
}

// `command` under a fresh Xvfb screen (tests/support/with-xvfb: a display no other test
// can take) with Mesa's software OpenGL.
std::string with_xvfb(const std::string& command) {
    const fs::path script = fs::path(TESSERA_TEST_DATA).parent_path() / "support" / "with-xvfb";
    return "env LIBGL_ALWAYS_SOFTWARE=1 sh " + script.string() + " " + command;
}

// The tessera command line under a fresh Xvfb screen.
std::string under_xvfb(const std::string& args) { return with_xvfb(std::string(TESSERA_EXE) + " " + args); }

class ViewCli : public tessera::test::ScratchDirTest {
protected:
    fs::path write(const std::string& name, const std::string& text) {
        std::ofstream(dir_ / name) << text;
        return dir_ / name;
    }
    // A screenshot after `spp` passes at rest (key P at frame spp + 2) and quit.
    std::string screenshot_script(int spp) {
        return write("shot.json", "{\"events\": [{\"frame\": " + std::to_string(spp + 2) + ", \"tap\": \"p\"}, " +
                                      "{\"frame\": " + std::to_string(spp + 3) + ", \"quit\": true}]}")
            .string();
    }
    void expect_screenshot_equals_render(const std::string& view_command, const std::string& backend,
                                         const std::string& method) {
        const std::string common = " --width 32 --height 32 --spp 3 --seed 5 --backend " + backend + " --method " + method;
        const CliResult v = run_shell(view_command + common + " --input-script " + screenshot_script(3) +
                                      " --screenshot " + (dir_ / "view.exr").string());
        ASSERT_EQ(v.exit_code, 0) << v.output;
        EXPECT_NE(v.output.find("screenshot of 3 passes"), std::string::npos) << v.output;
        const CliResult r = run_tessera("render" + common + " --out " + (dir_ / "render.exr").string());
        ASSERT_EQ(r.exit_code, 0) << r.output;
        expect_same_image(dir_ / "view.0000.exr", dir_ / "render.exr");
        EXPECT_TRUE(fs::exists(dir_ / "view.0000.png"));
    }
};

TEST_F(ViewCli, HeadlessScreenshotEqualsRender) {
    for (const char* backend : {"embree", "opencl"})
        for (const char* method : {"igi", "ais"}) {
            SCOPED_TRACE(std::string(backend) + " " + method);
            expect_screenshot_equals_render(std::string(TESSERA_EXE) + " view --headless", backend, method);
        }
}

TEST_F(ViewCli, HeadlessFlyThroughWritesTimesAndImages) {
    const fs::path path = write("path.json", fly_through());
    const CliResult r = run_tessera("view --headless --backend embree --width 32 --height 32 --camera-path " +
                                    path.string() + " --times " + (dir_ / "times.json").string() + " --frame-images " +
                                    (dir_ / "frames").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::ifstream in(dir_ / "times.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j["frames"].size(), 5u);
    // Frame 0 starts the accumulation (not a move); frame 1 moves.
    EXPECT_EQ(j["moving_frames"].get<int>(), 1);
    EXPECT_FALSE(j["frames"][0]["moving"].get<bool>());
    for (int i = 0; i < 5; ++i) {
        EXPECT_GT(j["frames"][i]["ms"].get<double>(), 0.0);
        // Frame 1's 1 cm step keeps frame 0's view points (ViewPointHistory): frame 2, the
        // first at rest, starts over with the camera's own, as render has them.
        EXPECT_EQ(j["frames"][i]["passes"].get<int>(), i < 3 ? 1 : i - 1);
        EXPECT_TRUE(fs::exists(tessera::frame_output_path(dir_ / "frames/frame.exr", i)));
    }
    EXPECT_NE(r.output.find("5 frames, 1 moving"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("was recorded on scene"), std::string::npos) << r.output;  // the path names none
}

// A view never moved has no moving-frame rate: the closing line says so (it counted
// frame 0, the run's start, as a move: "4 frames, 1 moving").
TEST_F(ViewCli, AStillRunHasNoMovingFrames) {
    const fs::path script = write("still.json", R"({"events": [{"frame": 3, "quit": true}]})");
    const CliResult r = run_tessera("view --headless --backend embree --width 16 --height 16 --input-script " +
                                    script.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("tessera view: 3 frames, none moving, 3 passes at the end"), std::string::npos) << r.output;
}

// T plays --frames; without them it did nothing, silently. On a static scene it says
// there is no animation (--frames 0:1 is refused there); on an animated one, which
// frames --frames may give.
TEST_F(ViewCli, TWithoutFramesSaysWhatItNeeds) {
    const fs::path script = write("t.json", R"({"events": [{"frame": 1, "tap": "t"}, {"frame": 2, "quit": true}]})");
    const std::string view = "view --headless --backend embree --width 16 --height 16 --input-script " + script.string();
    const CliResult still = run_tessera(view);
    ASSERT_EQ(still.exit_code, 0) << still.output;
    EXPECT_NE(still.output.find("T plays an animation; this scene has none"), std::string::npos) << still.output;
    const CliResult animated = run_tessera(view + " " + (fs::path(kScenes) / "cornell-box-animated.json").string());
    ASSERT_EQ(animated.exit_code, 0) << animated.output;
    EXPECT_NE(animated.output.find("T plays the frames of --frames FIRST:LAST (this scene has frames 0.."),
              std::string::npos)
        << animated.output;
    EXPECT_NE(animated.output.find("this run shows frame 0 only)"), std::string::npos) << animated.output;
}

// A path that names the scene it was recorded on: a note when replayed on another one.
TEST_F(ViewCli, APathOfAnotherSceneGetsANote) {
    std::string text = fly_through();
    text.insert(1, "\"scene\": \"sibenik\", ");
    const fs::path path = write("path.json", text);
    const CliResult r = run_tessera("view --headless --backend embree --width 16 --height 16 --camera-path " +
                                    path.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("tessera view: note: --camera-path " + path.string() +
                            " was recorded on scene sibenik; this run's scene is cornell-box"),
              std::string::npos) << r.output;
}

std::string file_bytes(const fs::path& p);

// --reference's error, the HUD's figure, also ends a headless run: on the summary line
// and in --times (null without a reference). The view of a render's own settings is that
// render to the bit (HeadlessScreenshotEqualsRender), so its error is 0.
TEST_F(ViewCli, HeadlessRunReportsTheErrorAgainstTheReference) {
    const std::string common = " --width 16 --height 16 --method direct --spp 2 --backend embree";
    const fs::path same = dir_ / "same.exr", other = dir_ / "other.exr", times = dir_ / "t.json";
    ASSERT_EQ(run_tessera("render" + common + " --seed 5 --out " + same.string()).exit_code, 0);
    ASSERT_EQ(run_tessera("render" + common + " --seed 9 --out " + other.string()).exit_code, 0);
    const fs::path script = write("quit.json", R"({"events": [{"frame": 5, "quit": true}]})");
    const auto view = [&](const std::string& reference) {
        const CliResult r = run_tessera("view --headless" + common + " --seed 5 --input-script " + script.string() +
                                        reference + " --times " + times.string());
        EXPECT_EQ(r.exit_code, 0) << r.output;
        return std::make_pair(r.output, nlohmann::json::parse(file_bytes(times))["relmse_vs_reference"]);
    };
    const auto [text_same, json_same] = view(" --reference " + same.string());
    EXPECT_NE(text_same.find("2 passes at the end, relMSE vs reference 0.000000"), std::string::npos) << text_same;
    EXPECT_EQ(json_same.get<double>(), 0.0);
    const auto [text_other, json_other] = view(" --reference " + other.string());
    EXPECT_GT(json_other.get<double>(), 1e-4) << text_other;
    const auto [text_none, json_none] = view("");
    EXPECT_TRUE(json_none.is_null());
    EXPECT_EQ(text_none.find("relMSE"), std::string::npos) << text_none;
}

std::string file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Screenshots are numbered from 0000 in every session, so an earlier session's screenshot
// given as --reference would be replaced by the second P: that number is skipped (said on
// stderr), the reference is left as it was, and a --times file of a screenshot's name too.
TEST_F(ViewCli, LaterScreenshotsStepOverTheRunsOtherFiles) {
    const std::string common = " --headless --width 16 --height 16 --method direct --spp 2 --backend embree";
    const fs::path ref = dir_ / "shot.0001.exr";
    ASSERT_EQ(run_tessera("render" + common.substr(11) + " --out " + ref.string()).exit_code, 0);
    const std::string before = file_bytes(ref);
    const fs::path script =
        write("s.json", R"({"events": [{"frame": 3, "tap": "p"}, {"frame": 4, "tap": "p"}, {"frame": 5, "tap": "p"}, )"
                        R"({"frame": 6, "quit": true}]})");
    const CliResult r = run_tessera("view" + common + " --reference " + ref.string() + " --input-script " +
                                    script.string() + " --times " + (dir_ / "shot.0002.png").string() +
                                    " --screenshot " + (dir_ / "shot.exr").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(file_bytes(ref), before) << "the reference was replaced";
    EXPECT_NE(r.output.find("screenshot 1 skipped: " + ref.string()), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("screenshot 2 skipped: " + (dir_ / "shot.0002.png").string()), std::string::npos)
        << r.output;
    for (const char* shot : {"shot.0000.exr", "shot.0003.exr", "shot.0004.exr"})
        EXPECT_TRUE(fs::exists(dir_ / shot)) << shot << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "shot.0002.exr"));
    EXPECT_TRUE(nlohmann::json::parse(file_bytes(dir_ / "shot.0002.png")).contains("frames"))
        << "--times holds its JSON, not a screenshot";
}

// SIGINT ends the run as Esc does, after the frame in progress: exit 130, one line, and
// --times and --frame-images hold every frame rendered (before, the signal killed the
// process, leaving frame images and no times).
TEST_F(ViewCli, SignalEndsTheRunKeepingItsFrames) {
    std::string cams;
    for (int i = 0; i < 3000; ++i)  // far longer than the test waits
        cams += std::string(i ? "," : "") + "{\"position\": [0.278, 0.273, " + std::to_string(-0.8 + 1e-4 * i) +
                "], \"look_at\": [0.278, 0.273, 0.0], \"up\": [0, 1, 0], \"vfov\": 39.3077}";
    const fs::path path = write("long.json", "{\"cameras\": [" + cams + "]}");
    bool sent = false;
    const CliResult r = tessera::test::run_watched(
        {TESSERA_EXE, "view", "--headless", "--backend", "embree", "--method", "igi", "--width", "16", "--height", "16",
         "--camera-path", path.string(), "--times", (dir_ / "times.json").string(), "--frame-images",
         (dir_ / "frames").string()},
        true, [&](pid_t pid, const std::string& out) {
            if (!sent && out.find("tessera view: cornell-box") != std::string::npos) ::kill(pid, SIGINT), sent = true;
        });
    ASSERT_TRUE(sent) << r.output;
    EXPECT_EQ(r.exit_code, 130) << r.output;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.output, m, std::regex("tessera: interrupted after ([0-9]+) viewer frames"))) << r.output;
    const size_t frames = std::stoul(m[1]);
    EXPECT_LT(frames, 3000u);
    std::ifstream in(dir_ / "times.json");
    ASSERT_TRUE(in) << r.output;
    EXPECT_EQ(nlohmann::json::parse(in)["frames"].size(), frames);
    size_t images = 0;  // the signal may come before the first frame: then no directory either
    if (fs::exists(dir_ / "frames"))
        for (const auto& e : fs::directory_iterator(dir_ / "frames")) images += e.path().extension() == ".exr";
    EXPECT_EQ(images, frames);
}

// Six cameras, each moved: every frame a moving frame.
std::string moving_path() {
    std::string cams;
    for (int i = 0; i < 6; ++i) {
        const std::string x = std::to_string(0.278 + 0.01 * i);
        cams += std::string(i ? "," : "") + "{\"position\": [" + x + ", 0.273, -0.8], \"look_at\": [" + x +
                ", 0.273, 0.0], \"up\": [0, 1, 0], \"vfov\": 39.3077}";
    }
    return "{\"cameras\": [" + cams + "]}";
}

// A target no frame can meet (1 ms for a 64x64 AIS frame at the floor scale; a 16x16 one
// came within 1 ms once the VPL stage got faster): the budget goes to its floor scale,
// --times says the scale and setting of every frame, the frames are written at the
// window's size, and one line says the target is out of reach with the rate reached.
TEST_F(ViewCli, TargetOutOfReachIsSaidOnceWithTheRate) {
    const fs::path path = write("path.json", moving_path());
    const CliResult r = run_tessera("view --headless --backend embree --method ais --width 128 --height 128 "
                                    "--target-fps 1000 --min-scale 0.5 --camera-path " + path.string() + " --times " +
                                    (dir_ / "times.json").string() + " --frame-images " + (dir_ / "frames").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const size_t line = r.output.find("--target-fps 1000 is out of reach: ");
    ASSERT_NE(line, std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("out of reach", r.output.find('\n', line)), std::string::npos) << "said once: " << r.output;
    EXPECT_NE(r.output.find("at the cheapest choice (scale 0.50, 64x64, tile ", line), std::string::npos) << r.output;
    std::ifstream in(dir_ / "times.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["target_fps"].get<double>(), 1000.0);
    ASSERT_EQ(j["frames"].size(), 6u);
    for (const auto& f : j["frames"]) {
        const auto& b = f["budget"];
        const double scale = b["scale"].get<double>();
        EXPECT_GE(scale, 0.5);
        EXPECT_LE(scale, 1.0);
        EXPECT_EQ(b["width"].get<int>(), static_cast<int>(std::lround(128 * scale)));
        EXPECT_GE(b["tile"].get<int>(), 1);
    }
    EXPECT_TRUE(j["frames"][5]["budget"]["out_of_reach"].get<bool>());
    const Image last = tessera::read_exr(tessera::frame_output_path(dir_ / "frames/frame.exr", 5));
    EXPECT_EQ(last.width, 128);
    EXPECT_EQ(last.height, 128);
}

TEST_F(ViewCli, BadOptionsGiveOneClearMessage) {
    struct Case {
        std::string args, needle;
    };
    const std::vector<Case> cases = {
        {"--headless", "--camera-path or --input-script"},
        {"--headless --record --camera-path x.json", "--record"},
        {"--headless --input-script " + write("bad.json", "{\"events\": [{\"frame\": 0}]}").string(), "events[0]"},
        {"--headless --camera-path " + (dir_ / "none.json").string(), "none.json"},
        {"--headless --input-script x --method magic", "--method"},
        {"--headless --input-script x --tile 9", "--tile 9"},
        {"--headless --input-script " + write("ok.json", "{\"events\": []}").string() + " --screenshot a.png",
         "must end in .exr"},
    };
    for (const Case& c : cases) {
        const CliResult r = run_tessera("view --backend embree " + c.args);
        EXPECT_NE(r.exit_code, 0) << c.args;
        EXPECT_NE(r.output.find("tessera: error:"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(c.needle), std::string::npos) << c.args << " should name " << c.needle << ":\n" << r.output;
    }
}

TEST_F(ViewCli, NoDisplayIsOneLineSuggestingRender) {
    const CliResult r = run_tessera("view --backend embree", "env -u DISPLAY -u WAYLAND_DISPLAY");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find("tessera render"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--headless"), std::string::npos) << r.output;
    if (window_tests_possible()) {
        EXPECT_NE(r.output.find("no display"), std::string::npos) << r.output;
    }
}

class ViewWindowCli : public ViewCli {
protected:
    void SetUp() override {
        ViewCli::SetUp();
        if (!window_tests_possible())
            GTEST_SKIP() << "no window module in this build, no Xvfb, or a sanitized build";
    }
};

TEST_F(ViewWindowCli, ScreenshotKeyEqualsRender) {
    for (const char* backend : {"embree", "opencl"}) {
        SCOPED_TRACE(backend);
        expect_screenshot_equals_render(under_xvfb("view"), backend, "igi");
    }
}

// A window's frames are not known at the start: a frame image that is the run's
// --reference is skipped, said on stderr, and the reference is left as it was.
TEST_F(ViewWindowCli, FrameImagesStepOverTheReference) {
    const std::string common = " --width 16 --height 16 --method direct --spp 2 --backend embree";
    fs::create_directories(dir_ / "fi");
    const fs::path ref = dir_ / "fi" / "frame.0002.exr";
    ASSERT_EQ(run_tessera("render" + common + " --out " + ref.string()).exit_code, 0);
    const std::string before = file_bytes(ref);
    const fs::path script = write("s.json", R"({"events": [{"frame": 4, "quit": true}]})");
    const CliResult r = run_shell(under_xvfb("view" + common + " --reference " + ref.string() + " --input-script " +
                                             script.string() + " --frame-images " + (dir_ / "fi").string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(file_bytes(ref), before) << "the reference was replaced";
    EXPECT_NE(r.output.find("frame image 2 skipped: " + ref.string()), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir_ / "fi" / "frame.0003.exr")) << r.output;
}

TEST_F(ViewWindowCli, FlyThroughGivesTheHeadlessImages) {
    const fs::path path = write("path.json", fly_through());
    const std::string common = "view --backend embree --width 32 --height 32 --camera-path " + path.string();
    const CliResult w = run_shell(under_xvfb(common + " --frame-images " + (dir_ / "window").string()));
    ASSERT_EQ(w.exit_code, 0) << w.output;
    const CliResult h = run_tessera(common + " --headless --frame-images " + (dir_ / "headless").string());
    ASSERT_EQ(h.exit_code, 0) << h.output;
    for (int i = 0; i < 5; ++i)
        expect_same_image(tessera::frame_output_path(dir_ / "window/frame.exr", i),
                          tessera::frame_output_path(dir_ / "headless/frame.exr", i));
}

// Real key events through the X server: W moves, C prints the camera, P takes a
// screenshot, Escape quits; Alt+M is the desktop's, not the viewer's (M switches igi to
// ais). The screenshot must equal an igi render of the printed camera with the pass count
// the viewer reports (however many passes the machine managed).
TEST_F(ViewWindowCli, XdotoolKeysMoveAndScreenshot) {
    if (tessera::test::shell_status("command -v xdotool >/dev/null") != 0) GTEST_SKIP() << "no xdotool";
    const std::string view = std::string(TESSERA_EXE) + " view --backend embree --width 32 --height 32 --spp 6 --seed 3" +
                             " --screenshot " + (dir_ / "key.exr").string();
    const std::string keys =
        "id=$(xdotool search --sync --onlyvisible --name 'Tessera') && xdotool windowfocus --sync $id && "
        "xdotool keydown w && sleep 0.3 && xdotool keyup w && sleep 1 && xdotool key alt+m && xdotool key c && "
        "xdotool key p && "
        "sleep 0.5 && xdotool key Escape";
    const std::string script = write("keys.sh", "#!/bin/sh\n" + view + " &\npid=$!\n(" + keys + ")\nwait $pid\n").string();
    const CliResult r = run_shell("timeout 120 " + with_xvfb("sh " + script));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::smatch camera, passes;
    ASSERT_TRUE(std::regex_search(r.output, camera, std::regex("\"camera\": \\{[^}]*\\}"))) << r.output;
    ASSERT_TRUE(std::regex_search(r.output, passes, std::regex("screenshot of ([0-9]+) pass"))) << r.output;
    const nlohmann::json cam = nlohmann::json::parse("{" + camera.str() + "}")["camera"];
    EXPECT_GT(cam["position"][2].get<double>(), -0.8 + 1e-3) << "W must move the camera forward (+z)";
    // The scene file with the printed camera; its mesh is found on the data path.
    const fs::path scene = write("moved.json", "{" + camera.str() +
                                                   ", \"objects\": [{\"mesh\": \"cornell-box.obj\", \"transform\": "
                                                   "{\"scale\": 0.001}}]}");
    const CliResult render = run_tessera("render " + scene.string() + " --data-dir " + kScenes +
                                         " --backend embree --method igi --width 32 --height 32 --seed 3 --spp " +
                                         passes[1].str() + " --out " + (dir_ / "render.exr").string());
    ASSERT_EQ(render.exit_code, 0) << render.output;
    expect_same_image(dir_ / "key.0000.exr", dir_ / "render.exr");
}

// A window viewer run steered from a shell script under its own Xvfb (XVFB_PID is the
// server's): `steps` runs once the window is up, with $id the window and $pid the viewer.
class ViewWindowScript : public ViewWindowCli {
protected:
    void SetUp() override {
        ViewWindowCli::SetUp();
        if (tessera::test::shell_status("command -v xdotool >/dev/null") != 0) GTEST_SKIP() << "no xdotool";
    }
    CliResult run_steered(const std::string& view_args, const std::string& steps) {
        const std::string view = std::string(TESSERA_EXE) + " view --backend embree --width 32 --height 32 --spp 2 " +
                                 view_args + " --times " + (dir_ / "times.json").string();
        const std::string script =
            write("steer.sh", "#!/bin/sh\n" + view + " &\npid=$!\nid=$(xdotool search --sync --onlyvisible --name "
                              "'Tessera') && xdotool windowfocus --sync $id && " + steps + "\nwait $pid\n")
                .string();
        return run_shell("timeout 120 " + with_xvfb("sh " + script));
    }
    size_t frames_in_times() {
        std::ifstream in(dir_ / "times.json");
        return in ? nlohmann::json::parse(in)["frames"].size() : 0;
    }
};

// A window resized from outside (it is made not resizable, but a window manager or a
// client can resize it anyway) shows the image at its aspect, centred between black
// bars: the 32x32 image in a 96x48 window is 48x48 at columns 24..71 (it was stretched
// over all 96). The window is read back at frame 150, some 5 s of the converged view's
// 30 frames a second, long after the resize.
TEST_F(ViewWindowScript, AResizedWindowKeepsTheImageAspect) {
    const fs::path shot = dir_ / "window.png";
    const CliResult r = run_steered("--screenshot-window " + shot.string() + " --screenshot-window-frame 150",
                                    "xdotool windowsize --sync $id 96 48 && xdotool key h && "
                                    "while [ ! -s " + shot.string() + " ]; do sleep 0.2; done && xdotool key Escape");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    int w = 0, h = 0, comp = 0;
    unsigned char* rgba = stbi_load(shot.c_str(), &w, &h, &comp, 4);
    ASSERT_NE(rgba, nullptr) << stbi_failure_reason();
    std::vector<int> lit(w, 0);  // pixels other than black, per column
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) lit[x] += rgba[4 * (y * w + x)] + rgba[4 * (y * w + x) + 1] + rgba[4 * (y * w + x) + 2] > 0;
    stbi_image_free(rgba);
    ASSERT_EQ(w, 96);
    ASSERT_EQ(h, 48);
    for (int x = 0; x < w; ++x) {
        if (x < 24 || x >= 72)
            EXPECT_EQ(lit[x], 0) << "column " << x << " is outside the image";
        else
            EXPECT_GT(lit[x], h / 2) << "column " << x << " is inside the image";
    }
}

// A window destroyed from outside ends the run as closing it does (Xlib's default
// handler exited 1 with BadWindow, writing no --times and no closing line).
TEST_F(ViewWindowScript, ADestroyedWindowEndsTheRunAsClosed) {
    const CliResult r = run_steered("", "sleep 1 && xdotool windowclose $id");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    // BadWindow or BadDrawable, by which request first meets the missing window.
    EXPECT_NE(r.output.find("the window was destroyed (X error: Bad"), std::string::npos) << r.output;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.output, m, std::regex("tessera view: ([0-9]+) frames"))) << r.output;
    EXPECT_EQ(frames_in_times(), std::stoul(m[1])) << r.output;
}

// A lost X connection (the server ended, or a client killed the viewer's:
// `xdotool windowkill`) ends the run with one error line, the frames' --times written.
TEST_F(ViewWindowScript, ALostDisplayEndsTheRunWritingItsFrames) {
    for (const char* cut : {"kill $XVFB_PID", "xdotool windowkill $id"}) {
        SCOPED_TRACE(cut);
        const CliResult r = run_steered("", std::string("sleep 1 && ") + cut);
        EXPECT_EQ(r.exit_code, 1) << r.output;
        std::smatch m;
        ASSERT_TRUE(std::regex_search(r.output, m,
                                      std::regex("tessera: error: lost the connection to the X server \\(the server "
                                                 "ended, or a client killed this one\\) after ([0-9]+) viewer frames; "
                                                 "written: times \\(")))
            << r.output;
        EXPECT_GT(std::stoul(m[1]), 0u);
        EXPECT_EQ(frames_in_times(), std::stoul(m[1])) << r.output;
    }
}

}  // namespace
