// Emitters in another surface's plane: moved off it, so both backends see the light.
#include "device/coincident_emitters.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <tuple>

#include "device/scene_buffers.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace tessera {
namespace {

constexpr float kLe = 10.0f;
constexpr float kMoved = -1.0f + 12.0f * 0x1p-23f;  // the light's z once moved off the wall

// The closed test box [-1,1] x [0,2] x [-1,1] (its ceiling light 1e-3 below the ceiling,
// apart from it), with a second light set into the back wall z = -1: the same plane,
// facing +z into the room like the wall, inside it. The camera looks at the back wall.
Scene light_in_the_back_wall() {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.7f), glm::vec3(1.0f), 0.3f);
    const uint32_t light = test::add_material(s, glm::vec3(0.0f), glm::vec3(kLe));
    test::add_quad(s, {-0.3f, 0.7f, -1.0f}, {0.6f, 0, 0}, {0, 0.6f, 0}, light);
    return s;
}

// The number of triangles whose vertices differ between a and b.
size_t triangles_changed(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    size_t n = 0;
    for (size_t t = 0; t < a.size() / 3; ++t)
        n += a[3 * t] != b[3 * t] || a[3 * t + 1] != b[3 * t + 1] || a[3 * t + 2] != b[3 * t + 2];
    return n;
}

TEST(CoincidentEmitters, LightInAWallMovesOffItTowardsTheSideItLights) {
    const Scene s = light_in_the_back_wall();
    std::vector<glm::vec3> p = s.positions;
    EXPECT_EQ(separate_coincident_emitters(s, p).moved, 2u);
    EXPECT_EQ(triangles_changed(s.positions, p), 2u) << "only the light's two triangles move";
    // To 6 ulps of the pair's largest coordinate, 2 (the wall's top), in front: 12 · 2^-23.
    const size_t first = p.size() - 6;
    for (size_t i = first; i < p.size(); ++i) {
        EXPECT_EQ(p[i].z, kMoved) << "vertex " << i;
        EXPECT_EQ(p[i].x, s.positions[i].x);
        EXPECT_EQ(p[i].y, s.positions[i].y);
    }
    // The geometry and the light list move together.
    const SceneBuffers b = make_scene_buffers(s);
    EXPECT_EQ(b.separated_emitters, 2u);
    EXPECT_EQ(b.tri_pos[9 * (s.triangle_count() - 1) + 2], kMoved);
    EXPECT_EQ(b.lights[(b.light_count - 1) * TS_LIGHT_FLOATS + TS_LIGHT_P0 + 2], kMoved);
}

TEST(CoincidentEmitters, LightsApartFromOrOnlyTouchingASurfaceStay) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.7f), glm::vec3(1.0f), 0.3f);  // 1e-3 apart
    const uint32_t light = test::add_material(s, glm::vec3(0.0f), glm::vec3(kLe));
    // Beside a panel of the wall material (closed_box's material 0), sharing its edge
    // x = 0.5 in its plane: touching only, as a light filling a hole in a ceiling.
    test::add_quad(s, {-0.5f, 0.5f, -0.99f}, {1.0f, 0, 0}, {0, 0.5f, 0}, 0);   // the panel, z = -0.99
    test::add_quad(s, {0.5f, 0.5f, -0.99f}, {0.5f, 0, 0}, {0, 0.5f, 0}, light);  // the light beside it
    // A light 1e-4 in front of the back wall: apart, by far more than the tolerance.
    test::add_quad(s, {-0.5f, 1.2f, -0.9999f}, {0.5f, 0, 0}, {0, 0.5f, 0}, light);
    std::vector<glm::vec3> p = s.positions;
    EXPECT_EQ(separate_coincident_emitters(s, p).moved, 0u);
    EXPECT_TRUE(p == s.positions);
}

TEST(CoincidentEmitters, LightFacingIntoTheWallMovesBehindIt) {
    Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.7f), glm::vec3(1.0f), 0.3f);
    const uint32_t light = test::add_material(s, glm::vec3(0.0f), glm::vec3(kLe));
    test::add_quad(s, {-0.3f, 0.7f, -1.0f}, {0, 0.6f, 0}, {0.6f, 0, 0}, light);  // faces -z
    std::vector<glm::vec3> p = s.positions;
    EXPECT_EQ(separate_coincident_emitters(s, p).moved, 2u);
    for (size_t i = p.size() - 6; i < p.size(); ++i) EXPECT_LT(p[i].z, -1.0f);
}

