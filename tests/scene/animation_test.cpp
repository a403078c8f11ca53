// Scene animation: keyframe interpolation, the pivot rule, material and camera keys,
// stable triangle and light lists across frames, and every validation error.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "device/scene_buffers.h"
#include "scene/animation.h"
#include "scene/scene_test_util.h"
#include "support/scratch_dir.h"

namespace tessera {
namespace {

using test::fixture;

constexpr float kEps = 1e-5f;

#define EXPECT_VEC3_NEAR(a, b)                \
    do {                                      \
        const glm::vec3 va = (a), vb = (b);   \
        EXPECT_NEAR(va.x, vb.x, kEps);        \
        EXPECT_NEAR(va.y, vb.y, kEps);        \
        EXPECT_NEAR(va.z, vb.z, kEps);        \
    } while (0)

// tests/data/quad.obj (the unit square in the xz plane, normal +y, material "grey")
// named "floor", and two JSON quad lights (json-light-0, json-light-1).
class AnimationTest : public test::ScratchDirTest {
protected:
    // The scene file with `animation` (raw JSON text) as its "animation" block and
    // `light0` as the first light's radiance.
    std::filesystem::path write_scene(const std::string& animation, const std::string& light0 = "[4, 3, 2]") {
        const std::filesystem::path file = dir_ / "anim.json";
        std::ofstream(file) << R"({"name": "anim", "camera": {"position": [0, 2, 3], "look_at": [0.5, 0, 0.5]},
  "objects": [{"name": "floor", "mesh": ")"
                            << fixture("quad.obj").string() << R"("}],
  "lights": [{"type": "quad", "corner": [0, 2, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": )"
                            << light0 << R"(},
             {"type": "quad", "corner": [2, 2, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": [1, 1, 1]}],
  "animation": )" << animation
                            << "}\n";
        return file;
    }
    Scene load(const std::string& animation, const std::string& light0 = "[4, 3, 2]") {
        return load_scene(write_scene(animation, light0), DataPath{});
    }
    std::string error(const std::string& animation, const std::string& light0 = "[4, 3, 2]") {
        return test::load_error(write_scene(animation, light0));
    }
};

// Index of the rest vertex at `p` in the floor's triangles.
size_t vertex_at(const Scene& s, glm::vec3 p) {
    for (size_t v = 0; v < 6; ++v)
        if (glm::length(s.positions[v] - p) < kEps) return v;
    ADD_FAILURE() << "no vertex at the given point";
    return 0;
}

const Material& material_named(const Scene& s, const std::string& name) {
    for (const Material& m : s.materials)
        if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
}

TEST_F(AnimationTest, ParsesTracks) {
    const Scene s = load(R"({"frames": 11, "objects": {"floor": [{"frame": 0}, {"frame": 10, "translate": [2, 0, 0]}]}})");
    EXPECT_EQ(s.animation.frame_count, 11);
    ASSERT_EQ(s.animation.objects.size(), 1u);
    EXPECT_EQ(s.animation.objects[0].objects, std::vector<uint32_t>{0u});
    EXPECT_EQ(s.animation.objects[0].keys.size(), 2u);
    EXPECT_EQ(s.objects[0].name, "floor");
}

TEST_F(AnimationTest, TranslateInterpolatesLinearly) {
    const Scene rest = load(R"({"frames": 11, "objects": {"floor": [{"frame": 0}, {"frame": 10, "translate": [2, 0, 0]}]}})");
    const Scene mid = scene_at_frame(rest, 5), end = scene_at_frame(rest, 10), start = scene_at_frame(rest, 0);
    for (size_t v = 0; v < 6; ++v) {
        EXPECT_VEC3_NEAR(start.positions[v], rest.positions[v]);
        EXPECT_VEC3_NEAR(mid.positions[v], rest.positions[v] + glm::vec3(1, 0, 0));
        EXPECT_VEC3_NEAR(end.positions[v], rest.positions[v] + glm::vec3(2, 0, 0));
    }
    // The lights are other objects: they stay put.
    for (size_t v = 6; v < rest.positions.size(); ++v) EXPECT_EQ(end.positions[v], rest.positions[v]);
}

TEST_F(AnimationTest, HoldsEndValuesOutsideTheKeys) {
    const Scene rest = load(
        R"({"frames": 10, "objects": {"floor": [{"frame": 2, "translate": [1, 0, 0]}, {"frame": 6, "translate": [3, 0, 0]}]}})");
    EXPECT_VEC3_NEAR(scene_at_frame(rest, 0).positions[0], rest.positions[0] + glm::vec3(1, 0, 0));
    EXPECT_VEC3_NEAR(scene_at_frame(rest, 2).positions[0], rest.positions[0] + glm::vec3(1, 0, 0));
    EXPECT_VEC3_NEAR(scene_at_frame(rest, 4).positions[0], rest.positions[0] + glm::vec3(2, 0, 0));
    EXPECT_VEC3_NEAR(scene_at_frame(rest, 9).positions[0], rest.positions[0] + glm::vec3(3, 0, 0));
}

TEST_F(AnimationTest, RotationSlerpsHalfway) {
    const Scene rest = load(R"({"frames": 3, "objects": {"floor": [
        {"frame": 0}, {"frame": 2, "rotate": {"axis": [0, 1, 0], "degrees": 90}}]}})");
    // About the pivot (0.5, 0, 0.5): the corner (0, 0, 0) is at (-0.5, 0, -0.5) from it;
    // 45° about +y takes that to (-√½, 0, 0), 90° to (-0.5, 0, 0.5).
    const size_t v = vertex_at(rest, {0, 0, 0});
    const float h = std::sqrt(0.5f);
    EXPECT_VEC3_NEAR(scene_at_frame(rest, 1).positions[v], glm::vec3(0.5f - h, 0, 0.5f));
    EXPECT_VEC3_NEAR(scene_at_frame(rest, 2).positions[v], glm::vec3(0, 0, 1));
    EXPECT_VEC3_NEAR(scene_at_frame(rest, 1).normals[v], glm::vec3(0, 1, 0));
}

TEST_F(AnimationTest, PivotIsTheRestBoundingBoxCentre) {
    const Scene rest = load(R"({"frames": 2, "objects": {"floor": [
        {"frame": 0, "translate": [1, 0, 0], "rotate": {"axis": [0, 0, 2], "degrees": 90}, "scale": 2}]}})");
    // p' = pivot + t + R·(s·(p − pivot)): (1, 0, 1) − (0.5, 0, 0.5) = (0.5, 0, 0.5), scaled
    // (1, 0, 1), rotated 90° about z (0, 1, 1), plus pivot and translate (1.5, 1, 1.5).
    const size_t v = vertex_at(rest, {1, 0, 1});
    for (const int frame : {0, 1}) {
        const Scene s = scene_at_frame(rest, frame);
        EXPECT_VEC3_NEAR(s.positions[v], glm::vec3(1.5f, 1.0f, 1.5f));
        EXPECT_VEC3_NEAR(s.normals[v], glm::vec3(-1, 0, 0));  // +y turned 90° about z
        EXPECT_VEC3_NEAR(test::geometric_normal(s, 0), glm::vec3(-1, 0, 0));
    }
}

