#include "scene/texture_file.h"

#include <memory>

#include <stb_image.h>  // the implementation lives in Debian's libstb

#include "scene/input_file.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {

Texture load_texture(const std::filesystem::path& file) {
    require_regular_file(file, "texture");
    int w = 0, h = 0, channels = 0;
    // The header's size first: a few bytes of PNG header can ask for gigabytes of pixels.
    if (stbi_info(file.string().c_str(), &w, &h, &channels))
        limits::check_image_size("texture", file.string(), w, h, 4);
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load(file.string().c_str(), &w, &h, &channels, 4), stbi_image_free);
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
