// The viewer's session without a window: an accumulation at rest equals render_frame
// with the same camera, method, settings and seed; movement restarts it; at rest after
// movement the image converges toward the still render; switches and the frame budget
// restart it with the right settings.
#include "view/view_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "image/resample.h"
#include "metrics/image_metrics.h"
#include "scene/animation.h"
#include "scene/loader.h"
#include "util/error.h"
#include "support/render_helpers.h"
#include "view/camera_control.h"

namespace tessera::view {
namespace {

Scene cornell() {
    return load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box.json", make_data_path(std::nullopt));
}

ViewOptions options(Method method, uint32_t spp, int size = 32) {
    ViewOptions o;
    o.backend = {BackendKind::Embree, ""};
    o.settings.method = method;
    o.settings.spp = spp;
    o.settings.width = o.settings.height = size;
    o.settings.seed = 7;
    return o;
}

// render_frame at `camera` with the session's settings and `spp` passes.
Image still(Scene scene, const Camera& camera, RenderSettings settings, uint32_t spp) {
    scene.camera.position = camera.position;
    scene.camera.look_at = camera.look_at;
    scene.camera.up = camera.up;
    scene.camera.vfov_deg = camera.vfov_deg;
    settings.spp = spp;
    return test::render_with(BackendKind::Embree, scene, settings);
}

// Equal within float rounding: both sides run the same code, so in practice bit for bit.
void expect_equal_images(const Image& view, const Image& render) {
    double peak = 0;
    for (const char* c : {"R", "G", "B", "variance.R"}) {
        const ImageChannel* a = view.find(c);
        const ImageChannel* b = render.find(c);
        ASSERT_TRUE(a && b) << c;
        ASSERT_EQ(a->data.size(), b->data.size());
        for (size_t i = 0; i < a->data.size(); ++i) {
            EXPECT_NEAR(a->data[i], b->data[i], 1e-6f * std::max(1.0f, std::fabs(b->data[i]))) << c << " " << i;
            peak = std::max(peak, double(b->data[i]));
        }
    }
    EXPECT_GT(peak, 0.0) << "a black image would make the comparison vacuous";
}

class ViewSessionMethods : public ::testing::TestWithParam<Method> {};

TEST_P(ViewSessionMethods, AccumulationAtRestEqualsRender) {
    const Scene scene = cornell();
    ViewOptions o = options(GetParam(), 3);
    ViewSession session(scene, o);
    for (int i = 0; i < 5; ++i) session.advance(1.0 / 30);  // the last two render nothing: 3 spp reached
    EXPECT_EQ(session.passes(), 3u);
    expect_equal_images(session.accumulation(), still(scene, scene.camera, o.settings, 3));
}

TEST(ViewSession, IcAndTicDrawARendersPathSubsets) {
    // At 4 spp a render draws 2 path subsets for ic and tic (ic_subsets_for); the
    // viewer makes tic's caches before any pass, so it must pick M from the same spp, or
    // its accumulation at rest would be another image than the render's.
    const Scene scene = cornell();
    for (Method m : {Method::Ic, Method::Tic}) {
        ViewOptions o = options(m, 4);
        ViewSession session(scene, o);
        for (int i = 0; i < 6; ++i) session.advance(1.0 / 30);
        EXPECT_EQ(session.passes(), 4u);
        expect_equal_images(session.accumulation(), still(scene, scene.camera, o.settings, 4));
    }
}

INSTANTIATE_TEST_SUITE_P(View, ViewSessionMethods,
                         ::testing::Values(Method::PathTrace, Method::Igi, Method::Ais, Method::AisMax, Method::Ic,
                                           Method::Tic),
                         [](const auto& info) {
                             std::string n = method_name(info.param);
                             n.erase(std::remove(n.begin(), n.end(), '-'), n.end());
                             return n;
                         });

TEST(ViewSession, MovingRestartsAndAtRestConvergesToTheStillRender) {
    const Scene scene = cornell();
    ViewOptions o = options(Method::Igi, 16);
    ViewSession session(scene, o);
    session.advance(1.0 / 30);
    const Image first = session.accumulation();
    session.handle({InputEvent::Kind::Press, 'W'});
    session.handle({InputEvent::Kind::Drag, 0, 15.0f, 0.0f});
    for (int i = 0; i < 3; ++i) {
        const FrameReport r = session.advance(1.0 / 30);
        EXPECT_TRUE(r.moving);
        EXPECT_EQ(r.passes, 1u);  // one fresh interleaved frame per moving frame
    }
    session.handle({InputEvent::Kind::Release, 'W'});
    EXPECT_GT(test::rel_mse(session.accumulation(), first), 1e-3) << "moving the camera must change the image";
    EXPECT_TRUE(camera_differs(session.camera(), scene.camera));

    const Image converged = still(scene, session.camera(), o.settings, 64);
    std::vector<double> errors = {test::rel_mse(session.accumulation(), converged)};
    for (uint32_t passes = 2; passes <= 16; passes *= 2) {
        while (session.passes() < passes) EXPECT_FALSE(session.advance(1.0 / 30).moving);
        errors.push_back(test::rel_mse(session.accumulation(), converged));
    }
    for (size_t i = 1; i < errors.size(); ++i)
        EXPECT_LT(errors[i], errors[i - 1]) << "the error against the still render must fall with passes";
    expect_equal_images(session.accumulation(), still(scene, session.camera(), o.settings, 16));
}

TEST(ViewSession, AKeyTappedBetweenFramesMovesForOneFrame) {
    const Scene scene = cornell();
    ViewOptions o = options(Method::Igi, 2);
    o.speed = 3.0f;
    ViewSession session(scene, o);
    session.handle({InputEvent::Kind::Press, 'W'});
    session.handle({InputEvent::Kind::Release, 'W'});
    session.advance(0.1);  // 3 units/s for 0.1 s along the view direction (+z)
    EXPECT_NEAR(session.camera().position.z, scene.camera.position.z + 0.3f, 1e-5f);
    session.advance(0.1);  // released: no further motion
    EXPECT_NEAR(session.camera().position.z, scene.camera.position.z + 0.3f, 1e-5f);
}

TEST(ViewSession, ResetKeyRestoresTheSceneCamera) {
    const Scene scene = cornell();
    ViewSession session(scene, options(Method::Igi, 2));
    session.handle({InputEvent::Kind::Press, 'D'});
    session.advance(0.5);
    session.handle({InputEvent::Kind::Release, 'D'});
    EXPECT_TRUE(camera_differs(session.camera(), scene.camera));
    session.handle({InputEvent::Kind::Press, 'R'});
    EXPECT_FALSE(camera_differs(session.camera(), scene.camera));
}

TEST(ViewSession, MethodAndComponentSwitchesRestartWithTheNewSettings) {
    const Scene scene = cornell();
    ViewOptions o = options(Method::Igi, 2);
    ViewSession session(scene, o);
    session.advance(0);
    session.advance(0);
    EXPECT_EQ(session.passes(), 2u);
    session.handle({InputEvent::Kind::Press, 'M'});  // igi → ais
    EXPECT_EQ(session.method(), Method::Ais);
    EXPECT_TRUE(session.advance(0).moving);
    session.advance(0);
    o.settings.method = Method::Ais;
    expect_equal_images(session.accumulation(), still(scene, scene.camera, o.settings, 2));
    session.handle({InputEvent::Kind::Press, '2'});  // ID off
    session.advance(0);
    session.advance(0);
    o.settings.igi.components = TS_COMPONENT_SS | TS_COMPONENT_PM | TS_COMPONENT_EDGE;  // the rest stay on
    expect_equal_images(session.accumulation(), still(scene, scene.camera, o.settings, 2));
}

// On a scene without a medium, PM alone would render black: the last of SS and ID stays
// on there (render refuses `--components pm` on it likewise).
TEST(ViewSession, PmAloneIsRefusedWithoutAMedium) {
    const Scene scene = cornell();
    ViewSession session(scene, options(Method::Igi, 1));
    session.handle({InputEvent::Kind::Press, '1'});  // SS off
    session.handle({InputEvent::Kind::Press, '2'});  // ID off: refused
    session.advance(0);
    ViewOptions o = options(Method::Igi, 1);
    o.settings.igi.components = TS_COMPONENT_ID | TS_COMPONENT_PM | TS_COMPONENT_EDGE;
    expect_equal_images(session.accumulation(), still(scene, scene.camera, o.settings, 1));
}

TEST(ViewSession, BudgetedMovingFramesThenFullSettingsAtRest) {
    const Scene scene = cornell();
    ViewOptions o = options(Method::Igi, 2);
    o.target_fps = 1000.0;  // 1 ms: the fastest setting
    o.pareto = {BudgetPoint{"igi", 8, 4, 1, 0.001, 0.5}, BudgetPoint{"igi", 2, 64, 16, 0.5, 0.1}};
    ViewSession session(scene, o);
    session.handle({InputEvent::Kind::Press, 'W'});
    session.advance(1.0 / 30);
    session.handle({InputEvent::Kind::Release, 'W'});
    RenderSettings budget = o.settings;
    budget.igi.tile = 8, budget.igi.paths_per_set = 4, budget.shadow_samples = 1;
    expect_equal_images(session.accumulation(), still(scene, session.camera(), budget, 1));
    bool hud_names_budget = false;
    for (const std::string& line : session.hud_lines(0))
        hud_names_budget |= line.size() > 35 && line.substr(line.size() - 35) == "tile 8, 4 VPL paths, 1 light sample";
    EXPECT_TRUE(hud_names_budget);
    session.advance(0);  // at rest: starts over with the full settings
    session.advance(0);
    expect_equal_images(session.accumulation(), still(scene, session.camera(), o.settings, 2));
}

// A budget no setting can meet at full resolution: moving frames drop to the scale's
// floor, render that many pixels with the same camera and upsample them to the window;
// at rest the accumulation is the full-resolution render's, bit for bit.
TEST(ViewSession, BudgetLowersTheResolutionWhileMovingAndNotAtRest) {
    const Scene scene = cornell();
    ViewOptions o = options(Method::Igi, 2, 64);
    o.target_fps = 1e6;  // 1 µs: no machine meets it, so the controller goes to the floor
    o.min_scale = 0.25;
    o.pareto = {BudgetPoint{"igi", 8, 4, 1, 1e-6, 0.5}};  // a sweep time no frame here can match
    // VPLs without view points: a moving frame is then the still render at its camera
    // (with view points it may keep an earlier camera's: KeptViewPointsStartOverAtRest).
    o.settings.igi.vpl_importance = 1;
    ViewSession session(scene, o);
    for (int f = 0; f < 4; ++f) {
        session.handle({InputEvent::Kind::Press, 'W'});
        const FrameReport r = session.advance(1.0 / 30);
        session.handle({InputEvent::Kind::Release, 'W'});
        ASSERT_TRUE(r.budget.applied);
        EXPECT_EQ(r.moving, f > 0);  // frame 0 starts the run: budgeted as a move, not counted as one
        EXPECT_GE(r.budget.scale, 0.25) << f;  // never below the floor
        EXPECT_EQ(r.budget.width, static_cast<int>(std::lround(64 * r.budget.scale))) << f;
        if (f == 0) {
            EXPECT_EQ(r.budget.scale, 1.0);  // before a measurement: the sweep's time fits
        }
    }
    const FrameReport last = session.advance(0);  // the camera rests; this frame restarts at full size
    EXPECT_FALSE(last.budget.applied);
    // The frame before it: the floor, 16x16, upsampled.
    session.handle({InputEvent::Kind::Press, 'W'});
    const FrameReport moved = session.advance(1.0 / 30);
    session.handle({InputEvent::Kind::Release, 'W'});
    ASSERT_EQ(moved.budget.width, 16);
    RenderSettings small = o.settings;
    small.igi.tile = 8, small.igi.paths_per_set = 4, small.shadow_samples = 1;
    small.width = small.height = 16;
    const Image upsampled = resize_bilinear(still(scene, session.camera(), small, 1), 64, 64);
    const Image shown = session.accumulation();
    ASSERT_EQ(shown.width, 64);
    EXPECT_EQ(shown.find("R")->data, upsampled.find("R")->data);
    // At rest: full size, the command line's settings, bit for bit the still render.
    session.advance(0);
    session.advance(0);
    const Image rest = session.accumulation();
    const Image render = still(scene, session.camera(), o.settings, 2);
    for (const char* c : {"R", "G", "B", "variance.R"}) EXPECT_EQ(rest.find(c)->data, render.find(c)->data) << c;
}

TEST(ViewSession, KeptViewPointsStartOverAtRest) {
    // A small move keeps the VPL selection's view points of the camera at rest before it
    // (ViewPointHistory), so the moving frame is not the still render at its own camera;
    // at rest the accumulation starts over and is the still render bit for bit.
    const Scene scene = cornell();
    ViewOptions o = options(Method::Igi, 2, 32);
    ASSERT_GT(o.settings.igi.vpl_importance, 1u);
    ViewSession session(scene, o);
    session.advance(0);
    session.handle({InputEvent::Kind::Press, 'W'});
    const FrameReport moved = session.advance(1.0 / 240);  // a short step: within the hysteresis
    session.handle({InputEvent::Kind::Release, 'W'});
    ASSERT_TRUE(moved.moving);
    EXPECT_NE(session.accumulation().find("R")->data, still(scene, session.camera(), o.settings, 1).find("R")->data)
        << "the moving frame kept the resting camera's view points";
    session.advance(0);
    session.advance(0);
    EXPECT_EQ(session.passes(), 2u);
    const Image rest = session.accumulation(), render = still(scene, session.camera(), o.settings, 2);
    for (const char* c : {"R", "G", "B", "variance.R"}) EXPECT_EQ(rest.find(c)->data, render.find(c)->data) << c;
}

// ic and tic have no sweep rows: the budget keeps their settings and changes only the
// resolution.
TEST(ViewSession, BudgetWithoutSweepRowsChangesOnlyTheResolution) {
    const Scene scene = cornell();
    ViewOptions o = options(Method::Ic, 1, 64);
    o.target_fps = 1e6;  // 1 µs: no frame on any machine is that fast, so the scale reaches its floor
    ViewSession session(scene, o);
    FrameReport r;
    for (int f = 0; f < 3; ++f) {
        session.handle({InputEvent::Kind::Press, 'W'});
        r = session.advance(1.0 / 30);
        session.handle({InputEvent::Kind::Release, 'W'});
    }
    ASSERT_TRUE(r.budget.applied);
    EXPECT_EQ(r.budget.scale, o.min_scale);  // the default floor
    EXPECT_EQ(r.budget.tile, o.settings.igi.tile);
    EXPECT_EQ(r.budget.shadow_samples, o.settings.shadow_samples);
    const Image acc = session.accumulation();  // a value: find() points into it
    for (float v : acc.find("R")->data) ASSERT_TRUE(std::isfinite(v));
}

TEST(ViewSession, PlayingAnAnimationRestartsEachFrameAndPauseHoldsTheImage) {
    const Scene rest = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box-animated.json",
                                  make_data_path(std::nullopt));
    ViewOptions o = options(Method::Igi, 4, 16);
    o.first_frame = 3;
    o.last_frame = 4;
    ViewSession session(rest, o);
    EXPECT_EQ(session.animation_frame(), 3);
    session.advance(0);
    session.handle({InputEvent::Kind::Press, 'T'});
    const FrameReport r = session.advance(0);
    EXPECT_EQ(session.animation_frame(), 4);
    EXPECT_TRUE(r.moving);
    EXPECT_EQ(r.passes, 1u);
    session.advance(0);
    EXPECT_EQ(session.animation_frame(), 3);  // wraps within --frames
    session.handle({InputEvent::Kind::Press, 'T'});  // stop: frame 3 accumulates
    session.advance(0);
    EXPECT_EQ(session.passes(), 2u);
    // The accumulation at rest on frame 3 is render's still of that frame.
    RenderSettings settings = o.settings;
    settings.spp = 2;
    expect_equal_images(session.accumulation(), test::render_with(BackendKind::Embree, scene_at_frame(rest, 3), settings));
    session.handle({InputEvent::Kind::Press, ' '});  // pause: no passes, the image kept
    const FrameReport paused = session.advance(0);
    EXPECT_FALSE(paused.rendered);
    EXPECT_EQ(session.passes(), 2u);
    EXPECT_TRUE(session.idle());
    EXPECT_THROW(session.set_animation_frame(5), InputError);
}

TEST(ViewSession, DisplayIsThePngToneMap) {
    const Scene scene = cornell();
    ViewOptions o = options(Method::Igi, 2);
    o.exposure = 1.0f;
    ViewSession session(scene, o);
    session.advance(0);
    std::vector<uint8_t> rgba;
    session.display(rgba);
    const Image img = session.accumulation();
    ASSERT_EQ(rgba.size(), size_t(32 * 32 * 4));
    int worst = 0, off = 0;
    for (size_t p = 0; p < 32 * 32; ++p)
        for (int c = 0; c < 3; ++c) {
            const double v = img.find(std::string(1, "RGB"[c]))->data[p];
            const int expected = int(std::lround(255.0 * metrics::tone_map_srgb(v, 1.0)));
            worst = std::max(worst, std::abs(int(rgba[4 * p + c]) - expected));
            off += rgba[4 * p + c] != expected;
        }
    // The same curve (image/srgb8.h). The display reads the accumulated sums in double, the
    // image holds their mean as float: a value within a float's rounding of a code's step
    // may land on either side of it, and only such values.
    EXPECT_LE(worst, 1);
    EXPECT_LE(off, 32 * 32 * 3 / 100);
}

// The HUD's rate is in what the method counts: rays for the igi family, camera samples
// for direct and pt (which trace inside one kernel; their rays showed as 0.00 Mrays/s),
// and only the igi family has a components part.
TEST(ViewSession, HudRateAndComponentsFollowTheMethod) {
    const Scene scene = cornell();
    for (Method m : {Method::Direct, Method::PathTrace, Method::Igi}) {
        ViewSession session(scene, options(m, 2));
        session.advance(0);
        const std::vector<std::string> hud = session.hud_lines(0);
        const bool igi = m == Method::Igi;
        double rate = 0.0;
        char unit[16] = "";
        ASSERT_EQ(std::sscanf(hud[0].c_str() + hud[0].find(" ms | ") + 6, "%lf %15s", &rate, unit), 2) << hud[0];
        EXPECT_STREQ(unit, igi ? "Mrays/s" : "Msamples/s") << method_name(m);
        EXPECT_GT(rate, 0.0) << method_name(m) << ": " << hud[0];
        bool components = false;
        for (const std::string& line : hud) components |= line.find("components ") != std::string::npos;
        EXPECT_EQ(components, igi) << method_name(m);
    }
}

TEST(ViewSession, AovKeyCyclesThroughWhatTheMethodProduces) {
    const Scene scene = cornell();  // no medium: no PM guidance
    ViewSession session(scene, options(Method::Ais, 2));
    session.advance(0);
    std::vector<std::string> seen;
    for (int i = 0; i < 8; ++i) {
        session.handle({InputEvent::Kind::Press, 'V'});
        session.handle({InputEvent::Kind::Release, 'V'});
        for (const std::string& line : session.hud_lines(0)) {
            const size_t at = line.find("AOV ");
            if (at != std::string::npos) seen.push_back(line.substr(at + 4, line.find(' ', at + 4) - at - 4));
        }
        std::vector<uint8_t> rgba;
        session.display(rgba);  // every AOV displays without throwing
    }
    const std::vector<std::string> expected = {"albedo", "normal", "depth", "guidance.SS", "guidance.ID",
                                               "sets.SS", "sets.ID", "radiance"};
    EXPECT_EQ(seen, expected);
}

// A session of `method` (4 spp) on the GPU variant, here on PoCL, after its first pass,
// which must be the host path's image bit for bit (both trace the light paths on the host).
std::unique_ptr<ViewSession> first_pass_on_the_device(const Scene& scene, Method method) {
    ViewOptions o = options(method, 4);
    o.backend = test::opencl_per_ray(true, false);
    auto device = std::make_unique<ViewSession>(scene, o);
    o.backend = test::opencl_per_ray(false, false);
    ViewSession host(scene, o);
    device->advance(0);
    host.advance(0);
    test::expect_images_identical(device->accumulation(), host.accumulation());
    return device;
}

// Where AIS is scheduled and resolved on the device (the GPU variant, here on PoCL) the
// viewer keeps the frame there while the radiance shows (no schedule sums on the host),
// the host path's image bit for bit. A guidance AOV restarts the accumulation on the
// host's schedule, whose sums it then shows.
TEST(ViewSession, AisOnTheDeviceRestartsForItsGuidanceAov) {
    const Scene scene = cornell();
    const std::unique_ptr<ViewSession> session = first_pass_on_the_device(scene, Method::Ais);
    ViewSession& device = *session;
    for (int i = 0; i < 4; ++i) {  // albedo, normal, depth, guidance.SS
        device.handle({InputEvent::Kind::Press, 'V'});
        device.handle({InputEvent::Kind::Release, 'V'});
    }
    bool shown = false;
    for (const std::string& line : device.hud_lines(0)) shown |= line.find("AOV guidance.SS") != std::string::npos;
    ASSERT_TRUE(shown);
    std::vector<uint8_t> rgba;
    device.display(rgba);  // the pass ran on the device: no schedule sums to show yet
    EXPECT_TRUE(std::all_of(rgba.begin(), rgba.end(), [](uint8_t v) { return v == 255; }));
    const FrameReport r = device.advance(0);  // the restart: the host's schedule from here on
    EXPECT_TRUE(r.moving);
    EXPECT_EQ(r.passes, 1u);
    device.display(rgba);
    size_t dark = 0;  // the guidance, scaled by its maximum: 0 in full light and umbra
    for (size_t p = 0; p < rgba.size() / 4; ++p) dark += rgba[4 * p] < 128;
    EXPECT_GT(dark, rgba.size() / 8);
    EXPECT_LT(dark, rgba.size() / 4);  // and some penumbra
}

// igi resolved on the device brings back the radiance alone while the radiance shows
// (IgiSettings::pass_aovs), the host path's radiance bit for bit; the albedo AOV restarts
// the accumulation with the whole pass, whose albedo it then shows.
TEST(ViewSession, IgiOnTheDeviceRestartsForThePassAovs) {
    const Scene scene = cornell();
    const std::unique_ptr<ViewSession> session = first_pass_on_the_device(scene, Method::Igi);
    ViewSession& device = *session;
    device.handle({InputEvent::Kind::Press, 'V'});  // albedo
    device.handle({InputEvent::Kind::Release, 'V'});
    std::vector<uint8_t> rgba;
    device.display(rgba);  // radiance-only passes so far: no albedo to show
    for (size_t p = 0; p < rgba.size() / 4; ++p) ASSERT_EQ(rgba[4 * p], 0) << p;
    const FrameReport r = device.advance(0);  // the restart, with the whole pass from here on
    EXPECT_TRUE(r.moving);
    EXPECT_EQ(r.passes, 1u);
    device.display(rgba);
    size_t bright = 0;  // red albedo 0.63-0.78 but on the green wall (scenes/cornell-box.mtl)
    for (size_t p = 0; p < rgba.size() / 4; ++p) bright += rgba[4 * p] > 100;
    EXPECT_GT(bright, rgba.size() / 8);
}

}  // namespace
}  // namespace tessera::view
