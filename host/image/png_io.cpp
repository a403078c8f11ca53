// 8-bit sRGB PNG preview of the R, G, B channels (stb_image_write, linked from libstb).
#include <stb_image_write.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "image/atomic_file.h"
#include "image/image_check.h"
#include "image/image_io.h"
#include "util/error.h"

namespace tessera {
namespace {

/// Linear value (already exposed) to an 8-bit sRGB code: clamp, exact OETF, round.
std::uint8_t encode_srgb(double v) {
    if (!(v > 0.0)) return 0;  // also NaN
    if (v >= 1.0) return 255;
    const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(e * 255.0));
}

void append(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

void write_png(const std::filesystem::path& path, const Image& image, float exposure) {
    detail::check_image(path, image);
    const ImageChannel* rgb[3] = {image.find("R"), image.find("G"), image.find("B")};
    for (int c = 0; c < 3; ++c)
        if (!rgb[c])
            throw RuntimeError("cannot write '" + path.string() + "': image has no '" +
                               std::string(1, "RGB"[c]) + "' channel for the PNG preview");
    if (!std::isfinite(exposure))
        throw RuntimeError("cannot write '" + path.string() + "': exposure is not finite");

    const double scale = std::exp2(static_cast<double>(exposure));
    const std::size_t pixels =
        static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    std::vector<std::uint8_t> pixels8(pixels * 3);
    for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c)
            pixels8[i * 3 + c] = encode_srgb(static_cast<double>(rgb[c]->data[i]) * scale);

    std::vector<unsigned char> encoded;
    if (!stbi_write_png_to_func(append, &encoded, image.width, image.height, 3,
                                pixels8.data(), image.width * 3))
        throw RuntimeError("cannot write '" + path.string() + "': PNG encoding failed");
    write_file_atomic(path, encoded.data(), encoded.size());
}

}  // namespace tessera
