#include "scene/texture_file.h"

#include <cctype>
#include <cstdint>

#include "scene/input_file.h"
#include "scene/jpeg_decode.h"
#include "scene/png_decode.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {

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

}  // namespace

Texture load_texture(const std::filesystem::path& file) {
    const std::string bytes = read_input_file(file, "texture", limits::kTextureFileBytes);
    if (bytes.size() > limits::kTextureFileBytes)  // grew after read_input_file's size check
        throw InputError(file.string() + ": texture of " + std::to_string(bytes.size()) + " bytes exceeds the limit of " +
                         std::to_string(limits::kTextureFileBytes) + " bytes");
    Texture tex;
    tex.path = file;
    DecodedImage image;
    if (is_png(bytes))
        image = decode_png(bytes, file.string());
    else if (is_jpeg(bytes))
        image = decode_jpeg(bytes, file.string());
    else
        throw InputError(file.string() + ": texture is not a PNG or JPEG image (" + format_hint(bytes) +
                         "); convert it to PNG");
    pack_texels(image.rgba.data(), image.width, image.height, tex);
    return tex;
}

}  // namespace tessera::scene_detail
