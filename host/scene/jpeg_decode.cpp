#include "scene/jpeg_decode.h"

#include <csetjmp>
#include <cstdio>  // jpeglib.h uses FILE

#include <jpeglib.h>
#include <jerror.h>  // JWRN_JPEG_EOF

#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {
namespace {

/// Progressive scans decoded at most: a real progressive JPEG has about 10, while a crafted
/// one of a few kB can hold thousands, each a pass over the whole coefficient buffer (the
/// decompression bomb libjpeg-turbo's own fuzzers bound at 500 scans).
constexpr int kMaxScans = 500;

// libjpeg reports an error by calling error_exit, which must not return: it jumps back
// to the setjmp of the step that called libjpeg (one of the C-style functions below,
// which hold no C++ object whose destructor the jump would skip).
struct JpegErrors {
    jpeg_error_mgr mgr;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

extern "C" void jump_on_error(j_common_ptr c) {
    auto* e = reinterpret_cast<JpegErrors*>(c->err);
    (*c->err->format_message)(c, e->message);
    std::longjmp(e->jump, 1);
}

// Warnings (level -1) let libjpeg go on with made-up data; a premature end of the data
// would decode as grey rows, so it is an error. Trace messages (level >= 0) are dropped.
extern "C" void error_on_truncation(j_common_ptr c, int level) {
    if (level < 0 && c->err->msg_code == JWRN_JPEG_EOF) jump_on_error(c);
}

extern "C" void limit_scans(j_common_ptr c) {
    auto* d = reinterpret_cast<j_decompress_ptr>(c);
    if (d->input_scan_number <= kMaxScans) return;
    auto* e = reinterpret_cast<JpegErrors*>(c->err);
    std::snprintf(e->message, sizeof e->message, "more than %d progressive scans", kMaxScans);
    std::longjmp(e->jump, 1);
}

struct Decoder {
    jpeg_decompress_struct info{};
    JpegErrors errors{};
    jpeg_progress_mgr progress{};
    bool created = false;

    Decoder() {
        info.err = jpeg_std_error(&errors.mgr);
        errors.mgr.error_exit = jump_on_error;
        errors.mgr.emit_message = error_on_truncation;
        progress.progress_monitor = limit_scans;
    }
    ~Decoder() {
        if (created) jpeg_destroy_decompress(&info);
    }
    Decoder(const Decoder&) = delete;
    Decoder& operator=(const Decoder&) = delete;
};

// Creates the decompressor and reads the header from memory; false with d.errors.message
// set on a libjpeg error.
bool read_header(Decoder& d, const std::string& bytes) {
    if (setjmp(d.errors.jump)) return false;
    jpeg_create_decompress(&d.info);
    d.created = true;
    d.info.progress = &d.progress;
    jpeg_mem_src(&d.info, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&d.info, TRUE);
    return true;
}

// Decodes every row into `out` (width × height × 4 bytes, allocated by the caller).
bool read_rows(Decoder& d, uint8_t* out) {
    if (setjmp(d.errors.jump)) return false;
    d.info.out_color_space = JCS_EXT_RGBA;
    jpeg_start_decompress(&d.info);
    while (d.info.output_scanline < d.info.output_height) {
        JSAMPROW row = out + size_t(d.info.output_scanline) * size_t(d.info.output_width) * 4;
        jpeg_read_scanlines(&d.info, &row, 1);
    }
    jpeg_finish_decompress(&d.info);
    return true;
}

}  // namespace

bool is_jpeg(const std::string& bytes) {
    return bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xFF &&
           static_cast<unsigned char>(bytes[1]) == 0xD8 && static_cast<unsigned char>(bytes[2]) == 0xFF;
}

DecodedImage decode_jpeg(const std::string& bytes, const std::string& file) {
    Decoder d;
    auto fail = [&](const std::string& why) {
        return InputError(file + ": texture is not a decodable JPEG image (libjpeg: " + why + ")");
    };
    if (!read_header(d, bytes)) throw fail(d.errors.message);
    if (d.info.jpeg_color_space == JCS_CMYK || d.info.jpeg_color_space == JCS_YCCK)
        throw InputError(file + ": texture is a CMYK JPEG image; Tessera reads grey, YCbCr and RGB JPEG textures: "
                                "convert it to RGB");
    limits::check_image_size("texture", file, d.info.image_width, d.info.image_height, 4);
    DecodedImage image;
    image.width = static_cast<int>(d.info.image_width);
    image.height = static_cast<int>(d.info.image_height);
    image.rgba.resize(size_t(image.width) * size_t(image.height) * 4);
    if (!read_rows(d, image.rgba.data())) throw fail(d.errors.message);
    return image;
}

}  // namespace tessera::scene_detail
