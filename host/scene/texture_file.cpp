#include "scene/texture_file.h"

#include <cctype>
#include <cstdint>
#include <cstring>
#include <memory>

#include <stb_image.h>  // the implementation lives in Debian's libstb

#include "scene/input_file.h"
#include "scene/jpeg_decode.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {

namespace {

// A PNG: the 8-byte signature, then chunks framed by 12 bytes (length, type, CRC).
constexpr size_t kPngSignatureBytes = 8, kPngChunkFrame = 12;

uint32_t big_endian32(const std::string& b, size_t at) {
    const auto u = [&](size_t i) { return uint32_t(static_cast<unsigned char>(b[at + i])); };
    return u(0) << 24 | u(1) << 16 | u(2) << 8 | u(3);
}

}  // namespace

bool is_png(const std::string& bytes) {
    static constexpr char kSignature[] = "\x89PNG\r\n\x1a\n";
    return bytes.size() >= kPngSignatureBytes && std::memcmp(bytes.data(), kSignature, kPngSignatureBytes) == 0;
}

void drop_empty_png_idat(std::string& bytes) {
    if (!is_png(bytes)) return;
    // One pass with a read and a write cursor, so a file of many empty chunks costs
    // linear time.
    size_t read = kPngSignatureBytes, write = kPngSignatureBytes;
    while (bytes.size() - read >= kPngChunkFrame) {
        const uint64_t frame = kPngChunkFrame + uint64_t(big_endian32(bytes, read));
        if (frame > bytes.size() - read) break;
        const bool empty_idat = frame == kPngChunkFrame && bytes.compare(read + 4, 4, "IDAT") == 0;
        if (!empty_idat) {
            if (write != read) std::memmove(&bytes[write], &bytes[read], size_t(frame));
            write += size_t(frame);
        }
        read += size_t(frame);
    }
    // The tail that is not a whole chunk stays, for stb_image to report.
    if (write != read) {
        std::memmove(&bytes[write], &bytes[read], bytes.size() - read);
        bytes.resize(bytes.size() - (read - write));
    }
}

void check_png_chunks(const std::string& bytes, const std::string& file) {
    if (!is_png(bytes)) return;
    for (size_t at = kPngSignatureBytes; at < bytes.size();) {
        const size_t left = bytes.size() - at;
        const uint64_t length = left >= 4 ? big_endian32(bytes, at) : 0;
        if (left < kPngChunkFrame || kPngChunkFrame + length > left)
            throw InputError(file + ": texture is not a decodable PNG image (the chunk at byte " + std::to_string(at) +
                             (left < kPngChunkFrame ? " is cut off"
                                                    : " declares " + std::to_string(length) + " bytes") +
                             ", past the end of the file's " + std::to_string(bytes.size()) + " bytes)");
        if (bytes.compare(at + 4, 4, "IEND") == 0) return;  // what follows IEND is not read
        at += size_t(kPngChunkFrame + length);
    }
}

namespace {

// What a file that is neither PNG nor JPEG looks like, by its signature, for the message.
std::string format_hint(const std::string& b) {
    auto starts = [&](const char* magic, size_t n) { return b.size() >= n && b.compare(0, n, magic, n) == 0; };
    if (starts("GIF8", 4)) return "its first bytes are those of a GIF image";
    if (starts("BM", 2)) return "its first bytes are those of a BMP image";
    if (starts("8BPS", 4)) return "its first bytes are those of a PSD image";
    if (starts("#?RADIANCE", 10) || starts("#?RGBE", 6)) return "its first bytes are those of a Radiance HDR image";
    if (starts("\x76\x2f\x31\x01", 4)) return "its first bytes are those of an OpenEXR image";
    if (starts("II*\0", 4) || starts("MM\0*", 4)) return "its first bytes are those of a TIFF image";
    if (b.size() >= 3 && b[0] == 'P' && b[1] >= '1' && b[1] <= '7' && std::isspace(static_cast<unsigned char>(b[2])))
        return "its first bytes are those of a PNM image";
    return "its first bytes match neither signature; a TGA, which has none, is also not read";
}

// `w` x `h` RGBA8 pixels from `p` as tex's texels, packed explicitly (R in the low byte)
// rather than copied, so the layout does not depend on the host's byte order.
void pack_texels(const uint8_t* p, int w, int h, Texture& tex) {
    tex.width = w;
    tex.height = h;
    tex.rgba8.resize(size_t(w) * size_t(h));
    for (auto& texel : tex.rgba8) {
        texel = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
        p += 4;
    }
}

// Decodes a PNG with stb_image into tex, after check_png_chunks and dropping its empty
// IDAT chunks (drop_empty_png_idat); packs from stb's buffer, so a texture costs two copies at most.
void decode_png(std::string& bytes, const std::string& file, Texture& tex) {
    check_png_chunks(bytes, file);
    drop_empty_png_idat(bytes);
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = static_cast<int>(bytes.size());  // kTextureFileBytes fits an int
    int w = 0, h = 0, channels = 0;
    // The header's size first: a few bytes of PNG header can ask for gigabytes of pixels.
    if (stbi_info_from_memory(data, size, &w, &h, &channels)) limits::check_image_size("texture", file, w, h, 4);
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(data, size, &w, &h, &channels, 4),
                                                     stbi_image_free);
    if (!pixels)
        throw InputError(file + ": texture is not a decodable PNG image (stb_image: " + stbi_failure_reason() + ")");
    pack_texels(pixels.get(), w, h, tex);
}

}  // namespace

Texture load_texture(const std::filesystem::path& file) {
    std::string bytes = read_input_file(file, "texture", limits::kTextureFileBytes);
    if (bytes.size() > limits::kTextureFileBytes)  // grew after read_input_file's size check
        throw InputError(file.string() + ": texture of " + std::to_string(bytes.size()) + " bytes exceeds the limit of " +
                         std::to_string(limits::kTextureFileBytes) + " bytes");
    Texture tex;
    tex.path = file;
    if (is_png(bytes)) {
        decode_png(bytes, file.string(), tex);
    } else if (is_jpeg(bytes)) {
        const DecodedImage image = decode_jpeg(bytes, file.string());
        pack_texels(image.rgba.data(), image.width, image.height, tex);
    } else {
        throw InputError(file.string() + ": texture is not a PNG or JPEG image (" + format_hint(bytes) +
                         "); convert it to PNG");
    }
    return tex;
}

}  // namespace tessera::scene_detail
