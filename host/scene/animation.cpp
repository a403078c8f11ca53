#include "scene/animation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/extent.h"
#include "scene/json_field.h"
#include "scene/posed_frames.h"
#include "scene/scene.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera {
namespace {

using scene_detail::JsonField;

// The key segment holding `frame`: keys[i] and keys[j] with weight t of keys[j]. Outside
// the keyed range both ends are the same key (hold).
template <class Key>
void find_segment(const std::vector<Key>& keys, int frame, size_t& i, size_t& j, float& t) {
    if (frame <= keys.front().frame) { i = j = 0; t = 0.0f; return; }
    if (frame >= keys.back().frame) { i = j = keys.size() - 1; t = 0.0f; return; }
    j = 1;
    while (keys[j].frame <= frame) ++j;
    i = j - 1;
    t = float(frame - keys[i].frame) / float(keys[j].frame - keys[i].frame);
}

// Vertex indices of object o's triangles: [first, last).
size_t first_vertex(const SceneObject& o) { return 3 * size_t(o.first_triangle); }
size_t last_vertex(const SceneObject& o) { return 3 * (size_t(o.first_triangle) + o.triangle_count); }

glm::vec3 bbox_centre(const Scene& s, const SceneObject& o) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (size_t v = first_vertex(o); v < last_vertex(o); ++v) {
        lo = glm::min(lo, s.positions[v]);
        hi = glm::max(hi, s.positions[v]);
    }
    return 0.5f * (lo + hi);
}

// Key k's pose of the rest object o; normals are left to the caller.
template <class Visit>
void pose_positions(const Scene& rest, const SceneObject& o, const ObjectKey& k, Visit visit) {
    if (o.triangle_count == 0) return;
    const glm::vec3 pivot = bbox_centre(rest, o);
    const glm::mat3 r = glm::mat3_cast(k.rotation);
    for (size_t v = first_vertex(o); v < last_vertex(o); ++v)
        visit(v, pivot + k.translate + r * (k.scale * (rest.positions[v] - pivot)));
}

void pose_object(const Scene& rest, Scene& out, const SceneObject& o, const ObjectKey& k) {
    pose_positions(rest, o, k, [&](size_t v, glm::vec3 p) { out.positions[v] = p; });
    // The inverse-transpose of scale·R is R/scale, and normals are renormalised: R alone.
    const glm::mat3 r = glm::mat3_cast(k.rotation);
    for (size_t v = first_vertex(o); v < last_vertex(o); ++v) out.normals[v] = glm::normalize(r * rest.normals[v]);
}

// Poses between keys are convex combinations of key poses (rotations keep lengths), so
// finite key poses bound every frame's.
bool key_pose_is_finite(const Scene& s, const SceneObject& o, const ObjectKey& k) {
    bool finite = true;
    pose_positions(s, o, k, [&](size_t, glm::vec3 p) {
        finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    });
    return finite;
}

// Whether every posed vertex lies within limits::kMaxCoordinate, as the rest pose must:
// a key that moved a room 3e20 away collapsed it and lost its lamp without a word.
bool key_pose_is_inside_limit(const Scene& s, const SceneObject& o, const ObjectKey& k) {
    bool inside = true;
    pose_positions(s, o, k, [&](size_t, glm::vec3 p) {
        inside = inside && std::fabs(p.x) <= limits::kMaxCoordinate && std::fabs(p.y) <= limits::kMaxCoordinate &&
                 std::fabs(p.z) <= limits::kMaxCoordinate;
    });
    return inside;
}

// Key `i` of `keys` turns the object relative to a neighbouring key: a slerp lies between.
bool key_turns(const std::vector<ObjectKey>& keys, size_t i) {
    return (i > 0 && keys[i - 1].rotation != keys[i].rotation) ||
           (i + 1 < keys.size() && keys[i + 1].rotation != keys[i].rotation);
}

