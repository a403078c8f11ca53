// The igi frame resolved where the kernels ran (kernels/shared/igi_resolve.h: the
// discontinuity filter and the composite as KernelId::IgiResolve over the surface and
// media kernels' outputs kept by Backend::launch_into) against the host's reconstruction
// (host/integrators/igi_frame.cpp, host/gi/discontinuity_filter.cpp), with the clamp's
// screen-space compensation (kernels/shared/igi_clamp_screen.h against
// host/gi/clamp_screen.cpp) or without. Both run the same shared functions and sum in
// double in window order, so the images must be the same bits; on a device without fp64
// the compensated float sums may differ by rounding only. Through a medium too: the
// compensation's transmittance takes the shared exponential (ts_exp3) on both sides, where
// the device's built-in exp and the host's expf had rounded apart (1 float of 13,530 on
// PoCL, 1 ulp).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "integrators/igi_frame.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "support/render_helpers.h"
#include "support/scoped_env.h"

namespace tessera {
namespace {

constexpr int kWidth = 41, kHeight = 33;  // not multiples of any tile: windows cross the borders

Scene scene_file(const char* name) {
    return load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / name, make_data_path(std::nullopt));
}

// The Cornell box from 2.5 times its camera distance: the box's outside and camera rays
// that escape (depth +inf, which only other escaped pixels accept) are in the frame.
Scene cornell_from_afar() {
    Scene s = scene_file("cornell-box.json");
    s.camera.position = s.camera.look_at + 2.5f * (s.camera.position - s.camera.look_at);
    return s;
}

struct ResolveCase {
    const char* name;
    Scene (*scene)();
    uint32_t tile;
    bool filter;
    uint32_t components;
    bool multiple_scattering;
    bool clamp_compensation;  // the clamp's screen-space compensation (shared/igi_clamp_screen.h)
};

const ResolveCase kCases[] = {
    {"CornellTile3", [] { return scene_file("cornell-box.json"); }, 3, true, 7u, true, true},
    {"CornellTile3Uncompensated", [] { return scene_file("cornell-box.json"); }, 3, true, 7u, true, false},
    {"FogTile4", [] { return scene_file("cornell-box-fog.json"); }, 4, true, 7u, true, true},
    {"FogSingleScatteringTile2", [] { return scene_file("cornell-box-fog.json"); }, 2, true, 7u, false, true},
    {"FogUnfiltered", [] { return scene_file("cornell-box-fog.json"); }, 3, false, 7u, true, true},
    {"FogTile4Uncompensated", [] { return scene_file("cornell-box-fog.json"); }, 4, true, 7u, true, false},
    {"FogWithoutSurfaceComponents", [] { return scene_file("cornell-box-fog.json"); }, 3, true,
     TS_COMPONENT_PM, true, true},
    {"EscapedRaysTile5", cornell_from_afar, 5, true, TS_COMPONENT_SS | TS_COMPONENT_ID, true, true},
};

const ResolveCase& case_named(const std::string& name) {
    for (const ResolveCase& c : kCases)
        if (name == c.name) return c;
    throw std::invalid_argument(name);
}

IgiSettings settings_of(const ResolveCase& c, bool component_aovs) {
    IgiSettings is;
    is.tile = c.tile;
    is.paths_per_set = 8;
    is.filter = c.filter;
    is.components = c.components;
    is.multiple_scattering = c.multiple_scattering;
    is.component_aovs = component_aovs;
    is.clamp_compensation = c.clamp_compensation;
    return is;
}

TsFrame frame_of(const Scene& s, const SceneBuffers& b, uint32_t pass) {
    RenderSettings rs;
    TsFrame f = make_render_frame(s.camera, kWidth, kHeight, b, rs);
    f.pass = pass;
    return f;
}

std::unique_ptr<Backend> backend_of(const Scene& s, const SceneBuffers& b, BackendKind kind, bool gpu_variant) {
    BackendOptions o{kind, ""};
    o.cl_gpu_variant = gpu_variant;
    return make_backend(o, b, plan_effects(s));
}

// Pixels whose radiance is positive, and whose depth is +inf.
void count_pixels(const std::vector<float>& pass, size_t* lit, size_t* escaped) {
    *lit = *escaped = 0;
    for (size_t p = 0; p < pass.size() / TS_PASS_FLOATS; ++p) {
        const float* o = &pass[p * TS_PASS_FLOATS];
        *lit += o[TS_PASS_RADIANCE] + o[TS_PASS_RADIANCE + 1] + o[TS_PASS_RADIANCE + 2] > 0.0f;
        *escaped += std::isinf(o[TS_PASS_DEPTH]);
    }
}

void expect_same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    ASSERT_EQ(a.size(), b.size());
    size_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a[i], &b[i], 4) != 0 && differ++ < 5)
            ADD_FAILURE() << "pixel " << i / TS_PASS_FLOATS << " float " << i % TS_PASS_FLOATS << ": " << a[i]
                          << " vs " << b[i];
    EXPECT_EQ(differ, 0u);
}

