// Whether a file of the shared data path (../shared/scenes, $TESSERA_DATA) is present,
// for tests that skip where a data scene is absent. They skip on the file's absence
// alone, never on a load error, so a broken scene or loader still fails them.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "scene/loader.h"

namespace tessera::test {

/// True when `relative` (e.g. "sibenik/sibenik.obj") exists under a root of `data`.
inline bool on_data_path(const DataPath& data, const std::string& relative) {
    for (const auto& r : data.roots)
        if (std::filesystem::exists(r / relative)) return true;
    return false;
}

/// on_data_path on the default data path (make_data_path without --data-dir).
inline bool on_data_path(const std::string& relative) {
    return on_data_path(make_data_path(std::nullopt), relative);
}

}  // namespace tessera::test