TEST_F(AnimationTest, MaterialKeys) {
    const Scene rest = load(R"({"frames": 5, "materials": {
        "grey": [{"frame": 0, "albedo": [0, 0, 0]}, {"frame": 4, "albedo": [0.8, 0.4, 0.2]}],
        "json-light-0": [{"frame": 0}, {"frame": 4, "emission": [0, 0, 0]}]}})");
    const Scene s2 = scene_at_frame(rest, 2), s1 = scene_at_frame(rest, 1);
    EXPECT_VEC3_NEAR(material_named(s2, "grey").albedo, glm::vec3(0.4f, 0.2f, 0.1f));
    EXPECT_VEC3_NEAR(material_named(s2, "grey").emission, glm::vec3(0.0f));  // no emission key: rest
    // A key without emission holds the rest value (4, 3, 2) at frame 0.
    EXPECT_VEC3_NEAR(material_named(s1, "json-light-0").emission, glm::vec3(3.0f, 2.25f, 1.5f));
    EXPECT_VEC3_NEAR(material_named(s1, "json-light-0").albedo, glm::vec3(0.0f));
    EXPECT_VEC3_NEAR(material_named(scene_at_frame(rest, 4), "json-light-0").emission, glm::vec3(0.0f));
    EXPECT_VEC3_NEAR(material_named(s1, "json-light-1").emission, glm::vec3(1.0f));
}

