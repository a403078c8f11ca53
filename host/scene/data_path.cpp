// DataPath lookup and the default scene location (declared in scene/loader.h).
#include <cstdlib>
#include <system_error>

#include "scene/input_file.h"
#include "scene/loader.h"
#include "util/error.h"

namespace tessera {

namespace fs = std::filesystem;

fs::path DataPath::resolve(const std::string& rel, const fs::path& scene_file) const {
    std::error_code ec;
    const fs::path p(rel);
    if (p.is_absolute()) {
        if (fs::exists(p, ec)) scene_detail::require_regular_file(p, "file named by " + scene_file.string());
        if (fs::is_regular_file(p, ec)) return p;
        throw InputError(scene_file.string() + ": file '" + rel + "' not found");
    }
    // Scene directory first, so a scene and its meshes can travel together; then the
    // data roots in priority order.
    std::vector<fs::path> dirs;
    dirs.push_back(scene_file.parent_path().empty() ? fs::path(".") : scene_file.parent_path());
    dirs.insert(dirs.end(), roots.begin(), roots.end());
    std::string tried;
    for (const auto& dir : dirs) {
        const fs::path candidate = dir / p;
        // A directory (or other non-file) of that name is an error, not a miss: going on
        // to the next directory would hide the user's mistake.
        if (fs::exists(candidate, ec)) scene_detail::require_regular_file(candidate, "file named by " + scene_file.string());
        if (fs::is_regular_file(candidate, ec)) return candidate;
        tried += (tried.empty() ? "" : ", ") + dir.string();
    }
    throw InputError(scene_file.string() + ": file '" + rel +
                     "' not found; directories tried: " + tried);
}

fs::path same_file(const fs::path& p) {
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(fs::absolute(p), ec);
    return ec ? fs::absolute(p).lexically_normal() : c;
}

DataPath make_data_path(const std::optional<fs::path>& data_dir) {
    DataPath data;
    if (data_dir && !data_dir->empty()) {
        std::error_code ec;
        if (!fs::is_directory(*data_dir, ec))
            throw InputError("--data-dir '" + data_dir->string() +
                             "' does not exist or is not a directory");
        data.roots.push_back(*data_dir);
    }
    if (const char* env = std::getenv("TESSERA_DATA"); env && *env) data.roots.emplace_back(env);
    data.roots.emplace_back(TESSERA_DEFAULT_DATA_DIR);
    return data;
}

fs::path default_scene_path() { return fs::path(TESSERA_SCENES_DIR) / "cornell-box.json"; }

}  // namespace tessera
