// `tessera compare` as a user runs it: metric values on known image pairs, FLIP against
// NVIDIA's reference implementation called directly, ColorVideoVDP (--cvvdp), and clear
// errors for bad input.
#include <sys/stat.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "support/shell.h"
#include <nlohmann/json.hpp>

#include "image/image_io.h"
#include "support/scratch_dir.h"

namespace fs = std::filesystem;
using tessera::Image;

namespace {

using tessera::test::CliResult;
using tessera::test::python_imports;
using tessera::test::run_shell;
using tessera::test::run_tessera;

CliResult run_compare(const std::string& args, const std::string& env = "") {
    return run_shell(env + " " + std::string(TESSERA_EXE) + " compare " + args);
}

bool flip_importable() { return python_imports("flip_evaluator, numpy"); }

// The interpreter `tessera compare --cvvdp` uses by default, and whether it imports pycvvdp.
std::string cvvdp_python() {
    const char* v = std::getenv("TESSERA_CVVDP_PYTHON");
    return v && *v ? v : "python3";
}
bool cvvdp_importable() {
    return run_shell(cvvdp_python() + " " + TESSERA_SOURCE_DIR + "/bench/cvvdp_metric.py --check").exit_code == 0;
}

// A deterministic test pattern: a smooth HDR gradient with a bright patch (values up to
// ~8, as in a rendering with a light source), perturbed by `noise` of relative amplitude.
bool hdrvdp_runs() {
    return run_shell(std::string("python3 ") + TESSERA_SOURCE_DIR + "/bench/hdrvdp_metric.py --check").exit_code == 0;
}

Image pattern(int w, int h, float noise, unsigned seed) {
    Image img{w, h, {{"R", {}}, {"G", {}}, {"B", {}}, {"variance.R", {}}}};
    for (auto& c : img.channels) c.data.resize(w * h);
    unsigned s = seed;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int i = y * w + x;
            const bool patch = x > w / 2 && y < h / 3;
            for (int c = 0; c < 3; ++c) {
                s = s * 1664525u + 1013904223u;  // LCG: fixed across platforms
                const float u = (s >> 8) * (1.0f / 16777216.0f) - 0.5f;
                const float base = patch ? 8.0f : 0.05f + 0.9f * x / w * (c + 1) / 3.0f + 0.3f * y / h;
                img.channels[c].data[i] = base * (1.0f + noise * u);
            }
            img.channels[3].data[i] = 1e3f;  // must be ignored: only R, G, B are compared
        }
    return img;
}

Image constant(int w, int h, float v) {
    Image img{w, h, {{"R", {}}, {"G", {}}, {"B", {}}}};
    for (auto& c : img.channels) c.data.assign(w * h, v);
    return img;
}

class CompareCli : public tessera::test::ScratchDirTest {
protected:
    std::string write(const std::string& name, const Image& img) {
        const fs::path p = dir_ / name;
        tessera::write_exr(p, img);
        return p.string();
    }
    nlohmann::json compare_json(const std::string& a, const std::string& b, const std::string& env = "") {
        CliResult r = run_compare(a + " " + b + " --json", env);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        return nlohmann::json::parse(r.output.substr(r.output.find('{')));
    }
    void expect_error(const std::string& args, const std::string& needle) {
        CliResult r = run_compare(args);
        EXPECT_NE(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find("tessera: error:"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(needle), std::string::npos) << "message should name " << needle << ":\n" << r.output;
    }
};

}  // namespace

TEST_F(CompareCli, ImageWithItselfHasZeroError) {
    const std::string a = write("a.exr", pattern(40, 30, 0.0f, 1));
    nlohmann::json j = compare_json(a, a);
    EXPECT_EQ(j["relmse"].get<double>(), 0.0);
    EXPECT_EQ(j["rmse"].get<double>(), 0.0);
    EXPECT_TRUE(j["psnr_db"].is_null()) << "infinite PSNR is JSON null";
    if (j["flip"].contains("mean")) {
        EXPECT_EQ(j["flip"]["mean"].get<double>(), 0.0);
        EXPECT_EQ(j["flip"]["p_gt_0_1"].get<double>(), 0.0);
    }
    CliResult text = run_compare(a + " " + a + " --no-flip");
    EXPECT_EQ(text.exit_code, 0) << text.output;
    EXPECT_NE(text.output.find("PSNR       inf dB"), std::string::npos) << text.output;
}

