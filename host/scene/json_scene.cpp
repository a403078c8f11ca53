// load_scene: the JSON scene format (documented in scenes/README.md) to a Scene.
#include <cmath>
#include <limits>
#include <map>

#include "scene/json_field.h"
#include "scene/loader.h"
#include "scene/obj_mesh.h"
#include "scene/texture_file.h"
#include "scene/transform.h"
#include "util/error.h"
#include "util/input_limits.h"
#include "util/terminal_safe.h"

namespace tessera {

using scene_detail::JsonField;
using scene_detail::read_colour;
namespace fs = std::filesystem;

namespace {

Camera read_camera(const JsonField& j) {
    j.require_known_keys({"position", "look_at", "up", "vfov", "resolution"});
    Camera cam;
    cam.position = j["position"].vec3();
    cam.look_at = j["look_at"].vec3();
    if (auto up = j.find("up")) cam.up = up->vec3();
    if (auto vfov = j.find("vfov")) {
        cam.vfov_deg = vfov->number();
        if (!(cam.vfov_deg > 0.0f && cam.vfov_deg < 180.0f))
            vfov->fail("vertical field of view must be in (0, 180) degrees");
    }
    if (auto res = j.find("resolution")) {
        if (res->size() != 2) res->fail("expected [width, height]");
        cam.width = res->at(0).integer();
        cam.height = res->at(1).integer();
        for (const int v : {cam.width, cam.height})
            if (v <= 0 || v > 16384) res->fail("each resolution must be in 1..16384 pixels");
    }
    scene_detail::check_camera_view(j, cam.position, cam.look_at, cam.up);
    return cam;
}

// Whether every coordinate of p lies within ±limits::kMaxCoordinate.
bool inside_coordinate_limit(glm::vec3 p) {
    return std::fabs(p.x) <= limits::kMaxCoordinate && std::fabs(p.y) <= limits::kMaxCoordinate &&
           std::fabs(p.z) <= limits::kMaxCoordinate;
}

std::string shown_point(glm::vec3 p) {
    return "(" + limits::shown_limit(p.x) + ", " + limits::shown_limit(p.y) + ", " + limits::shown_limit(p.z) + ")";
}

std::string coordinate_limit_text() { return "beyond " + limits::shown_coordinate_limit(); }

scene_detail::Transform read_transform(const std::optional<JsonField>& j) {
    glm::vec3 scale(1.0f), translate(0.0f);
    std::vector<scene_detail::Rotation> rotations;
    if (!j) return scene_detail::make_transform(scale, rotations, translate);
    j->require_known_keys({"scale", "rotate", "translate"});
    if (auto s = j->find("scale")) {
        scale = s->raw().is_array() ? s->vec3() : glm::vec3(s->number());
        if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f)
            s->fail("scale must not be zero (the transform would be singular)");
    }
    if (auto r = j->find("rotate")) {
        for (size_t i = 0; i < r->size(); ++i) {
            const JsonField rot = r->at(i);
            rot.require_known_keys({"axis", "degrees"});
            const glm::vec3 axis = rot["axis"].vec3();
            if (!(glm::dot(axis, axis) > 0.0f) || !std::isfinite(glm::dot(axis, axis)))
                rot["axis"].fail("rotation axis is zero (or its length overflows a float)");
            rotations.push_back({axis, rot["degrees"].number()});
        }
    }
    if (auto t = j->find("translate")) translate = t->vec3();
    const auto transform = scene_detail::make_transform(scale, rotations, translate);
    // A scale so small that the determinant underflows the float range would lose the
    // mirror test (flips_winding: -0 is not < 0) and make the normal matrix infinite.
    // (One that overflows keeps its sign; overflowing positions are caught later.)
    const float det = glm::determinant(glm::mat3(transform.matrix));
    if (!(std::fabs(det) >= std::numeric_limits<float>::min()))
        j->fail("the transform's determinant " + std::to_string(det) +
                " is zero or below the float range (scale too small)");
    return transform;
}

// Loads each OBJ once (instancing a mesh twice shares its materials and textures).
struct MeshEntry {
    scene_detail::ObjMesh mesh;
    std::vector<uint32_t> material_index;  ///< scene.materials index of each mesh.materials entry
};

// The index of `m` in scene.materials, appending it unless an equal one is there: two
// OBJs that read one MTL file (or both fall back to the default grey) share its materials.
uint32_t find_or_add_material(Scene& scene, const Material& m) {
    for (size_t j = 0; j < scene.materials.size(); ++j)
        if (scene.materials[j] == m) return static_cast<uint32_t>(j);
    scene.materials.push_back(m);
    return static_cast<uint32_t>(scene.materials.size() - 1);
}

void read_objects(const JsonField& objects, const DataPath& data, Scene& scene,
                  std::map<fs::path, int>& texture_ids) {
    std::map<fs::path, MeshEntry> meshes;
    if (objects.size() == 0) objects.fail("a scene needs at least one object");
    for (size_t i = 0; i < objects.size(); ++i) {
        const JsonField obj = objects.at(i);
        obj.require_known_keys({"name", "mesh", "transform"});
        const JsonField mesh_key = obj["mesh"];
        const std::string rel = mesh_key.string();
        if (rel.empty()) mesh_key.fail("must name an OBJ file, not be empty");
        fs::path file;
        try {
            file = data.resolve(rel, scene.source);
        } catch (const InputError& e) {
            throw InputError(std::string(e.what()) + " (key '" + mesh_key.key() + "')");
        }
        const auto transform = read_transform(obj.find("transform"));
        const fs::path key = same_file(file);  // "a.obj", "./a.obj": one mesh
        auto it = meshes.find(key);
        if (it == meshes.end()) {
            MeshEntry entry{scene_detail::load_obj_mesh(file), {}};
            scene.inputs.push_back(file);
            scene.notes.insert(scene.notes.end(), entry.mesh.notes.begin(), entry.mesh.notes.end());
            for (const fs::path& mtl : entry.mesh.mtl_files) scene.inputs.push_back(mtl);
            for (const fs::path& tex : entry.mesh.texture_files) scene.inputs.push_back(tex);
            for (Material m : entry.mesh.materials) {
                if (m.texture >= 0) {
                    const fs::path& tex = entry.mesh.texture_files[size_t(m.texture)];
                    auto [t, added] = texture_ids.try_emplace(same_file(tex), int(scene.textures.size()));
                    if (added) {
                        try {
                            scene.textures.push_back(scene_detail::load_texture(tex));
                        } catch (const InputError& e) {  // the file's own message, then where it is named
                            throw InputError(std::string(e.what()) + " (" +
                                             entry.mesh.texture_roles[size_t(m.texture)] + ")");
                        }
                    }
                    m.texture = t->second;
                }
                entry.material_index.push_back(find_or_add_material(scene, m));
            }
            it = meshes.emplace(key, std::move(entry)).first;
        }
        const size_t first = scene.positions.size();
        std::string name = rel + "#" + std::to_string(i);
        if (auto n = obj.find("name")) name = n->string();
        scene.objects.push_back({name, static_cast<uint32_t>(scene.triangle_count()), 0u});
        scene_detail::append_mesh(scene, it->second.mesh, transform, it->second.material_index);
        // A finite vertex times a finite transform can still overflow (scale 3e38 and a
        // translation of 3e38): infinite positions would poison the BVH and every pixel.
        for (size_t v = first; v < scene.positions.size(); ++v) {
            const glm::vec3 p = scene.positions[v];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                obj.fail("the transformed mesh '" + rel + "' has a vertex coordinate that overflows a float");
        }
        for (size_t v = first; v < scene.positions.size(); ++v) {
            const glm::vec3 p = scene.positions[v];
            if (!inside_coordinate_limit(p)) {
                // The transform's key where there is one (it put the vertex there), else the object's.
                const std::optional<JsonField> t = obj.find("transform");
                (t ? *t : obj).fail("the transformed mesh '" + rel + "' has a vertex at " + shown_point(p) + ", " +
                                    coordinate_limit_text());
            }
        }
        scene.objects.back().triangle_count =
            static_cast<uint32_t>(scene.triangle_count()) - scene.objects.back().first_triangle;
    }
}

void apply_material_overrides(const JsonField& overrides, Scene& scene) {
    overrides.require_object();
    for (const auto& [name, value] : overrides.raw().items()) {
        if (scene_detail::is_comment_key(name)) continue;
        const JsonField o(value, overrides.file(), overrides.key() + "." + name);
        o.require_known_keys({"albedo", "emission"});
        bool found = false;
        for (auto& m : scene.materials) {
            if (m.name != name) continue;
            found = true;
            if (auto a = o.find("albedo")) m.albedo = read_colour(*a, scene_detail::Colour::Albedo);
            if (auto e = o.find("emission")) m.emission = read_colour(*e, scene_detail::Colour::Radiance);
        }
        if (!found) o.fail("no loaded MTL material is named '" + name + "'");
    }
}

void read_lights(const JsonField& lights, Scene& scene) {
    for (size_t i = 0; i < lights.size(); ++i) {
        const JsonField l = lights.at(i);
        l.require_known_keys({"type", "corner", "edge1", "edge2", "radiance"});
        const std::string type = l["type"].string();
        if (type != "quad") l["type"].fail("unknown light type '" + type + "' (supported: quad)");
        const glm::vec3 e1 = l["edge1"].vec3(), e2 = l["edge2"].vec3();
        const glm::vec3 n = glm::cross(e1, e2);
        if (!(glm::dot(n, n) > 0.0f) || !std::isfinite(glm::dot(n, n)))
            l.fail("edge1 and edge2 must be non-zero and not parallel (and their cross product finite)");
        const glm::vec3 corner = l["corner"].vec3();
        for (const glm::vec3 p : {corner + e1, corner + e2, corner + e1 + e2})
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                l.fail("a corner of the quad overflows a float");
        for (const glm::vec3 p : {corner, corner + e1, corner + e2, corner + e1 + e2})
            if (!inside_coordinate_limit(p)) l.fail("a corner of the quad lies at " + shown_point(p) + ", " +
                                                    coordinate_limit_text());
        const auto first = static_cast<uint32_t>(scene.triangle_count());
        scene_detail::append_quad_light(scene, l["corner"].vec3(), e1, e2,
                                        read_colour(l["radiance"], scene_detail::Colour::Radiance),
                                        "json-light-" + std::to_string(i));
        scene.objects.push_back({"json-light-" + std::to_string(i), first, 2u, true});
    }
}

// The medium's optical depth over the scene's diagonal, (σ_a + σ_s)·D per channel in
// double, against limits::kMaxOpticalDepth; D from the geometry and lights loaded so far
// (everything but the medium). A scene of one point (D = 0) has no depth to bound.
void check_optical_depth(const JsonField& j, const Scene& scene) {
    const double d = scene.diagonal();
    const Medium& m = scene.medium;
    for (int c = 0; c < 3; ++c) {
        const double tau = (double(m.sigma_a[c]) + double(m.sigma_s[c])) * d;
        if (tau > limits::kMaxOpticalDepth)
            j.fail("sigma_a + sigma_s = " + limits::shown_limit(double(m.sigma_a[c]) + double(m.sigma_s[c])) +
                   " per scene unit gives an optical depth of " + limits::shown_limit(tau) +
                   " over the scene's diagonal (" + limits::shown_limit(d) + " scene units); the limit is " +
                   limits::shown_limit(limits::kMaxOpticalDepth) + ", already opaque past 1e-7 of it");
    }
}

// "medium": {"sigma_a": [r,g,b], "sigma_s": [r,g,b], "g": 0.0,
//            "box": {"min": [x,y,z], "max": [x,y,z]}}   (box optional)
void read_medium(const JsonField& j, Scene& scene) {
    j.require_known_keys({"sigma_a", "sigma_s", "g", "box"});
    Medium& m = scene.medium;
    m.sigma_a = read_colour(j["sigma_a"], scene_detail::Colour::Coefficient);
    m.sigma_s = read_colour(j["sigma_s"], scene_detail::Colour::Coefficient);
    check_optical_depth(j, scene);
    if (auto g = j.find("g")) {
        m.g = g->number();
        if (!(m.g > -1.0f && m.g < 1.0f)) g->fail("must lie in (-1, 1)");
    }
    if (auto box = j.find("box")) {
        box->require_known_keys({"min", "max"});
        m.bounded = true;
        m.box_min = (*box)["min"].vec3();
        m.box_max = (*box)["max"].vec3();
        for (int a = 0; a < 3; ++a)
            if (!(m.box_min[a] < m.box_max[a])) box->fail("min must be below max on every axis");
    }
    scene.has_medium = true;
}

// emission_max, not emission: a light that is dark in the rest pose but lit in some
// frame makes a valid scene; one that is dark in every frame does not. A light is an
// emissive triangle of non-zero area, as the light list counts it (add_lights,
// device/scene_buffers.cpp); an emitter whose area overflows a float is refused.
bool has_emitter(const Scene& scene) {
    bool any = false;
    for (uint32_t i = 0; i < scene.triangle_count(); ++i) {
        const Material& m = scene.materials[scene.material[i]];
        const glm::vec3 e = m.emission_max;
        if (!(e.x > 0.0f || e.y > 0.0f || e.z > 0.0f)) continue;
        const float area = scene.triangle_area(i);
        if (!std::isfinite(area))
            throw InputError(scene.source.string() + ": emissive triangle " + std::to_string(i) + " (material '" +
                             m.name + "') has an area that overflows a float");
        any = any || area > 0.0f;
    }
    return any;
}

// A name that prints as itself in a log line: no control characters (a terminal's
// escape sequences; C1's U+009B is one too), not empty. Paths are not made from it
// (cli/option_checks.h).
bool is_printable_name(const std::string& name) { return !name.empty() && is_printable_line(name); }

}  // namespace

