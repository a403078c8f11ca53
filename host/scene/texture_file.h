// Decoding one image file into a Texture (RGBA8, sRGB, row 0 = top).
#pragma once
#include <filesystem>
#include <string>

#include "scene/scene.h"

namespace tessera::scene_detail {

/// Decodes a PNG (libpng, scene/png_decode.h) or JPEG (libjpeg-turbo, scene/jpeg_decode.h)
/// texture, told apart by their signatures, to 4 channels (a grey or RGB image gets
/// A = 255). The file is read whole (at most limits::kTextureFileBytes). Other formats are
/// refused, with what their signature looks like: each decoder here is one its upstream
/// fuzzes. Throws InputError naming the file if it is missing, a directory, not a regular
/// file, too large, neither PNG nor JPEG, or undecodable (with the decoder's reason).
Texture load_texture(const std::filesystem::path& file);

}  // namespace tessera::scene_detail
