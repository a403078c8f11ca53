// Tests for host/image: EXR round trip, PNG tone mapping, atomic writes and errors.
#include <stb_image.h>
#include <gtest/gtest.h>

#include "support/error_of.h"
#include "support/scratch_dir.h"
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "image/atomic_file.h"
#include "image/image_io.h"
#include "util/error.h"

namespace fs = std::filesystem;
using tessera::test::error_of;
using tessera::Image;
using tessera::InputError;
using tessera::RuntimeError;

namespace {

/// A fresh directory per test, removed afterwards.
class ImageIoTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern = (fs::temp_directory_path() / "tessera-image-XXXXXX").string();
        std::vector<char> buf(pattern.begin(), pattern.end());
        buf.push_back('\0');
        ASSERT_NE(::mkdtemp(buf.data()), nullptr) << std::strerror(errno);
        dir = buf.data();
    }
    void TearDown() override {
        std::error_code ec;
        fs::permissions(dir, fs::perms::owner_all, fs::perm_options::add, ec);
        fs::remove_all(dir, ec);
    }
    fs::path dir;
};

/// Bit pattern of a float, so comparisons are exact even for NaN and -0.
std::uint32_t bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

void spit(const fs::path& p, const std::string& s) {
    std::ofstream out(p, std::ios::binary);
    out << s;
}

/// Files in `d` other than `keep` (to catch leftover temporaries).
std::vector<std::string> others(const fs::path& d, const std::string& keep) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(d))
        if (e.path().filename() != keep) names.push_back(e.path().filename().string());
    return names;
}

/// A w×h image whose channels all hold `value` in every pixel.
Image uniform(int w, int h, float r, float g, float b) {
    Image img;
    img.width = w;
    img.height = h;
    const std::size_t n = static_cast<std::size_t>(w) * h;
    img.channels = {{"R", std::vector<float>(n, r)},
                    {"G", std::vector<float>(n, g)},
                    {"B", std::vector<float>(n, b)}};
    return img;
}

/// Decodes a PNG to 8-bit RGB.
std::vector<unsigned char> decode_png(const fs::path& p, int& w, int& h) {
    int comp = 0;
    unsigned char* data = stbi_load(p.c_str(), &w, &h, &comp, 3);
    EXPECT_NE(data, nullptr) << stbi_failure_reason();
    if (!data) return {};
    EXPECT_EQ(comp, 3);
    std::vector<unsigned char> out(data, data + static_cast<std::size_t>(w) * h * 3);
    stbi_image_free(data);
    return out;
}

}  // namespace

TEST_F(ImageIoTest, FindReturnsChannelOrNull) {
    Image img = uniform(1, 1, 1, 2, 3);
    ASSERT_NE(img.find("G"), nullptr);
    EXPECT_EQ(img.find("G")->data[0], 2.0f);
    EXPECT_EQ(img.find("A"), nullptr);
}

TEST_F(ImageIoTest, ExrRoundTripIsBitExactWithExtraChannels) {
    const int w = 7, h = 5;
    Image img;
    img.width = w;
    img.height = h;
    const char* names[] = {"R", "G", "B", "albedo.R", "N.X", "Z"};
    const float specials[] = {0.0f, -0.0f, 1e-40f /* denormal */,
                              std::numeric_limits<float>::max(),
                              std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(),
                              std::numeric_limits<float>::quiet_NaN()};
    int k = 0;
    for (const char* name : names) {
        tessera::ImageChannel c{name, {}};
        for (int i = 0; i < w * h; ++i) {
            float v = std::sin(0.37f * static_cast<float>(i + 11 * k)) * std::pow(10.0f, k - 2);
            if (i < 7 && k == 0) v = specials[i];
            c.data.push_back(v);
        }
        img.channels.push_back(std::move(c));
        ++k;
    }
    const fs::path p = dir / "round.exr";
    tessera::write_exr(p, img);
    EXPECT_TRUE(others(dir, "round.exr").empty());

    Image back = tessera::read_exr(p);
    EXPECT_EQ(back.width, w);
    EXPECT_EQ(back.height, h);
    ASSERT_EQ(back.channels.size(), img.channels.size());
    for (const auto& c : img.channels) {
        const tessera::ImageChannel* b = back.find(c.name);
        ASSERT_NE(b, nullptr) << c.name;
        ASSERT_EQ(b->data.size(), c.data.size()) << c.name;
        for (std::size_t i = 0; i < c.data.size(); ++i)
            ASSERT_EQ(bits(b->data[i]), bits(c.data[i])) << c.name << "[" << i << "]";
    }
}