// Grows `reach` by every pose the keys give object o (motion_bounds).
void grow_by_object_motion(const Scene& rest, const SceneObject& o, const std::vector<ObjectKey>& keys,
                           SceneBounds& reach) {
    if (o.triangle_count == 0) return;
    SceneBounds box;
    for (size_t v = first_vertex(o); v < last_vertex(o); ++v) box.grow(rest.positions[v]);
    // pose_positions' pivot, and the largest offset from it as posing rounds it (float
    // subtraction is monotone): the rounded pivot may lie off the box's centre.
    const glm::vec3 pivot = 0.5f * (box.lo + box.hi), half = glm::max(box.hi - pivot, pivot - box.lo);
    for (size_t i = 0; i < keys.size(); ++i) {
        const ObjectKey& k = keys[i];
        glm::vec3 extent;  // the posed box's half-size about pivot + translate
        if (key_turns(keys, i)) {
            extent = glm::vec3(k.scale * glm::length(half));
        } else {
            const glm::mat3 r = glm::mat3_cast(k.rotation);
            // A rotated box's extent on axis a: Σ_b |R_ab| × half_b (columns are r[b]).
            extent = k.scale * (glm::abs(r[0]) * half.x + glm::abs(r[1]) * half.y + glm::abs(r[2]) * half.z);
        }
        // Posing rounds at the magnitudes it adds: 1e-5 of them is ~80 float ulps.
        const glm::vec3 m = glm::abs(pivot) + glm::abs(k.translate) + extent;
        const glm::vec3 slack(1e-5f * std::max({m.x, m.y, m.z}));
        const glm::vec3 centre = pivot + k.translate;
        reach.grow(centre - extent - slack);
        reach.grow(centre + extent + slack);
    }
}

ObjectKey object_key_at(const std::vector<ObjectKey>& keys, int frame) {
    size_t i, j;
    float t;
    find_segment(keys, frame, i, j, t);
    const ObjectKey &a = keys[i], &b = keys[j];
    ObjectKey k;
    k.frame = frame;
    k.translate = glm::mix(a.translate, b.translate, t);
    k.rotation = glm::slerp(a.rotation, b.rotation, t);
    k.scale = glm::mix(a.scale, b.scale, t);
    return k;
}

glm::vec3 mix_opt(const std::optional<glm::vec3>& a, const std::optional<glm::vec3>& b, glm::vec3 rest, float t) {
    return glm::mix(a.value_or(rest), b.value_or(rest), t);
}

Camera camera_at(const Camera& rest, const std::vector<CameraKey>& keys, int frame) {
    Camera c = rest;
    if (keys.empty()) return c;
    size_t i, j;
    float t;
    find_segment(keys, frame, i, j, t);
    c.position = glm::mix(keys[i].position, keys[j].position, t);
    c.look_at = glm::mix(keys[i].look_at, keys[j].look_at, t);
    return c;
}

// ---- parsing ----

int read_key_frame(const JsonField& key, int frames, int previous) {
    const JsonField f = key["frame"];
    const int frame = f.integer();
    if (frame < 0 || frame >= frames)
        f.fail("frame " + std::to_string(frame) + " is outside the animation's frames 0.." +
               std::to_string(frames - 1));
    if (frame <= previous)
        f.fail("key frames must increase (the previous key is at frame " + std::to_string(previous) + ")");
    return frame;
}

// Checks the key list (each key may hold `known` members) and calls read(key, frame) for
// each key.
template <class Read>
void for_each_key(const JsonField& list, int frames, std::initializer_list<std::string_view> known, Read read) {
    if (list.size() == 0) list.fail("a track needs at least one key");
    int previous = -1;
    for (size_t i = 0; i < list.size(); ++i) {
        const JsonField key = list.at(i);
        key.require_object();
        key.require_known_keys(known);
        previous = read_key_frame(key, frames, previous);
        read(key, previous);
    }
}

