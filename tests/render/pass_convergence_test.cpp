// With passes (each a fresh frame: new VPL sets and light samples, the camera ray jittered
// anew inside the pixel, the texture footprint narrowing as 1/sqrt(pass + 1)), every
// interactive method's accumulated image approaches the path tracer's image of the same
// transport: its error against a converged `pt` render falls with the pass count, on the
// Cornell box, its fog version (multiple scattering, the default, against `pt`; single
// scattering against `pt --max-scatter 1`) and a textured scene (a minified checker,
// whose reference is the texels' mean under each pixel).
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "scene/loader.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace tessera {
namespace {

struct ConvergenceCase {
    const char* name;
    Scene scene;
    uint32_t max_scatter;  ///< the reference's: 1 where the methods compute single scattering
    bool multiple_scattering = true;
};

std::vector<ConvergenceCase> cases() {
    const DataPath data = make_data_path(std::nullopt);
    const std::filesystem::path dir(TESSERA_SCENES_DIR);
    return {{"cornell", load_scene(dir / "cornell-box.json", data), 0},
            {"cornell-fog", load_scene(dir / "cornell-box-fog.json", data), 0},
            {"cornell-fog-single", load_scene(dir / "cornell-box-fog.json", data), 1, false},
            {"checker", test::checker_floor(), 0}};
}

RenderSettings small(Method m, uint32_t spp) {
    RenderSettings rs;
    rs.method = m;
    rs.width = rs.height = 24;
    rs.spp = spp;
    rs.igi.paths_per_set = 8;
    rs.ic.paths = 64;
    return rs;
}

TEST(PassConvergence, ErrorAgainstPathTracerFallsWithPasses) {
    for (const ConvergenceCase& c : cases()) {
        RenderSettings rs = small(Method::PathTrace, 2048);
        rs.max_scatter = c.max_scatter;
        const Image ref = test::render_with(BackendKind::Embree, c.scene, rs);
        // Away from the light: its edge pixels' error is the camera jitter's coverage of a
        // bright emitter, as large in any single pass (a 2-pass render can have 7× the
        // relMSE of a 1-pass one), not a measure of the lighting.
        const std::vector<bool> keep = test::away_from_emitter(ref);
        rs.seed += 1000;  // the reference's own noise: a second seed against it
        const double noise = test::rel_mse_where(test::render_with(BackendKind::Embree, c.scene, rs), ref, keep);
        for (Method m : {Method::Igi, Method::Ais, Method::Ic}) {
            double err[3];
            const uint32_t passes[3] = {1, 4, 16};
            for (int i = 0; i < 3; ++i)
            {
                RenderSettings rs = small(m, passes[i]);
                rs.igi.multiple_scattering = c.multiple_scattering;
                err[i] = test::rel_mse_where(test::render_with(BackendKind::Embree, c.scene, rs), ref, keep);
            }
            std::printf("  %s %s: relMSE at 1, 4, 16 passes %.4g %.4g %.4g (reference noise %.4g)\n",
                        method_name(m), c.name, err[0], err[1], err[2], noise);
            EXPECT_LT(err[1], err[0]) << method_name(m) << " " << c.name;
            // Falling further, or already down to (twice) the reference's noise, where it cannot.
            EXPECT_LT(err[2], std::max(err[1], 2.0 * noise)) << method_name(m) << " " << c.name;
        }
    }
}

}  // namespace
}  // namespace tessera
