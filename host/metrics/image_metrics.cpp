#include "metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "util/error.h"

namespace tessera::metrics {

RgbImage rgb_for_metrics(const Image& image, const std::filesystem::path& path) {
    const ImageChannel* ch[3] = {image.find("R"), image.find("G"), image.find("B")};
    for (int c = 0; c < 3; ++c)
        if (!ch[c]) throw InputError(path.string() + ": no '" + std::string(1, "RGB"[c]) + "' channel");
    RgbImage out{image.width, image.height, {}};
    const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    out.rgb.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = ch[c]->data[i];
            if (!std::isfinite(v))
                throw InputError(path.string() + ": " + (std::isnan(v) ? "NaN" : "infinite") + " value in channel " +
                                 std::string(1, "RGB"[c]) + " at pixel (" +
                                 std::to_string(image.x0 + int(i % image.width)) + ", " +
                                 std::to_string(image.y0 + int(i / image.width)) + ")");  // the file's coordinates
            out.rgb[3 * i + c] = v;
        }
    return out;
}

void check_same_size(const RgbImage& ref, const std::filesystem::path& ref_path, const RgbImage& test,
                     const std::filesystem::path& test_path) {
    if (ref.width != test.width || ref.height != test.height)
        throw InputError("image sizes differ: " + ref_path.string() + " is " + std::to_string(ref.width) + "x" +
                         std::to_string(ref.height) + ", " + test_path.string() + " is " +
                         std::to_string(test.width) + "x" + std::to_string(test.height));
}

namespace {
void require_same_size(const RgbImage& a, const RgbImage& b) {
    if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size() || a.rgb.empty())
        throw InputError("image metrics: images must be non-empty and of the same size");
}
}  // namespace

std::vector<double> rel_se_map(const RgbImage& ref, const RgbImage& test, double eps) {
    require_same_size(ref, test);
    std::vector<double> map(ref.rgb.size() / 3);
    for (std::size_t p = 0; p < map.size(); ++p) {
        double s = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double r = ref.rgb[3 * p + c], d = test.rgb[3 * p + c] - r;
            s += d * d / (r * r + eps);
        }
        map[p] = s / 3.0;
    }
    return map;
}

double rel_mse(const RgbImage& ref, const RgbImage& test, double eps) {
    const std::vector<double> map = rel_se_map(ref, test, eps);
    double s = 0.0;
    for (double v : map) s += v;
    return s / static_cast<double>(map.size());
}

double rmse(const RgbImage& ref, const RgbImage& test) {
    require_same_size(ref, test);
    double s = 0.0;
    for (std::size_t i = 0; i < ref.rgb.size(); ++i) {
        const double d = static_cast<double>(test.rgb[i]) - ref.rgb[i];
        s += d * d;
    }
    return std::sqrt(s / static_cast<double>(ref.rgb.size()));
}

double tone_map_srgb(double x, double exposure) {
    const double v = std::clamp(x * std::exp2(exposure), 0.0, 1.0);
    if (v == 1.0) return 1.0;  // 1.055 - 0.055 rounds to 1 - 2^-53; peak must be exactly 1
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double psnr_tonemapped(const RgbImage& ref, const RgbImage& test, double exposure) {
    require_same_size(ref, test);
    double s = 0.0;
    for (std::size_t i = 0; i < ref.rgb.size(); ++i) {
        const double d = tone_map_srgb(test.rgb[i], exposure) - tone_map_srgb(ref.rgb[i], exposure);
        s += d * d;
    }
    const double mse = s / static_cast<double>(ref.rgb.size());
    if (mse == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(1.0 / mse);
}

void write_error_map_png(const std::filesystem::path& path, int width, int height, const std::vector<double>& map,
                         double lo, double hi) {
    Image img{width, height, {{"R", {}}, {"G", {}}, {"B", {}}}};
    for (auto& ch : img.channels) ch.data.resize(map.size());
    const double llo = std::log10(lo), lhi = std::log10(hi);
    // write_png applies the sRGB OETF, so colours are chosen in display space and decoded
    // to linear here; the round trip gives the intended 8-bit colour.
    auto to_linear = [](double e) { return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); };
    for (std::size_t i = 0; i < map.size(); ++i) {
        const double t = map[i] > 0.0 ? std::clamp((std::log10(map[i]) - llo) / (lhi - llo), 0.0, 1.0) : 0.0;
        const double rgb[3] = {std::clamp(3.0 * t, 0.0, 1.0), std::clamp(3.0 * t - 1.0, 0.0, 1.0),
                               std::clamp(3.0 * t - 2.0, 0.0, 1.0)};
        for (int c = 0; c < 3; ++c) img.channels[c].data[i] = static_cast<float>(to_linear(rgb[c]));
    }
    write_png(path, img, 0.0f);
}

}  // namespace tessera::metrics
