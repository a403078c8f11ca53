// PNG textures through libpng (host/scene/png_decode.cpp): every colour type and bit depth,
// interlaced or not, with and without tRNS, decodes texel for texel as stb_image (which
// decoded them before, and still decodes the PNGs in tests/image); damaged files are
// refused with libpng's reason, and what stb_image needed workarounds for decodes.
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <sys/resource.h>

#include <png.h>
#include <stb_image.h>
#include <zlib.h>

#include "scene/png_decode.h"
#include "scene/scene_test_util.h"
#include "util/error.h"

namespace tessera {
namespace {

using scene_detail::DecodedImage;

/// What an encoded test image is: its IHDR colour type and bit depth, Adam7 or not, and
/// whether it carries a tRNS chunk (palette alphas, or one transparent grey/RGB value).
struct Variant {
    int colour_type, bit_depth;
    bool interlaced, trns;
};

void append_to(png_structp png, png_bytep data, png_size_t n) {
    static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), n);
}
void no_flush(png_structp) {}

// Raw rows in the file's own sample layout. Pixels of 8 bits or more are drawn from four
// random prototypes, so a tRNS value equal to the first pixel's marks about a quarter of them.
std::vector<std::vector<png_byte>> raw_rows(const Variant& v, int w, int h, std::mt19937& rng, int channels) {
    const int bits = channels * v.bit_depth, row_bytes = (w * bits + 7) / 8;
    std::vector<std::vector<png_byte>> rows(size_t(h), std::vector<png_byte>(static_cast<size_t>(row_bytes)));
    if (bits < 8) {
        for (auto& row : rows)
            for (auto& b : row) b = png_byte(rng());
        return rows;
    }
    std::vector<std::vector<png_byte>> prototypes(4, std::vector<png_byte>(static_cast<size_t>(bits / 8)));
    for (auto& p : prototypes)
        for (auto& b : p) b = png_byte(rng());
    for (auto& row : rows)
        for (int x = 0; x < w; ++x) {
            const auto& p = prototypes[rng() % 4];
            std::copy(p.begin(), p.end(), row.begin() + x * (bits / 8));
        }
    return rows;
}

/// What write_png needs, prepared by the caller, so that the function holding the setjmp
/// owns no C++ object a longjmp could leave behind.
struct Encoding {
    Variant v;
    int w, h;
    png_bytepp rows;
    png_colorp palette;
    int palette_size;
    png_bytep alphas;
    png_color_16p transparent;
};

// Appends the PNG of `e` to `out`; false on a libpng error (its default handler prints why).
bool write_png(const Encoding& e, std::string& out) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, &out, append_to, no_flush);
    png_set_IHDR(png, info, png_uint_32(e.w), png_uint_32(e.h), e.v.bit_depth, e.v.colour_type,
                 e.v.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_gAMA(png, info, 1.0);
    const bool palette = e.v.colour_type == PNG_COLOR_TYPE_PALETTE;
    if (palette) png_set_PLTE(png, info, e.palette, e.palette_size);
    if (e.v.trns) png_set_tRNS(png, info, e.alphas, palette ? e.palette_size : 0, e.transparent);
    png_write_info(png, info);
    png_write_image(png, e.rows);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

/// Encodes a w×h image of `v` with pseudo-random samples (libpng's writer), a gAMA of 1.0
/// too, which a decoder that converted gamma would act on.
std::string encode(const Variant& v, int w, int h, uint32_t seed) {
    std::mt19937 rng(seed);
    const int channels = v.colour_type == PNG_COLOR_TYPE_RGB_ALPHA ? 4
                         : v.colour_type == PNG_COLOR_TYPE_RGB    ? 3
                         : v.colour_type == PNG_COLOR_TYPE_GA     ? 2
                                                                  : 1;
    auto rows = raw_rows(v, w, h, rng, channels);
    std::vector<png_bytep> row_ptrs;
    for (auto& r : rows) row_ptrs.push_back(r.data());
    std::vector<png_color> palette(size_t(1) << std::min(v.bit_depth, 8));
    for (auto& c : palette) c = {png_byte(rng()), png_byte(rng()), png_byte(rng())};
    std::vector<png_byte> alphas(palette.size());
    for (auto& a : alphas) a = png_byte(rng());
    png_color_16 transparent{};
    if (v.bit_depth >= 8 && v.colour_type != PNG_COLOR_TYPE_PALETTE) {  // the first pixel's value
        auto sample = [&](int i) {
            return v.bit_depth == 16 ? png_uint_16(rows[0][size_t(2 * i)] << 8 | rows[0][size_t(2 * i + 1)])
                                     : png_uint_16(rows[0][size_t(i)]);
        };
        transparent.gray = sample(0);
        transparent.red = sample(0);
        if (channels == 3) transparent.green = sample(1), transparent.blue = sample(2);
    } else {
        transparent.gray = png_uint_16(rng() & ((1u << v.bit_depth) - 1));
    }
    std::string out;
    const Encoding e{v, w, h, row_ptrs.data(), palette.data(), int(palette.size()), alphas.data(), &transparent};
    if (!write_png(e, out)) out.clear();
    return out;
}

std::vector<uint8_t> stb_rgba(const std::string& bytes, int& w, int& h) {
    int channels = 0;
    stbi_uc* p = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h,
                                       &channels, 4);
    if (!p) return {};
    std::vector<uint8_t> v(p, p + size_t(w) * size_t(h) * 4);
    stbi_image_free(p);
    return v;
}