class IgiResolveCases : public ::testing::TestWithParam<ResolveCase> {};

// OpenCL's GPU variant (forced on the CPU device) resolves on the device unless component
// AOVs are wanted; both ways give the same bits, over two passes (two VPL sets and
// Cranley–Patterson shifts).
TEST_P(IgiResolveCases, DeviceResolveEqualsHostReconstruction) {
    const ResolveCase& c = GetParam();
    const Scene s = c.scene();
    const SceneBuffers b = make_scene_buffers(s);
    auto device = backend_of(s, b, BackendKind::OpenCL, true), host = backend_of(s, b, BackendKind::OpenCL, true);
    ASSERT_TRUE(device->resolves_on_device());
    IgiFrame on_device(*device, b, plan_effects(s), settings_of(c, false));
    IgiFrame on_host(*host, b, plan_effects(s), settings_of(c, true));
    for (uint32_t pass : {0u, 1u}) {
        std::vector<float> d, h;
        on_device.render_pass(frame_of(s, b, pass), d);
        on_host.render_pass(frame_of(s, b, pass), h);
        expect_same_bits(d, h);
        size_t lit, escaped;
        count_pixels(h, &lit, &escaped);
        // (the box's outside, seen from afar, is unlit)
        EXPECT_GT(lit, size_t(kWidth * kHeight) / 10) << "a black frame would make the comparison vacuous";
        if (c.scene == cornell_from_afar) {
            EXPECT_GT(escaped, size_t(kWidth * kHeight) / 10);
            EXPECT_LT(escaped, size_t(kWidth * kHeight) * 9 / 10);
        }
    }
    EXPECT_EQ(device->dispatch_count(KernelId::IgiResolve), 2u);
    EXPECT_EQ(host->dispatch_count(KernelId::IgiResolve), 0u);
    const uint64_t compensated = c.clamp_compensation && (c.components & TS_COMPONENT_ID) ? 2u : 0u;
    EXPECT_EQ(device->dispatch_count(KernelId::IgiClampGather), compensated);
    EXPECT_EQ(host->dispatch_count(KernelId::IgiClampGather), 0u);
}

INSTANTIATE_TEST_SUITE_P(Scenes, IgiResolveCases, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.name); });

// The kernel compiled as C++ (Embree backend) and as OpenCL for the CPU (16-ray packet
// surface kernel) equals the host's reconstruction of the same pass too. These backends
// resolve on the host by default, so the test launches the kernels itself.
TEST(IgiResolve, KernelEqualsHostOnEmbreeAndOpenclCpu) {
    const Scene s = scene_file("cornell-box-fog.json");
    const SceneBuffers b = make_scene_buffers(s);
    for (BackendKind kind : {BackendKind::Embree, BackendKind::OpenCL}) {
        SCOPED_TRACE(kind == BackendKind::Embree ? "embree" : "opencl");
        auto be = backend_of(s, b, kind, false);
        ASSERT_FALSE(be->resolves_on_device());
        const ResolveCase& c = case_named("FogTile4");
        IgiFrame igi(*be, b, plan_effects(s), settings_of(c, false));
        const TsFrame f = igi.prepare(frame_of(s, b, 0));
        std::vector<float> host, device;
        igi.render_pass(f, host);  // also leaves the pass's VPLs as the backend's inputs
        be->launch_into(KernelId::IgiSurface, f, KernelInput::IgiSurface);
        be->launch_into(KernelId::IgiMedia, f, KernelInput::IgiMedia);
        ASSERT_EQ(f.igi_clamp_screen, 1u);
        be->launch_into(KernelId::IgiClampRecords, f, KernelInput::ClampRecords);
        be->launch_into(KernelId::IgiClampGather, f, KernelInput::ClampResidual);
        be->launch(KernelId::IgiResolve, f, device);
        expect_same_bits(device, host);
        size_t lit, escaped;
        count_pixels(host, &lit, &escaped);
        EXPECT_GT(lit, size_t(kWidth * kHeight) / 10) << "a black frame would make the comparison vacuous";
    }
}

