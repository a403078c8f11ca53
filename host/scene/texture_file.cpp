#include "scene/texture_file.h"

#include <cstdint>
#include <cstring>
#include <memory>

#include <stb_image.h>  // the implementation lives in Debian's libstb

#include "scene/input_file.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {

namespace {

uint32_t big_endian32(const std::string& b, size_t at) {
    const auto u = [&](size_t i) { return uint32_t(static_cast<unsigned char>(b[at + i])); };
    return u(0) << 24 | u(1) << 16 | u(2) << 8 | u(3);
}

}  // namespace

void drop_empty_png_idat(std::string& bytes) {
    static constexpr char kSignature[] = "\x89PNG\r\n\x1a\n";
    constexpr size_t kSignatureBytes = 8, kChunkFrame = 12;  // length, type, CRC
    if (bytes.size() < kSignatureBytes || std::memcmp(bytes.data(), kSignature, kSignatureBytes) != 0) return;
    // One pass with a read and a write cursor, so a file of many empty chunks costs
    // linear time.
    size_t read = kSignatureBytes, write = kSignatureBytes;
    while (bytes.size() - read >= kChunkFrame) {
        const uint64_t frame = kChunkFrame + uint64_t(big_endian32(bytes, read));
        if (frame > bytes.size() - read) break;
        const bool empty_idat = frame == kChunkFrame && bytes.compare(read + 4, 4, "IDAT") == 0;
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

Texture load_texture(const std::filesystem::path& file) {
    std::string bytes = read_input_file(file, "texture", limits::kTextureFileBytes);
    if (bytes.size() > limits::kTextureFileBytes)  // grew after read_input_file's size check
        throw InputError(file.string() + ": texture of " + std::to_string(bytes.size()) + " bytes exceeds the limit of " +
                         std::to_string(limits::kTextureFileBytes) + " bytes");
    drop_empty_png_idat(bytes);
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = static_cast<int>(bytes.size());  // kTextureFileBytes fits an int
    int w = 0, h = 0, channels = 0;
    // The header's size first: a few bytes of PNG header can ask for gigabytes of pixels.
    if (stbi_info_from_memory(data, size, &w, &h, &channels))
        limits::check_image_size("texture", file.string(), w, h, 4);
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(data, size, &w, &h, &channels, 4),
                                                     stbi_image_free);
    if (!pixels)
        throw InputError(file.string() + ": texture is not a decodable image (stb_image: " + stbi_failure_reason() +
                         "; it reads PNG, JPEG, TGA, BMP, PSD, GIF, HDR, PIC and PNM)");
    Texture tex;
    tex.path = file;
    tex.width = w;
    tex.height = h;
    tex.rgba8.resize(static_cast<size_t>(w) * static_cast<size_t>(h));
    const stbi_uc* p = pixels.get();
    // Pack explicitly (R in the low byte) rather than memcpy, so the layout does not
    // depend on the host's byte order.
    for (auto& texel : tex.rgba8) {
        texel = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
        p += 4;
    }
    return tex;
}

}  // namespace tessera::scene_detail