TEST_F(CompareCli, KnownPerturbation) {
    // Every pixel 0.25 -> 0.5: relMSE = 0.0625 / 0.0725; RMSE = 0.25; tone-mapped sRGB values
    // 0.537099 and 0.735357, PSNR = 10 log10(1 / 0.198258^2) = 14.0554 dB.
    const std::string a = write("a.exr", constant(8, 8, 0.25f)), b = write("b.exr", constant(8, 8, 0.5f));
    nlohmann::json j = compare_json(a, b + " --no-flip");
    EXPECT_NEAR(j["relmse"].get<double>(), 0.0625 / 0.0725, 1e-9);
    EXPECT_NEAR(j["rmse"].get<double>(), 0.25, 1e-9);
    EXPECT_NEAR(j["psnr_db"].get<double>(), 14.0554, 1e-3);
    EXPECT_EQ(j["flip"]["unavailable"], "disabled by --no-flip");
}

// Into directories that do not exist yet: made at the write, as every output's (before,
// FLIP's own writer failed on a missing directory and failed the run).
TEST_F(CompareCli, WritesErrorMaps) {
    const std::string a = write("a.exr", pattern(16, 16, 0.0f, 1)), b = write("b.exr", pattern(16, 16, 0.3f, 2));
    const fs::path map = dir_ / "maps" / "map.png", fmap = dir_ / "maps" / "flip" / "flip.png";
    CliResult r = run_compare(a + " " + b + " --map " + map.string() + " --flip-map " + fmap.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    ASSERT_TRUE(fs::exists(map));
    EXPECT_GT(fs::file_size(map), 50u);
    if (flip_importable()) {
        EXPECT_TRUE(fs::exists(fmap)) << r.output;
    }
}

TEST_F(CompareCli, MismatchedSizes) {
    const std::string a = write("a.exr", constant(8, 8, 1.f)), b = write("b.exr", constant(8, 9, 1.f));
    expect_error(a + " " + b, "b.exr is 8x9");
}

TEST_F(CompareCli, NanOrInfInEitherImage) {
    Image bad = constant(8, 8, 1.f);
    bad.channels[2].data[10] = std::nanf("");
    const std::string a = write("a.exr", constant(8, 8, 1.f)), b = write("nan.exr", bad);
    expect_error(a + " " + b, "nan.exr: NaN value in channel B at pixel (2, 1)");
    expect_error(b + " " + a, "nan.exr: NaN");
    bad.channels[2].data[10] = INFINITY;
    const std::string c = write("inf.exr", bad);
    expect_error(a + " " + c, "inf.exr: infinite");
}

// The same pixels in the same order but a shifted data window: not the same image.
TEST_F(CompareCli, DifferentDataWindows) {
    Image shifted = constant(8, 8, 1.f);
    shifted.x0 = 10;
    const std::string a = write("a.exr", constant(8, 8, 1.f)), b = write("shifted.exr", shifted);
    EXPECT_EQ(tessera::read_exr(b).x0, 10);
    expect_error(a + " " + b + " --no-flip", "data windows differ");
    expect_error(a + " " + b + " --no-flip", "shifted.exr at (10, 0)");
}

// An EXR wider than limits::kImageSide is refused from its header, before its pixels.
TEST_F(CompareCli, OversizedImageIsRefusedFromItsHeader) {
    const std::string a = write("a.exr", constant(8, 8, 1.f)), wide = write("wide.exr", constant(20000, 1, 1.f));
    expect_error(a + " " + wide + " --no-flip", "wide.exr: EXR image of 20000x1 pixels exceeds the limit of 16384 pixels per side");
}

TEST_F(CompareCli, NegativeReference) {
    Image negative = constant(8, 8, 1.f);
    negative.channels[1].data[9] = -0.5f;
    const std::string a = write("a.exr", constant(8, 8, 1.f)), n = write("neg.exr", negative);
    expect_error(n + " " + a + " --no-flip", "reference " + n + ": negative value -0.500000 in channel G at pixel (1, 1)");
    EXPECT_EQ(run_compare(a + " " + n + " --no-flip").exit_code, 0) << "a test image may be negative (a denoiser's)";
}

// Pixels are named in the file's own coordinates, which start at its data window's origin
// (the data-window message above uses them; the value checks counted from 0).
TEST_F(CompareCli, PixelsAreNamedInTheDataWindowsCoordinates) {
    Image ref = constant(8, 8, 1.f), test = constant(8, 8, 1.f);
    ref.x0 = test.x0 = 10;
    ref.y0 = test.y0 = 20;
    ref.channels[1].data[9] = -0.5f;
    test.channels[0].data[9] = std::nanf("");
    const std::string r = write("ref.exr", ref), t = write("test.exr", test);
    expect_error(r + " " + t + " --no-flip", "test.exr: NaN value in channel R at pixel (11, 21)");
    test.channels[0].data[9] = 1.0f;
    expect_error(r + " " + write("test2.exr", test) + " --no-flip",
                 "negative value -0.500000 in channel G at pixel (11, 21)");
}

// FLIP sees the pixels tessera reads: the package's own EXR loader returned a valid file
// written bottom row first (lineOrder DECREASING_Y) upside down, FLIP 0.65 for an image
// against itself. A black reference gives HDR-FLIP no exposure range: 0 against black,
// otherwise unavailable with that reason (it was "exited with status 255").
TEST_F(CompareCli, FlipReadsWhatTesseraReadsAndNamesABlackReference) {
    if (!python_imports("flip_evaluator, numpy, OpenEXR")) GTEST_SKIP() << "flip-evaluator, numpy or OpenEXR missing";
    const std::string a = write("a.exr", pattern(32, 24, 0.0f, 1)), flipped = (dir_ / "a_decreasing_y.exr").string();
    ASSERT_EQ(run_shell("python3 -c \"import OpenEXR, sys\n"
                        "ch = OpenEXR.File(sys.argv[1], separate_channels=True).channels()\n"
                        "h = {'compression': OpenEXR.ZIP_COMPRESSION, 'type': OpenEXR.scanlineimage, "
                        "'lineOrder': OpenEXR.DECREASING_Y}\n"
                        "OpenEXR.File(h, {c: ch[c].pixels for c in 'RGB'}).write(sys.argv[2])\" " +
                        a + " " + flipped)
                  .exit_code,
              0);
    nlohmann::json j = compare_json(a, flipped);
    ASSERT_TRUE(j["flip"].contains("mean")) << j.dump();
    EXPECT_EQ(j["flip"]["mean"].get<double>(), 0.0);
    const std::string black = write("black.exr", constant(32, 24, 0.f));
    j = compare_json(black, black);
    ASSERT_TRUE(j["flip"].contains("mean")) << j.dump();
    EXPECT_EQ(j["flip"]["mean"].get<double>(), 0.0);
    j = compare_json(black, a);
    EXPECT_NE(j["flip"]["unavailable"].get<std::string>().find("the reference is black everywhere"), std::string::npos)
        << j.dump();
}

// Each map is a PNG: a map named .exr would hold PNG bytes under an EXR name.
TEST_F(CompareCli, MapsMustBePng) {
    const std::string a = write("a.exr", constant(8, 8, 1.f));
    for (const char* option : {"--map", "--flip-map"}) {
        const fs::path map = dir_ / "m.exr";
        expect_error(a + " " + a + " " + option + " " + map.string(), std::string(option) + " " + map.string() + ": the map is written as PNG");
        EXPECT_FALSE(fs::exists(map));
    }
}

TEST_F(CompareCli, MissingChannel) {
    Image rg{4, 4, {{"R", std::vector<float>(16, 1.f)}, {"G", std::vector<float>(16, 1.f)}}};
    const std::string a = write("a.exr", constant(4, 4, 1.f)), b = write("rg.exr", rg);
    expect_error(a + " " + b, "rg.exr: no 'B' channel");
}

TEST_F(CompareCli, UnreadableOrMissingFile) {
    const std::string a = write("a.exr", constant(4, 4, 1.f));
    const fs::path junk = dir_ / "junk.exr";
    std::ofstream(junk) << "not an exr";
    expect_error(a + " " + junk.string(), "junk.exr");
    expect_error((dir_ / "missing.exr").string() + " " + a, "missing.exr");
}

TEST_F(CompareCli, FlipUnavailableKeepsOtherMetrics) {
    const std::string a = write("a.exr", constant(4, 4, 0.25f)), b = write("b.exr", constant(4, 4, 0.5f));
    nlohmann::json j = compare_json(a, b, "TESSERA_FLIP_SCRIPT=/nonexistent/flip_metric.py");
    EXPECT_NEAR(j["relmse"].get<double>(), 0.0625 / 0.0725, 1e-9);
    EXPECT_NE(j["flip"]["unavailable"].get<std::string>().find("not found"), std::string::npos) << j.dump();
    j = compare_json(a, b, "TESSERA_PYTHON=/nonexistent/python3");
    EXPECT_NE(j["flip"]["unavailable"].get<std::string>().find("python3"), std::string::npos) << j.dump();
    CliResult text = run_compare(a + " " + b, "TESSERA_FLIP_SCRIPT=/nonexistent/flip_metric.py");
    EXPECT_EQ(text.exit_code, 0) << text.output;
    EXPECT_NE(text.output.find("FLIP       unavailable: script /nonexistent/flip_metric.py not found"),
              std::string::npos)
        << text.output;
}

// A TMPDIR that is not a directory: FLIP, which needs its output files there, is
// unavailable and says why; the other metrics stand (it failed the whole run, naming
// neither TMPDIR nor its value). A full stdout fails the run: the metrics did not arrive.
TEST_F(CompareCli, FlipWithoutATemporaryDirectoryKeepsOtherMetrics) {
    const std::string a = write("a.exr", constant(4, 4, 0.25f)), b = write("b.exr", constant(4, 4, 0.5f));
    const nlohmann::json j = compare_json(a, b, "TMPDIR=/nonexistent/tmp");
    EXPECT_NEAR(j["relmse"].get<double>(), 0.0625 / 0.0725, 1e-9);
    EXPECT_NE(j["flip"]["unavailable"].get<std::string>().find("TMPDIR=/nonexistent/tmp"), std::string::npos)
        << j.dump();
    const CliResult full =
        run_shell("{ " + std::string(TESSERA_EXE) + " compare " + a + " " + b + " --json --no-flip > /dev/full; }");
    EXPECT_EQ(full.exit_code, 1) << full.output;
    EXPECT_NE(full.output.find("tessera: error: cannot write to standard output: No space left on device"),
              std::string::npos)
        << full.output;
}

// A FLIP map asked for and not written fails the run (exit 1), and leaves --map unwritten
// too (and their new directory unmade); asked for with --no-flip it is refused before any work (exit 2).
TEST_F(CompareCli, FlipMapThatCannotBeWrittenFailsTheRun) {
    const std::string a = write("a.exr", constant(4, 4, 0.25f)), b = write("b.exr", constant(4, 4, 0.5f));
    const fs::path flip_map = dir_ / "new" / "f.png", map = dir_ / "new" / "m.png";
    CliResult r = run_compare(a + " " + b + " --flip-map " + flip_map.string() + " --map " + map.string(),
                              "TESSERA_FLIP_SCRIPT=/nonexistent/flip_metric.py");
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("tessera: error: --flip-map " + flip_map.string() +
                            ": not written: FLIP did not run (script /nonexistent/flip_metric.py not found)"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "new"));  // nor the directory the maps would be in
    r = run_compare(a + " " + b + " --no-flip --flip-map " + flip_map.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--flip-map " + flip_map.string() + ": FLIP writes it, and --no-flip skips FLIP"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(flip_map));
}

// The mean FLIP `tessera compare` reports must be what the reference implementation gives
// when called directly on the same pixels, passed as raw floats (so this also checks that
// the EXR loader the script uses reads R, G, B and not, say, variance.R).
TEST_F(CompareCli, FlipMatchesReferenceImplementation) {
    if (!flip_importable()) GTEST_SKIP() << "python3 module flip_evaluator not importable";
    struct Pair { float noise; unsigned seed; };
    for (Pair p : {Pair{0.05f, 2}, Pair{0.3f, 3}, Pair{1.0f, 4}}) {
        const int w = 48, h = 32;
        const Image ref = pattern(w, h, 0.0f, 1), test = pattern(w, h, p.noise, p.seed);
        const std::string a = write("ref.exr", ref), b = write("test.exr", test);
        nlohmann::json j = compare_json(a, b);
        ASSERT_TRUE(j["flip"].contains("mean")) << j.dump();
        // Raw interleaved float32 RGB for numpy.
        auto raw = [&](const Image& img, const std::string& name) {
            std::ofstream f(dir_ / name, std::ios::binary);
            for (int i = 0; i < w * h; ++i)
                for (int c = 0; c < 3; ++c) f.write(reinterpret_cast<const char*>(&img.channels[c].data[i]), 4);
            return (dir_ / name).string();
        };
        const std::string ra = raw(ref, "ref.bin"), rb = raw(test, "test.bin");
        const std::string py =
            "import numpy as np, flip_evaluator as f\n"
            "r = np.fromfile('" + ra + "', np.float32).reshape(" + std::to_string(h) + ", " + std::to_string(w) + ", 3)\n"
            "t = np.fromfile('" + rb + "', np.float32).reshape(r.shape)\n"
            "e, m, _ = f.evaluate(r, t, 'HDR', applyMagma=False)\n"
            "e = np.asarray(e).reshape(r.shape[0], r.shape[1], -1)[:, :, 0]\n"
            "print(repr(float(m)), 100 * float(np.mean(e > 0.1)), 100 * float(np.mean(e > 0.3)))\n";
        std::ofstream(dir_ / "direct.py") << py;
        CliResult d = run_shell("python3 " + (dir_ / "direct.py").string());
        ASSERT_EQ(d.exit_code, 0) << d.output;
        double mean = 0, p1 = 0, p3 = 0;
        ASSERT_EQ(std::sscanf(d.output.c_str(), "%lf %lf %lf", &mean, &p1, &p3), 3) << d.output;
        EXPECT_GT(mean, 0.0);
        EXPECT_NEAR(j["flip"]["mean"].get<double>(), mean, 1e-6 * std::max(1.0, mean)) << "noise " << p.noise;
        EXPECT_NEAR(j["flip"]["p_gt_0_1"].get<double>(), p1, 1e-9);
        EXPECT_NEAR(j["flip"]["p_gt_0_3"].get<double>(), p3, 1e-9);
    }
}

// --cvvdp with no usable ColorVideoVDP: one error naming the option, before any work (the
// --map output is not written), whether the interpreter comes from the option or the
// environment. Without --cvvdp, compare neither needs nor runs it.
TEST_F(CompareCli, CvvdpUnavailableIsOneErrorBeforeAnyWork) {
    const std::string a = write("a.exr", constant(4, 4, 0.25f)), b = write("b.exr", constant(4, 4, 0.5f));
    const fs::path map = dir_ / "map.png";
    CliResult r = run_compare(a + " " + b + " --cvvdp --cvvdp-python /nonexistent/python3 --map " + map.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("tessera: error: --cvvdp: ColorVideoVDP is not available with /nonexistent/python3"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("relMSE"), std::string::npos) << "no metric printed:\n" << r.output;
    EXPECT_FALSE(fs::exists(map));
    r = run_compare(a + " " + b + " --cvvdp --json", "TESSERA_CVVDP_PYTHON=/nonexistent/py3");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--cvvdp: ColorVideoVDP is not available with /nonexistent/py3"), std::string::npos)
        << r.output;
    r = run_compare(a + " " + b + " --cvvdp", "TESSERA_CVVDP_SCRIPT=/nonexistent/cvvdp_metric.py");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--cvvdp: script /nonexistent/cvvdp_metric.py not found"), std::string::npos)
        << r.output;
    nlohmann::json j = compare_json(a, b + " --no-flip", "TESSERA_CVVDP_PYTHON=/nonexistent/py3");
    EXPECT_EQ(j["cvvdp"]["unavailable"], "not requested (--cvvdp)");
}

// Another command's option is named as such, not taken for a typo of one of compare's
// ("--spp: did you mean --map?").
TEST_F(CompareCli, AnotherCommandsOptionIsSaidToBeTheirs) {
    const std::string a = write("a.exr", constant(4, 4, 0.25f));
    expect_error(a + " " + a + " --spp 4", "--spp is an option of tessera render, view");
    const CliResult r = run_compare(a + " " + a + " --spp 4");
    EXPECT_EQ(r.output.find("did you mean"), std::string::npos) << r.output;
    expect_error(a + " " + a + " --mapp x.png", "--mapp: did you mean --map?");
}

TEST_F(CompareCli, CvvdpOptionsNeedCvvdp) {
    const std::string a = write("a.exr", constant(4, 4, 0.25f));
    expect_error(a + " " + a + " --cvvdp-map " + (dir_ / "m.png").string(), "--cvvdp-map");
    expect_error(a + " " + a + " --cvvdp-python python3", "--cvvdp-python");
}

// The plumbing from the script's JSON to compare's text and JSON, with a stand-in
// interpreter (a shell script) answering --check and printing fixed values.
TEST_F(CompareCli, CvvdpValuesReachTextAndJson) {
    const fs::path py = dir_ / "fakepy";
    std::ofstream(py) << "#!/bin/sh\n"
                         "[ \"$2\" = --check ] && { echo 'cvvdp 0.5.7, torch 2.9.0'; exit 0; }\n"
                         "echo '{\"jod\": 8.5, \"p_ge_1jod\": 20.25, \"p_ge_2_44jod\": 1.5, \"d_mean\": 0.08, "
                         "\"implementation\": \"cvvdp 0.5.7, torch 2.9.0\", \"viewing\": {\"display_photometry\": "
                         "\"standard_hdr_linear\", \"peak_cd_m2\": 1500, \"pixels_per_degree\": 32.45, "
                         "\"reference_mean_luminance_cd_m2\": 100}}'\n";
    ::chmod(py.c_str(), 0755);
    const std::string a = write("a.exr", constant(4, 4, 0.25f)), b = write("b.exr", constant(4, 4, 0.5f));
    nlohmann::json j = compare_json(a, b + " --no-flip --cvvdp --cvvdp-python " + py.string());
    EXPECT_EQ(j["cvvdp"]["jod"].get<double>(), 8.5);
    EXPECT_EQ(j["cvvdp"]["p_ge_1jod"].get<double>(), 20.25);
    EXPECT_EQ(j["cvvdp"]["p_ge_2_44jod"].get<double>(), 1.5);
    EXPECT_EQ(j["cvvdp"]["pixels_per_degree"].get<double>(), 32.45);
    EXPECT_EQ(j["cvvdp"]["display"], "standard_hdr_linear");
    CliResult text = run_compare(a + " " + b + " --no-flip --cvvdp", "TESSERA_CVVDP_PYTHON=" + py.string());
    EXPECT_EQ(text.exit_code, 0) << text.output;
    EXPECT_NE(text.output.find("cvvdp      8.5000 JOD, 20.250% of pixels >= 1 JOD, 1.500% >= 2.44 JOD "
                               "(ColorVideoVDP, cvvdp 0.5.7, torch 2.9.0; standard_hdr_linear display, peak 1500 "
                               "cd/m^2, 32.45 pixels/degree, reference mean 100 cd/m^2)"),
              std::string::npos)
        << text.output;
}

// Ctrl-C or SIGTERM while a metric tool runs (HDR-VDP takes minutes) ends compare by the
// signal with nothing left behind: not the map's temporary, nor the tool's captured
// output in $TMPDIR; and the tool ends with it (a `kill PID` reaches compare alone), so
// it cannot write its map again after compare removed it. The tool is asked first, with
// SIGINT as a terminal's Ctrl-C, and given time to clean up its own temporaries (here a
// trap that removes one, as Python's temporary directories are).
TEST_F(CompareCli, ASignalDuringAToolLeavesNoFile) {
    const fs::path py = dir_ / "slowpy";
    // Arguments: script, reference, test, --heatmap, map.
    std::ofstream(py) << "#!/bin/sh\n"
                         "[ \"$2\" = --check ] && { echo 'cvvdp 0.5.7'; exit 0; }\n"
                         "d=$(dirname \"$0\"); own=\"$TMPDIR/tool-own\"; touch \"$own\"\n"
                         "trap 'rm -f \"$own\"; exit 130' INT\n"
                         "echo partial > \"$5\"; echo $$ > \"$d/tool.pid\"; touch \"$d/started\"\n"
                         "for i in $(seq 200); do sleep 0.05; done\n";  // 10 s at most, if it is left running
    ::chmod(py.c_str(), 0755);
    const std::string a = write("a.exr", constant(4, 4, 0.25f)), b = write("b.exr", constant(4, 4, 0.5f));
    fs::create_directories(dir_ / "tmp");
    fs::create_directories(dir_ / "maps");
    for (const char* signal : {"TERM", "INT"}) {
        SCOPED_TRACE(signal);
        fs::remove(dir_ / "started");
        // A background job in a script starts with SIGINT ignored: --default-signal gives
        // compare the terminal's default, which it then handles.
        const CliResult r = run_shell("cd " + dir_.string() + " && (TMPDIR=" + (dir_ / "tmp").string() +
                                      " env --default-signal=INT " + TESSERA_EXE + " compare " + a + " " + b +
                                      " --no-flip --cvvdp --cvvdp-python " + py.string() +
                                      " --cvvdp-map maps/m.png & pid=$!; " +
                                      "for i in $(seq 200); do [ -e started ] && break; sleep 0.05; done; " +
                                      "kill -" + signal + " $pid; wait $pid; echo \"status $?\"; " +
                                      "kill -0 $(cat tool.pid) 2>/dev/null && echo 'tool alive')");
        ASSERT_TRUE(fs::exists(dir_ / "started")) << r.output;
        EXPECT_NE(r.output.find(std::string("status ") + (signal[0] == 'T' ? "143" : "130")), std::string::npos)
            << r.output;
        EXPECT_EQ(r.output.find("tool alive"), std::string::npos) << r.output;  // ended and reaped
        EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "maps"), {}), 0) << r.output;
        EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "tmp"), {}), 0) << r.output;  // its own one too
    }
}

