// The length the VPL clamps are relative to (clamp_extent): the bounds' diagonal, with
// outlying bits of surface left out; the texture coordinates the kernels read; and the
// mip chains an animation's frames take from the frame before.
#include "device/scene_buffers.h"

#include <cstring>
#include <filesystem>

#include <gtest/gtest.h>

#include "kernels/shared/kernel_inputs.h"
#include "kernels/shared/layout_scene.h"
#include "scene/animation.h"
#include "scene/loader.h"
#include "support/data_files.h"
#include "support/test_scenes.h"

namespace tessera {
namespace {

float bounds_diagonal(const SceneBuffers& b) {
    const SceneBounds& s = b.bounds;
    return glm::length(s.hi - s.lo);
}

// The Cornell-sized box alone, and with a 1 cm triangle 1 km away (out of every view):
// the whole bounds' diagonal grows about 1,000 times, the clamp's length not at all, so
// b = 1/(c·D)² and the image stay as they were (a stray vertex of an imported mesh).
TEST(ClampExtent, AStrayTriangleFarAwayIsLeftOut) {
    Scene s = test::closed_box({0, 0, 0}, {0.556f, 0.549f, 0.559f}, glm::vec3(0.5f), glm::vec3(5.0f), 0.1f);
    const float box = bounds_diagonal(make_scene_buffers(s));
    EXPECT_FLOAT_EQ(clamp_extent(make_scene_buffers(s)), box);
    test::add_quad(s, {1000.0f, 0.0f, 0.0f}, {0.01f, 0.0f, 0.0f}, {0.0f, 0.01f, 0.0f}, s.material[0]);
    const SceneBuffers far = make_scene_buffers(s);
    EXPECT_GT(bounds_diagonal(far), 1000.0f);
    EXPECT_FLOAT_EQ(clamp_extent(far), box);
}

// Scene-relative: the box at 10⁻³ and 10⁴ times its size gives D times that (the same c
// the same image at any scale).
TEST(ClampExtent, ScalesWithTheScene) {
    for (float k : {1e-3f, 1.0f, 1e4f}) {
        Scene s = test::closed_box({0, 0, 0}, {2 * k, k, 3 * k}, glm::vec3(0.5f), glm::vec3(5.0f), 0.2f * k);
        test::add_quad(s, {1000 * k, 0, 0}, {0.01f * k, 0, 0}, {0, 0.01f * k, 0}, s.material[0]);
        EXPECT_NEAR(clamp_extent(make_scene_buffers(s)), std::sqrt(14.0f) * k, 1e-6f * k) << k;
    }
}

// Every shipped scene (those whose data is on the data path): the trimmed bounds are the
// whole bounds, as their walls and floors each hold more than 1% of the area, so D is the
// bounding box's diagonal as before.
TEST(ClampExtent, IsTheBoundsDiagonalOfTheShippedScenes) {
    const DataPath data = make_data_path(std::nullopt);
    int loaded = 0;
    for (const auto& entry : std::filesystem::directory_iterator(TESSERA_SCENES_DIR)) {
        if (entry.path().extension() != ".json") continue;
        const std::string name = entry.path().filename().string();
        if (name.rfind("sibenik", 0) == 0 && !test::on_data_path(data, "sibenik/sibenik.obj")) continue;
        const SceneBuffers b = make_scene_buffers(load_scene(entry.path(), data));
        EXPECT_FLOAT_EQ(clamp_extent(b), bounds_diagonal(b)) << name;
        ++loaded;
    }
    EXPECT_GE(loaded, 10);
}

// A 40 × 40 floor of unit quads (3,200 triangles, trim 0.16) with `specks` quads of two
// triangles of area 1e-6 at x = -1000. With 10 the first 1/64 of the triangles by x (50)
// holds floor triangles and more than the trim: those alone are sorted. With 60 it holds
// specks alone, under the trim: all are sorted. Either way the specks are left out.
TEST(ClampExtent, LeavesSpecksOutWhetherItSortsTheEndsOrAll) {
    for (int specks : {10, 60}) {
        Scene s;
        const uint32_t m = test::add_material(s, glm::vec3(0.5f));
        for (int x = 0; x < 40; ++x)
            for (int z = 0; z < 40; ++z) test::add_quad(s, glm::vec3(x, 0, z), {0, 0, 1}, {1, 0, 0}, m);
        for (int i = 0; i < specks; ++i)
            test::add_quad(s, glm::vec3(-1000.0f, 0, 0.5f * i), {0, 0, 1e-3f}, {2e-3f, 0, 0}, m);
        const SceneBuffers b = make_scene_buffers(s);
        ASSERT_EQ(b.triangle_count, 3200u + 2u * specks);
        EXPECT_GT(bounds_diagonal(b), 1000.0f);
        EXPECT_FLOAT_EQ(clamp_extent(b), 40.0f * std::sqrt(2.0f)) << specks;
        EXPECT_EQ(b.clamp_length, clamp_extent(b)) << specks;
    }
}

// A scene without area (one degenerate triangle) keeps the bounds' diagonal.
TEST(ClampExtent, ASceneWithoutAreaKeepsTheBoundsDiagonal) {
    Scene s;
    const uint32_t m = test::add_material(s, glm::vec3(0.5f));
    for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1, 2, 2), glm::vec3(2, 4, 4)}) {
        s.positions.push_back(p);
        s.normals.push_back({0, 0, 1});
        s.uvs.push_back({0, 0});
    }
    s.material.push_back(m);
    EXPECT_FLOAT_EQ(clamp_extent(make_scene_buffers(s)), 6.0f);
}

