// The light paths' seed (gi/light_paths.h): the same seed draws the same VPLs bit for bit,
// another seed independent ones, and the default seed keeps the project's sequence. End to
// end, every method renders the same bits for the same seed and another image for another
// seed, and the VPL methods' VPL sets change with it (igi's, ic's and tic's).
#include <cstring>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "gi/ic_passes.h"
#include "gi/light_paths.h"
#include "gi/vpl_generator.h"
#include "render/renderer.h"
#include "support/render_helpers.h"

namespace tessera {
namespace {

std::vector<float> vpls_of(Backend& backend, const SceneBuffers& buffers, uint32_t seed) {
    VplSettings vs;
    vs.sets = 2;
    vs.paths_per_set = 16;
    vs.seed = seed;
    return generate_vpls(backend, buffers, vs).vpls;
}

TEST(LightPaths, SeedDrawsIndependentPaths) {
    EXPECT_EQ(light_path_seed_mix(1u), 0u) << "seed 1 keeps the sequence the figures were measured with";
    EXPECT_NE(light_path_seed_mix(2u), 0u);
    const Scene scene = test::cornell_box();
    const SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = make_backend({BackendKind::Embree, ""}, buffers, plan_effects(scene));
    const std::vector<float> a = vpls_of(*backend, buffers, 1), again = vpls_of(*backend, buffers, 1);
    const std::vector<float> b = vpls_of(*backend, buffers, 2);
    ASSERT_GT(a.size(), 20u * TS_VPL_FLOATS);
    EXPECT_EQ(a, again);
    // Another seed: no VPL position in common (independent Halton scrambling).
    size_t shared = 0;
    for (size_t i = 0; i < a.size(); i += TS_VPL_FLOATS)
        for (size_t j = 0; j < b.size(); j += TS_VPL_FLOATS)
            shared += std::memcmp(&a[i + TS_VPL_POSITION], &b[j + TS_VPL_POSITION], 3 * sizeof(float)) == 0;
    EXPECT_EQ(shared, 0u);
}

TEST(LightPaths, EveryMethodRendersItsSeed) {
    const Scene scene = test::cornell_box();
    for (Method m : {Method::Direct, Method::PathTrace, Method::Igi, Method::Ais, Method::AisMax, Method::Ic,
                     Method::Tic}) {
        RenderSettings rs;
        rs.method = m;
        rs.width = rs.height = 16;
        rs.spp = 2;
        rs.ic.paths = 16;
        rs.aovs = m != Method::Direct && m != Method::PathTrace;
        const Image one = test::render_with(BackendKind::Embree, scene, rs);
        test::expect_images_identical(one, test::render_with(BackendKind::Embree, scene, rs));
        rs.seed = 2;
        const Image two = test::render_with(BackendKind::Embree, scene, rs);
        EXPECT_GT(test::rel_mse(two, one), 1e-6) << method_name(m);
        if (!rs.aovs) continue;
        // The indirect component depends on the VPLs alone (not the light samples): it
        // changes with the seed only if the VPL sets do. Measured before the fix, igi's
        // ID moved by relMSE ~1e-4 (the interleave's shift); with new VPLs by ~1e-2.
        double diff = 0.0;
        size_t n = 0;
        for (const char* c : {"ID.R", "ID.G", "ID.B"}) {
            const auto &x = one.find(c)->data, &y = two.find(c)->data;
            for (size_t i = 0; i < x.size(); ++i, ++n)
                diff += (double(x[i]) - y[i]) * (double(x[i]) - y[i]) / (double(y[i]) * y[i] + 1e-2);
        }
        EXPECT_GT(diff / double(n), 1e-3) << method_name(m) << ": the VPLs must change with the seed";
    }
}

}  // namespace
}  // namespace tessera
