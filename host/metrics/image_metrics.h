// Full-reference image error metrics for comparing a rendering with a reference:
// relMSE, RMSE and PSNR (this file), and FLIP through NVIDIA's reference implementation
// (metrics/flip.h). Used by `tessera compare` and the accuracy sweeps (bench/accuracy).
#pragma once
#include <filesystem>
#include <vector>

#include "image/image_io.h"

namespace tessera::metrics {

/// Linear RGB radiance, interleaved (r, g, b per pixel, row 0 at the top), in W/(sr·m²).
struct RgbImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  ///< 3 * width * height values
};

/// The R, G, B channels of `image`, checked for use as a metric input. Throws InputError
/// naming `path` (the file the image came from) if a channel is missing or a value is
/// NaN or infinite: a single bad pixel would make every mean-based metric meaningless.
RgbImage rgb_for_metrics(const Image& image, const std::filesystem::path& path);

/// Throws InputError naming both files unless `ref` and `test` have the same size.
void check_same_size(const RgbImage& ref, const std::filesystem::path& ref_path, const RgbImage& test,
                     const std::filesystem::path& test_path);

/// Relative MSE (Rousselle, Knaus and Zwicker, "Adaptive sampling and reconstruction using
/// greedy error minimization", SIGGRAPH Asia 2011):
///   relMSE = mean over pixels p and channels c of (t_pc - r_pc)² / (r_pc² + eps),  eps = 0.01.
/// Dimensionless; eps keeps dark reference pixels from dominating. Same size required.
double rel_mse(const RgbImage& ref, const RgbImage& test, double eps = 0.01);

/// Per-pixel relative squared error, the mean over R, G, B of (t - r)² / (r² + eps):
/// the map whose mean is rel_mse().
std::vector<double> rel_se_map(const RgbImage& ref, const RgbImage& test, double eps = 0.01);

/// Root-mean-square error of the linear radiance, sqrt(mean over pixels and channels of
/// (t - r)²), in the images' radiance unit (W/(sr·m²)).
double rmse(const RgbImage& ref, const RgbImage& test);

/// The display tone map PSNR uses, the same as `tessera render`'s PNG preview:
/// clamp(x · 2^exposure, 0, 1), then the sRGB OETF (IEC 61966-2-1). Result in [0, 1].
double tone_map_srgb(double x, double exposure = 0.0);

/// PSNR in dB of the tone-mapped images (tone_map_srgb), peak value 1:
///   PSNR = 10 log10(1 / MSE),  MSE = mean over pixels and channels of (T(t) - T(r))².
/// +infinity when the tone-mapped images are identical.
double psnr_tonemapped(const RgbImage& ref, const RgbImage& test, double exposure = 0.0);

/// Writes `map` (one value per pixel, >= 0) as a false-colour PNG: log10 of the value from
/// `lo` (black) to `hi` (white) through red and yellow ("hot" colour map). Atomic.
void write_error_map_png(const std::filesystem::path& path, int width, int height, const std::vector<double>& map,
                         double lo = 1e-4, double hi = 1.0);

}  // namespace tessera::metrics
