// Decoding one image file into a Texture (RGBA8, sRGB, row 0 = top).
#pragma once
#include <filesystem>
#include <string>

#include "scene/scene.h"

namespace tessera::scene_detail {

/// Decodes a PNG (stb_image, after drop_empty_png_idat()) or JPEG (libjpeg-turbo,
/// scene/jpeg_decode.h) texture, told apart by their signatures, to 4 channels (a grey or
/// RGB image gets A = 255). The file is read whole (at most limits::kTextureFileBytes).
/// Other formats are refused: stb_image 2.27 reads more, but its JPEG decoder writes out
/// of bounds on a crafted file, and its other decoders had no fuzzing here. Throws
/// InputError naming the file if it is missing, a directory, not a regular file, too
/// large, neither PNG nor JPEG (with what its signature looks like), or undecodable (with
/// the decoder's reason).
Texture load_texture(const std::filesystem::path& file);

/// Throws InputError "<file>: texture is not a decodable PNG image (the chunk at byte N
/// ...)" when a chunk of the PNG in `bytes`, up to IEND, is cut off or declares more bytes
/// than the file has left. stb_image 2.27 grows its IDAT buffer to a chunk's declared
/// length before reading it, so a file of a few bytes could make it allocate 2 GB
/// (found by scripts/fuzz). Bytes that are not a PNG are left to the caller.
void check_png_chunks(const std::string& bytes, const std::string& file);

/// Whether `bytes` start with the 8-byte PNG signature.
bool is_png(const std::string& bytes);

/// Removes every zero-length IDAT chunk (12 bytes: length 0, type, CRC) from the PNG in
/// `bytes`, in place, leaving all other bytes in order. The image data stream is the
/// concatenation of the IDAT chunks' data (PNG spec, 11.2.4), so the decoded image is the
/// same; the reason is stb_image 2.27 (Debian 12), which on a leading empty IDAT copies
/// zero bytes to a null buffer, undefined behaviour its fuzzing found. Bytes that are not
/// a PNG, and whatever follows a chunk that runs past the end, are left as they are for
/// the decoder to judge.
void drop_empty_png_idat(std::string& bytes);

}  // namespace tessera::scene_detail
