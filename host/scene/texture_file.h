// Decoding one image file into a Texture (RGBA8, sRGB, row 0 = top).
#pragma once
#include <filesystem>
#include <string>

#include "scene/scene.h"

namespace tessera::scene_detail {

/// Decodes `file` with stb_image, forcing 4 channels (a grey or RGB image gets
/// A = 255). The file is read whole (at most limits::kTextureFileBytes) and, if it is a
/// PNG, passed through drop_empty_png_idat() first. Throws InputError naming the file if
/// it is missing, a directory, not a regular file, too large, or undecodable (with
/// stb_image's reason).
Texture load_texture(const std::filesystem::path& file);

/// Removes every zero-length IDAT chunk (12 bytes: length 0, type, CRC) from the PNG in
/// `bytes`, in place, leaving all other bytes in order. The image data stream is the
/// concatenation of the IDAT chunks' data (PNG spec, 11.2.4), so the decoded image is the
/// same; the reason is stb_image 2.27 (Debian 12), which on a leading empty IDAT copies
/// zero bytes to a null buffer, undefined behaviour its fuzzing found. Bytes that are not
/// a PNG, and whatever follows a chunk that runs past the end, are left as they are for
/// the decoder to judge.
void drop_empty_png_idat(std::string& bytes);

}  // namespace tessera::scene_detail
