#include "view/camera_path.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "image/atomic_file.h"
#include "util/error.h"

namespace tessera::view {
namespace {

glm::vec3 read_vec3(const nlohmann::json& e, const char* key, const std::string& where) {
    if (!e.contains(key) || !e[key].is_array() || e[key].size() != 3)
        throw InputError(where + ": \"" + key + "\" must be an array of 3 numbers");
    glm::vec3 v;
    for (int i = 0; i < 3; ++i) {
        if (!e[key][i].is_number() || !std::isfinite(e[key][i].get<double>()))
            throw InputError(where + ": \"" + key + "\" must be an array of 3 finite numbers");
        v[i] = e[key][i].get<float>();
    }
    return v;
}

}  // namespace

std::vector<PathFrame> read_camera_path(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError("--camera-path " + path.string() + ": cannot open the file");
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw InputError("--camera-path " + path.string() + ": not valid JSON (" + e.what() + ")");
    }
    if (!doc.is_object() || !doc.contains("cameras") || !doc["cameras"].is_array() || doc["cameras"].empty())
        throw InputError("--camera-path " + path.string() + ": expected an object with a non-empty \"cameras\" array");
    std::vector<PathFrame> frames;
    for (size_t i = 0; i < doc["cameras"].size(); ++i) {
        const nlohmann::json& e = doc["cameras"][i];
        const std::string where = "--camera-path " + path.string() + ": cameras[" + std::to_string(i) + "]";
        if (!e.is_object()) throw InputError(where + ": expected an object");
        PathFrame f;
        f.camera.position = read_vec3(e, "position", where);
        f.camera.look_at = read_vec3(e, "look_at", where);
        f.camera.up = read_vec3(e, "up", where);
        if (!e.contains("vfov") || !e["vfov"].is_number() || !(e["vfov"].get<double>() > 0) ||
            !(e["vfov"].get<double>() < 180))
            throw InputError(where + ": \"vfov\" must be a number of degrees in (0, 180)");
        f.camera.vfov_deg = e["vfov"].get<float>();
        if (e.contains("frame")) {
            if (!e["frame"].is_number_integer() || e["frame"].get<int>() < 0)
                throw InputError(where + ": \"frame\" must be an integer >= 0");
            f.frame = e["frame"].get<int>();
        }
        frames.push_back(f);
    }
    return frames;
}

void write_camera_path(const std::filesystem::path& path, const std::vector<PathFrame>& frames) {
    std::string text = "{\"cameras\": [\n";
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