TEST_F(ImageIoTest, ExrRowZeroIsTop) {
    Image img = uniform(2, 3, 0, 0, 0);
    for (auto& c : img.channels)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 2; ++x) c.data[y * 2 + x] = static_cast<float>(10 * y + x);
    const fs::path p = dir / "rows.exr";
    tessera::write_exr(p, img);
    Image back = tessera::read_exr(p);
    EXPECT_EQ(back.find("R")->data, img.find("R")->data);
}

TEST_F(ImageIoTest, ExrOverwritesExistingFile) {
    const fs::path p = dir / "a.exr";
    tessera::write_exr(p, uniform(2, 2, 1, 1, 1));
    tessera::write_exr(p, uniform(3, 1, 5, 6, 7));
    Image back = tessera::read_exr(p);
    EXPECT_EQ(back.width, 3);
    EXPECT_EQ(back.height, 1);
    EXPECT_EQ(back.find("B")->data, std::vector<float>(3, 7.0f));
    EXPECT_TRUE(others(dir, "a.exr").empty());
}

TEST_F(ImageIoTest, PngEncodesExactSrgbBytes) {
    // Pixel values: 0, 0.0031308 (OETF knee), 0.5, 1, 2 (clamped), -1 (clamped), NaN.
    const float values[] = {0.0f, 0.0031308f, 0.5f, 1.0f, 2.0f, -1.0f,
                            std::numeric_limits<float>::quiet_NaN(), 0.18f};
    // 12.92 * 0.0031308 * 255 = 10.31 -> 10; 1.055 * 0.5^(1/2.4) - 0.055 = 0.73536 -> 187.5 -> 188;
    // 1.055 * 0.18^(1/2.4) - 0.055 = 0.46135 -> 117.6 -> 118.
    const unsigned char expected[] = {0, 10, 188, 255, 255, 0, 0, 118};
    const int w = 8;
    Image img;
    img.width = w;
    img.height = 1;
    img.channels = {{"R", std::vector<float>(values, values + w)},
                    {"G", std::vector<float>(w, 1.0f)},
                    {"B", std::vector<float>(w, 0.0f)},
                    {"Z", std::vector<float>(w, 42.0f)}};
    const fs::path p = dir / "ramp.png";
    tessera::write_png(p, img);
    EXPECT_TRUE(others(dir, "ramp.png").empty());
    int dw = 0, dh = 0;
    std::vector<unsigned char> px = decode_png(p, dw, dh);
    ASSERT_EQ(dw, w);
    ASSERT_EQ(dh, 1);
    for (int x = 0; x < w; ++x) {
        EXPECT_EQ(px[x * 3 + 0], expected[x]) << "x=" << x;
        EXPECT_EQ(px[x * 3 + 1], 255) << "x=" << x;
        EXPECT_EQ(px[x * 3 + 2], 0) << "x=" << x;
    }
}

TEST_F(ImageIoTest, PngExposureScalesByPowerOfTwo) {
    const fs::path a = dir / "a.png", b = dir / "b.png", c = dir / "c.png";
    tessera::write_png(a, uniform(2, 2, 0.25f, 0.5f, 0.1f), 1.0f);
    tessera::write_png(b, uniform(2, 2, 0.5f, 1.0f, 0.2f), 0.0f);
    tessera::write_png(c, uniform(2, 2, 1.0f, 2.0f, 0.4f), -1.0f);
    int w, h;
    std::vector<unsigned char> pa = decode_png(a, w, h);
    std::vector<unsigned char> pb = decode_png(b, w, h);
    std::vector<unsigned char> pc = decode_png(c, w, h);
    EXPECT_EQ(pa, pb);
    EXPECT_EQ(pc, pb);
    ASSERT_EQ(pb.size(), 12u);
    EXPECT_EQ(pb[0], 188);
    EXPECT_EQ(pb[1], 255);
}

