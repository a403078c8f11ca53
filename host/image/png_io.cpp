// 8-bit sRGB PNG preview of the R, G, B channels, and 8-bit RGBA captures, encoded by libpng.
#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "image/atomic_file.h"
#include "image/image_check.h"
#include "image/image_io.h"
#include "image/srgb8.h"
#include "util/error.h"

namespace tessera {
namespace {

// libpng reports an error by calling preview_error, which keeps the message and jumps
// back to encode_rgb8's setjmp; encode_rgb8 holds no C++ object the jump would skip.
extern "C" void preview_error(png_structp png, png_const_charp message) {
    std::snprintf(static_cast<char*>(png_get_error_ptr(png)), 256, "%s", message);
    png_longjmp(png, 1);
}

extern "C" void preview_warning(png_structp, png_const_charp) {}

extern "C" void preview_append(png_structp png, png_bytep data, png_size_t n) {
    auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
    bool grown = true;
    try {
        out->insert(out->end(), data, data + n);
    } catch (const std::bad_alloc&) {  // no exception may cross libpng's C frames
        grown = false;
    }
    if (!grown) png_error(png, "out of memory");  // jumps: not from inside the handler
}

extern "C" void preview_flush(png_structp) {}

// 8-bit rows of `channels` samples a pixel (3: RGB, 4: RGBA), top first, to PNG bytes
// appended to `out`; false with libpng's message in `message` (256 bytes) on failure.
// zlib level 3 with libpng's per-row filter choice: a 512² preview in 37-51 ms where
// stb_image_write took 79-138 (sRGB encoding included), its files ~20% smaller
// (bench/results/frame_output.md); a sequence writes one a frame.
bool encode_8bit(const std::uint8_t* pixels, int width, int height, int channels, std::vector<unsigned char>& out,
                 char* message) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, message, preview_error, preview_warning);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, &out, preview_append, preview_flush);
    png_set_compression_level(png, 3);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8,
                 channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);  // the bytes are sRGB-encoded
    png_write_info(png, info);
    for (int y = 0; y < height; ++y) png_write_row(png, pixels + size_t(y) * size_t(width) * size_t(channels));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
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
    // The exact curve's codes without a pow per value (image/srgb8.h): 2-3 ms at 512², not 25.
    for (int c = 0; c < 3; ++c) srgb8_encode(rgb[c]->data.data(), pixels, scale, pixels8.data() + c, 3);

    std::vector<unsigned char> encoded;
    char message[256] = "";
    if (!encode_8bit(pixels8.data(), image.width, image.height, 3, encoded, message))
        throw RuntimeError("cannot write '" + path.string() + "': PNG encoding failed: " + message);
    write_file_atomic(path, encoded.data(), encoded.size());
}

void write_png_rgba8(const std::filesystem::path& path, const std::uint8_t* rgba, int width, int height) {
    if (width <= 0 || height <= 0 || !rgba)
        throw RuntimeError("cannot write '" + path.string() + "': an empty " + std::to_string(width) + "x" +
                           std::to_string(height) + " image");
    std::vector<unsigned char> encoded;
    char message[256] = "";
    if (!encode_8bit(rgba, width, height, 4, encoded, message))
        throw RuntimeError("cannot write '" + path.string() + "': PNG encoding failed: " + message);
    write_file_atomic(path, encoded.data(), encoded.size());
}

}  // namespace tessera
