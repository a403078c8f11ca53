// Backend::set_scene: a backend given a new scene renders what a fresh backend for that
// scene renders, bit for bit, on both backends; also when the new scene needs other
// compile-time effects (OpenCL rebuilds its programs then).
#include <cstring>
#include <memory>

#include <gtest/gtest.h>

#include "scene/animation.h"
#include "support/render_helpers.h"

namespace tessera {
namespace {

Scene scene_file(const char* name) {
    return load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / name, make_data_path(std::nullopt));
}

RenderSettings igi_settings() {
    RenderSettings s;
    s.method = Method::Igi;
    s.width = s.height = 24;
    s.spp = 1;
    s.igi.paths_per_set = 4;
    return s;
}

// Every channel of a and b equal bit for bit (NaN never passes: the renders are finite).
void expect_same_pixels(const Image& a, const Image& b, const std::string& what) {
    ASSERT_EQ(a.channels.size(), b.channels.size()) << what;
    for (size_t c = 0; c < a.channels.size(); ++c) {
        const auto& x = a.channels[c].data;
        const auto& y = b.channels[c].data;
        ASSERT_EQ(x.size(), y.size()) << what;
        size_t differ = 0;
        for (size_t i = 0; i < x.size(); ++i) differ += std::memcmp(&x[i], &y[i], sizeof(float)) != 0;
        EXPECT_EQ(differ, 0u) << what << ", channel " << a.channels[c].name;
    }
}

class SetScene : public ::testing::TestWithParam<BackendKind> {};

// The chain: frames 0 and 7 of the animation (the cube moved, the light dimmed), then
// the foggy box (a medium: OpenCL's programs need TS_HAS_MEDIUM), then back to frame 0.
TEST_P(SetScene, RendersWhatAFreshBackendRenders) {
    const Scene rest = scene_file("cornell-box-animated.json");
    const Scene chain[] = {scene_at_frame(rest, 0), scene_at_frame(rest, 7), scene_file("cornell-box-fog.json"),
                           scene_at_frame(rest, 0)};
    const char* names[] = {"frame 0", "frame 7", "foggy box", "frame 0 again"};
    const RenderSettings s = igi_settings();
    std::unique_ptr<SceneBuffers> buffers;
    std::unique_ptr<Backend> kept;
    for (int i = 0; i < 4; ++i) {
        auto next = std::make_unique<SceneBuffers>(make_scene_buffers(chain[i]));
        const EffectPlan plan = plan_effects(chain[i]);
        give_scene(kept, {GetParam(), ""}, *next, plan);
        buffers = std::move(next);
        const Image a = render_frame(*kept, chain[i], *buffers, s);
        const Image b = test::render_with(GetParam(), chain[i], s);
        expect_same_pixels(a, b, names[i]);
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, SetScene, ::testing::Values(BackendKind::OpenCL, BackendKind::Embree));

// program_build_seconds counts the programs a run built or loaded (render_frame takes it
// out of its pass times): some for OpenCL's first frame, none more for a second frame
// that launches the same kernels; none at all on Embree, which compiles nothing.
TEST(ProgramBuildSeconds, CountsOnlyTheFirstBuildOfEachProgram) {
    const Scene scene = scene_file("cornell-box.json");
    const SceneBuffers buffers = make_scene_buffers(scene);
    std::unique_ptr<Backend> cl, embree;
    give_scene(cl, {BackendKind::OpenCL, ""}, buffers, plan_effects(scene));
    give_scene(embree, {BackendKind::Embree, ""}, buffers, plan_effects(scene));
    EXPECT_EQ(cl->program_build_seconds(), 0.0);
    (void)render_frame(*cl, scene, buffers, igi_settings());
    const double first = cl->program_build_seconds();
    EXPECT_GT(first, 0.0);
    (void)render_frame(*cl, scene, buffers, igi_settings());
    EXPECT_EQ(cl->program_build_seconds(), first);
    (void)render_frame(*embree, scene, buffers, igi_settings());
    EXPECT_EQ(embree->program_build_seconds(), 0.0);
}

}  // namespace
}  // namespace tessera