std::vector<Variant> every_variant() {
    std::vector<Variant> all;
    const std::pair<int, std::vector<int>> kinds[] = {
        {PNG_COLOR_TYPE_GRAY, {1, 2, 4, 8, 16}}, {PNG_COLOR_TYPE_GA, {8, 16}},   {PNG_COLOR_TYPE_RGB, {8, 16}},
        {PNG_COLOR_TYPE_RGB_ALPHA, {8, 16}},     {PNG_COLOR_TYPE_PALETTE, {1, 2, 4, 8}}};
    for (const auto& [type, depths] : kinds)
        for (int depth : depths)
            for (bool interlaced : {false, true})
                for (bool trns : {false, true})
                    if (!trns || !(type & PNG_COLOR_MASK_ALPHA)) all.push_back({type, depth, interlaced, trns});
    return all;
}

// 13×7: odd sizes leave Adam7 passes partly empty and 1/2/4-bit rows ending mid-byte.
TEST(PngDecode, EveryColourTypeAndDepthDecodesAsStbImage) {
    const auto variants = every_variant();
    EXPECT_EQ(variants.size(), 52u);
    uint32_t seed = 1;
    for (const Variant& v : variants) {
        SCOPED_TRACE("colour type " + std::to_string(v.colour_type) + ", " + std::to_string(v.bit_depth) + " bits" +
                     (v.interlaced ? ", interlaced" : "") + (v.trns ? ", tRNS" : ""));
        const std::string bytes = encode(v, 13, 7, seed++);
        ASSERT_FALSE(bytes.empty());
        int w = 0, h = 0;
        const std::vector<uint8_t> want = stb_rgba(bytes, w, h);
        ASSERT_EQ(want.size(), size_t(13 * 7 * 4));
        const DecodedImage got = scene_detail::decode_png(bytes, "t.png");
        EXPECT_EQ(got.width, 13);
        EXPECT_EQ(got.height, 7);
        EXPECT_EQ(got.rgba, want);
    }
}

// The transparent value of a tRNS chunk is in the test images (a quarter of the pixels of
// 8 bits or more), so the comparison above covers alpha 0 as well as 255.
TEST(PngDecode, TrnsMakesItsValueTransparent) {
    const std::string bytes = encode({PNG_COLOR_TYPE_RGB, 16, false, true}, 13, 7, 5);
    const DecodedImage got = scene_detail::decode_png(bytes, "t.png");
    int transparent = 0;
    for (size_t i = 3; i < got.rgba.size(); i += 4) transparent += got.rgba[i] == 0;
    EXPECT_EQ(got.rgba[3], 0);  // the first pixel holds the tRNS value
    EXPECT_GT(transparent, 91 / 8);
    EXPECT_LT(transparent, 91 / 2);
}

