// First-person camera controls of the viewer as pure functions of the camera and the
// input: no window, no clock (the caller passes the distance or the angles), so tests
// can drive them exactly. The camera is the scene's pinhole Camera (scene/scene.h):
// moving shifts position and look_at together (the look distance is kept), turning
// rotates the view direction about the camera's up vector (yaw) and its right vector
// (pitch).
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace tessera::view {

/// Moves `camera` by `distance` scene units along `axes` in its own frame: x to the
/// right, y along camera.up, z forward (the view direction); `axes` need not be unit
/// (W and D held: (1, 0, 1) moves √2·distance). look_at moves with the position.
Camera move_camera(const Camera& camera, glm::vec3 axes, float distance);

/// Turns `camera` by `yaw` radians about camera.up (positive: to the left, as a mouse
/// drag to the right turns right with yaw < 0) and by `pitch` radians up. The pitch is
/// limited so that the view direction stays at least 1° from ±up (make_frame needs them
/// not parallel). The look distance |look_at − position| is kept.
Camera turn_camera(const Camera& camera, float yaw, float pitch);

/// True when the two cameras give different frames (position, look_at, up or vfov differ).
bool camera_differs(const Camera& a, const Camera& b);

/// The camera as the "camera" block of a scene file (scenes/README.md), numbers with 9
/// significant digits so that reading it back gives the same floats:
/// {"position": [...], "look_at": [...], "up": [...], "vfov": ..., "resolution": [w, h]}.
std::string camera_json(const Camera& camera);

/// A default movement speed for a scene: a tenth of its bounding-box diagonal per
/// second, so that crossing the scene takes about ten seconds at any scale (a quarter
/// took Sibenik's 40-unit nave in 3 s, too fast to look at anything; scroll speeds up).
float default_speed(const Scene& scene);

}  // namespace tessera::view
