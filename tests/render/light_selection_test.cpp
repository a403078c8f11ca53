// Lights are picked by their animation maximum (Material::emission_max), not by this
// frame's emission, so a dimmed light is picked more often than its power warrants. The
// estimators must stay unbiased: the MIS weight of an emitter hit uses the pick pdf the
// light sampler really has (materials [12], layout_scene.h), so the image cannot depend on
// emission_max.
#include <gtest/gtest.h>

#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace tessera {
namespace {

Scene two_lights() {
    // A large ceiling light (the box's) and a wall light, close to the surfaces they
    // light, where BSDF sampling carries a large share of the MIS-weighted estimate.
    Scene s = test::closed_box({0, 0, 0}, {1, 1, 1}, glm::vec3(0.6f), glm::vec3(4.0f), 0.4f);
    const uint32_t wall_light = test::add_material(s, glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 3.0f));
    test::add_quad(s, {0.001f, 0.2f, 0.2f}, {0, 0.6f, 0}, {0, 0, 0.6f}, wall_light);  // faces +x
    return s;
}

TEST(LightSelection, ImageDoesNotDependOnTheAnimationMaximum) {
    const Scene plain = two_lights();
    Scene dimmed = plain;
    dimmed.materials[1].emission_max = 8.0f * dimmed.materials[1].emission;  // at 1/8 of its maximum
    for (Method m : {Method::PathTrace, Method::Direct}) {
        RenderSettings s;
        s.method = m;
        s.spp = 64;
        s.shadow_samples = 2;
        s.max_depth = 3;
        const Image a = test::render_with(BackendKind::Embree, plain, s);
        const Image b = test::render_with(BackendKind::Embree, dimmed, s);
        // Means over the image's 1024 pixels × 64 spp: their noise is well below 1% (the
        // two runs draw the same samples, so the difference is smaller still). A pick pdf
        // taken from this frame's emission instead would weight the strategies
        // inconsistently and shift the mean by several percent.
        for (const char* c : {"R", "G", "B"}) {
            const double ma = test::channel_mean(a, c), mb = test::channel_mean(b, c);
            EXPECT_NEAR(mb / ma, 1.0, 0.01) << method_name(m) << " " << c;
        }
    }
}

}  // namespace
}  // namespace tessera
