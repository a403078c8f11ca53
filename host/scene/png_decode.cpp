#include "scene/png_decode.h"

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <png.h>

#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {
namespace {

// The file's bytes, whole in memory, and how far libpng has read them.
struct Source {
    const unsigned char* data;
    size_t size;
    size_t at;
};

// libpng reports an error by calling keep_and_jump, which must not return: it keeps the
// message and jumps back to the setjmp of the step that called libpng (read_header or
// read_rows below, which hold no C++ object whose destructor the jump would skip).
struct PngErrors {
    char message[256];
};

extern "C" void keep_and_jump(png_structp png, png_const_charp message) {
    auto* e = static_cast<PngErrors*>(png_get_error_ptr(png));
    std::snprintf(e->message, sizeof e->message, "%s", message);
    png_longjmp(png, 1);
}

// Warnings leave a decodable image: an ancillary chunk with a bad CRC or an odd colour
// profile is skipped, and stb_image, whose texels these are, reads no ancillary chunk but
// tRNS anyway.
extern "C" void ignore_warning(png_structp, png_const_charp) {}

extern "C" void read_from_source(png_structp png, png_bytep out, png_size_t n) {
    auto* s = static_cast<Source*>(png_get_io_ptr(png));
    if (n > s->size - s->at) {
        char why[96];
        std::snprintf(why, sizeof why, "the file ends at byte %zu, before the image does", s->size);
        png_error(png, why);
    }
    std::memcpy(out, s->data + s->at, n);
    s->at += n;
}

struct Decoder {
    PngErrors errors{};
    Source source;
    png_structp png = nullptr;
    png_infop info = nullptr;

    explicit Decoder(const std::string& bytes)
        : source{reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), 0} {
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &errors, keep_and_jump, ignore_warning);
        if (png) info = png_create_info_struct(png);
    }
    ~Decoder() { png_destroy_read_struct(&png, &info, nullptr); }  // takes null pointers
    Decoder(const Decoder&) = delete;
    Decoder& operator=(const Decoder&) = delete;
};

// Reads the signature and the chunks up to the first IDAT; false with d.errors.message
// set on a libpng error. Every ancillary chunk but tRNS is skipped unread, as stb_image
// did: libpng would keep each text chunk's text, and a zTXt chunk of 8 kB inflates to the
// 8 MB it allows a chunk, in up to 1,000 chunks.
bool read_header(Decoder& d) {
    if (setjmp(png_jmpbuf(d.png))) return false;
    png_set_read_fn(d.png, &d.source, read_from_source);
    png_set_keep_unknown_chunks(d.png, PNG_HANDLE_CHUNK_NEVER, nullptr, -1);
    png_read_info(d.png, d.info);
    return true;
}

// The tRNS colour of a grey or RGB image whose samples do not fit the bit depth (the PNG
// spec, 11.3.2.1, forbids it): libpng would mask it to the depth and make the pixels of
// the masked value transparent, stb_image none. "" when there is none or it fits.
std::string trns_out_of_range(png_structp png, png_infop info) {
    png_color_16p colour = nullptr;
    if (!png_get_tRNS(png, info, nullptr, nullptr, &colour) || !colour) return "";
    const int type = png_get_color_type(png, info), depth = png_get_bit_depth(png, info);
    if (type == PNG_COLOR_TYPE_PALETTE || depth == 16) return "";
    const unsigned max = (1u << depth) - 1;
    const bool grey = type == PNG_COLOR_TYPE_GRAY;
    if (grey ? colour->gray <= max : colour->red <= max && colour->green <= max && colour->blue <= max) return "";
    const std::string value = grey ? std::to_string(colour->gray)
                                   : std::to_string(colour->red) + ", " + std::to_string(colour->green) + ", " +
                                         std::to_string(colour->blue);
    return "its tRNS colour (" + value + ") does not fit its " + std::to_string(depth) + "-bit samples";
}

// Decodes every row, as RGBA8, into `rows` (height pointers to row_bytes each, allocated
// by the caller). The chunks after the image data are not read: nothing in them is used.
bool read_rows(Decoder& d, png_bytepp rows, size_t row_bytes) {
    if (setjmp(png_jmpbuf(d.png))) return false;
    png_set_expand(d.png);       // palette -> RGB, grey of 1/2/4 bits -> 8, tRNS -> alpha
    png_set_strip_16(d.png);     // 16-bit samples -> their high byte, as stb_image
    png_set_gray_to_rgb(d.png);
    png_set_add_alpha(d.png, 0xFF, PNG_FILLER_AFTER);  // only where there is no alpha
    png_set_interlace_handling(d.png);
    png_read_update_info(d.png, d.info);
    if (png_get_rowbytes(d.png, d.info) != row_bytes) png_error(d.png, "rows are not RGBA8 after expansion");
    png_read_image(d.png, rows);
    return true;
}

}  // namespace

bool is_png(const std::string& bytes) {
    static constexpr char kSignature[] = "\x89PNG\r\n\x1a\n";
    return bytes.size() >= 8 && std::memcmp(bytes.data(), kSignature, 8) == 0;
}

DecodedImage decode_png(const std::string& bytes, const std::string& file) {
    Decoder d(bytes);
    auto fail = [&](const std::string& why) {
        return InputError(file + ": texture is not a decodable PNG image (libpng: " + why + ")");
    };
    if (!d.png || !d.info) throw fail("out of memory creating the reader");
    if (!read_header(d)) throw fail(d.errors.message);
    if (const std::string why = trns_out_of_range(d.png, d.info); !why.empty())
        throw InputError(file + ": texture is not a valid PNG image (" + why + ")");
    const png_uint_32 width = png_get_image_width(d.png, d.info), height = png_get_image_height(d.png, d.info);
    limits::check_image_size("texture", file, width, height, 4);
    DecodedImage image;
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    const size_t row_bytes = size_t(width) * 4;
    image.rgba.resize(row_bytes * height);
    std::vector<png_bytep> rows(height);
    for (size_t y = 0; y < rows.size(); ++y) rows[y] = image.rgba.data() + y * row_bytes;
    if (!read_rows(d, rows.data(), row_bytes)) throw fail(d.errors.message);
    return image;
}

}  // namespace tessera::scene_detail