ObjectKey read_object_key(const JsonField& j, int frame) {
    ObjectKey k;
    k.frame = frame;
    if (auto t = j.find("translate")) k.translate = t->vec3();
    if (auto r = j.find("rotate")) {
        r->require_known_keys({"axis", "degrees"});
        const glm::vec3 axis = (*r)["axis"].vec3();
        if (!(glm::dot(axis, axis) > 0.0f) || !std::isfinite(glm::dot(axis, axis)))
            (*r)["axis"].fail("rotation axis is zero (or its length overflows a float)");
        k.rotation = glm::angleAxis(glm::radians((*r)["degrees"].number()), glm::normalize(axis));
    }
    if (auto s = j.find("scale")) {
        k.scale = s->number();
        // A negative scale would mirror (turning triangles inside out) and interpolating
        // towards it would pass through zero.
        if (!(k.scale > 0.0f)) s->fail("scale must be > 0 (zero is singular, a negative one mirrors)");
    }
    return k;
}

void read_object_tracks(const JsonField& j, Scene& scene, int frames) {
    j.require_object();
    for (const auto& [name, value] : j.raw().items()) {
        if (scene_detail::is_comment_key(name)) continue;
        const JsonField list(value, j.file(), j.key() + "." + name);
        ObjectTrack track;
        track.name = name;
        for (uint32_t i = 0; i < scene.objects.size(); ++i)
            if (scene.objects[i].name == name) track.objects.push_back(i);
        if (track.objects.empty()) list.fail("the scene has no object named '" + name + "'");
        for_each_key(list, frames, {"frame", "translate", "rotate", "scale"}, [&](const JsonField& key, int frame) {
            track.keys.push_back(read_object_key(key, frame));
            for (const uint32_t o : track.objects)
                if (!key_pose_is_finite(scene, scene.objects[o], track.keys.back()))
                    key.fail("the posed object has a vertex coordinate that overflows a float");
                else if (!key_pose_is_inside_limit(scene, scene.objects[o], track.keys.back()))
                    key.fail("the posed object has a vertex beyond " + limits::shown_coordinate_limit());
        });
        scene.animation.objects.push_back(std::move(track));
    }
}

void read_material_tracks(const JsonField& j, Scene& scene, int frames) {
    j.require_object();
    for (const auto& [name, value] : j.raw().items()) {
        if (scene_detail::is_comment_key(name)) continue;
        const JsonField list(value, j.file(), j.key() + "." + name);
        MaterialTrack track;
        track.name = name;
        for (uint32_t i = 0; i < scene.materials.size(); ++i)
            if (scene.materials[i].name == name) track.materials.push_back(i);
        if (track.materials.empty()) list.fail("the scene has no material named '" + name + "'");
        for_each_key(list, frames, {"frame", "albedo", "emission"}, [&](const JsonField& key, int frame) {
            MaterialKey k;
            k.frame = frame;
            if (auto a = key.find("albedo")) k.albedo = scene_detail::read_colour(*a, scene_detail::Colour::Albedo);
            if (auto e = key.find("emission")) k.emission = scene_detail::read_colour(*e, scene_detail::Colour::Radiance);
            track.keys.push_back(k);
        });
        // Values between keys are convex combinations of key values: the keys bound them.
        for (const uint32_t m : track.materials) {
            Material& mat = scene.materials[m];
            glm::vec3 top(0.0f);
            for (const MaterialKey& k : track.keys) top = glm::max(top, k.emission.value_or(mat.emission));
            mat.emission_max = top;
        }
        scene.animation.materials.push_back(std::move(track));
    }
}

void read_camera_track(const JsonField& list, Scene& scene, int frames) {
    for_each_key(list, frames, {"frame", "position", "look_at"}, [&](const JsonField& key, int frame) {
        CameraKey k{frame, scene.camera.position, scene.camera.look_at};
        if (auto p = key.find("position")) k.position = p->vec3();
        if (auto l = key.find("look_at")) k.look_at = l->vec3();
        scene_detail::check_camera_view(key, k.position, k.look_at, scene.camera.up);
        scene.animation.camera.push_back(k);
    });
    // Two valid keys can still interpolate to a degenerate view in between.
    for (int f = 0; f < frames; ++f) {
        const Camera c = camera_at(scene.camera, scene.animation.camera, f);
        scene_detail::check_camera_view(list, c.position, c.look_at, c.up,
                                        "at frame " + std::to_string(f) + ", between its keys: ");
    }
}

}  // namespace

