// Effects follow the scene: the plan, and the OpenCL defines it produces.
#include "device/effect_plan.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "device/scene_buffers.h"
#include "kernels/shared/layout_igi.h"
#include "support/test_scenes.h"

namespace tessera {
namespace {

bool has(const std::vector<std::string>& v, const std::string& x) { return std::find(v.begin(), v.end(), x) != v.end(); }

TEST(EffectPlan, NoMediumMeansNoMediaWork) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(5.0f), 0.3f);
    EffectPlan p = plan_effects(s);
    EXPECT_TRUE(p.area_lights);
    EXPECT_TRUE(p.indirect);
    EXPECT_FALSE(p.medium);
    EXPECT_FALSE(p.textures);
    EXPECT_FALSE(has(p.cl_defines(), "-DTS_HAS_MEDIUM"));
    EXPECT_EQ(make_scene_buffers(s).medium[14], 0.0f);  // the kernels' "present" flag
}

TEST(EffectPlan, MediumIsCompiledInOnlyWhenItDoesSomething) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(5.0f), 0.3f);
    s.has_medium = true;  // declared, but all coefficients zero: nothing to simulate
    EXPECT_FALSE(plan_effects(s).medium);
    EXPECT_EQ(make_scene_buffers(s).medium[14], 0.0f);
    s.medium.sigma_s = glm::vec3(0.1f);
    EXPECT_TRUE(plan_effects(s).medium);
    EXPECT_TRUE(has(plan_effects(s).cl_defines(), "-DTS_HAS_MEDIUM"));
    EXPECT_EQ(make_scene_buffers(s).medium[14], 1.0f);
}

TEST(EffectPlan, BlackSurfacesNeedNoIndirectLight) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.0f), glm::vec3(5.0f), 0.3f);
    EXPECT_FALSE(plan_effects(s).indirect);
}

// PM computes light only where a medium is called for, ID only where light meets a
// diffuse surface that reflects; edge samples alone refine nothing.
TEST(EffectPlan, ComponentsComputeOnlyWhatTheSceneHas) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(5.0f), 0.3f);
    EffectPlan p = plan_effects(s);
    EXPECT_TRUE(p.components_compute(TS_COMPONENT_SS));
    EXPECT_TRUE(p.components_compute(TS_COMPONENT_ID | TS_COMPONENT_PM));
    EXPECT_FALSE(p.components_compute(TS_COMPONENT_PM));
    EXPECT_FALSE(p.components_compute(TS_COMPONENT_PM | TS_COMPONENT_EDGE));
    EXPECT_FALSE(p.components_compute(0u));
    EXPECT_EQ(p.idle_reason(TS_COMPONENT_PM), "PM computes nothing (medium: none declared); add ss or id");
    EXPECT_EQ(p.idle_reason(TS_COMPONENT_PM, EffectPlan::Naming::Key),
              "PM computes nothing (medium: none declared); turn on SS (1) or ID (2)");
    EXPECT_EQ(p.idle_reason(TS_COMPONENT_SS | TS_COMPONENT_PM), "");
    // A medium that only absorbs: PM is its transmittance, no light of its own.
    s.has_medium = true;
    s.medium.sigma_a = glm::vec3(0.1f);
    p = plan_effects(s);
    EXPECT_TRUE(p.medium);
    EXPECT_FALSE(p.components_compute(TS_COMPONENT_PM));
    EXPECT_EQ(p.idle_reason(TS_COMPONENT_PM), "PM computes nothing (the medium only absorbs: sigma_s is zero); add ss or id");
    s.medium.sigma_s = glm::vec3(0.1f);
    p = plan_effects(s);
    EXPECT_TRUE(p.components_compute(TS_COMPONENT_PM));
    EXPECT_FALSE(p.components_compute(TS_COMPONENT_EDGE));
    EXPECT_EQ(p.idle_reason(TS_COMPONENT_EDGE), "edge samples only refine the other components' pixels; add ss, id or pm");
}

