// Camera paths (--camera-path): a fly-through recorded by the viewer, one camera per
// displayed frame, replayed by the window or headless (`tessera view --headless`).
#pragma once
#include <filesystem>
#include <vector>

#include "scene/scene.h"

namespace tessera::view {

/// One frame of a path: the camera (its resolution is unused; the viewer's is kept) and
/// the animation frame shown (0 for a static scene).
struct PathFrame {
    Camera camera;
    int frame = 0;
};

/// Reads {"cameras": [{"position": [x,y,z], "look_at": [x,y,z], "up": [x,y,z], "vfov": deg,
/// "frame": F (optional, default 0)}, ...]}. Consecutive equal cameras are a camera at
/// rest: the viewer accumulates passes there. Throws InputError naming the file and entry
/// when a field is missing or not finite, or the list is empty.
std::vector<PathFrame> read_camera_path(const std::filesystem::path& path);

/// Writes `frames` in the format read_camera_path reads (numbers with 9 significant
/// digits, so reading gives the same floats), atomically. Throws RuntimeError naming the
/// file when it cannot be written.
void write_camera_path(const std::filesystem::path& path, const std::vector<PathFrame>& frames);

}  // namespace tessera::view
