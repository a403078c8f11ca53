// The VPLs' importance where the kernels run (kernels/shared/vpl_importance.h,
// vpl_importance_items.h; gi/vpl_importance.h's vpl_view_importance_in_kernels): the same
// floats as the host's reference bit for bit on PoCL and Embree (double sums) and within
// the built-ins' rounding on a GPU, the float form within its rounding, medium VPLs at 0,
// and a GPU-variant backend's VPL lists the same as the host's.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/frame.h"
#include "gi/light_paths.h"
#include "gi/vpl_generator.h"
#include "gi/vpl_importance.h"
#include "support/render_helpers.h"
#include "kernels/shared/vpl.h"
#include "kernels/shared/vpl_importance.h"
#include "opencl/device.h"
#include "support/scoped_env.h"

namespace tessera {
namespace {

struct Candidates {
    ViewPoints view;
    std::vector<float> vpls;
};

// The view points of a 16² grid and the VPLs of 4 × 9 × 32 light paths, with medium
// VPLs in fog: what generate_vpls weighs at its defaults.
Candidates candidates(const Scene& scene, const SceneBuffers& buffers) {
    auto embree = make_backend({BackendKind::Embree, ""}, buffers, plan_effects(scene));
    const TsFrame frame = make_frame(scene.camera, 64, 64, 1, 1, buffers.light_count);
    Candidates c;
    c.view = trace_view_points(*embree, buffers, frame, 16);
    VplSettings vs;
    vs.paths_per_set = 128;
    vs.medium_scattering = true;
    c.vpls = generate_vpls(*embree, buffers, vs).vpls;
    return c;
}

class VplImportanceKernels : public ::testing::TestWithParam<const char*> {};

TEST_P(VplImportanceKernels, EqualTheHostsImportanceBitForBit) {
    const Scene scene = test::shipped_scene((std::string(GetParam()) + ".json").c_str());
    SceneBuffers buffers = make_scene_buffers(scene);
    const Candidates c = candidates(scene, buffers);
    ASSERT_EQ(c.view.count(), 256u);
    const size_t nv = c.vpls.size() / TS_VPL_FLOATS;
    ASSERT_GT(nv, 500u);
    const float g_clamp = 100.0f;
    const std::vector<float> host = vpl_view_importance(c.view, c.vpls, g_clamp);
    size_t medium = 0, positive = 0;
    for (size_t i = 0; i < nv; ++i) {
        if (ts::ts_vpl_in_medium(&c.vpls[i * TS_VPL_FLOATS])) {
            ++medium;
            EXPECT_EQ(host[i], 0.0f);
        }
        positive += host[i] > 0.0f;
    }
    EXPECT_GT(positive, nv / 2);
    if (std::string(GetParam()) == "cornell-box-fog") {
        EXPECT_GT(medium, 0u) << "the fog case has medium VPLs";
    }
    // Also with E in parts of 100 VPLs (not a divisor of nv: the last part is short), as a
    // GPU may sum it: the same floats, as E is a double sum of float terms, exact in any
    // order here. A part skipped or added twice moves every Φ.
    const size_t chunk = 100;
    ASSERT_NE(nv % chunk, 0u);
    for (auto [kind, parts] : {std::pair{BackendKind::OpenCL, size_t(0)}, std::pair{BackendKind::Embree, size_t(0)},
                               std::pair{BackendKind::OpenCL, chunk}, std::pair{BackendKind::Embree, chunk}}) {
        auto backend = make_backend({kind, ""}, buffers, plan_effects(scene));
        const std::vector<float> got = vpl_view_importance_in_kernels(*backend, c.view, c.vpls, g_clamp, parts);
        if (kind == BackendKind::Embree || select_cl_device("").type == "CPU") {
            EXPECT_EQ(got, host) << (kind == BackendKind::OpenCL ? "OpenCL" : "Embree") << ", parts of " << parts;
            continue;
        }
        // A GPU's built-ins (dot, normalize) may round a few ulps apart from C++, and
        // each VPL sums 256 positive terms in double: within 1e-5 relative (~20 float
        // operations a term, a few ulps each, ~1e-6; 10x left). A term whose cosine is a
        // knife edge (|cos| < 1e-6) may be in on one side only; it is at most 1e-6 of the
        // clamped term's bound lum · g_clamp, so four such terms are allowed for.
        ASSERT_EQ(got.size(), host.size());
        for (size_t i = 0; i < nv; ++i) {
            const float lum = ts::ts_vpl_importance_luminance(&c.vpls[i * TS_VPL_FLOATS]);
            EXPECT_NEAR(got[i], host[i], 1e-5f * host[i] + 4e-6f * lum * g_clamp) << "VPL " << i << ", parts of "
                                                                                 << parts;
        }
    }
    // The float form (once: its program build is the test's cost): within float rounding
    // of the terms' sum (256 points).
    if (std::string(GetParam()) != "cornell-box") return;
    test::ScopedEnv options("TESSERA_CL_OPTIONS", "-DTS_NO_DOUBLE");
    auto backend = make_backend({BackendKind::OpenCL, ""}, buffers, plan_effects(scene));
    const std::vector<float> single = vpl_view_importance_in_kernels(*backend, c.view, c.vpls, g_clamp);
    ASSERT_EQ(single.size(), host.size());
    bool differs = false;
    for (size_t i = 0; i < nv; ++i) {
        EXPECT_NEAR(single[i], host[i], 1e-4f * host[i] + 1e-12f) << i;
        differs |= single[i] != host[i];
    }
    EXPECT_TRUE(differs) << "-DTS_NO_DOUBLE no longer reaches the kernels";
}

INSTANTIATE_TEST_SUITE_P(Scenes, VplImportanceKernels, ::testing::Values("cornell-box", "cornell-box-fog"),
                         [](const auto& info) { return std::string(info.param) == "cornell-box" ? "CornellBox" : "Fog"; });

// No points or no VPLs: nothing to launch, every VPL 0; a view that sees none of the VPLs'
// light (points behind them) gives 0 as the host does.
TEST(VplImportanceKernelsEdge, EmptyInputsAndDarkViewsGiveZeros) {
    const Scene scene = test::cornell_box();
    SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = make_backend({BackendKind::OpenCL, ""}, buffers, plan_effects(scene));
    const Candidates c = candidates(scene, buffers);
    EXPECT_TRUE(vpl_view_importance_in_kernels(*backend, c.view, {}, 100.0f).empty());
    EXPECT_EQ(vpl_view_importance_in_kernels(*backend, ViewPoints{}, c.vpls, 100.0f),
              std::vector<float>(c.vpls.size() / TS_VPL_FLOATS, 0.0f));
    ViewPoints behind;
    behind.position = {0.0f, -1e6f, 0.0f};  // far below the floor, facing down
    behind.normal = behind.geo_normal = {0.0f, -1.0f, 0.0f};
    EXPECT_EQ(vpl_view_importance_in_kernels(*backend, behind, c.vpls, 100.0f),
              vpl_view_importance(behind, c.vpls, 100.0f));
}

}  // namespace
}  // namespace tessera