Scene scene_at_frame(const Scene& rest, int frame) {
    // PosedFrames holds the rule for motion_bounds and clamp_length (assigned either way:
    // `rest` may itself be a posed copy carrying another frame 0's).
    return PosedFrames(rest).at(frame);
}

float frame_zero_clamp_length(const Scene& rest) {
    std::vector<glm::vec3> positions = rest.positions;
    for (const ObjectTrack& track : rest.animation.objects) {
        const ObjectKey k = object_key_at(track.keys, 0);
        for (const uint32_t o : track.objects)
            pose_positions(rest, rest.objects[o], k, [&](size_t v, glm::vec3 p) { positions[v] = p; });
    }
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float));  // positions as 9 floats a triangle
    SceneBounds bounds;
    for (const glm::vec3& p : positions) bounds.grow(p);
    return trimmed_diagonal(reinterpret_cast<const float*>(positions.data()), positions.size() / 3, bounds);
}

SceneBounds still_bounds(const Scene& scene) {
    std::vector<bool> moves(scene.triangle_count(), false);
    for (const ObjectTrack& track : scene.animation.objects)
        for (const uint32_t o : track.objects) {
            const SceneObject& obj = scene.objects[o];
            std::fill_n(moves.begin() + obj.first_triangle, obj.triangle_count, true);
        }
    SceneBounds still;
    for (size_t v = 0; v < scene.positions.size(); ++v)
        if (!moves[v / 3]) still.grow(scene.positions[v]);
    return still;
}

SceneBounds motion_bounds(const Scene& rest) {
    SceneBounds reach;
    for (const ObjectTrack& track : rest.animation.objects)
        for (const uint32_t o : track.objects) grow_by_object_motion(rest, rest.objects[o], track.keys, reach);
    return reach;
}

namespace scene_detail {

Scene pose_frame(const Scene& rest, int frame, const SceneBounds& motion, float clamp_length) {
    const Animation& a = rest.animation;
    const int frames = std::max(a.frame_count, 1);
    if (frame < 0 || frame >= frames)
        throw InputError(rest.source.string() + ": frame " + std::to_string(frame) + " is outside the animation of " +
                         rest.name + " (frames 0.." + std::to_string(frames - 1) + ")");
    Scene out = rest;
    for (const ObjectTrack& track : a.objects) {
        const ObjectKey k = object_key_at(track.keys, frame);
        for (const uint32_t o : track.objects) pose_object(rest, out, rest.objects[o], k);
    }
    for (const MaterialTrack& track : a.materials) {
        size_t i, j;
        float t;
        find_segment(track.keys, frame, i, j, t);
        for (const uint32_t m : track.materials) {
            const Material& r = rest.materials[m];
            out.materials[m].albedo = mix_opt(track.keys[i].albedo, track.keys[j].albedo, r.albedo, t);
            out.materials[m].emission = mix_opt(track.keys[i].emission, track.keys[j].emission, r.emission, t);
        }
    }
    out.camera = camera_at(rest.camera, a.camera, frame);
    out.motion_bounds = motion;
    out.clamp_length = clamp_length;
    return out;
}


void read_animation(const JsonField& j, Scene& scene) {
    j.require_known_keys({"frames", "objects", "materials", "camera"});
    const JsonField frames_key = j["frames"];
    const int frames = frames_key.integer();
    if (frames < 1 || frames > kMaxAnimationFrames)
        frames_key.fail("an animation needs frames in 1.." + std::to_string(kMaxAnimationFrames));
    scene.animation = Animation{};
    scene.animation.frame_count = frames;
    if (auto o = j.find("objects")) read_object_tracks(*o, scene, frames);
    if (auto m = j.find("materials")) read_material_tracks(*m, scene, frames);
    if (auto c = j.find("camera")) read_camera_track(*c, scene, frames);
}

}  // namespace scene_detail
}  // namespace tessera
