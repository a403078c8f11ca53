// Decoding one image file into a Texture (RGBA8, sRGB, row 0 = top).
#pragma once
#include <filesystem>

#include "scene/scene.h"

namespace tessera::scene_detail {

/// Decodes `file` with stb_image, forcing 4 channels (a grey or RGB image gets
/// A = 255). Throws InputError naming the file if it is missing, a directory, not a
/// regular file, or undecodable (with stb_image's reason).
Texture load_texture(const std::filesystem::path& file);

}  // namespace tessera::scene_detail
