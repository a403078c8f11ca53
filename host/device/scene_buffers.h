// The scene as flat buffers in the layouts of kernels/shared/layout_scene.h: what both
// backends read. The OpenCL backend uploads them; the Embree backend points the shared
// shading code at them directly.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace tessera {

struct SceneBuffers {
    std::vector<float> tri_pos;      ///< 9 floats per triangle
    std::vector<float> tri_nrm;      ///< 9 floats per triangle
    std::vector<float> tri_uv;       ///< 6 floats per triangle, moved by whole repeats toward [0, 1)
    std::vector<uint32_t> tri_mat;   ///< 1 per triangle
    std::vector<float> materials;    ///< TS_MATERIAL_FLOATS per material
    std::vector<uint32_t> tex_info;  ///< 4 per texture
    std::vector<uint32_t> tex_texels; ///< every texture's mip chain (device/texture_mips.h)
    std::vector<float> lights;       ///< TS_LIGHT_FLOATS per emissive triangle
    std::vector<float> light_cdf;    ///< 1 per light
    std::vector<float> medium;       ///< TS_MEDIUM_FLOATS (all zero when there is none)
    uint32_t triangle_count = 0;
    uint32_t light_count = 0;
    float light_power = 0.0f;        ///< Σ luminance(Le_max) × area over lights (the pick weights)
    uint32_t separated_emitters = 0; ///< emitters moved off a coincident surface (coincident_emitters.h)
    uint32_t stacked_emitters = 0;   ///< emitters on a light facing the same way (coincident_emitters.h)
    /// The bounds of every vertex in tri_pos, scene units (empty without triangles).
    SceneBounds bounds;
    /// A box the same in every frame of an animation: Scene::motion_bounds joined to the
    /// still triangles' bounds (still_bounds, as the scene places them, before emitters
    /// are moved off coincident surfaces), or `bounds` where motion_bounds is empty. The
    /// light paths' far roulette region (docs/path-tracing.md §3), so tic's kept paths
    /// match a rebuild's; the roulette is unbiased for any region, so it need not hold
    /// every vertex to the ulp.
    SceneBounds reach;
    /// The VPL clamps' length D, scene units: the scene's Scene::clamp_length where set
    /// (an animation whose objects move: frame 0's, in every frame), else
    /// clamp_extent(*this). Made once here, not per integrator (the viewer makes one at
    /// every camera move).
    float clamp_length = 0.0f;
};

/// TS_MAT_* for a material: MTL illum 3 and 5 are mirrors, illum 7 a dielectric
/// (refraction with Fresnel), everything else Lambertian.
uint32_t material_kind(const Material& m);

/// Flattens `scene` (one posed frame; see scene_at_frame). Every triangle of positive
/// area whose material may emit in some frame of the animation (any channel of
/// Le_max = max(emission, emission_max) > 0) becomes a light, and lights are picked in
/// proportion to power = luminance(Le_max) × area (Rec. 709 luminance weights), so the
/// light list, light_count and light_cdf are the same in every frame of an animation;
/// the radiance stored per light is this frame's `emission` (possibly zero).
/// light_power is the total luminance(Le_max) × area; each material stores its
/// luminance(Le_max) (materials TS_MAT_SELECTION), so the kernels' MIS weight for an emitter hit by a
/// BSDF sample uses the exact pick pdf luminance(Le_max) / light_power in every frame,
/// however the lights dim. An emitter lying on another surface, overlapping it, is moved
/// off it by a few ulps first (separate_coincident_emitters), in the geometry and the
/// light list alike. Buffers that would be empty get one zero element, so every device
/// buffer can be created.
///
/// `earlier`: buffers made by make_scene_buffers (unmodified) from another frame of the
/// same scene, or null. Where its mip chains were made from textures equal to `scene`'s
/// (the same count, sizes and level-0 texels, which is checked), tex_info and tex_texels
/// are copied from it, not remade: textures do not animate, and remaking Sibenik's three
/// took about 25 of the call's 33 ms in every frame of an animation
/// (bench/results/frame_setup.md). The result is then the same either way.
SceneBuffers make_scene_buffers(const Scene& scene, const SceneBuffers* earlier = nullptr);

/// The length D the VPL clamps are relative to (b = 1/(c·D)², docs/igi.md §4), scene units,
/// of buffers from make_scene_buffers: trimmed_diagonal (scene/extent.h) of their
/// triangles (tri_pos) and `bounds`.
float clamp_extent(const SceneBuffers& b);

}  // namespace tessera