// Texture coordinates far from 0 are moved by whole repeats toward [0, 1): textures repeat,
// and interpolating numbers near 1e6 (a float's step is 1/16 there) rendered a textured
// floor at relMSE 1e-2 from the same floor at UVs near 0. Now their buffers are equal, so
// their images are on both backends. The offsets are whole numbers, and the fixture's UVs
// multiples of 1/16, so every shifted value is exact.
TEST(SceneBuffers, TextureCoordinatesMoveByWholeRepeatsTowardZero) {
    const Scene plain = test::checker_floor();
    Scene far = plain;
    for (glm::vec2& uv : far.uvs) uv += glm::vec2(1.0e6f, -3.0e6f);
    ASSERT_NE(far.uvs[0], plain.uvs[0]);
    const SceneBuffers a = make_scene_buffers(plain), b = make_scene_buffers(far);
    EXPECT_EQ(a.tri_uv, b.tri_uv);
    for (float t : a.tri_uv) {
        EXPECT_GE(t, 0.0f);
        EXPECT_LE(t, 1.0f);
    }
}

// Bit for bit: materials hold integers (a texture index of -1 reads as a NaN float).
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// An animation's frames take the mip chains of the frame before (textures do not animate).
// The earlier buffers' coarsest texel is changed so a copy shows: taken where the textures
// are the same, remade where one texel of level 0 differs or a texture is added.
TEST(SceneBuffers, TakesTheEarlierMipChainsOnlyForTheSameTextures) {
    const Scene scene = test::checker_floor();
    const SceneBuffers fresh = make_scene_buffers(scene);
    SceneBuffers earlier = fresh;
    ASSERT_GT(earlier.tex_texels.size(), 256u * 256u);
    earlier.tex_texels.back() ^= 0x00010101u;  // the 1x1 level, which make_scene_buffers never makes so

    const SceneBuffers same = make_scene_buffers(scene, &earlier);
    EXPECT_EQ(same.tex_info, earlier.tex_info);
    EXPECT_EQ(same.tex_texels, earlier.tex_texels);
    EXPECT_EQ(same.tri_pos, fresh.tri_pos);

    Scene changed = scene;
    changed.textures[0].rgba8[1000] ^= 0x00000001u;
    const SceneBuffers remade = make_scene_buffers(changed, &earlier);
    EXPECT_EQ(remade.tex_texels, make_scene_buffers(changed).tex_texels);
    EXPECT_NE(remade.tex_texels.back(), earlier.tex_texels.back());

    Scene more = scene;
    more.textures.push_back(scene.textures[0]);
    const SceneBuffers two = make_scene_buffers(more, &earlier);
    EXPECT_EQ(two.tex_info.size(), 2u * TS_TEX_INFO_UINTS);
    EXPECT_EQ(two.tex_texels, make_scene_buffers(more).tex_texels);
}

// The animated Sibenik's frames, each made from the one before as a sequence does, equal
// frames made from nothing, in every buffer the backends read.
TEST(SceneBuffers, AnAnimationsFramesFromTheFrameBeforeEqualFreshOnes) {
    const DataPath data = make_data_path(std::nullopt);
    if (!test::on_data_path(data, "sibenik/sibenik.obj")) GTEST_SKIP() << "no Sibenik on the data path";
    const Scene rest = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "sibenik-animated.json", data);
    ASSERT_FALSE(rest.textures.empty());
    SceneBuffers before = make_scene_buffers(scene_at_frame(rest, 0));
    for (int frame : {1, 17}) {
        const Scene scene = scene_at_frame(rest, frame);
        const SceneBuffers next = make_scene_buffers(scene, &before), fresh = make_scene_buffers(scene);
#define TS_EXPECT_SAME_BUFFER(field, type, what) EXPECT_TRUE(same_bits(next.field, fresh.field)) << what;
        TS_SCENE_BUFFERS(TS_EXPECT_SAME_BUFFER)
#undef TS_EXPECT_SAME_BUFFER
        EXPECT_NE(next.tri_pos, before.tri_pos);  // the frame moved something
        before = next;
    }
}

}  // namespace
}  // namespace tessera