// The real metric (skipped where pycvvdp does not import; set TESSERA_CVVDP_PYTHON to a
// venv's python): identical images are 10 JOD with an all-zero distortion map.
TEST_F(CompareCli, CvvdpIdenticalImagesAreTenJod) {
    if (!cvvdp_importable()) GTEST_SKIP() << cvvdp_python() << " cannot import pycvvdp";
    const std::string a = write("a.exr", pattern(64, 48, 0.0f, 1));
    const fs::path map = dir_ / "cvvdp.png";
    nlohmann::json j = compare_json(a, a + " --no-flip --cvvdp --cvvdp-map " + map.string());
    EXPECT_EQ(j["cvvdp"]["jod"].get<double>(), 10.0) << j.dump();
    EXPECT_EQ(j["cvvdp"]["p_ge_1jod"].get<double>(), 0.0);
    EXPECT_EQ(j["cvvdp"]["p_ge_2_44jod"].get<double>(), 0.0);
    EXPECT_EQ(j["cvvdp"]["d_mean"].get<double>(), 0.0);
    EXPECT_EQ(j["cvvdp"]["pixels_per_degree"].get<double>(), 32.45);
    EXPECT_EQ(j["cvvdp"]["reference_mean_luminance_cd_m2"].get<double>(), 100.0);
    EXPECT_TRUE(fs::exists(map));
}

