// The texture layer of the input contract (host/scene/texture_file.cpp and the map_Kd
// lookup in obj_mesh.cpp): a texture that is missing, a directory, neither PNG nor JPEG,
// or not decodable is rejected with the texture's path (and, where the MTL names it, the
// MTL file and material) and the reason; PNG and JPEG textures decode to their texels.
#include <cstdint>
#include <fstream>
#include <string>

#include "scene/scene_test_util.h"
#include "scene/texture_file.h"
#include "support/scratch_dir.h"

namespace tessera {
namespace {

enum class Make { Nothing, Directory, Text, Empty, TruncatedPng, HugePng, Gif, Pnm, TruncatedJpeg, CmykJpeg, Png };

struct BadTexture {
    const char* name;
    Make make;          ///< what is put at <dir>/tex.png
    const char* what;   ///< the reason the message must give
};

std::string read_fixture(const std::string& name) { return test::read_bytes(test::fixture(name)); }

class TextureFiles : public test::ScratchDirTest {
protected:
    void make_texture(Make make) {
        const auto tex = dir_ / "tex.png";
        const std::string bytes = read_fixture("checker.png");
        switch (make) {
            case Make::Nothing: break;
            case Make::Directory: std::filesystem::create_directories(tex); break;
            case Make::Text: std::ofstream(tex) << "not an image\n"; break;
            case Make::Empty: std::ofstream{tex}; break;
            case Make::TruncatedPng: std::ofstream(tex, std::ios::binary) << bytes.substr(0, bytes.size() / 2); break;
            // A PNG header (signature, IHDR) asking for 20000 x 8 pixels, then an empty IDAT
            // chunk: libpng reads the chunks up to the first IDAT before the size is checked.
            case Make::HugePng:
                std::ofstream(tex, std::ios::binary)
                    << bytes.substr(0, 8) << test::png_chunk("IHDR", std::string("\0\0\x4e\x20\0\0\0\x08\x08\x06\0\0\0", 13))
                    << test::png_chunk("IDAT", "");
                break;
            case Make::Gif: std::ofstream(tex, std::ios::binary) << "GIF89a" << std::string(20, '\0'); break;
            case Make::Pnm: std::ofstream(tex, std::ios::binary) << "P6\n2 2\n255\n" << std::string(12, '\x7f'); break;
            case Make::TruncatedJpeg: {
                const std::string jpeg = read_fixture("checker.jpg");
                std::ofstream(tex, std::ios::binary) << jpeg.substr(0, jpeg.size() / 2);
                break;
            }
            case Make::CmykJpeg: std::ofstream(tex, std::ios::binary) << read_fixture("cmyk.jpg"); break;
            case Make::Png: std::ofstream(tex, std::ios::binary) << bytes; break;
        }
    }
    std::filesystem::path write_scene() {
        std::ofstream(dir_ / "mesh.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nusemtl m\nf 1 3 2\n";
        std::ofstream(dir_ / "m.mtl") << "newmtl m\nKd 1 1 1\nmap_Kd tex.png\n";
        std::ofstream(dir_ / "s.json") << R"({"camera": {"position": [0,1,3], "look_at": [0,0,0]},
            "objects": [{"mesh": "mesh.obj"}],
            "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [0,0,1], "radiance": [1,1,1]}]})";
        return dir_ / "s.json";
    }
};

class TextureInput : public TextureFiles, public ::testing::WithParamInterface<BadTexture> {};

TEST_P(TextureInput, NamesTheTextureAndTheReason) {
    make_texture(GetParam().make);
    const std::string e = test::load_error(write_scene());
    EXPECT_CONTAINS(e, (dir_ / "tex.png").string() + ": ");
    EXPECT_CONTAINS(e, GetParam().what);
}

TEST_P(TextureInput, LoadTextureAloneNamesTheFile) {
    make_texture(GetParam().make);
    try {
        scene_detail::load_texture(dir_ / "tex.png");
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_CONTAINS(e.what(), (dir_ / "tex.png").string() + ": texture");
        EXPECT_CONTAINS(e.what(), GetParam().what);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Texture, TextureInput,
    ::testing::Values(BadTexture{"Missing", Make::Nothing, "not found"},
                      BadTexture{"Directory", Make::Directory, "is a directory, not a file"},
                      BadTexture{"NotAnImage", Make::Text, "texture is not a PNG or JPEG image (its first bytes match neither"},
                      BadTexture{"Empty", Make::Empty, "texture is not a PNG or JPEG image"},
                      BadTexture{"Gif", Make::Gif, "those of a GIF image); convert it to PNG"},
                      BadTexture{"Pnm", Make::Pnm, "those of a PNM image); convert it to PNG"},
                      BadTexture{"TruncatedPng", Make::TruncatedPng, "texture is not a decodable PNG image (libpng: the file ends at byte "},
                      // A truncated JPEG is an error, not an image whose missing rows are grey.
                      BadTexture{"TruncatedJpeg", Make::TruncatedJpeg, "texture is not a decodable JPEG image (libjpeg: "},
                      BadTexture{"CmykJpeg", Make::CmykJpeg, "texture is a CMYK JPEG image"},
                      // A header asking for more than limits::kImageSide: refused before decoding.
                      BadTexture{"HugeHeader", Make::HugePng, "texture of 20000x8 pixels exceeds the limit of 16384"}),
    [](const auto& info) { return std::string(info.param.name); });

// The map_Kd message also says which MTL line and material named the texture.
// The line is map_Kd's (line 3), where the file is named, not newmtl's.
TEST_F(TextureFiles, MapKdMessageNamesTheMaterial) {
    const std::string e = test::load_error(write_scene());
    EXPECT_CONTAINS(e, "map_Kd of " + (dir_ / "m.mtl").string() + ":3: material 'm'");
}

// JPEG textures decode through libjpeg-turbo: two 8x8 blocks of one colour each (quality
// 100, no chroma subsampling), baseline and progressive, land within 3 of their values
// (the DCT's rounding; a swapped channel or row order is off by 160), and a grey JPEG
// becomes grey RGB; A = 255.
uint8_t channel(uint32_t texel, int c) { return uint8_t(texel >> (8 * c)); }

TEST(JpegTexture, DecodesBaselineAndProgressiveToTheirColours) {
    for (const char* name : {"checker.jpg", "checker_progressive.jpg"}) {
        SCOPED_TRACE(name);
        const Texture t = scene_detail::load_texture(test::fixture(name));
        ASSERT_EQ(t.width, 16);
        ASSERT_EQ(t.height, 8);
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 16; ++x) {
                const uint32_t texel = t.rgba8[size_t(y) * 16 + x];
                const int want[3] = {x < 8 ? 200 : 40, 40, x < 8 ? 40 : 200};
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(channel(texel, c), want[c], 3) << x << "," << y;
                EXPECT_EQ(channel(texel, 3), 255);
            }
    }
}

TEST(JpegTexture, GreyBecomesGreyRgb) {
    const Texture t = scene_detail::load_texture(test::fixture("grey.jpg"));
    ASSERT_EQ(t.rgba8.size(), 64u);
    for (uint32_t texel : t.rgba8) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(channel(texel, c), 100, 2);
        EXPECT_EQ(channel(texel, 3), 255);
    }
}

TEST_F(TextureFiles, ValidTextureLoads) {
    make_texture(Make::Png);
    const Scene s = load_scene(write_scene(), DataPath{});
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].width, 2);
}

}  // namespace
}  // namespace tessera
