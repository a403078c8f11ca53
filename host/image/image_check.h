// Internal to host/image: validation shared by the writers.
#pragma once
#include <filesystem>

#include "image/image_io.h"

namespace tessera::detail {

/// Throws RuntimeError naming `path` unless `image` has a positive size, at least one
/// channel, unique non-empty channel names and width*height values in every channel.
/// Called before any file is created, so an invalid image never touches the target.
void check_image(const std::filesystem::path& path, const Image& image);

}  // namespace tessera::detail
