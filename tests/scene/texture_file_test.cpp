// The texture layer of the input contract (host/scene/texture_file.cpp and the map_Kd
// lookup in obj_mesh.cpp): a texture that is missing, a directory, or not a decodable
// image is rejected with the texture's path (and, where the MTL names it, the MTL file and
// material) and the reason.
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>

#include "scene/scene_test_util.h"
#include "scene/texture_file.h"
#include "support/scratch_dir.h"

namespace tessera {
namespace {

enum class Make { Nothing, Directory, Text, Empty, TruncatedPng, HugePnm, Png };

struct BadTexture {
    const char* name;
    Make make;          ///< what is put at <dir>/tex.png
    const char* what;   ///< the reason the message must give
};

class TextureFiles : public test::ScratchDirTest {
protected:
    void make_texture(Make make) {
        const auto tex = dir_ / "tex.png";
        std::ifstream png(test::fixture("checker.png"), std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(png)), std::istreambuf_iterator<char>());
        switch (make) {
            case Make::Nothing: break;
            case Make::Directory: std::filesystem::create_directories(tex); break;
            case Make::Text: std::ofstream(tex) << "not an image\n"; break;
            case Make::Empty: std::ofstream{tex}; break;
            case Make::TruncatedPng: std::ofstream(tex, std::ios::binary) << bytes.substr(0, bytes.size() / 2); break;
            case Make::HugePnm: std::ofstream(tex, std::ios::binary) << "P6\n20000 8\n255\n" << bytes; break;
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
                      BadTexture{"NotAnImage", Make::Text, "texture is not a decodable image"},
                      BadTexture{"Empty", Make::Empty, "texture is not a decodable image"},
                      BadTexture{"TruncatedPng", Make::TruncatedPng, "texture is not a decodable image"},
                      // A header asking for more than limits::kImageSide: refused before decoding.
                      BadTexture{"HugeHeader", Make::HugePnm, "texture of 20000x8 pixels exceeds the limit of 16384"}),
    [](const auto& info) { return std::string(info.param.name); });

// The map_Kd message also says which MTL line and material named the texture.
TEST_F(TextureFiles, MapKdMessageNamesTheMaterial) {
    const std::string e = test::load_error(write_scene());
    EXPECT_CONTAINS(e, "map_Kd of " + (dir_ / "m.mtl").string() + ":1: material 'm'");
}

// A chunk as it sits in a PNG: big-endian length, type, data, and a CRC (zeros here:
// neither drop_empty_png_idat nor stb_image checks it).
std::string png_chunk(const std::string& type, const std::string& data) {
    const auto n = static_cast<uint32_t>(data.size());
    const char length[4] = {char(n >> 24), char(n >> 16), char(n >> 8), char(n)};
    return std::string(length, 4) + type + data + std::string(4, '\0');
}

const std::string kPngSignature("\x89PNG\r\n\x1a\n", 8);

TEST(DropEmptyPngIdat, RemovesOnlyZeroLengthIdatChunks) {
    const std::string ihdr = png_chunk("IHDR", std::string(13, '\1')), data = png_chunk("IDAT", "xyz");
    const std::string text = png_chunk("tEXt", ""), end = png_chunk("IEND", "");
    std::string bytes = kPngSignature + ihdr + png_chunk("IDAT", "") + png_chunk("IDAT", "") + data + text +
                        png_chunk("IDAT", "") + end;
    scene_detail::drop_empty_png_idat(bytes);
    // Empty chunks of other types (tEXt, IEND) stay.
    EXPECT_EQ(bytes, kPngSignature + ihdr + data + text + end);
}

TEST(DropEmptyPngIdat, LeavesOtherBytesAndTruncatedTailsAlone) {
    std::string not_png = "P6\n1 1\n255\n" + png_chunk("IDAT", "");
    const std::string before = not_png;
    scene_detail::drop_empty_png_idat(not_png);
    EXPECT_EQ(not_png, before);
    // A chunk whose length runs past the end stops the walk: it and what follows stay.
    const std::string empty = png_chunk("IDAT", ""), overlong = png_chunk("IDAT", "ab").substr(0, 9);
    std::string bytes = kPngSignature + empty + overlong + empty;
    scene_detail::drop_empty_png_idat(bytes);
    EXPECT_EQ(bytes, kPngSignature + overlong + empty);
}

// A PNG whose image data starts with an empty IDAT chunk (valid: the data stream is the
// IDAT chunks' concatenation) decodes to the texels of the same file without it. Under
// UBSan the scene fuzzer's seed seed-empty_idat covers the stb_image defect it avoids.
TEST_F(TextureFiles, EmptyIdatChunkDecodesLikeTheFileWithoutIt) {
    make_texture(Make::Png);
    const Texture plain = scene_detail::load_texture(dir_ / "tex.png");
    std::ifstream in(dir_ / "tex.png", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t idat = bytes.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    bytes.insert(idat - 4, png_chunk("IDAT", ""));
    std::ofstream(dir_ / "empty_idat.png", std::ios::binary) << bytes;
    const Texture t = scene_detail::load_texture(dir_ / "empty_idat.png");
    EXPECT_EQ(t.width, plain.width);
    EXPECT_EQ(t.height, plain.height);
    EXPECT_EQ(t.rgba8, plain.rgba8);
}

TEST_F(TextureFiles, ValidTextureLoads) {
    make_texture(Make::Png);
    const Scene s = load_scene(write_scene(), DataPath{});
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].width, 2);
}

}  // namespace
}  // namespace tessera
