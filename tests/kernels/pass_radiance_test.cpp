// A device frame's radiance-only pass (kernels/shared/pass_radiance.h, IgiSettings::pass_aovs
// false) against its whole pass: OpenCL's GPU variant, forced on the CPU device, renders
// the same frames both ways on two fresh backends. The radiance kernels run the whole pass's
// functions and keep the radiance, so the radiance-only pass must be TS_PASS_RADIANCE_FLOATS
// a pixel and the whole pass's radiance bit for bit, for igi and for AIS without edges, with
// edge samples merged, and with an edge schedule that gave no samples.
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "integrators/ais_frame.h"
#include "kernels/shared/layout_pass.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "support/render_helpers.h"

namespace tessera {
namespace {

constexpr int kWidth = 41, kHeight = 33;  // not multiples of any tile: windows cross the borders

std::unique_ptr<Backend> gpu_variant(const SceneBuffers& b, const Scene& s) {
    return make_backend(test::opencl_per_ray(true), b, plan_effects(s));
}

struct RadianceCase {
    const char* name;
    const char* scene;
    bool adaptive;
    uint32_t components;
    float edge_trigger;  // above 1 no pixel is flagged (contrast is in [0, 1]): no edge samples
    KernelId read_back;  // the kernel that writes the radiance-only pass
};

const uint32_t kSurface = TS_COMPONENT_SS | TS_COMPONENT_ID;
const uint32_t kAll = kSurface | TS_COMPONENT_PM | TS_COMPONENT_EDGE;

const RadianceCase kCases[] = {
    {"Igi", "cornell-box.json", false, kAll, 0.05f, KernelId::IgiResolveRadiance},
    {"IgiFog", "cornell-box-fog.json", false, kAll, 0.05f, KernelId::IgiResolveRadiance},
    {"AisNoEdges", "cornell-box.json", true, kSurface, 0.05f, KernelId::IgiResolveRadiance},
    {"AisEdgesMerged", "cornell-box.json", true, kAll, 0.05f, KernelId::AisEdgeMergeRadiance},
    {"AisFogEdgesMerged", "cornell-box-fog.json", true, kAll, 0.05f, KernelId::AisEdgeMergeRadiance},
    {"AisEdgesWithoutSamples", "cornell-box.json", true, kAll, 2.0f, KernelId::PassRadiance},
};

class PassRadiance : public ::testing::TestWithParam<RadianceCase> {};

TEST_P(PassRadiance, IsTheWholePassRadianceBitForBit) {
    const RadianceCase& c = GetParam();
    const Scene scene = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / c.scene, make_data_path(std::nullopt));
    const SceneBuffers b = make_scene_buffers(scene);
    IgiSettings is;
    is.tile = 3;
    is.paths_per_set = 8;
    is.components = c.components;
    is.edges.trigger = c.edge_trigger;
    auto whole_be = gpu_variant(b, scene), radiance_be = gpu_variant(b, scene);
    ASSERT_TRUE(radiance_be->resolves_on_device());
    auto make = [&](Backend& be, bool pass_aovs) -> std::unique_ptr<IgiFrame> {
        IgiSettings s = is;
        s.pass_aovs = pass_aovs;
        if (c.adaptive) return std::make_unique<AisFrame>(be, b, plan_effects(scene), s);
        return std::make_unique<IgiFrame>(be, b, plan_effects(scene), s);
    };
    auto whole = make(*whole_be, true), radiance = make(*radiance_be, false);
    const size_t pixels = size_t(kWidth) * kHeight;
    for (uint32_t pass = 0; pass < 2; ++pass) {
        TsFrame f = make_render_frame(scene.camera, kWidth, kHeight, b, RenderSettings{});
        f.pass = pass;
        std::vector<float> w, r;
        whole->render_pass(f, w);
        radiance->render_pass(f, r);
        ASSERT_EQ(w.size(), pixels * TS_PASS_FLOATS);
        ASSERT_EQ(r.size(), pixels * TS_PASS_RADIANCE_FLOATS);
        size_t differ = 0, lit = 0;
        for (size_t p = 0; p < pixels; ++p)
            for (int k = 0; k < TS_PASS_RADIANCE_FLOATS; ++k) {
                const float a = w[p * TS_PASS_FLOATS + TS_PASS_RADIANCE + k], x = r[p * TS_PASS_RADIANCE_FLOATS + k];
                lit += a > 0.0f;
                if (std::memcmp(&a, &x, 4) != 0 && differ++ < 5)
                    ADD_FAILURE() << "pass " << pass << " pixel " << p << " channel " << k << ": " << a << " vs " << x;
            }
        EXPECT_EQ(differ, 0u);
        EXPECT_GT(lit, pixels) << "a black frame would make the comparison vacuous";
    }
    // The radiance-only kernel wrote both passes; the whole pass's kernels ran on the other
    // backend only.
    EXPECT_EQ(radiance_be->dispatch_count(c.read_back), 2u);
    EXPECT_EQ(radiance_be->dispatch_count(KernelId::AisEdgeMerge), 0u);
    for (KernelId k : {KernelId::IgiResolveRadiance, KernelId::AisEdgeMergeRadiance, KernelId::PassRadiance})
        EXPECT_EQ(whole_be->dispatch_count(k), 0u);
    if (c.read_back == KernelId::IgiResolveRadiance) {
        EXPECT_EQ(radiance_be->dispatch_count(KernelId::IgiResolve), 0u);
    }
}

INSTANTIATE_TEST_SUITE_P(Frames, PassRadiance, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.name); });

// Frames reconstructed on the host (Embree, OpenCL's CPU variant) write the whole pass
// whatever pass_aovs says: the setting only changes a device frame's read-back.
TEST(PassRadianceOnTheHost, WholePassWhateverTheSetting) {
    const Scene scene = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box.json",
                                   make_data_path(std::nullopt));
    const SceneBuffers b = make_scene_buffers(scene);
    auto be = make_backend({BackendKind::Embree, ""}, b, plan_effects(scene));
    ASSERT_FALSE(be->resolves_on_device());
    IgiSettings is;
    is.pass_aovs = false;
    IgiFrame igi(*be, b, plan_effects(scene), is);
    std::vector<float> out;
    igi.render_pass(make_render_frame(scene.camera, kWidth, kHeight, b, RenderSettings{}), out);
    EXPECT_EQ(out.size(), size_t(kWidth) * kHeight * TS_PASS_FLOATS);
}

}  // namespace
}  // namespace tessera