TEST_F(ImageIoTest, PngRowZeroIsTop) {
    Image img = uniform(1, 2, 0, 0, 0);
    img.channels[0].data = {1.0f, 0.0f};  // top red, bottom black
    const fs::path p = dir / "rows.png";
    tessera::write_png(p, img);
    int w, h;
    std::vector<unsigned char> px = decode_png(p, w, h);
    ASSERT_EQ(px.size(), 6u);
    EXPECT_EQ(px[0], 255);
    EXPECT_EQ(px[3], 0);
}

// A window's RGBA capture (the viewer's --screenshot-window) keeps its bytes, alpha
// included, rows top first; an empty capture is refused before any file is made.
TEST_F(ImageIoTest, PngRgba8KeepsItsBytes) {
    const std::vector<std::uint8_t> rgba = {255, 0, 0, 255, 0, 128, 0, 64,  // top row
                                            0, 0, 7, 0, 250, 251, 252, 253};
    const fs::path p = dir / "capture.png";
    tessera::write_png_rgba8(p, rgba.data(), 2, 2);
    int w = 0, h = 0, comp = 0;
    unsigned char* data = stbi_load(p.c_str(), &w, &h, &comp, 4);
    ASSERT_NE(data, nullptr) << stbi_failure_reason();
    EXPECT_EQ(w, 2);
    EXPECT_EQ(h, 2);
    EXPECT_EQ(comp, 4);
    EXPECT_EQ(std::vector<std::uint8_t>(data, data + 16), rgba);
    stbi_image_free(data);

    const fs::path q = dir / "empty.png";
    const std::string msg = error_of([&] { tessera::write_png_rgba8(q, rgba.data(), 0, 2); });
    EXPECT_NE(msg.find(q.string()), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(q));
}

