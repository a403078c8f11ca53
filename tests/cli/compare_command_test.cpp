// `tessera compare` as a user runs it: metric values on known image pairs, FLIP against
// NVIDIA's reference implementation called directly, and clear errors for bad input.
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
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
using tessera::test::run_shell;
using tessera::test::run_tessera;

CliResult run_compare(const std::string& args, const std::string& env = "") {
    return run_shell(env + " " + std::string(TESSERA_EXE) + " compare " + args);
}

bool flip_importable() { return run_shell("python3 -c 'import flip_evaluator, numpy'").exit_code == 0; }

// A deterministic test pattern: a smooth HDR gradient with a bright patch (values up to
// ~8, as in a rendering with a light source), perturbed by `noise` of relative amplitude.
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

TEST_F(CompareCli, WritesErrorMaps) {
    const std::string a = write("a.exr", pattern(16, 16, 0.0f, 1)), b = write("b.exr", pattern(16, 16, 0.3f, 2));
    const fs::path map = dir_ / "map.png", fmap = dir_ / "flip.png";
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
