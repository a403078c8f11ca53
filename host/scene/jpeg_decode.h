// Decoding a JPEG texture with libjpeg-turbo (Debian's libjpeg62-turbo), the well-kept,
// continuously fuzzed decoder, rather than stb_image's, whose Huffman table builder in
// Debian 12's stb_image 2.27 writes past its array on a crafted file (found by
// scripts/fuzz in minutes).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace tessera::scene_detail {

/// Whether `bytes` start with a JPEG's SOI marker and the next marker's 0xFF.
bool is_jpeg(const std::string& bytes);

/// An RGBA8 image: `rgba` holds width × height × 4 bytes, row 0 = the image's top row.
struct DecodedImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

/// Decodes the JPEG in `bytes` (baseline or progressive; grey, YCbCr or RGB) to RGBA8 with
/// A = 255. Throws InputError "<file>: texture ..." naming the reason: libjpeg's message for
/// a corrupt or truncated file (a premature end of data is an error, not grey rows),
/// CMYK or YCCK colour, more than kMaxScans progressive scans, or a size over the limits
/// of util/input_limits.h, checked from the header before any pixel is decoded.
DecodedImage decode_jpeg(const std::string& bytes, const std::string& file);

}  // namespace tessera::scene_detail
