// Scene loading: a JSON scene file naming OBJ/MTL meshes, transforms, the camera and
// optional light and material overrides. The JSON format is documented in
// scenes/README.md.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace tessera {

/// Where files the project does not ship are looked up. A relative path in a scene
/// file is tried, in order: next to the scene file, in each `roots` entry.
/// `roots` is built by make_data_path(): --data-dir (if given), then $TESSERA_DATA
/// (if set), then the default data directory, the `shared/scenes` folder beside the
/// source checkout
/// (TESSERA_DEFAULT_DATA_DIR, set at configure time).
struct DataPath {
    std::vector<std::filesystem::path> roots;

    /// Resolves `rel` (a path written in `scene_file`). Throws InputError naming
    /// `rel`, `scene_file` and every directory tried when nothing exists.
    std::filesystem::path resolve(const std::string& rel,
                                  const std::filesystem::path& scene_file) const;
};

/// The file `p` names, as one path for all its spellings ("a.obj", "./a.obj", a link
/// to it): absolute, symbolic links resolved as far as they exist, normalised. For
/// comparing files (meshes loaded once, outputs against inputs, checkpoint scenes).
std::filesystem::path same_file(const std::filesystem::path& p);

/// Builds the data path from the --data-dir option (may be empty) and the environment.
DataPath make_data_path(const std::optional<std::filesystem::path>& data_dir);

/// Loads a scene file. Throws InputError (naming the file, and the line or JSON key
/// where known) for: a missing or unreadable file, malformed JSON, a missing required
/// key, an OBJ that fails to parse or has out-of-range indices or non-finite vertices,
/// a missing MTL or texture, and a scene with no emitter (no MTL Ke and no JSON light).
Scene load_scene(const std::filesystem::path& scene_file, const DataPath& data);

/// Path of the built-in default scene, `scenes/cornell-box.json`, looked up beside the
/// executable's source tree (TESSERA_SCENES_DIR, set at configure time).
std::filesystem::path default_scene_path();

}  // namespace tessera