TEST_F(AnimationTest, CameraKeys) {
    const Scene rest = load(R"({"frames": 5, "camera": [
        {"frame": 0}, {"frame": 4, "position": [4, 2, 3]}]})");
    const Camera c = scene_at_frame(rest, 2).camera;
    EXPECT_VEC3_NEAR(c.position, glm::vec3(2, 2, 3));
    EXPECT_VEC3_NEAR(c.look_at, glm::vec3(0.5f, 0, 0.5f));  // no look_at key: rest
    EXPECT_EQ(c.vfov_deg, rest.camera.vfov_deg);
    const Scene moved = load(R"({"frames": 3, "camera": [{"frame": 1, "look_at": [1, 0, 1]}]})");
    EXPECT_VEC3_NEAR(scene_at_frame(moved, 0).camera.look_at, glm::vec3(1, 0, 1));
}

TEST_F(AnimationTest, TrianglesKeepCountAndOrder) {
    const Scene rest = load(R"({"frames": 4, "objects": {"floor": [{"frame": 0},
        {"frame": 3, "translate": [0, 1, 0], "rotate": {"axis": [1, 0, 0], "degrees": 30}}]},
        "materials": {"grey": [{"frame": 3, "albedo": [1, 1, 1]}]}})");
    for (int f = 0; f < 4; ++f) {
        const Scene s = scene_at_frame(rest, f);
        EXPECT_EQ(s.triangle_count(), rest.triangle_count());
        EXPECT_EQ(s.material, rest.material);
        EXPECT_EQ(s.uvs, rest.uvs);
        EXPECT_EQ(s.materials.size(), rest.materials.size());
        EXPECT_EQ(s.animation.frame_count, 4);
        ASSERT_EQ(s.objects.size(), rest.objects.size());
        for (size_t o = 0; o < s.objects.size(); ++o) EXPECT_EQ(s.objects[o].name, rest.objects[o].name);
    }
}

TEST_F(AnimationTest, FrameOutsideTheAnimationThrows) {
    const Scene rest = load(R"({"frames": 4, "objects": {"floor": [{"frame": 0}]}})");
    EXPECT_THROW(scene_at_frame(rest, 4), InputError);
    EXPECT_THROW(scene_at_frame(rest, -1), InputError);
    const Scene still = load_scene(fixture("light.json"), DataPath{});
    EXPECT_EQ(still.animation.frame_count, 0);
    EXPECT_EQ(scene_at_frame(still, 0).positions, still.positions);
    try {
        scene_at_frame(still, 1);
        ADD_FAILURE() << "frame 1 of a static scene was accepted";
    } catch (const InputError& e) {
        EXPECT_CONTAINS(e.what(), "frame 1");
    }
}

TEST_F(AnimationTest, EmissionMaxIsTheLargestKeyedEmission) {
    const Scene rest = load(R"({"frames": 5, "materials": {"json-light-0": [
        {"frame": 0, "emission": [1, 5, 0]}, {"frame": 4, "emission": [3, 0, 0]}]}})");
    EXPECT_VEC3_NEAR(material_named(rest, "json-light-0").emission_max, glm::vec3(3, 5, 0));
    EXPECT_VEC3_NEAR(material_named(rest, "json-light-1").emission_max, glm::vec3(1));
    EXPECT_VEC3_NEAR(material_named(rest, "grey").emission_max, glm::vec3(0));
    const Scene still = load_scene(fixture("light.json"), DataPath{});
    for (const Material& m : still.materials) EXPECT_EQ(m.emission_max, m.emission);
}

// Whether every vertex of `s`'s first `count` (all by default) lies in `b`.
bool holds_every_vertex(const SceneBounds& b, const Scene& s, size_t count = SIZE_MAX) {
    for (size_t v = 0; v < std::min(count, s.positions.size()); ++v)
        if (glm::any(glm::lessThan(s.positions[v], b.lo)) || glm::any(glm::greaterThan(s.positions[v], b.hi)))
            return false;
    return true;
}

