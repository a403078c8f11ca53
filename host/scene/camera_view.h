// Whether a camera's position, look_at and up give an image: the one test both the scene
// loader (scene_detail::check_camera_view) and make_frame (device/frame.cpp) apply, so a
// camera the loader accepts always renders and one make_frame would refuse is refused at
// load, with the key that holds it.
#pragma once
#include <cmath>

#include <glm/glm.hpp>

namespace tessera {

/// Why `position`, `look_at` and `up` (scene units; up need not be unit length) make no
/// camera basis, or nullptr when they do. make_frame builds the basis from
/// forward = normalize(look_at - position) and right = cross(forward, up), so:
/// - look_at - position must have a finite, non-zero squared length;
/// - up's squared length must be finite;
/// - |right| must exceed 1e-6·|up|, i.e. up must be more than ~1e-6 rad from the view
///   direction. Below that, right is float round-off (one in 2^20 of up's length) and its
///   direction, which turns the image about the view, follows the last bits of the input.
inline const char* camera_view_problem(glm::vec3 position, glm::vec3 look_at, glm::vec3 up) {
    const glm::vec3 view = look_at - position;
    const float view2 = glm::dot(view, view);
    if (!std::isfinite(view2)) return "look_at - position overflows a float";
    if (view2 == 0.0f) return "look_at equals position";
    const float up2 = glm::dot(up, up);
    if (!std::isfinite(up2)) return "up's squared length overflows a float";
    const glm::vec3 right = glm::cross(view / std::sqrt(view2), up);
    if (!(glm::length(right) > 1e-6f * std::sqrt(up2))) return "up is zero or parallel to the view direction";
    return nullptr;
}

}  // namespace tessera