Scene load_scene(const fs::path& scene_file, const DataPath& data) {
    const nlohmann::json doc = scene_detail::parse_json_file(scene_file);
    const JsonField root(doc, scene_file, "");
    root.require_known_keys(
        {"name", "stands_in_for", "camera", "objects", "lights", "materials", "medium", "animation"});
    Scene scene;
    scene.source = scene_file;
    scene.inputs.push_back(scene_file);
    scene.name = scene_file.stem().string();
    if (auto name = root.find("name")) {
        scene.name = name->string();
        if (!is_printable_name(scene.name))
            name->fail("must be a name to print: not empty, no control characters (the logs show it)");
    }
    if (auto s = root.find("stands_in_for")) (void)s->string();  // free text, type-checked only
    scene.camera = read_camera(root["camera"]);
    std::map<fs::path, int> texture_ids;
    read_objects(root["objects"], data, scene, texture_ids);
    // Overrides apply to MTL materials only, so they run before the lights add theirs.
    if (auto m = root.find("materials")) apply_material_overrides(*m, scene);
    if (auto l = root.find("lights")) read_lights(*l, scene);
    if (auto m = root.find("medium")) read_medium(*m, scene);
    for (Material& m : scene.materials) m.emission_max = m.emission;
    // Last: it names objects, MTL materials and JSON lights, and raises emission_max.
    if (auto a = root.find("animation")) scene_detail::read_animation(*a, scene);
    if (!has_emitter(scene))
        throw InputError(scene_file.string() + ": scene " + scene.name +
                         " has no lights (no MTL Ke and no JSON light, or only emitters of zero area)");
    return scene;
}

}  // namespace tessera