// Without a turn, poses between keys mix the key poses linearly: the motion bounds are
// the key poses' boxes (plus the 1e-5 slack, here 4e-5), and the scene buffers' reach,
// the far roulette's region for light paths, is the same box in every frame.
TEST_F(AnimationTest, MotionBoundsAreTheKeyPosesWithoutATurn) {
    const Scene rest = load(R"({"frames": 11, "objects": {"floor": [
        {"frame": 0}, {"frame": 10, "translate": [2, 0, 0], "scale": 2}]}})");
    // Key 10: pivot (0.5, 0, 0.5) + (2, 0, 0), half-size 2 × (0.5, 0, 0.5).
    const SceneBounds m = motion_bounds(rest);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(m.lo[a], glm::vec3(0, 0, -0.5f)[a], 5e-5f) << a;
        EXPECT_NEAR(m.hi[a], glm::vec3(3.5f, 0, 1.5f)[a], 5e-5f) << a;
    }
    const SceneBuffers first = make_scene_buffers(scene_at_frame(rest, 0));
    for (int f = 0; f < 11; ++f) {
        const Scene s = scene_at_frame(rest, f);
        EXPECT_TRUE(holds_every_vertex(m, s, 6)) << "frame " << f;  // the floor's
        // The reach is built from the still lights and m alone, yet holds every vertex.
        const SceneBuffers b = make_scene_buffers(s);
        EXPECT_TRUE(holds_every_vertex(b.reach, s)) << "frame " << f;
        EXPECT_EQ(b.reach, first.reach) << "frame " << f;
        // The frame's own bounds reach the last key's pose only at its frame.
        EXPECT_EQ(b.bounds.hi.x < b.reach.hi.x - 0.1f, f < 10) << "frame " << f;
    }
}

// A turn between keys: a slerp carries the corners outside both key poses' boxes, and
// the bounds hold the sphere about the pivot instead (radius: the half-diagonal √½).
// The floor's vertices are the scene's first 6 (the lights stand still).
TEST_F(AnimationTest, MotionBoundsHoldATurningObject) {
    const Scene rest = load(R"({"frames": 9, "objects": {"floor": [
        {"frame": 0}, {"frame": 8, "translate": [0, 1, 0], "rotate": {"axis": [0, 1, 0], "degrees": 90}}]}})");
    const SceneBounds m = motion_bounds(rest);
    const float r = std::sqrt(0.5f);
    EXPECT_NEAR(m.lo.x, 0.5f - r, 5e-5f);
    EXPECT_NEAR(m.hi.y, 1.0f + r, 5e-5f);
    for (int f = 0; f < 9; ++f) EXPECT_TRUE(holds_every_vertex(m, scene_at_frame(rest, f), 6)) << "frame " << f;
    // Frame 4 turns the floor 45°: its corner (0, 0, 0) lies at x = 0.5 − √½, outside
    // both key poses' boxes (x ≥ 0).
    EXPECT_LT(scene_at_frame(rest, 4).positions[vertex_at(rest, {0, 0, 0})].x, -0.2f);
}

// No object moves (a material track alone): no motion bounds, and the reach is the
// frame's own bounds.
TEST_F(AnimationTest, NoMotionBoundsWhereNothingMoves) {
    const Scene rest = load(R"({"frames": 3, "materials": {"grey": [{"frame": 2, "albedo": [0, 0, 0]}]}})");
    EXPECT_TRUE(motion_bounds(rest).empty());
    const Scene s = scene_at_frame(rest, 1);
    const SceneBuffers b = make_scene_buffers(s);
    EXPECT_FALSE(b.bounds.empty());
    EXPECT_EQ(b.reach, b.bounds);
    // Nor a clamp length of frame 0's: the frame's own, the same in every frame.
    EXPECT_EQ(s.clamp_length, 0.0f);
    EXPECT_EQ(b.clamp_length, clamp_extent(b));
}

