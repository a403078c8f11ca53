// Camera paths (--camera-path): a fly-through recorded by the viewer, one camera per
// displayed frame, replayed by the window or headless (`tessera view --headless`).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace tessera::view {

/// One frame of a path: the camera (its resolution is unused; the viewer's is kept) and
/// the animation frame shown (0 for a static scene).
struct PathFrame {
    Camera camera;
    int frame = 0;
};

/// Reads {"scene": NAME (optional), "cameras": [{"position": [x,y,z], "look_at": [x,y,z],
/// "up": [x,y,z], "vfov": deg, "frame": F (optional, default 0)}, ...]} (scene units and
/// degrees). NAME is the scene's "name" the path was recorded on, returned in `*scene`
/// ("" when absent) so that a path replayed on another scene can be said. Consecutive equal
/// cameras are a camera at rest: the viewer accumulates passes there. The whole file is
/// checked before it is returned, so nothing renders from a path that fails later.
/// Throws InputError "--camera-path <file>: key 'cameras[2].up' = [0,1,0]: <why>" for a
/// missing, misspelt or unknown key, a value that is not finite or out of range (vfov in
/// (0, 180), frame in 0..limits::kViewFrames-1), a camera whose view is degenerate (up zero
/// or parallel to the view, look_at equal to position), an empty list or more than
/// limits::kPathEntries cameras, and for the file errors of scene_detail::parse_json_file.
std::vector<PathFrame> read_camera_path(const std::filesystem::path& path, std::string* scene = nullptr);

/// Writes `frames` in the format read_camera_path reads (numbers with 9 significant
/// digits, so reading gives the same floats), with `scene` as its "scene" key (none when
/// empty), atomically. Throws RuntimeError naming the file when it cannot be written.
void write_camera_path(const std::filesystem::path& path, const std::vector<PathFrame>& frames,
                       const std::string& scene = "");

}  // namespace tessera::view
