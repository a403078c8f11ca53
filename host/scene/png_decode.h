// Decoding a PNG texture with libpng (Debian's libpng16), the reference decoder, fuzzed
// continuously upstream, rather than stb_image's: Debian 12's stb_image 2.27 needed two
// workarounds here (it grew its buffer to a chunk's declared length before reading it, and
// copied to a null buffer on an empty IDAT chunk; both found by scripts/fuzz).
#pragma once
#include <string>

#include "scene/jpeg_decode.h"  // DecodedImage

namespace tessera::scene_detail {

/// Whether `bytes` start with the 8-byte PNG signature.
bool is_png(const std::string& bytes);

/// Decodes the PNG in `bytes` (any colour type, bit depth 1–16, interlaced or not) to
/// RGBA8, texel for texel what stb_image gives: palette and tRNS expanded to RGBA, grey
/// replicated to RGB, 1/2/4-bit samples scaled to 0–255, 16-bit samples cut to their high
/// byte, A = 255 where the image has no alpha, and no gamma or colour-profile conversion
/// (gAMA, sRGB, iCCP and every other ancillary chunk but tRNS are skipped unread). Throws
/// InputError "<file>: texture is not a decodable PNG image (libpng: <reason>)" for a
/// corrupt, truncated or CRC-damaged file, "<file>: texture is not a valid PNG image
/// (...)" for a tRNS colour outside the bit depth (which stb_image and libpng would read
/// differently), or a size over the limits of util/input_limits.h, checked from the header
/// before any pixel is decoded.
DecodedImage decode_png(const std::string& bytes, const std::string& file);

}  // namespace tessera::scene_detail
