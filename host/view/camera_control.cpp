#include "view/camera_control.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tessera::view {
namespace {

glm::vec3 rotate_about(glm::vec3 v, glm::vec3 axis, float angle) {
    // Rodrigues' rotation formula; `axis` is unit length.
    const float c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0f - c);
}

}  // namespace

Camera move_camera(const Camera& camera, glm::vec3 axes, float distance) {
    const glm::vec3 forward = glm::normalize(camera.look_at - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::normalize(camera.up);
    const glm::vec3 delta = (right * axes.x + up * axes.y + forward * axes.z) * distance;
    Camera moved = camera;
    moved.position += delta;
    moved.look_at += delta;
    return moved;
}

Camera turn_camera(const Camera& camera, float yaw, float pitch) {
    const glm::vec3 view = camera.look_at - camera.position;
    const float dist = glm::length(view);
    const glm::vec3 up = glm::normalize(camera.up);
    glm::vec3 forward = rotate_about(view / dist, up, yaw);
    // Limit the pitch: the angle between forward and up stays in [1°, 179°].
    const float limit = glm::radians(1.0f);
    const float from_up = std::acos(std::clamp(glm::dot(forward, up), -1.0f, 1.0f));
    const float target = std::clamp(from_up - pitch, limit, glm::pi<float>() - limit);
    const glm::vec3 right = glm::normalize(glm::cross(forward, up));
    forward = rotate_about(forward, right, from_up - target);
    Camera turned = camera;
    turned.look_at = camera.position + forward * dist;
    return turned;
}

bool camera_differs(const Camera& a, const Camera& b) {
    return a.position != b.position || a.look_at != b.look_at || a.up != b.up || a.vfov_deg != b.vfov_deg;
}

std::string camera_json(const Camera& c) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "\"camera\": {\"position\": [%.9g, %.9g, %.9g], \"look_at\": [%.9g, %.9g, %.9g], "
                  "\"up\": [%.9g, %.9g, %.9g], \"vfov\": %.9g, \"resolution\": [%d, %d]}",
                  c.position.x, c.position.y, c.position.z, c.look_at.x, c.look_at.y, c.look_at.z, c.up.x, c.up.y,
                  c.up.z, c.vfov_deg, c.width, c.height);
    return buf;
}

float default_speed(const Scene& scene) { return 0.1f * (scene.positions.empty() ? 1.0f : scene.diagonal()); }

}  // namespace tessera::view
