// CPU-side scene description, the output of the loader and the input of every backend.
//
// All geometry is flattened to world-space triangles (object transforms applied at
// load). Units are the scene's own ("scene units"); radiance values (emission) are in
// W/(sr·m²) with m read as scene units. The y axis is up by convention of the data.
#pragma once
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/animation.h"

namespace tessera {

/// An 8-bit texture as decoded from its file: `rgba8[y * width + x]` packs R in the low
/// byte, then G, B, A (little-endian RGBA). Values are sRGB-encoded; kernels linearise.
/// Row 0 is the top row of the image file, so a lookup uses y = (1 - v) * height.
struct Texture {
    std::filesystem::path path;
    int width = 0;
    int height = 0;
    std::vector<uint32_t> rgba8;
};

/// A material: Lambertian, or by `illum` a mirror or a smooth dielectric, which every
/// method's camera path follows to a diffuse surface (MTL illum 3, 5, 7).
struct Material {
    std::string name;
    glm::vec3 albedo{0.5f};      ///< diffuse reflectance Kd, each channel in [0, 1]
    glm::vec3 emission{0.0f};    ///< emitted radiance Ke, W/(sr·m²); non-zero makes an area light
    /// Per-channel maximum of `emission` over the scene's animation, W/(sr·m²) (equal to
    /// `emission` for a static scene; set by the loader). Light selection uses it, so the
    /// light list and its probabilities stay fixed while a light dims, even to zero.
    /// A scene built in code may leave it zero: make_scene_buffers then uses `emission`.
    glm::vec3 emission_max{0.0f};
    int texture = -1;            ///< index into Scene::textures for map_Kd, or -1
    glm::vec3 specular{0.0f};    ///< Ks, each channel in [0, 1]: mirror reflectance (illum 3, 5)
    int illum = 2;               ///< MTL illumination model, 0..10: 3, 5 mirror; 7 dielectric; else Lambertian
    float ior = 1.0f;            ///< MTL Ni, the dielectric's index of refraction (illum 7): finite, >= 0 (> 0 for illum 7)

    /// The emission lights are chosen and weighed by: the animation's maximum, or
    /// `emission` where a scene built in code left emission_max zero.
    glm::vec3 emission_bound() const { return glm::max(emission, emission_max); }
    /// The specular kinds of `illum` (MTL): 3 and 5 a mirror, 7 a smooth dielectric.
    bool is_mirror() const { return illum == 3 || illum == 5; }
    bool is_dielectric() const { return illum == 7; }
    /// Whether it emits in some frame, which makes its triangles lights.
    bool may_emit() const {
        const glm::vec3 e = emission_bound();
        return e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
    }

