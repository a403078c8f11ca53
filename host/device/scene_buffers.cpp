#include "device/scene_buffers.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "device/coincident_emitters.h"
#include "device/texture_mips.h"
#include "kernels/shared/layout_scene.h"
#include "kernels/shared/sampling.h"
#include "scene/extent.h"

namespace tessera {
namespace {

float luminance_of(const glm::vec3& c) { return ts::ts_luminance(ts::make_float3(c.x, c.y, c.z)); }

// The first `count` vectors' components, x y z after one another: glm::vec3 is three
// packed floats.
std::vector<float> flat(const std::vector<glm::vec3>& v, size_t count) {
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
    std::vector<float> out(3 * count);
    if (count > 0) std::memcpy(out.data(), v.data(), out.size() * sizeof(float));
    return out;
}
void put3(float* f, const glm::vec3& a) { f[0] = a.x, f[1] = a.y, f[2] = a.z; }

// Appends triangle corners uv[0..2], shifted by the floor of their smallest value on each
// axis. Textures repeat (ts_texture_bilinear), so the image is the same, and the
// kernels interpolate numbers near [0, 1]: at UVs of 1e6 a float's step is 1/16, and each
// backend's barycentrics (equal to about 1e-7) put the lookup texels apart (pt relMSE 1e-3
// between Embree and OpenCL). One triangle spanning a huge UV range keeps that limit, and
// one spanning more than a float holds (vt -3e38 and 3e38) keeps its own UVs.
void push_uvs(std::vector<float>& out, const glm::vec2* uv) {
    const glm::vec2 shift = glm::floor(glm::min(uv[0], glm::min(uv[1], uv[2])));
    bool finite = true;
    for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(uv[k].x - shift.x) && std::isfinite(uv[k].y - shift.y);
    for (int k = 0; k < 3; ++k) {
        const glm::vec2 t = finite ? uv[k] - shift : uv[k];
        out.insert(out.end(), {t.x, t.y});
    }
}

template <class T>
void ensure_nonempty(std::vector<T>& v) {
    if (v.empty()) v.push_back(T{});
}

void add_medium(const Scene& scene, SceneBuffers& b) {
    const Medium& m = scene.medium;
    b.medium.assign(TS_MEDIUM_FLOATS, 0.0f);
    // A declared medium with all-zero coefficients does nothing: leave it disabled.
    if (!scene.has_medium || (m.sigma_a == glm::vec3(0.0f) && m.sigma_s == glm::vec3(0.0f))) return;
    float* f = b.medium.data();
    put3(f + TS_MEDIUM_SIGMA_A, m.sigma_a);
    put3(f + TS_MEDIUM_SIGMA_S, m.sigma_s);
    f[TS_MEDIUM_G] = m.g;
    f[TS_MEDIUM_BOUNDED] = m.bounded ? 1.0f : 0.0f;
    put3(f + TS_MEDIUM_BOX_MIN, m.box_min);
    put3(f + TS_MEDIUM_BOX_MAX, m.box_max);
    f[TS_MEDIUM_PRESENT] = 1.0f;
}

void add_materials(const Scene& scene, SceneBuffers& b) {
    for (const Material& m : scene.materials) {
        const uint32_t kind = material_kind(m);
        const glm::vec3 ks = m.specular == glm::vec3(0.0f) ? glm::vec3(1.0f) : m.specular;
        float f[TS_MATERIAL_FLOATS] = {};
        put3(f + TS_MAT_ALBEDO, m.albedo);
        put3(f + TS_MAT_EMISSION, m.emission);
        put3(f + TS_MAT_SPECULAR, ks);
        f[TS_MAT_IOR] = m.ior > 0.0f ? m.ior : 1.0f;
        f[TS_MAT_SELECTION] = luminance_of(m.emission_bound());
        int tex = m.texture;
        std::memcpy(&f[TS_MAT_TEXTURE], &tex, 4);
        std::memcpy(&f[TS_MAT_KIND], &kind, 4);
        b.materials.insert(b.materials.end(), f, f + TS_MATERIAL_FLOATS);
    }
}

// Whether `earlier`'s mip chains were made from textures equal to `scene`'s: the same
// count, sizes and level-0 texels (a chain's level 0 is its texture; build_mip_chain).
bool same_textures(const Scene& scene, const SceneBuffers& earlier) {
    if (scene.textures.empty() || earlier.tex_info.size() != TS_TEX_INFO_UINTS * scene.textures.size()) return false;
    for (size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        const uint32_t* info = &earlier.tex_info[TS_TEX_INFO_UINTS * i];
        if (info[TS_TEX_WIDTH] != uint32_t(t.width) || info[TS_TEX_HEIGHT] != uint32_t(t.height) ||
            t.rgba8.size() != size_t(t.width) * size_t(t.height) ||
            size_t(info[TS_TEX_OFFSET]) + t.rgba8.size() > earlier.tex_texels.size() ||
            !std::equal(t.rgba8.begin(), t.rgba8.end(), earlier.tex_texels.begin() + info[TS_TEX_OFFSET]))
            return false;
    }
    return true;
}

void add_textures(const Scene& scene, SceneBuffers& b, const SceneBuffers* earlier) {
    if (earlier && same_textures(scene, *earlier)) {
        b.tex_info = earlier->tex_info;
        b.tex_texels = earlier->tex_texels;
        return;
    }
    for (const Texture& t : scene.textures) {
        uint32_t info[TS_TEX_INFO_UINTS] = {};
        info[TS_TEX_OFFSET] = static_cast<uint32_t>(b.tex_texels.size());
        info[TS_TEX_WIDTH] = static_cast<uint32_t>(t.width);
        info[TS_TEX_HEIGHT] = static_cast<uint32_t>(t.height);
        info[TS_TEX_LEVELS] = mip_level_count(info[TS_TEX_WIDTH], info[TS_TEX_HEIGHT]);
        b.tex_info.insert(b.tex_info.end(), info, info + TS_TEX_INFO_UINTS);
        const std::vector<uint32_t> chain = build_mip_chain(t.rgba8, info[TS_TEX_WIDTH], info[TS_TEX_HEIGHT]);
        b.tex_texels.insert(b.tex_texels.end(), chain.begin(), chain.end());
    }
}

// `positions`: the scene's, with coincident emitters separated (the BVHs' geometry).
void add_lights(const Scene& scene, const std::vector<glm::vec3>& positions, SceneBuffers& b) {
    double total = 0.0;
    std::vector<double> power;
    for (uint32_t i = 0; i < scene.triangle_count(); ++i) {
        const Material& m = scene.materials[scene.material[i]];
        const glm::vec3& le = m.emission;
        // Which triangles are lights, and how often each is picked, follow the animation's
        // maximum, not this frame's emission: the list is then the same in every frame
        // (light paths keep their light index) and a light dimmed to zero keeps its place.
        const glm::vec3 weight = m.emission_bound();
        if (!m.may_emit()) continue;
        glm::vec3 p0 = positions[3 * i], e1 = positions[3 * i + 1] - p0, e2 = positions[3 * i + 2] - p0;
        const float area = scene.triangle_area(i);
        if (!(area > 0.0f)) continue;  // a zero-area emitter carries no power
        float f[TS_LIGHT_FLOATS] = {};
        put3(f + TS_LIGHT_P0, p0);
        put3(f + TS_LIGHT_E1, e1);
        put3(f + TS_LIGHT_E2, e2);
        put3(f + TS_LIGHT_RADIANCE, le);
        f[TS_LIGHT_AREA] = area;
        std::memcpy(&f[TS_LIGHT_PRIM], &i, 4);
        b.lights.insert(b.lights.end(), f, f + TS_LIGHT_FLOATS);
        power.push_back(static_cast<double>(luminance_of(weight)) * area);
        total += power.back();
    }
    b.light_count = static_cast<uint32_t>(power.size());
    // The kernels' MIS pdf for an emitter hit is (the material's selection luminance) /
    // light_power: the probability ts_sample_light picks that point with.
    b.light_power = static_cast<float>(total);
    double run = 0.0;
    for (size_t i = 0; i < power.size(); ++i) {
        run += power[i];
        b.light_cdf.push_back(i + 1 == power.size() ? 1.0f : static_cast<float>(run / total));
    }
}

}  // namespace

uint32_t material_kind(const Material& m) {
    if (m.is_mirror()) return TS_MAT_MIRROR;
    if (m.is_dielectric()) return TS_MAT_DIELECTRIC;
    return TS_MAT_DIFFUSE;
}

SceneBuffers make_scene_buffers(const Scene& scene, const SceneBuffers* earlier) {
    SceneBuffers b;
    const size_t n = scene.triangle_count();
    b.triangle_count = static_cast<uint32_t>(n);
    b.tri_uv.reserve(6 * n);
    std::vector<glm::vec3> positions = scene.positions;
    const CoincidentEmitters coincident = separate_coincident_emitters(scene, positions);
    b.separated_emitters = static_cast<uint32_t>(coincident.moved);
    b.stacked_emitters = static_cast<uint32_t>(coincident.stacked);
    b.tri_pos = flat(positions, 3 * n);
    b.tri_nrm = flat(scene.normals, 3 * n);
    for (size_t i = 0; i < n; ++i) push_uvs(b.tri_uv, &scene.uvs[3 * i]);
    b.tri_mat = scene.material;
    add_materials(scene, b);
    add_textures(scene, b, earlier);
    add_lights(scene, positions, b);
    add_medium(scene, b);
    for (size_t i = 0; i < b.tri_pos.size(); i += 3) b.bounds.grow(glm::make_vec3(&b.tri_pos[i]));
    b.reach = b.bounds;
    if (!scene.motion_bounds.empty()) {
        b.reach = still_bounds(scene);
        b.reach.grow(scene.motion_bounds);
    }
    b.clamp_length = scene.clamp_length > 0.0f ? scene.clamp_length : clamp_extent(b);
    for (auto* v : {&b.tri_pos, &b.tri_nrm, &b.tri_uv, &b.materials, &b.lights, &b.light_cdf})
        ensure_nonempty(*v);
    for (auto* v : {&b.tri_mat, &b.tex_info, &b.tex_texels}) ensure_nonempty(*v);
    return b;
}

float clamp_extent(const SceneBuffers& b) { return trimmed_diagonal(b.tri_pos.data(), b.tri_pos.size() / 9, b.bounds); }

}  // namespace tessera
