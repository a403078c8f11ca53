// What writing a frame's files costs (render --frames writes an EXR and a PNG preview per
// frame): write_exr with OpenEXR's thread pool off (before 2026-12-01) and on (one thread
// a hardware thread, as write_exr sets it), and the PNG preview through stb_image_write
// (before) and write_png (libpng, zlib level 3), on EXR frames given on the command
// line. Medians of --repeats writes, ms, and the files' sizes. Writes frame_output_bench.md.
#include <ImfThreading.h>
#include <stb_image_write.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/machine.h"
#include "image/atomic_file.h"
#include "image/image_io.h"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

template <class F>
double median_ms(int repeats, F&& f) {
    std::vector<double> v;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = Clock::now();
        f();
        v.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

// The preview as write_png made it before: the same sRGB bytes, stb's encoder.
void write_png_stb(const fs::path& path, const Image& image) {
    const ImageChannel* rgb[3] = {image.find("R"), image.find("G"), image.find("B")};
    const size_t pixels = size_t(image.width) * size_t(image.height);
    std::vector<std::uint8_t> px(pixels * 3);
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) {
            const double v = rgb[c]->data[i];
            const double e = !(v > 0.0) ? 0.0 : v >= 1.0 ? 1.0 : v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
            px[i * 3 + c] = static_cast<std::uint8_t>(std::lround(e * 255.0));
        }
    std::vector<unsigned char> bytes;
    stbi_write_png_to_func([](void* out, void* data, int n) {
        auto* b = static_cast<std::vector<unsigned char>*>(out);
        b->insert(b->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + n);
    }, &bytes, image.width, image.height, 3, px.data(), image.width * 3);
    write_file_atomic(path, bytes.data(), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Tessera: the cost of writing a frame's EXR and PNG preview"};
    std::vector<std::string> frames;
    std::string out_dir = "bench/results";
    int repeats = 5;
    app.add_option("exr", frames, "rendered frames (EXR) to write again")->required()->check(CLI::ExistingFile);
    app.add_option("--repeats", repeats)->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--out", out_dir)->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    const fs::path scratch = fs::temp_directory_path() / ("tessera-frame-output-" + std::to_string(::getpid()));
    fs::create_directories(scratch);
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::string md = "# Writing one frame's files (ms, median of " + std::to_string(repeats) + ")\n\nMachine: " +
                     bench::machine_description() +
                     ".\n\n| frame | size | channels | EXR, 1 thread | EXR, " + std::to_string(threads) +
                     " threads | EXR bytes | PNG, stb | PNG, write_png (libpng) | stb bytes | libpng bytes |\n"
                     "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string& path : frames) {
        const Image image = read_exr(path);
        const fs::path exr = scratch / "f.exr", png = scratch / "f.png", png_stb = scratch / "s.png";
        write_exr(exr, image);  // sets the pool once (write_exr's own call_once)
        Imf::setGlobalThreadCount(0);
        const double exr_one = median_ms(repeats, [&] { write_exr(exr, image); });
        Imf::setGlobalThreadCount(threads);
        const double exr_all = median_ms(repeats, [&] { write_exr(exr, image); });
        const double stb = median_ms(repeats, [&] { write_png_stb(png_stb, image); });
        const double lib = median_ms(repeats, [&] { write_png(png, image); });
        char row[400];
        std::snprintf(row, sizeof row, "| %s | %dx%d | %zu | %.1f | %.1f | %ju | %.1f | %.1f | %ju | %ju |\n",
                      fs::path(path).filename().c_str(), image.width, image.height, image.channels.size(), exr_one,
                      exr_all, std::uintmax_t(fs::file_size(exr)), stb, lib, std::uintmax_t(fs::file_size(png_stb)),
                      std::uintmax_t(fs::file_size(png)));
        md += row;
        std::fprintf(stderr, "%s", row);
    }
    fs::remove_all(scratch);
    fs::create_directories(out_dir);
    std::ofstream(fs::path(out_dir) / "frame_output_bench.md") << md;
    return 0;
}