// The VPL clamps' length D (b = 1/(c·D)²) is frame 0's in every frame where objects move.
// Each frame's own would follow the floor 100 units away, 27 times as long, and with it
// the clamp of the light everywhere else; an animation rendered from frame 3 on gets the
// same D as one from frame 0.
TEST_F(AnimationTest, ClampLengthIsFrameZerosInEveryFrame) {
    const Scene rest = load(R"({"frames": 5, "objects": {"floor": [
        {"frame": 1}, {"frame": 4, "translate": [100, 0, 0]}]}})");
    const Scene zero = scene_at_frame(rest, 0);
    ASSERT_GT(zero.clamp_length, 0.0f);
    EXPECT_FLOAT_EQ(zero.clamp_length, clamp_extent(make_scene_buffers(zero)));
    for (int f = 4; f >= 0; --f) {
        const Scene s = scene_at_frame(rest, f);
        EXPECT_EQ(s.clamp_length, zero.clamp_length) << "frame " << f;
        EXPECT_EQ(make_scene_buffers(s).clamp_length, zero.clamp_length) << "frame " << f;
    }
    EXPECT_GT(clamp_extent(make_scene_buffers(scene_at_frame(rest, 4))), 20.0f * zero.clamp_length);

    // Frame 0's pose, not the rest pose: here frame 0 is the far one.
    const Scene away = load(R"({"frames": 3, "objects": {"floor": [
        {"frame": 0, "translate": [100, 0, 0]}, {"frame": 2}]}})");
    const Scene far0 = scene_at_frame(away, 0);
    EXPECT_FLOAT_EQ(far0.clamp_length, clamp_extent(make_scene_buffers(far0)));
    EXPECT_GT(far0.clamp_length, 20.0f * zero.clamp_length);
    EXPECT_EQ(make_scene_buffers(scene_at_frame(away, 2)).clamp_length, far0.clamp_length);

    // A posed frame used as a rest scene without its object tracks: no frame 0's length
    // carried over from the animation it came from.
    Scene still = far0;
    still.animation.objects.clear();
    EXPECT_EQ(scene_at_frame(still, 1).clamp_length, 0.0f);
}

TEST_F(AnimationTest, LightListStaysWhileALightDimsToZero) {
    const Scene rest = load(R"({"frames": 5, "materials": {"json-light-0": [
        {"frame": 0}, {"frame": 4, "emission": [0, 0, 0]}]}})");
    const SceneBuffers b0 = make_scene_buffers(scene_at_frame(rest, 0));
    EXPECT_EQ(b0.light_count, 4u);
    for (const int f : {1, 2, 4}) {
        const SceneBuffers b = make_scene_buffers(scene_at_frame(rest, f));
        EXPECT_EQ(b.light_count, b0.light_count) << "frame " << f;
        EXPECT_EQ(b.light_cdf, b0.light_cdf) << "frame " << f;
    }
    // Light 0 (the first triangle of json-light-0) keeps its place with zero radiance.
    const SceneBuffers b4 = make_scene_buffers(scene_at_frame(rest, 4));
    EXPECT_EQ(b4.lights[9], 0.0f);
    EXPECT_EQ(b4.lights[10], 0.0f);
    EXPECT_EQ(b4.lights[11], 0.0f);
    EXPECT_EQ(b0.lights[9], 4.0f);
}

TEST_F(AnimationTest, LightDarkAtRestButLitLaterCounts) {
    const Scene rest = load(R"({"frames": 3, "materials": {"json-light-0": [{"frame": 2, "emission": [2, 2, 2]}]}})",
                            "[0, 0, 0]");
    EXPECT_VEC3_NEAR(material_named(rest, "json-light-0").emission_max, glm::vec3(2));
    EXPECT_VEC3_NEAR(material_named(scene_at_frame(rest, 0), "json-light-0").emission, glm::vec3(2));
}

TEST_F(AnimationTest, NoLightsWhenEmissionMaxIsZero) {
    // Both lights are lit at rest but dark in every frame: emission_max is zero.
    const std::string e = error(R"({"frames": 2, "materials": {
        "json-light-0": [{"frame": 0, "emission": [0, 0, 0]}],
        "json-light-1": [{"frame": 0, "emission": [0, 0, 0]}, {"frame": 1, "emission": [0, 0, 0]}]}})");
    EXPECT_CONTAINS(e, "has no lights");
}

struct BadAnimation {
    const char* animation;
    const char* key;
    const char* what;
};

class AnimationErrors : public AnimationTest, public ::testing::WithParamInterface<BadAnimation> {};

TEST_P(AnimationErrors, NameFileAndKey) {
    const std::string e = error(GetParam().animation);
    EXPECT_CONTAINS(e, "anim.json");
    EXPECT_CONTAINS(e, std::string("key '") + GetParam().key + "'");
    EXPECT_CONTAINS(e, GetParam().what);
}