// More noise, lower JOD and more pixels over each threshold; and since both images are
// scaled so that the reference's mean luminance is 100 cd/m^2, multiplying both by 8 (exact
// in float) leaves the verdict unchanged up to float rounding of the mean.
TEST_F(CompareCli, CvvdpFallsWithNoiseAndIgnoresOverallScale) {
    if (!cvvdp_importable()) GTEST_SKIP() << cvvdp_python() << " cannot import pycvvdp";
    const int w = 64, h = 48;
    Image ref = pattern(w, h, 0.0f, 1), weak = pattern(w, h, 0.05f, 2), strong = pattern(w, h, 0.6f, 3);
    const std::string r = write("ref.exr", ref);
    const nlohmann::json jw = compare_json(r, write("weak.exr", weak) + " --no-flip --cvvdp")["cvvdp"];
    const nlohmann::json js = compare_json(r, write("strong.exr", strong) + " --no-flip --cvvdp")["cvvdp"];
    EXPECT_LT(jw["jod"].get<double>(), 10.0);
    EXPECT_LT(js["jod"].get<double>(), jw["jod"].get<double>());
    EXPECT_GT(js["p_ge_1jod"].get<double>(), jw["p_ge_1jod"].get<double>());
    EXPECT_GT(js["p_ge_1jod"].get<double>(), 0.0);
    for (const auto* j : {&jw, &js}) {
        EXPECT_LE((*j)["p_ge_2_44jod"].get<double>(), (*j)["p_ge_1jod"].get<double>());
        EXPECT_LE((*j)["p_ge_1jod"].get<double>(), 100.0);
    }
    for (Image* img : {&ref, &strong})
        for (int c = 0; c < 3; ++c)
            for (float& v : img->channels[c].data) v *= 8.0f;
    const nlohmann::json j8 =
        compare_json(write("ref8.exr", ref), write("strong8.exr", strong) + " --no-flip --cvvdp")["cvvdp"];
    EXPECT_NEAR(j8["jod"].get<double>(), js["jod"].get<double>(), 1e-4);
    EXPECT_NEAR(j8["p_ge_1jod"].get<double>(), js["p_ge_1jod"].get<double>(), 100.0 / (w * h) + 1e-9);
}

