// bench/gpu/box_downsample: 2x2 box means of an EXR written by Tessera, read back by
// Tessera; and one error naming the file for a size the factor does not divide. The
// script needs Python's OpenEXR module; where no interpreter here has it (python3, or
// $TESSERA_CVVDP_PYTHON, whose venv does), the test skips, saying so.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "image/image_io.h"
#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;

namespace tessera {
namespace {

class BoxDownsample : public test::ScratchDirTest {};

// The first of python3 and $TESSERA_CVVDP_PYTHON that imports OpenEXR and numpy, or "".
std::string python_with_openexr() {
    std::vector<std::string> candidates = {"python3"};
    if (const char* p = std::getenv("TESSERA_CVVDP_PYTHON"); p && *p) candidates.emplace_back(p);
    for (const auto& py : candidates)
        if (test::python_imports("OpenEXR, numpy", py)) return py;
    return "";
}

Image rgb_image(int w, int h) {
    Image img{w, h, {{"R", {}}, {"G", {}}, {"B", {}}}};
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < w * h; ++i) img.channels[c].data.push_back(float(i * (c + 1)) + 0.25f);
    return img;
}

TEST_F(BoxDownsample, AveragesTwoByTwoBlocks) {
    const std::string py = python_with_openexr();
    if (py.empty()) GTEST_SKIP() << "no python3 here imports OpenEXR (bench/requirements.txt)";
    const fs::path in = dir_ / "in.exr", out = dir_ / "out.exr";
    write_exr(in, rgb_image(4, 2));  // pixels 0..3 in row 0, 4..7 in row 1
    const auto r = test::run_shell(py + " " + TESSERA_SOURCE_DIR + "/bench/gpu/box_downsample " + in.string() + " " +
                                   out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const Image o = read_exr(out);
    ASSERT_EQ(o.width, 2);
    ASSERT_EQ(o.height, 1);
    for (int c = 0; c < 3; ++c) {
        const ImageChannel* ch = o.find(std::string(1, "RGB"[c]));
        ASSERT_NE(ch, nullptr);
        // Block (0,0) holds pixels 0, 1, 4, 5; block (1,0) holds 2, 3, 6, 7.
        EXPECT_FLOAT_EQ(ch->data[0], (c + 1) * 2.5f + 0.25f);
        EXPECT_FLOAT_EQ(ch->data[1], (c + 1) * 4.5f + 0.25f);
    }
}

TEST_F(BoxDownsample, SizeNotDivisibleStopsNamingTheFile) {
    const std::string py = python_with_openexr();
    if (py.empty()) GTEST_SKIP() << "no python3 here imports OpenEXR (bench/requirements.txt)";
    const fs::path in = dir_ / "odd.exr", out = dir_ / "out.exr";
    write_exr(in, rgb_image(3, 2));
    const auto r = test::run_shell(py + " " + TESSERA_SOURCE_DIR + "/bench/gpu/box_downsample " + in.string() + " " +
                                   out.string() + " 2");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("odd.exr: 3x2 is not divisible by 2"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace tessera