INSTANTIATE_TEST_SUITE_P(
    Animation, AnimationErrors,
    ::testing::Values(
        BadAnimation{R"({"frames": 0})", "animation.frames", "frames in 1..100000"},
        BadAnimation{R"({"frames": 100001})", "animation.frames", "frames in 1..100000"},
        BadAnimation{R"({"frames": 18446744073709551615})", "animation.frames", "integer out of range"},
        BadAnimation{R"({"frames": 1e999})", "animation.frames", "'1e999' overflows a double"},
        BadAnimation{R"({"frames": "30"})", "animation.frames", "expected an integer, got string"},
        // Unknown keys (misspellings) at every level of the block, with a suggestion.
        BadAnimation{R"({"frames": 3, "frame": 2})", "animation.frame", "did you mean 'frames'?"},
        BadAnimation{R"({"frames": 3, "object": {}})", "animation.object", "did you mean 'objects'?"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "translat": [1, 0, 0]}]}})",
                     "animation.objects.floor[0].translat", "did you mean 'translate'?"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "rotate": {"axis": [0, 1, 0], "degree": 5}}]}})",
                     "animation.objects.floor[0].rotate.degree", "did you mean 'degrees'?"},
        BadAnimation{R"({"frames": 3, "materials": {"grey": [{"frame": 0, "emision": [1, 1, 1]}]}})",
                     "animation.materials.grey[0].emision", "did you mean 'emission'?"},
        BadAnimation{R"({"frames": 3, "camera": [{"frame": 0, "look_at": [0, 0, 0], "positon": [0, 1, 3]}]})",
                     "animation.camera[0].positon", "did you mean 'position'?"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "scale": [1, 1, 1]}]}})",
                     "animation.objects.floor[0].scale", "expected a number, got array"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "scale": 1e39}]}})",
                     "animation.objects.floor[0].scale", "not finite"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "rotate": {"axis": [0, 1, 0], "degrees": 1e999}}]}})",
                     "animation.objects.floor[0].rotate.degrees", "overflows a double"},
        BadAnimation{R"({"frames": 3, "camera": [{"frame": 0, "position": [0, 0, 3e38], "look_at": [0, 0, -3e38]}]})",
                     "animation.camera[0]", "overflows a float"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0.5}]}})", "animation.objects.floor[0].frame",
                     "expected an integer"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": {"frame": 0}}})", "animation.objects.floor",
                     "expected an array"},
        BadAnimation{R"({"frames": 2.5})", "animation.frames", "integer"},
        BadAnimation{R"({"frames": 3, "objects": {"nope": [{"frame": 0}]}})", "animation.objects.nope",
                     "no object named 'nope'"},
        BadAnimation{R"({"frames": 3, "materials": {"nope": [{"frame": 0}]}})", "animation.materials.nope",
                     "no material named 'nope'"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 1}, {"frame": 1}]}})",
                     "animation.objects.floor[1].frame", "must increase"},
        BadAnimation{R"({"frames": 3, "camera": [{"frame": 2}, {"frame": 0}]})", "animation.camera[1].frame",
                     "must increase"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 3}]}})", "animation.objects.floor[0].frame",
                     "outside"},
        BadAnimation{R"({"frames": 3, "materials": {"grey": [{"frame": -1}]}})", "animation.materials.grey[0].frame",
                     "outside"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": []}})", "animation.objects.floor", "at least one key"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "translate": [1e39, 0, 0]}]}})",
                     "animation.objects.floor[0].translate[0]", "not finite"},
        BadAnimation{R"({"frames": 3, "materials": {"grey": [{"frame": 0, "emission": [1, 1e39, 0]}]}})",
                     "animation.materials.grey[0].emission[1]", "not finite"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "translate": [3e38, 0, 0], "scale": 1e38}]}})",
                     "animation.objects.floor[0]", "overflows a float"},
        // Within the float range but past limits::kMaxCoordinate, as the rest pose may not be.
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0}, {"frame": 2, "translate": [3e20, 0, 0]}]}})",
                     "animation.objects.floor[1]", "beyond the limit of ±1e+10 scene units"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "rotate": {"axis": [0, 0, 0], "degrees": 5}}]}})",
                     "animation.objects.floor[0].rotate.axis", "axis is zero"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "scale": 0}]}})",
                     "animation.objects.floor[0].scale", "scale must be > 0"},
        BadAnimation{R"({"frames": 3, "objects": {"floor": [{"frame": 0, "scale": -1}]}})",
                     "animation.objects.floor[0].scale", "scale must be > 0"},
        BadAnimation{R"({"frames": 3, "materials": {"grey": [{"frame": 0, "albedo": [1.5, 0, 0]}]}})",
                     "animation.materials.grey[0].albedo", "<= 1"},
        BadAnimation{R"({"frames": 3, "materials": {"grey": [{"frame": 0, "emission": [-1, 0, 0]}]}})",
                     "animation.materials.grey[0].emission", ">= 0"},
        BadAnimation{R"({"frames": 3, "camera": [{"frame": 0, "position": [0.5, 0, 0.5]}]})", "animation.camera[0]",
                     "look_at equals position"},
        BadAnimation{R"({"frames": 3, "camera": [{"frame": 0, "position": [0.5, 1, 0.5]}]})", "animation.camera[0]",
                     "parallel"},
        BadAnimation{R"({"frames": 3, "camera": [{"frame": 0, "position": [0.5, 3, 0.5], "look_at": [0.5, 0, 0.5000001]}]})",
                     "animation.camera[0]", "parallel"},
        // Two valid keys whose interpolation passes through look_at: the frame is named.
        BadAnimation{R"({"frames": 3, "camera": [{"frame": 0, "position": [0, 0.5, -1], "look_at": [0, 0.5, 0]},
                                                 {"frame": 2, "position": [0, 0.5, 1], "look_at": [0, 0.5, 0]}]})",
                     "animation.camera", "at frame 1, between its keys: look_at equals position"}));