    bool operator==(const Material&) const = default;
};

/// An axis-aligned box, scene units; lo > hi (the default) is the empty box.
struct SceneBounds {
    glm::vec3 lo{INFINITY};
    glm::vec3 hi{-INFINITY};

    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    void grow(glm::vec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
    void grow(const SceneBounds& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
    bool operator==(const SceneBounds&) const = default;
};

/// A homogeneous participating medium. Coefficients are per scene unit (1/length);
/// the extinction is sigma_a + sigma_s. Henyey–Greenstein phase function with
/// asymmetry g in (-1, 1). Without a box the medium fills all space; with one it fills
/// the axis-aligned box [box_min, box_max] (the boundary is not a surface: it neither
/// reflects nor refracts).
struct Medium {
    glm::vec3 sigma_a{0.0f};
    glm::vec3 sigma_s{0.0f};
    float g = 0.0f;
    bool bounded = false;
    glm::vec3 box_min{0.0f};
    glm::vec3 box_max{0.0f};
};

/// Pinhole camera. `vfov_deg` is the full vertical field of view in degrees.
struct Camera {
    glm::vec3 position{0.0f, 1.0f, 3.0f};
    glm::vec3 look_at{0.0f, 1.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float vfov_deg = 40.0f;
    int width = 512;
    int height = 512;
};

/// A scene object: one `objects` entry of the scene file (or one JSON light), i.e. the
/// triangles [first_triangle, first_triangle + triangle_count) placed by one transform.
/// Objects are what an animation moves and what temporal caching tracks as occluders.
struct SceneObject {
    std::string name;          ///< the JSON "name", else "<mesh file>#<index>" or "json-light-<i>"
    uint32_t first_triangle = 0;
    uint32_t triangle_count = 0;
    bool json_light = false;   ///< a quad of the scene file's "lights", not a mesh
};

/// The loaded scene. Per-triangle arrays are parallel: triangle i has vertices
/// positions[3i..3i+2], shading normals normals[3i..3i+2] (unit length, world space,
/// the geometric normal where the mesh has none), texture coordinates uvs[3i..3i+2]
/// ((0,0) where the mesh has none) and material index material[i].
/// The geometric normal (and so the front face of an emitter) is
/// cross(p1 - p0, p2 - p0): counter-clockwise winding seen from the front.
struct Scene {
    std::string name;
    std::filesystem::path source;   ///< the scene file it came from ("" for built-in)
    /// Every file the loader read: the scene file, then each OBJ, its MTL files and their
    /// textures, as resolved (empty for a scene built in code). No output may be one.
    std::vector<std::filesystem::path> inputs;
    /// What the loader changed without an error, one sentence each naming the file, line
    /// and value (an MTL Kd above 1 clamped to 1); render, info and view print them as notes.
    std::vector<std::string> notes;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<uint32_t> material;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    /// Contiguous triangle ranges in file order, covering every triangle; empty for a
    /// scene built in code (then all triangles count as one object).
    std::vector<SceneObject> objects;
    Camera camera;
    /// Keyframes (frame_count 0: static). The arrays above are the rest pose; use
    /// scene_at_frame() (scene/animation.h) for the scene at a frame.
    Animation animation;
    /// A box every pose of the objects the animation moves lies in, in every frame
    /// (motion_bounds, scene/animation.h); set by scene_at_frame, empty where no object
    /// track holds a triangle. The scene buffers' reach joins it to the bounds of the
    /// triangles that stay (still_bounds), so that box is the same in every frame.
    SceneBounds motion_bounds;
    /// The VPL clamps' length D (docs/igi.md §4), scene units, for every frame of an
    /// animation whose object tracks move triangles: frame 0's (trimmed_diagonal of its
    /// triangles, scene/extent.h), set by scene_at_frame; 0 elsewhere, where the scene
    /// buffers take the frame's own. Per frame, an object leaving the room lengthened D
    /// frame by frame (an experiment, docs/igi.md §4: the animated Cornell box's cube
    /// moved 3 units behind the camera, 0.96 to 3.44 over 30 frames), so the clamp, and
    /// the light of a room nothing in view had changed, changed with it, and tic re-summed
    /// every record in every frame. Code that edits a posed scene's positions must set it
    /// to 0 (or to its own frame 0's), or the buffers keep the old length.
    float clamp_length = 0.0f;
    bool has_medium = false;   ///< true when the scene file declares a "medium"
    Medium medium;

    size_t triangle_count() const { return material.size(); }

    /// Triangle i's area in scene units² (float, as the light list weighs emitters).
    float triangle_area(size_t i) const {
        const glm::vec3 p0 = positions[3 * i];
        return 0.5f * glm::length(glm::cross(positions[3 * i + 1] - p0, positions[3 * i + 2] - p0));
    }

    /// The diagonal of the positions' bounding box in scene units; 0 with no positions.
    float diagonal() const {
        SceneBounds b;
        for (const glm::vec3& p : positions) b.grow(p);
        return positions.empty() ? 0.0f : glm::length(b.hi - b.lo);
    }
};

}  // namespace tessera