// Without fp64 (-DTS_NO_DOUBLE builds the float forms on PoCL) the window sums are
// compensated floats: each component mean is then within 1.5 ulps of the double sum's
// (the compensated sum of at most 64 values of one sign is within an ulp of exact, the
// division adds half an ulp). The composite's five roundings (each ≤ 0.5 ulp of a
// positive quantity) happen in both computations, so the radiance may differ by up to
// 1.5 + 2 × 2.5 = 6.5 ulps: 7 allowed (measured: 4).
TEST(IgiResolve, CompensatedFloatSumsMatchDoubleSumsWithinSevenUlps) {
    test::ScopedEnv options("TESSERA_CL_OPTIONS", "-DTS_NO_DOUBLE");
    const ResolveCase& c = case_named("FogTile4Uncompensated");
    const Scene s = c.scene();
    const SceneBuffers b = make_scene_buffers(s);
    auto device = backend_of(s, b, BackendKind::OpenCL, true), host = backend_of(s, b, BackendKind::OpenCL, true);
    IgiFrame on_device(*device, b, plan_effects(s), settings_of(c, false));
    IgiFrame on_host(*host, b, plan_effects(s), settings_of(c, true));
    std::vector<float> d, h;
    on_device.render_pass(frame_of(s, b, 0), d);
    on_host.render_pass(frame_of(s, b, 0), h);
    ASSERT_EQ(d.size(), h.size());
    int64_t worst = 0;
    size_t differ = 0;
    for (size_t i = 0; i < d.size(); ++i) {
        ASSERT_EQ(std::signbit(d[i]), std::signbit(h[i])) << i;
        int32_t a, e;
        std::memcpy(&a, &d[i], 4);
        std::memcpy(&e, &h[i], 4);
        worst = std::max<int64_t>(worst, std::abs(int64_t(a) - e));
        differ += a != e;
    }
    std::printf("  float sums: %zu of %zu floats differ, by at most %lld ulps\n", differ, d.size(),
                static_cast<long long>(worst));
    EXPECT_LE(worst, 7);
    // The float sums must have run (357 of 13,530 floats differed when measured): none
    // differing would mean -DTS_NO_DOUBLE no longer reaches the kernels.
    EXPECT_GT(differ, 0u);
    size_t lit, escaped;
    count_pixels(h, &lit, &escaped);
    EXPECT_GT(lit, size_t(kWidth * kHeight) / 10) << "a black frame would make the comparison vacuous";
}

// render --aov keeps the components on the host (integrator_settings), so a backend that
// resolves on the device still writes the SS/ID/PM channels.
TEST(IgiResolve, ComponentAovsBringTheComponentsBack) {
    const Scene s = scene_file("cornell-box-fog.json");
    const SceneBuffers b = make_scene_buffers(s);
    auto be = backend_of(s, b, BackendKind::OpenCL, true);
    RenderSettings rs = test::packet_test_settings(Method::Igi);
    rs.aovs = true;
    const Image with = render_frame(*be, s, b, rs);
    EXPECT_EQ(be->dispatch_count(KernelId::IgiResolve), 0u);
    for (const char* ch : {"SS_filtered.R", "ID_filtered.G", "PM_filtered.B"})
        EXPECT_NE(with.find(ch), nullptr) << ch;
    rs.aovs = false;
    const Image without = render_frame(*be, s, b, rs);
    // Resolved on the device, and with no AOVs, checkpoint or cluster to feed, read back as
    // radiance alone (IgiSettings::pass_aovs).
    EXPECT_EQ(be->dispatch_count(KernelId::IgiResolveRadiance), rs.spp);
    EXPECT_EQ(be->dispatch_count(KernelId::IgiResolve), 0u);
    EXPECT_EQ(without.find("SS_filtered.R"), nullptr);
    EXPECT_EQ(be->dispatch_count(KernelId::IgiClampGather), rs.spp) << "the compensation runs on the device too";
    // The same radiance bits: the AOVs change where the frame is resolved, not its sums.
    ASSERT_FALSE(without.channels.empty());
    for (const auto& ch : without.channels) {
        const auto* same = with.find(ch.name);
        ASSERT_NE(same, nullptr) << ch.name;
        EXPECT_TRUE(same->data == ch.data) << ch.name;
    }
    rs.igi.clamp_compensation = false;
    const Image clamped = render_frame(*be, s, b, rs);
    EXPECT_EQ(be->dispatch_count(KernelId::IgiClampGather), rs.spp);
    EXPECT_GT(test::image_sum(without), test::image_sum(clamped)) << "the compensation adds light";
}

}  // namespace
}  // namespace tessera