// --hdrvdp without a usable HDR-VDP-3: one error naming the option and the reason, before
// any work (the --map output is not written). The reason is the script's: a stand-in that
// answers --check as the real one does without Octave (exit 3, the message on stderr).
TEST_F(CompareCli, HdrvdpUnavailableIsOneErrorBeforeAnyWork) {
    const std::string a = write("a.exr", constant(4, 4, 0.25f)), b = write("b.exr", constant(4, 4, 0.5f));
    const fs::path map = dir_ / "map.png";
    CliResult r = run_compare(a + " " + b + " --hdrvdp --map " + map.string(),
                              "TESSERA_HDRVDP_SCRIPT=/nonexistent/hdrvdp_metric.py");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("tessera: error: --hdrvdp: script /nonexistent/hdrvdp_metric.py not found"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(map));
    const fs::path fake = dir_ / "no_octave.py";
    std::ofstream(fake) << "import sys\nprint('hdrvdp_metric: octave-cli not found (Debian: apt-get install octave "
                           "octave-statistics octave-image)', file=sys.stderr)\nsys.exit(3)\n";
    r = run_compare(a + " " + b + " --hdrvdp --map " + map.string(), "TESSERA_HDRVDP_SCRIPT=" + fake.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--hdrvdp: HDR-VDP-3 is not available: hdrvdp_metric: octave-cli not found"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("relMSE"), std::string::npos) << "no metric printed:\n" << r.output;
    EXPECT_FALSE(fs::exists(map));
    nlohmann::json j = compare_json(a, b + " --no-flip", "TESSERA_HDRVDP_SCRIPT=" + fake.string());
    EXPECT_EQ(j["hdrvdp"]["unavailable"], "not requested (--hdrvdp)");
}

// The plumbing from the script's JSON line to compare's text and JSON, with a stand-in
// script answering --check and printing fixed values.
TEST_F(CompareCli, HdrvdpValuesReachTextAndJson) {
    const fs::path fake = dir_ / "fixed.py";
    std::ofstream(fake) << "import sys\n"
                           "if sys.argv[1] == '--check':\n    print('hdrvdp-3.0.7 in GNU Octave, version 7.3.0')\n"
                           "else:\n    print('{\"p_ge_75\": 24.25, \"p_ge_95\": 2.5, \"q_jod\": 8.125, "
                           "\"pixels_per_degree\": 32.45, \"implementation\": \"hdrvdp-3.0.7 in GNU Octave\"}')\n";
    const std::string a = write("a.exr", constant(4, 4, 0.25f)), b = write("b.exr", constant(4, 4, 0.5f));
    const std::string env = "TESSERA_HDRVDP_SCRIPT=" + fake.string();
    nlohmann::json j = compare_json(a, b + " --no-flip --hdrvdp", env);
    EXPECT_EQ(j["hdrvdp"]["p_ge_75"].get<double>(), 24.25);
    EXPECT_EQ(j["hdrvdp"]["p_ge_95"].get<double>(), 2.5);
    EXPECT_EQ(j["hdrvdp"]["q_jod"].get<double>(), 8.125);
    EXPECT_EQ(j["hdrvdp"]["pixels_per_degree"].get<double>(), 32.45);
    CliResult text = run_compare(a + " " + b + " --no-flip --hdrvdp", env);
    EXPECT_EQ(text.exit_code, 0) << text.output;
    EXPECT_NE(text.output.find("HDR-VDP-3  24.250% of pixels P >= 75%, 2.500% P >= 95%, Q 8.1250 JOD "
                               "(hdrvdp-3.0.7 in GNU Octave; 32.45 pixels/degree, reference mean 100 cd/m^2)"),
              std::string::npos)
        << text.output;
}

// The real metric (skipped where Octave, its packages or the sources are missing):
// identical images show no visible difference; noise shows some, more noise more; and as
// both images are scaled so that the reference's mean luminance is 100 cd/m^2, scaling
// both by 8 (exact in float) leaves the verdict unchanged.
TEST_F(CompareCli, HdrvdpSeesNoiseAndIgnoresOverallScale) {
    if (!hdrvdp_runs()) GTEST_SKIP() << "bench/hdrvdp_metric.py --check fails (no Octave or HDR-VDP-3 sources)";
    const int w = 64, h = 48;
    Image ref = pattern(w, h, 0.0f, 1), weak = pattern(w, h, 0.05f, 2), strong = pattern(w, h, 0.6f, 3);
    const std::string r = write("ref.exr", ref);
    const nlohmann::json same = compare_json(r, r + " --no-flip --hdrvdp")["hdrvdp"];
    EXPECT_EQ(same["p_ge_75"].get<double>(), 0.0) << same.dump();
    EXPECT_NEAR(same["q_jod"].get<double>(), 10.0, 1e-6);
    const nlohmann::json jw = compare_json(r, write("weak.exr", weak) + " --no-flip --hdrvdp")["hdrvdp"];
    const nlohmann::json js = compare_json(r, write("strong.exr", strong) + " --no-flip --hdrvdp")["hdrvdp"];
    std::printf("  HDR-VDP-3 weak noise: %s\n  strong noise: %s\n", jw.dump().c_str(), js.dump().c_str());
    EXPECT_LT(js["q_jod"].get<double>(), jw["q_jod"].get<double>());
    EXPECT_GT(js["p_ge_75"].get<double>(), jw["p_ge_75"].get<double>());
    EXPECT_LE(js["p_ge_95"].get<double>(), js["p_ge_75"].get<double>());
    for (Image* img : {&ref, &strong})
        for (int c = 0; c < 3; ++c)
            for (float& v : img->channels[c].data) v *= 8.0f;
    const nlohmann::json j8 =
        compare_json(write("ref8.exr", ref), write("strong8.exr", strong) + " --no-flip --hdrvdp")["hdrvdp"];
    EXPECT_NEAR(j8["q_jod"].get<double>(), js["q_jod"].get<double>(), 1e-4);
    EXPECT_NEAR(j8["p_ge_75"].get<double>(), js["p_ge_75"].get<double>(), 100.0 / (w * h) + 1e-9);
}