TEST_F(ImageIoTest, PngWithoutRgbThrowsNamingPath) {
    Image img = uniform(2, 2, 1, 1, 1);
    img.channels.erase(img.channels.begin() + 1);  // drop G
    const fs::path p = dir / "nog.png";
    EXPECT_THROW(tessera::write_png(p, img), RuntimeError);
    const std::string msg = error_of([&] { tessera::write_png(p, img); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("'G'"), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(p));
    EXPECT_TRUE(others(dir, "").empty());
}

TEST_F(ImageIoTest, WriteUnderARegularFileThrowsNamingPath) {
    std::ofstream(dir / "file") << "not a directory";
    const fs::path exr = dir / "file" / "x.exr";
    const fs::path png = dir / "file" / "x.png";
    Image img = uniform(2, 2, 1, 1, 1);
    EXPECT_THROW(tessera::write_exr(exr, img), RuntimeError);
    EXPECT_THROW(tessera::write_png(png, img), RuntimeError);
    std::string msg = error_of([&] { tessera::write_exr(exr, img); });
    EXPECT_NE(msg.find(exr.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("cannot create the directory"), std::string::npos) << msg;
    msg = error_of([&] { tessera::write_png(png, img); });
    EXPECT_NE(msg.find(png.string()), std::string::npos) << msg;
}

// The writers make a missing directory (atomic_file.h), so --out into a new one works.
TEST_F(ImageIoTest, WriteIntoMissingDirectoryMakesIt) {
    const fs::path exr = dir / "no-such-dir" / "x.exr";
    tessera::write_exr(exr, uniform(2, 2, 1, 1, 1));
    EXPECT_TRUE(fs::is_regular_file(exr));
}

TEST_F(ImageIoTest, WriteIntoProcThrowsNamingPath) {
    // /proc refuses new files even for root.
    const fs::path p = "/proc/tessera-image-test.exr";
    std::string msg = error_of([&] { tessera::write_exr(p, uniform(1, 1, 1, 1, 1)); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
    EXPECT_THROW(tessera::write_exr(p, uniform(1, 1, 1, 1, 1)), RuntimeError);
}

TEST_F(ImageIoTest, WriteIntoReadOnlyDirectoryKeepsExistingFile) {
    if (::geteuid() == 0) GTEST_SKIP() << "running as root: permissions do not stop writes";
    const fs::path exr = dir / "old.exr", png = dir / "old.png";
    spit(exr, "old exr bytes");
    spit(png, "old png bytes");
    ASSERT_EQ(::chmod(dir.c_str(), 0555), 0);
    Image img = uniform(2, 2, 1, 1, 1);
    std::string msg = error_of([&] { tessera::write_exr(exr, img); });
    EXPECT_NE(msg.find(exr.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(std::strerror(EACCES)), std::string::npos) << msg;
    EXPECT_THROW(tessera::write_exr(exr, img), RuntimeError);
    EXPECT_THROW(tessera::write_png(png, img), RuntimeError);
    EXPECT_EQ(tessera::test::file_bytes(exr), "old exr bytes");
    EXPECT_EQ(tessera::test::file_bytes(png), "old png bytes");
}

TEST_F(ImageIoTest, InvalidImageLeavesExistingFileUntouched) {
    const fs::path exr = dir / "keep.exr", png = dir / "keep.png";
    tessera::write_exr(exr, uniform(2, 2, 0.5f, 0.5f, 0.5f));
    tessera::write_png(png, uniform(2, 2, 0.5f, 0.5f, 0.5f));
    const std::string old_exr = tessera::test::file_bytes(exr), old_png = tessera::test::file_bytes(png);

    Image zero = uniform(2, 2, 1, 1, 1);
    zero.width = 0;
    Image mismatch = uniform(2, 2, 1, 1, 1);
    mismatch.channels[2].data.pop_back();
    Image none;
    none.width = none.height = 2;
    Image dup = uniform(2, 2, 1, 1, 1);
    dup.channels[1].name = "R";
    for (const Image* bad : {&zero, &mismatch, &none, &dup}) {
        EXPECT_THROW(tessera::write_exr(exr, *bad), RuntimeError);
        EXPECT_THROW(tessera::write_png(png, *bad), RuntimeError);
        const std::string msg = error_of([&] { tessera::write_exr(exr, *bad); });
        EXPECT_NE(msg.find(exr.string()), std::string::npos) << msg;
    }
    EXPECT_EQ(tessera::test::file_bytes(exr), old_exr);
    EXPECT_EQ(tessera::test::file_bytes(png), old_png);
    EXPECT_EQ(tessera::read_exr(exr).find("R")->data, std::vector<float>(4, 0.5f));
    std::vector<std::string> rest = others(dir, "keep.exr");
    EXPECT_EQ(rest, std::vector<std::string>{"keep.png"});
}

TEST_F(ImageIoTest, FailedWriteCallbackRemovesTemporaryAndKeepsTarget) {
    const fs::path p = dir / "t.bin";
    spit(p, "original");
    EXPECT_THROW(tessera::replace_file_atomic(p,
                                              [](const fs::path& temp) {
                                                  spit(temp, "partial");
                                                  throw RuntimeError("boom");
                                              }),
                 RuntimeError);
    EXPECT_EQ(tessera::test::file_bytes(p), "original");
    EXPECT_TRUE(others(dir, "t.bin").empty());
    tessera::write_file_atomic(p, "new", 3);
    EXPECT_EQ(tessera::test::file_bytes(p), "new");
    EXPECT_TRUE(others(dir, "t.bin").empty());
}

TEST_F(ImageIoTest, ReadMissingFileThrowsInputErrorNamingIt) {
    const fs::path p = dir / "missing.exr";
    EXPECT_THROW(tessera::read_exr(p), InputError);
    const std::string msg = error_of([&] { tessera::read_exr(p); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
}

TEST_F(ImageIoTest, ReadGarbageFileThrowsInputErrorNamingIt) {
    const fs::path garbage = dir / "garbage.exr";
    spit(garbage, std::string(1000, 'x'));
    EXPECT_THROW(tessera::read_exr(garbage), InputError);
    std::string msg = error_of([&] { tessera::read_exr(garbage); });
    EXPECT_NE(msg.find(garbage.string()), std::string::npos) << msg;

    // A truncated real EXR.
    const fs::path truncated = dir / "truncated.exr";
    tessera::write_exr(truncated, uniform(64, 64, 0.3f, 0.2f, 0.1f));
    std::string bytes = tessera::test::file_bytes(truncated);
    spit(truncated, bytes.substr(0, bytes.size() / 2));
    EXPECT_THROW(tessera::read_exr(truncated), InputError);
    msg = error_of([&] { tessera::read_exr(truncated); });
    EXPECT_NE(msg.find(truncated.string()), std::string::npos) << msg;

    // A directory is not an image either.
    EXPECT_THROW(tessera::read_exr(dir), InputError);
}
