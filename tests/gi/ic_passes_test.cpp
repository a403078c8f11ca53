// The instant caches of a frame's passes (gi/ic_passes.h): pass p of ic and of tic draws
// path block p, so tic's frame 0 is ic's image for any spp, tic's passes carry different
// VPLs that stay the ones ic would draw after the update, the clamp loosens per pass,
// the caches over the memory budget are released, and the stats sum over the passes.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "gi/ic_passes.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "support/render_helpers.h"
#include "util/error.h"

namespace tessera {
namespace {

RenderSettings small(Method m, uint32_t spp) {
    RenderSettings s;
    s.method = m;
    s.spp = spp;
    s.width = s.height = 32;
    s.igi.tile = 1;
    s.ic.paths = 32;
    return s;
}

class IcPassesOn : public ::testing::TestWithParam<BackendKind> {};

TEST(IcSubsets, FollowTheSppAndTheImageSize) {
    // docs/instant-caching.md §2b: 1 below 4 spp, 2 below 16, then 4 on small images and 16
    // from 2^16 pixels; a given M stays as given.
    EXPECT_EQ(ic_subsets_for(1, 512 * 512), 1u);
    EXPECT_EQ(ic_subsets_for(4, 512 * 512), 2u);
    EXPECT_EQ(ic_subsets_for(15, 512 * 512), 2u);
    EXPECT_EQ(ic_subsets_for(16, 128 * 96), 4u);
    EXPECT_EQ(ic_subsets_for(16, 256 * 256 - 1), 4u);
    EXPECT_EQ(ic_subsets_for(16, 256 * 256), 16u);
    EXPECT_EQ(ic_subsets_for(64, 384 * 256), 16u);
    RenderSettings s;
    s.spp = 16;
    EXPECT_EQ(integrator_settings(s, 384, 256).ic.subsets, 16u);
    EXPECT_EQ(integrator_settings(s, 128, 96).ic.subsets, 4u);
    s.ic.subsets = 3;
    EXPECT_EQ(integrator_settings(s, 384, 256).ic.subsets, 3u);
}

TEST_P(IcPassesOn, TicFrameZeroIsIcForEverySpp) {
    // Pass p of both draws path block p with pass p's clamp and places the same records
    // from the same G-buffer: the same bits, at any spp. (Before, tic drew block 0 in
    // every pass with a fixed clamp: its spp = 4 image was its spp = 1 image.)
    const Scene scene = test::cornell_box();
    // spp 4 and 16 draw 2 and 4 path subsets (ic_subsets_for: a small image) in both;
    // the last round gives the 16 a larger image draws at 16 spp.
    struct Case {
        uint32_t spp, subsets;  // subsets 0: by spp and size
    };
    for (const Case c : {Case{1, 0}, Case{2, 0}, Case{4, 0}, Case{16, 0}, Case{16, 16}}) {
        RenderSettings ic = small(Method::Ic, c.spp), tic = small(Method::Tic, c.spp);
        ic.ic.subsets = tic.ic.subsets = c.subsets;
        test::expect_images_identical(test::render_with(GetParam(), scene, ic), test::render_with(GetParam(), scene, tic));
    }
    const Image one = test::render_with(GetParam(), scene, small(Method::Tic, 1));
    const Image four = test::render_with(GetParam(), scene, small(Method::Tic, 4));
    EXPECT_GT(test::rel_mse(four, one), 1e-5) << "tic's passes must differ";
}

TEST_P(IcPassesOn, EachPassKeepsItsOwnLightPathsAcrossFrames) {
    // Two frames of the animated Cornell box with tic at 2 spp: after the update, pass p's
    // cache gathers from exactly the VPLs ic draws for pass p on that frame, and passes 0
    // and 1 gather from different VPLs. With the paths as drawn (K = 1): paths kept for
    // the view are kept for the view of the frame the cache was built on
    // (KeepsThePathsItKeptForTheFirstView).
    const Scene rest = test::shipped_scene("cornell-box-animated.json");
    RenderSettings tic = small(Method::Tic, 2);
    tic.ic.path_importance = 1;
    tic.ic.temporal = true;
    tic.ic_state = std::make_shared<IcPassCaches>(tic.ic, rest.objects);
    RenderStats stats;
    for (int f = 0; f < 2; ++f) {
        const Scene scene = scene_at_frame(rest, f);
        const SceneBuffers buffers = make_scene_buffers(scene);
        auto backend = make_backend({GetParam(), ""}, buffers, plan_effects(scene));
        render_frame(*backend, scene, buffers, tic, &stats);
        if (f == 0) {
            // Frame 0 traces both passes' paths afresh; the stats sum over the passes.
            EXPECT_EQ(stats.ic.paths_retraced, 2u * tic.ic.paths);  // K = 1: the paths as drawn
            EXPECT_EQ(stats.ic.records, tic.ic_state->pass(0).cache().records().size() +
                                            tic.ic_state->pass(1).cache().records().size());
            EXPECT_NE(stats.detail.find("summed over 2 passes"), std::string::npos) << stats.detail;
        }
    }
    EXPECT_GT(stats.ic.paths_retraced, 0u) << "the light dims on frame 1: every path of both passes re-traced";
    EXPECT_EQ(tic.ic_state->kept(), 2u);
    const std::vector<float>& v0 = tic.ic_state->pass(0).vpls();
    const std::vector<float>& v1 = tic.ic_state->pass(1).vpls();
    EXPECT_NE(v0, v1);
    const Scene scene = scene_at_frame(rest, 1);
    const SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = make_backend({GetParam(), ""}, buffers, plan_effects(scene));
    for (uint32_t pass : {0u, 1u}) {
        RenderSettings ic = small(Method::Ic, pass + 1);  // ic's one cache holds its last pass
        ic.ic.path_importance = 1;
        ic.ic_state = std::make_shared<IcPassCaches>(ic.ic, rest.objects);
        render_frame(*backend, scene, buffers, ic);
        EXPECT_EQ(ic.ic_state->pass(pass).vpls(), tic.ic_state->pass(pass).vpls()) << "pass " << pass;
    }
}

TEST_P(IcPassesOn, KeepsThePathsItKeptForTheFirstView) {
    // At the default K = 8, a pass's cache keeps paths for the view it was built for
    // (select_paths): 8·paths candidates, paths' worth kept, weights 1/p. Over an animation
    // the temporal update re-traces kept paths with the same indices and weights, so
    // its estimate stays unbiased and equal to the rebuild.
    const Scene rest = test::shipped_scene("cornell-box-animated.json");
    RenderSettings tic = small(Method::Tic, 1);
    ASSERT_EQ(tic.ic.path_importance, 8u);
    tic.ic.temporal = true;
    tic.ic_state = std::make_shared<IcPassCaches>(tic.ic, rest.objects);
    std::vector<std::pair<uint64_t, float>> first;
    for (int f = 0; f < 3; ++f) {
        const Scene scene = scene_at_frame(rest, f);
        const SceneBuffers buffers = make_scene_buffers(scene);
        auto backend = make_backend({GetParam(), ""}, buffers, plan_effects(scene));
        RenderStats stats;
        render_frame(*backend, scene, buffers, tic, &stats);
        std::vector<std::pair<uint64_t, float>> now;
        for (const LightPath& p : tic.ic_state->pass(0).paths()) now.emplace_back(p.index, p.weight);
        if (f == 0) {
            EXPECT_EQ(stats.ic.paths_retraced, 8u * tic.ic.paths) << "frame 0 traces every candidate";
            EXPECT_GT(stats.ic.view_rays, 0u) << "the candidates' VPLs test the view points' visibility";
            EXPECT_LE(stats.ic.view_rays, uint64_t(tic.ic.view_rays) * stats.ic.light_path_rays)
                << "S per candidate VPL, each at most one per light-path ray";
            first = now;
            continue;
        }
        EXPECT_EQ(now, first) << "frame " << f << ": the same paths with the same weights";
    }
    // Kept: on average `paths` of the 8·paths candidates, each with weight 1/p ≥ 1.
    EXPECT_GT(first.size(), tic.ic.paths / 2);
    EXPECT_LT(first.size(), 2 * tic.ic.paths);
    size_t weighted = 0;
    for (const auto& [index, weight] : first) {
        EXPECT_LT(index, 8u * tic.ic.paths) << "path block 0 of 8·paths candidates";
        EXPECT_GE(weight, 1.0f);
        weighted += weight > 1.0f;
    }
    EXPECT_GT(weighted, first.size() / 2) << "most kept paths had p < 1";
}

TEST(IcPasses, ReleasesCachesOverTheMemoryBudget) {
    IcSettings s;
    s.temporal = true;
    IcPassCaches caches(s, {});
    EXPECT_FALSE(caches.after_pass(0)) << "nothing kept yet";
    EXPECT_THROW(static_cast<const IcPassCaches&>(caches).pass(3), std::out_of_range);
    IcSettings bad;
    bad.min_radius_px = 0.0f;
    EXPECT_THROW(IcPassCaches(bad, {}), InputError) << "bad settings fail before the first pass";
    IcSettings fresh;  // ic: one cache serves every pass
    IcPassCaches ic(fresh, {});
    EXPECT_EQ(&ic.pass(0), &ic.pass(5));
    EXPECT_NE(&caches.pass(0), &caches.pass(1));
}

INSTANTIATE_TEST_SUITE_P(Backends, IcPassesOn, ::testing::Values(BackendKind::Embree, BackendKind::OpenCL),
                         [](const auto& info) { return info.param == BackendKind::Embree ? "Embree" : "OpenCL"; });

}  // namespace
}  // namespace tessera
