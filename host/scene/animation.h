// Keyframe animation of a scene: rigid(+uniform scale) object motion, material albedo
// and emission, and the camera. The scene-file block is documented in scenes/README.md.
//
// The loaded Scene holds the *rest pose* (the geometry, materials and camera as the
// scene file places them without animation); scene_at_frame() poses it. Posing never
// adds, removes or reorders triangles, so a triangle index names the same surface in
// every frame (temporal caching relies on that).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace tessera {

struct Scene;

/// One key of an object track. The transform acts on the object's world-space rest
/// geometry about `pivot` (the centre of the object's rest bounding box):
/// p' = pivot + translate + R·(scale·(p − pivot)); normals by the inverse-transpose.
/// Fields a key omits hold the rest value (no translation, no rotation, scale 1).
struct ObjectKey {
    int frame = 0;
    glm::vec3 translate{0.0f};                    ///< scene units
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};   ///< unit quaternion
    float scale = 1.0f;                           ///< uniform, > 0
};

/// One key of a material track; an absent field holds the material's rest value.
struct MaterialKey {
    int frame = 0;
    std::optional<glm::vec3> albedo;    ///< each channel in [0, 1]
    std::optional<glm::vec3> emission;  ///< W/(sr·m²), each channel >= 0
};

/// One key of the camera track (absent fields were filled with the rest camera's).
struct CameraKey {
    int frame = 0;
    glm::vec3 position{0.0f};  ///< scene units
    glm::vec3 look_at{0.0f};   ///< scene units
};

/// Keys of one named object (every Scene::objects entry of that name).
struct ObjectTrack {
    std::string name;
    std::vector<uint32_t> objects;  ///< indices into Scene::objects
    std::vector<ObjectKey> keys;    ///< non-empty, frames strictly increasing
};

/// Keys of one named material (every Scene::materials entry of that name).
struct MaterialTrack {
    std::string name;
    std::vector<uint32_t> materials;  ///< indices into Scene::materials
    std::vector<MaterialKey> keys;    ///< non-empty, frames strictly increasing
};

/// A scene's animation. Frames are integers 0..frame_count−1. Between two keys values
/// are interpolated linearly in the frame number (rotations by quaternion slerp, which
/// takes the shorter arc: a turn of more than 180° needs intermediate keys); before the
/// first key and after the last one the end key's value holds.
struct Animation {
    int frame_count = 0;  ///< 0: a static scene (only frame 0 exists)
    std::vector<ObjectTrack> objects;
    std::vector<MaterialTrack> materials;
    std::vector<CameraKey> camera;  ///< empty: the camera does not move

    bool animated() const { return frame_count > 0; }
};

/// The scene posed at `frame`: positions and normals of animated objects, material
/// albedo and emission, camera position and look_at. Triangle count, order, uvs,
/// material indices, textures, objects and `animation` are copied unchanged from
/// `rest`. Throws InputError (naming the scene file and the frame) when `frame` is
/// outside [0, frame_count) — for a static scene only frame 0 is valid, and returns
/// a copy of `rest`. Sets the result's motion_bounds (motion_bounds(rest)) and
/// clamp_length (frame_zero_clamp_length(rest) where object tracks move triangles, else 0),
/// both found from `rest` in every call: a sequence poses through PosedFrames
/// (scene/posed_frames.h), which finds them once.
Scene scene_at_frame(const Scene& rest, int frame);

struct SceneBounds;

/// A box, scene units, that every pose of every object an object track of `rest` moves
/// lies in, at every frame; empty where no object track holds a triangle. Each key poses
/// the object's rest bounding box (whose centre is the pivot): between two keys of one
/// rotation a pose is the linear mix of theirs, so the two posed boxes bound it; where the
/// rotation changes, a slerp can carry a corner outside both, so each key gives the cube
/// about its translated pivot that holds the sphere of radius scale × the rest box's
/// half-diagonal, and the centre and radius move linearly between keys. Each box is grown
/// by 1e-5 of the magnitudes posing adds, for its float rounding. Cost: one pass over the
/// moving objects' vertices and one step per key (once per sequence through PosedFrames;
/// scene_at_frame makes it in every call, beside its copy of every vertex). What for: the light paths' far roulette region
/// (docs/path-tracing.md §3) must be the same in every frame, or tic's updated cache would
/// differ from a rebuild (docs/instant-caching.md §8).
SceneBounds motion_bounds(const Scene& rest);

/// trimmed_diagonal (scene/extent.h) of the triangles of frame 0 of `rest`'s animation,
/// scene units: what scene_at_frame records as every frame's Scene::clamp_length where
/// object tracks move triangles. Cost: a copy of every vertex and the extent's partial
/// sorts (Sibenik: ~3.3 ms, bench/results/frame_setup.md), in place of the buffers' own
/// (2 ms): once per sequence through PosedFrames, in every call of scene_at_frame.
float frame_zero_clamp_length(const Scene& rest);

/// The bounds, scene units, of the triangles of `scene` (any frame's) that no object
/// track moves: the same in every frame (empty where every triangle moves).
SceneBounds still_bounds(const Scene& scene);

namespace scene_detail {

class JsonField;

/// The most frames an animation may have: 100,000 is 55 minutes at 30 frames/s, far
/// beyond a render's; a larger count is a typo, and the loader checks the camera of
/// every frame (read_animation), which must stay quick.
constexpr int kMaxAnimationFrames = 100000;

/// Reads the "animation" block into scene.animation, checked against the loaded
/// objects and materials (so it runs after objects, overrides and lights), and raises
/// every Material::emission_max to the largest emission its keys reach. Throws
/// InputError naming the file and JSON key for: an unknown key (a misspelling; comment
/// keys aside), frames outside 1..kMaxAnimationFrames, an unknown object or
/// material name, an empty key list, key frames not strictly increasing or outside
/// [0, frames), non-finite numbers, a key whose pose overflows a float, a zero
/// rotation axis, a scale <= 0, albedo outside
/// [0, 1], negative emission, and a camera key whose look_at equals its position or
/// whose view direction is parallel to camera.up.
void read_animation(const JsonField& j, Scene& scene);

/// scene_at_frame with the rest scene's motion_bounds and clamp_length given, as
/// scene_at_frame finds them per call and PosedFrames (scene/posed_frames.h) once.
Scene pose_frame(const Scene& rest, int frame, const SceneBounds& motion, float clamp_length);

}  // namespace scene_detail
}  // namespace tessera
