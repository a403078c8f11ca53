#include "view/camera_path.h"

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "image/atomic_file.h"
#include "scene/json_field.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::view {
namespace {

using scene_detail::JsonField;

PathFrame read_entry(const JsonField& e) {
    e.require_known_keys({"position", "look_at", "up", "vfov", "frame"});
    PathFrame f;
    f.camera.position = e["position"].vec3();
    f.camera.look_at = e["look_at"].vec3();
    f.camera.up = e["up"].vec3();
    // The same test as the scene's camera block: a path replays through the same camera code.
    scene_detail::check_camera_view(e, f.camera.position, f.camera.look_at, f.camera.up);
    const JsonField vfov = e["vfov"];
    f.camera.vfov_deg = vfov.number();
    if (!(f.camera.vfov_deg > 0.0f && f.camera.vfov_deg < 180.0f)) vfov.fail("must be degrees in (0, 180)");
    if (const auto frame = e.find("frame")) {
        f.frame = frame->integer();
        if (f.frame < 0 || f.frame >= limits::kViewFrames)
            frame->fail("must be an animation frame in 0.." + std::to_string(limits::kViewFrames - 1));
    }
    return f;
}

std::vector<PathFrame> read_entries(const std::filesystem::path& path, std::string* scene) {
    const nlohmann::json doc = scene_detail::parse_json_file(path, "camera path");
    const JsonField root(doc, path, "");
    root.require_known_keys({"scene", "cameras"});
    if (const auto name = root.find("scene")) {
        const std::string text = name->string();  // a string, checked as every key is
        if (scene) *scene = text;
    }
    const JsonField cameras = root["cameras"];
    if (cameras.size() == 0) cameras.fail("a camera path needs at least one camera");
    if (cameras.size() > limits::kPathEntries)
        cameras.fail("more than " + std::to_string(limits::kPathEntries) + " cameras (the limit for a path)");
    std::vector<PathFrame> frames;
    frames.reserve(cameras.size());
    for (size_t i = 0; i < cameras.size(); ++i) frames.push_back(read_entry(cameras.at(i)));
    return frames;
}

}  // namespace

std::vector<PathFrame> read_camera_path(const std::filesystem::path& path, std::string* scene) {
    try {
        if (scene) scene->clear();
        return read_entries(path, scene);
    } catch (const InputError& e) {
        throw InputError(std::string("--camera-path ") + e.what());
    }
}

void write_camera_path(const std::filesystem::path& path, const std::vector<PathFrame>& frames,
                       const std::string& scene) {
    std::string text = "{";
    if (!scene.empty()) text += "\"scene\": " + nlohmann::json(scene).dump() + ",\n ";
    text += "\"cameras\": [\n";
    char buf[512];
    for (size_t i = 0; i < frames.size(); ++i) {
        const Camera& c = frames[i].camera;
        std::snprintf(buf, sizeof buf,
                      "  {\"position\": [%.9g, %.9g, %.9g], \"look_at\": [%.9g, %.9g, %.9g], \"up\": [%.9g, %.9g, "
                      "%.9g], \"vfov\": %.9g, \"frame\": %d}%s\n",
                      c.position.x, c.position.y, c.position.z, c.look_at.x, c.look_at.y, c.look_at.z, c.up.x, c.up.y,
                      c.up.z, c.vfov_deg, frames[i].frame, i + 1 < frames.size() ? "," : "");
        text += buf;
    }
    text += "]}\n";
    write_file_atomic(path, text.data(), text.size());
}

}  // namespace tessera::view