// Black walls: ID computes nothing, and --components id is refused where SS would light
// the image; a scene without lights refuses no choice (every one renders its emitters).
TEST(EffectPlan, IdOnBlackSurfacesIsIdle) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.0f), glm::vec3(5.0f), 0.3f);
    EffectPlan p = plan_effects(s);
    EXPECT_FALSE(p.computes(TS_COMPONENT_ID));
    EXPECT_EQ(p.idle_reason(TS_COMPONENT_ID), "ID computes nothing (no diffuse surface reflects); add ss");
    s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(0.0f), 0.3f);
    p = plan_effects(s);
    EXPECT_FALSE(p.components_compute(TS_COMPONENT_SS | TS_COMPONENT_ID | TS_COMPONENT_PM));
    EXPECT_EQ(p.idle_reason(TS_COMPONENT_ID), "");
}

// Over the animation, walls black at rest but coloured by a later key reflect: the option
// checks read this plan, so --components id is not refused for a scene whose frame 0 (or
// any frame) lights it.
TEST(EffectPlan, AWallColouredByALaterKeyReflectsOverTheAnimation) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.0f), glm::vec3(5.0f), 0.3f);
    s.animation.frame_count = 3;
    MaterialTrack t;
    t.name = "walls";
    t.materials = {0};
    MaterialKey rest, coloured;
    rest.frame = 0;
    coloured.frame = 2;
    coloured.albedo = glm::vec3(0.5f);
    t.keys = {rest, coloured};
    s.animation.materials.push_back(t);
    EXPECT_FALSE(plan_effects(s).indirect);
    EXPECT_TRUE(plan_effects_over_animation(s).indirect);
    EXPECT_EQ(plan_effects_over_animation(s).idle_reason(TS_COMPONENT_ID), "");
}

// A mirror's Kd is not read (bsdf.h): black diffuse walls with a mirror call for no ID,
// whatever the mirror's Kd; the same walls in grey do.
TEST(EffectPlan, AMirrorsKdIsNotReflection) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.0f), glm::vec3(5.0f), 0.3f);
    const uint32_t mirror = test::add_material(s, glm::vec3(0.5f));
    s.materials[mirror].illum = 3;
    s.materials[mirror].specular = glm::vec3(1.0f);
    test::add_quad(s, {-0.5f, 0.5f, -0.9f}, {1, 0, 0}, {0, 1, 0}, mirror);
    EXPECT_FALSE(plan_effects(s).indirect);
    s.materials[mirror].illum = 2;  // the same Kd on a diffuse material reflects
    EXPECT_TRUE(plan_effects(s).indirect);
}

// describe() names the one reason that holds, so `tessera info` tells the user what to change.
TEST(EffectPlan, DescribeNamesTheReasonThatHolds) {
    const auto line = [](const EffectPlan& p, const std::string& head) {
        for (const std::string& l : p.describe())
            if (l.rfind(head, 0) == 0) return l;
        return std::string("(no line)");
    };
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(5.0f), 0.3f);
    EXPECT_EQ(line(plan_effects(s), "medium"), "medium (PM):          no (none declared)");
    s.has_medium = true;
    EXPECT_EQ(line(plan_effects(s), "medium"), "medium (PM):          no (declared, but sigma_a and sigma_s are zero)");
    s.medium.sigma_a = glm::vec3(0.1f);
    EXPECT_EQ(line(plan_effects(s), "medium"),
              "medium (PM):          yes (absorbs only: its transmittance, no in-scattered light)");
    s.medium.sigma_s = glm::vec3(0.0f, 0.1f, 0.0f);
    EXPECT_EQ(line(plan_effects(s), "medium"), "medium (PM):          yes");
    EXPECT_EQ(line(plan_effects(s), "indirect"), "indirect diffuse (ID): yes");
    Scene black = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.0f), glm::vec3(5.0f), 0.3f);
    EXPECT_EQ(line(plan_effects(black), "indirect"), "indirect diffuse (ID): no (no diffuse surface reflects)");
    Scene dark = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(0.0f), 0.3f);
    EXPECT_EQ(line(plan_effects(dark), "indirect"), "indirect diffuse (ID): no (no light)");
}

}  // namespace
}  // namespace tessera