// A two-sided light: two lights back to back in one plane. Both move, each towards the
// side it lights, whatever their order; two lights facing the same way stay (they would
// move as far) and are counted as stacked.
TEST(CoincidentEmitters, BackToBackLightsMoveApartAndTwinsStay) {
    for (bool down_first : {false, true}) {
        Scene s;
        const uint32_t light = test::add_material(s, glm::vec3(0.0f), glm::vec3(kLe));
        const uint32_t other = test::add_material(s, glm::vec3(0.0f), glm::vec3(2.0f));
        const glm::vec3 c(-0.5f, 1.0f, -0.5f), x(1, 0, 0), z(0, 0, 1);
        if (down_first) test::add_quad(s, c, x, z, other);  // faces -y
        test::add_quad(s, c, z, x, light);                   // faces +y
        if (!down_first) test::add_quad(s, c, x, z, other);
        test::add_quad(s, c + glm::vec3(0, 0.5f, 0), z, x, light);   // twins facing +y
        test::add_quad(s, c + glm::vec3(0, 0.5f, 0), z, x, other);
        std::vector<glm::vec3> p = s.positions;
        const CoincidentEmitters found = separate_coincident_emitters(s, p);
        EXPECT_EQ(found.moved, 4u) << "the back-to-back pair's four triangles";
        // Each twin triangle lies on its twin (not on its quad's other half, which it only
        // touches): counted, so info and render can say their light counts twice.
        EXPECT_EQ(found.stacked, 4u) << "the twins' four triangles";
        EXPECT_EQ(make_scene_buffers(s).stacked_emitters, 4u);
        for (size_t i = 0; i < 12; ++i) {
            const float n = glm::cross(s.positions[3 * (i / 3) + 1] - s.positions[3 * (i / 3)],
                                       s.positions[3 * (i / 3) + 2] - s.positions[3 * (i / 3)]).y;
            EXPECT_EQ(p[i].y > 1.0f, n > 0.0f) << "vertex " << i << ": each moves towards the side it lights";
            EXPECT_NE(p[i].y, 1.0f);
        }
        for (size_t i = 12; i < 24; ++i) EXPECT_EQ(p[i], s.positions[i]) << "twin vertex " << i;
    }
}

// A light modelled in a wall's plane, then rotated and written with 6 decimals as an
// exporter would: its vertices lie up to a few ulps off the wall's plane, both ways.
TEST(CoincidentEmitters, RotatedAndRoundedLightInAWallMoves) {
    const glm::mat3 r = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1, 2, 3))));
    auto rounded = [&](glm::vec3 v) { return glm::round((r * v + glm::vec3(3.0f)) * 1e6f) / 1e6f; };
    size_t moved = 0, lights = 0;
    for (int k = 0; k < 20; ++k) {
        Scene s;
        const uint32_t wall = test::add_material(s, glm::vec3(0.7f));
        const uint32_t light = test::add_material(s, glm::vec3(0.0f), glm::vec3(kLe));
        const float o = 0.05f * float(k);
        // A long thin wall strip and a light quad inside it, in the plane z = 0.
        for (const auto& [corner, e1, e2, m] :
             {std::tuple{glm::vec3(-2, -0.1f + o, 0), glm::vec3(4, 0, 0), glm::vec3(0, 0.4f, 0), wall},
              std::tuple{glm::vec3(-0.3f, o, 0), glm::vec3(0.6f, 0, 0), glm::vec3(0, 0.2f, 0), light}}) {
            const glm::vec3 q0 = rounded(corner), q1 = rounded(corner + e1), q3 = rounded(corner + e2);
            test::add_quad(s, q0, q1 - q0, q3 - q0, m);
        }
        std::vector<glm::vec3> p = s.positions;
        moved += separate_coincident_emitters(s, p).moved;
        lights += 2;
    }
    EXPECT_EQ(moved, lights) << "every light triangle of the 20 placements";
}

// The light set into the wall, seen from the room: before the separation OpenCL's
// traversal kept the wall (the first triangle at the tie) and Embree the light (the
// last), so `direct` was 0.19 against 0.56 and `pt` 0.40 against 0.75 on a scene like it.
// Now every pixel inside the light's image is Le on both, and the images agree.
TEST(CoincidentEmitters, BothBackendsSeeALightSetIntoAWall) {
    const Scene s = light_in_the_back_wall();
    for (Method m : {Method::Direct, Method::PathTrace}) {
        RenderSettings rs;
        rs.method = m;
        rs.spp = 4;
        const Image cl = test::render_with(BackendKind::OpenCL, s, rs);
        const Image em = test::render_with(BackendKind::Embree, s, rs);
        // The camera at z = 0.98 with vfov 80° sees the light (0.6 wide, 1.98 away) as about
        // 5 pixels of 32: a pixel all of whose samples hit the light is exactly Le.
        size_t lit_cl = 0, lit_em = 0;
        for (size_t i = 0; i < cl.find("R")->data.size(); ++i) {
            lit_cl += cl.find("R")->data[i] == kLe;
            lit_em += em.find("R")->data[i] == kLe;
        }
        EXPECT_GE(lit_cl, 4u) << method_name(m) << ": OpenCL shows the wall where the light is";
        EXPECT_EQ(lit_cl, lit_em) << method_name(m);
        // Both draw the same samples: only rounding separates them (printed; 0.64 for
        // `direct` before the separation).
        for (const char* c : {"R", "G", "B"}) {
            const double ratio = test::channel_mean(cl, c) / test::channel_mean(em, c);
            std::printf("  %s %s: OpenCL / Embree %.6f\n", method_name(m), c, ratio);
            EXPECT_NEAR(ratio, 1.0, 1e-3) << method_name(m) << " " << c;
        }
    }
}

}  // namespace
}  // namespace tessera