// ---- the shipped scenes ----

bool data_has(const std::string& rel) {
    for (const auto& root : make_data_path(std::nullopt).roots)
        if (std::filesystem::exists(root / rel)) return true;
    return false;
}

TEST(AnimatedScenes, CornellBox) {
    const Scene rest = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box-animated.json",
                                  make_data_path(std::nullopt));
    EXPECT_EQ(rest.animation.frame_count, 30);
    ASSERT_EQ(rest.objects.size(), 2u);
    EXPECT_EQ(rest.objects[1].name, "cube");
    EXPECT_EQ(rest.objects[1].triangle_count, 12u);
    const Scene last = scene_at_frame(rest, 29);
    const uint32_t first = rest.objects[1].first_triangle;
    for (size_t v = 3 * first; v < rest.positions.size(); ++v)
        EXPECT_VEC3_NEAR(last.positions[v], rest.positions[v] + glm::vec3(-0.40f, 0, 0));
    for (size_t i = 0; i < rest.objects[1].triangle_count; ++i)  // the cube is wound outward
        EXPECT_GT(glm::dot(test::geometric_normal(rest, first + i),
                           rest.positions[3 * (first + i)] - glm::vec3(0.48f, 0.03f, 0.032f)),
                  0.0f);
    EXPECT_VEC3_NEAR(material_named(rest, "light").emission_max, glm::vec3(17, 12, 4));
    EXPECT_VEC3_NEAR(material_named(last, "light").emission, glm::vec3(6.8f, 4.8f, 1.6f));
    EXPECT_VEC3_NEAR(material_named(last, "red").albedo, glm::vec3(0.1f, 0.2f, 0.63f));
    const SceneBuffers b0 = make_scene_buffers(scene_at_frame(rest, 0)), b29 = make_scene_buffers(last);
    EXPECT_EQ(b0.light_count, 2u);
    EXPECT_EQ(b29.light_count, 2u);
    EXPECT_EQ(b0.light_cdf, b29.light_cdf);
}

TEST(AnimatedScenes, Sibenik) {
    if (!data_has("sibenik/sibenik.obj")) GTEST_SKIP() << "sibenik/sibenik.obj not on the data path";
    const Scene rest = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "sibenik-animated.json",
                                  make_data_path(std::nullopt));
    EXPECT_EQ(rest.animation.frame_count, 30);
    ASSERT_EQ(rest.objects.size(), 2u + 4u);  // cathedral, cube, 4 lights
    EXPECT_EQ(rest.objects[1].name, "cube");
    const Scene last = scene_at_frame(rest, 29);
    const size_t v = 3 * size_t(rest.objects[1].first_triangle);
    EXPECT_VEC3_NEAR(last.positions[v], rest.positions[v] + glm::vec3(8, 0, 0));
    EXPECT_EQ(last.positions[0], rest.positions[0]);  // the cathedral stays
}

}  // namespace
}  // namespace tessera