// The data set's PNG textures (Sibenik's) decode as stb_image decoded them, byte for byte.
TEST(PngDecode, SibenikTexturesDecodeAsStbImage) {
    const std::filesystem::path dir = std::filesystem::path(TESSERA_DEFAULT_DATA_DIR) / "sibenik";
    if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << dir << " not present";
    int n = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".png") continue;
        SCOPED_TRACE(entry.path().string());
        const std::string bytes = test::read_bytes(entry.path());
        int w = 0, h = 0;
        const std::vector<uint8_t> want = stb_rgba(bytes, w, h);
        const DecodedImage got = scene_detail::decode_png(bytes, entry.path().string());
        EXPECT_EQ(got.width, w);
        EXPECT_EQ(got.height, h);
        EXPECT_TRUE(got.rgba == want);  // not EXPECT_EQ: a mismatch would print megabytes
        ++n;
    }
    EXPECT_GE(n, 1);
}

// Splits a PNG at its first IDAT chunk: (bytes before it, the rest).
std::pair<std::string, std::string> at_first_idat(const std::string& bytes) {
    const size_t idat = bytes.find("IDAT");
    EXPECT_NE(idat, std::string::npos);
    return {bytes.substr(0, idat - 4), bytes.substr(idat - 4)};
}

std::string decode_error(const std::string& bytes) {
    try {
        scene_detail::decode_png(bytes, "t.png");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

// A zero-length IDAT chunk is valid (the image data is the IDAT chunks' concatenation,
// PNG spec 11.2.4), and so is an ancillary chunk whose CRC is wrong (skipped); both
// decode to the texels of the plain file. (stb_image 2.27 copied to a null buffer on the
// first; the fuzz seed seed-empty_idat keeps it covered.)
TEST(PngDecode, EmptyIdatAndAncillaryChunkWithABadCrcDecodeLikeThePlainFile) {
    const std::string plain = test::read_bytes(test::fixture("checker.png"));
    const DecodedImage want = scene_detail::decode_png(plain, "t.png");
    const auto [head, tail] = at_first_idat(plain);
    std::string bad_text = test::png_chunk("tEXt", std::string("Comment\0x", 9));
    bad_text.back() ^= 1;
    for (const std::string& bytes : {head + test::png_chunk("IDAT", "") + tail, head + bad_text + tail}) {
        const DecodedImage got = scene_detail::decode_png(bytes, "t.png");
        EXPECT_EQ(got.width, want.width);
        EXPECT_EQ(got.rgba, want.rgba);
    }
}

// A damaged IDAT CRC, a file cut inside a chunk and a chunk declaring more bytes than the
// file holds (stb_image 2.27 first grew its buffer to the declared length, 2 GB from a few
// bytes) are refused with libpng's reason, without decoding made-up pixels.
TEST(PngDecode, DamagedOrTruncatedFilesAreRefused) {
    const std::string plain = test::read_bytes(test::fixture("checker.png"));
    const auto [head, tail] = at_first_idat(plain);
    std::string bad_crc = tail;  // IDAT's CRC, after its 8-byte head and its data
    const size_t idat_length = size_t(uint8_t(tail[2])) << 8 | uint8_t(tail[3]);
    bad_crc[8 + idat_length] ^= 0x40;
    EXPECT_CONTAINS(decode_error(head + bad_crc), "t.png: texture is not a decodable PNG image (libpng: IDAT: CRC error");
    EXPECT_CONTAINS(decode_error(plain.substr(0, head.size() + 10)),
                    "(libpng: the file ends at byte " + std::to_string(head.size() + 10) + ", before the image does)");
    std::string huge = test::png_chunk("IDAT", "xy");
    huge[0] = '\x7f';
    EXPECT_CONTAINS(decode_error(head + huge), "t.png: texture is not a decodable PNG image (libpng: ");
    EXPECT_CONTAINS(decode_error(std::string("\x89PNG\r\n\x1a\n", 8)), "(libpng: the file ends at byte 8");
}

// An image whose compressed data ends before its last row (a valid zlib stream, under an
// IHDR that declares more rows) is refused, not completed with made-up rows.
TEST(PngDecode, ImageDataShorterThanItsHeaderIsRefused) {
    const std::string plain = encode({PNG_COLOR_TYPE_RGB, 8, false, false}, 13, 7, 3);
    const std::string tall = test::png_chunk("IHDR", plain.substr(16, 4) + std::string("\0\0\0\x09", 4) +
                                                         plain.substr(24, 5));
    const std::string bytes = plain.substr(0, 8) + tall + plain.substr(8 + 25);
    ASSERT_EQ(bytes.size(), plain.size());
    EXPECT_CONTAINS(decode_error(bytes), "t.png: texture is not a decodable PNG image (libpng: Not enough image data)");
}

// A tRNS colour that does not fit the bit depth (PNG spec 11.3.2.1) is refused naming it:
// libpng would mask it to the depth and stb_image would not, so no texels are right.
TEST(PngDecode, TrnsColourOutsideTheBitDepthIsRefused) {
    struct Case {
        Variant v;
        std::string trns, what;
    };
    const Case cases[] = {
        {{PNG_COLOR_TYPE_GRAY, 2, false, false}, std::string("\0\x05", 2), "(its tRNS colour (5) does not fit its 2-bit"},
        {{PNG_COLOR_TYPE_GRAY, 8, true, false}, std::string("\x01\x05", 2), "(its tRNS colour (261) does not fit its 8-bit"},
        {{PNG_COLOR_TYPE_RGB, 8, false, false}, std::string("\0\x01\0\x02\x01\x2c", 6),
         "(its tRNS colour (1, 2, 300) does not fit its 8-bit samples)"}};
    for (const Case& c : cases) {
        const auto [head, tail] = at_first_idat(encode(c.v, 13, 7, 9));
        EXPECT_CONTAINS(decode_error(head + test::png_chunk("tRNS", c.trns) + tail),
                        "t.png: texture is not a valid PNG image " + c.what);
    }
    const auto [head, tail] = at_first_idat(encode({PNG_COLOR_TYPE_GRAY, 2, false, false}, 13, 7, 9));
    EXPECT_NO_THROW(scene_detail::decode_png(head + test::png_chunk("tRNS", std::string("\0\x03", 2)) + tail, "t.png"));
}

// Text chunks are skipped unread: sixteen zTXt chunks of about 8 kB, each inflating to
// 7.9 MB (libpng keeps up to 1,000 of them, each up to 8 MB), leave the texels as they are
// and the process's peak memory within 64 MB of where it was (it rose by ~130 MB when
// libpng kept their text).
TEST(PngDecode, TextChunksAreSkippedUnread) {
    const std::string plain = test::read_bytes(test::fixture("checker.png"));
    const DecodedImage want = scene_detail::decode_png(plain, "t.png");
    const std::string text(7'900'000, 'a');
    std::string packed(compressBound(uLong(text.size())), '\0');
    uLongf packed_size = uLongf(packed.size());
    ASSERT_EQ(compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
                        reinterpret_cast<const Bytef*>(text.data()), uLong(text.size()), 9),
              Z_OK);
    packed.resize(packed_size);
    const std::string ztxt = test::png_chunk("zTXt", std::string("Comment\0\0", 9) + packed);
    auto [head, tail] = at_first_idat(plain);
    for (int i = 0; i < 16; ++i) head += ztxt;
    rusage before{}, after{};
    ::getrusage(RUSAGE_SELF, &before);
    const DecodedImage got = scene_detail::decode_png(head + tail, "t.png");
    ::getrusage(RUSAGE_SELF, &after);
    EXPECT_EQ(got.rgba, want.rgba);
    EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 64 * 1024) << "KiB";  // ru_maxrss: KiB on Linux
}

TEST(PngDecode, IsPngReadsTheSignature) {
    EXPECT_TRUE(scene_detail::is_png(std::string("\x89PNG\r\n\x1a\n", 8)));
    EXPECT_FALSE(scene_detail::is_png(std::string("\x89PNG\r\n\x1a", 7)));
    EXPECT_FALSE(scene_detail::is_png("GIF89a and more"));
}

}  // namespace
}  // namespace tessera
