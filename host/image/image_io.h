// Image output and input. Every write is atomic: the image goes to a temporary file in
// the target directory, which is renamed over the target only after a complete,
// successful write, so a failed or interrupted run never leaves a truncated image and
// never damages an existing file.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tessera {

/// A float image with named channels, stored planar: `channels[c].data[y * width + x]`,
/// row 0 at the top. Channel names follow OpenEXR conventions ("R", "G", "B",
/// "albedo.R", "N.X", "Z", "variance.R", ...). Radiance channels are in W/(sr·m²).
struct ImageChannel {
    std::string name;
    std::vector<float> data;
};
struct Image {
    int width = 0;
    int height = 0;
    std::vector<ImageChannel> channels;
    /// Pixel coordinates of the top-left pixel: an EXR's data window minimum (0, 0 for
    /// every image Tessera renders; write_exr writes the data window there).
    int x0 = 0, y0 = 0;

    /// The channel called `name`, or nullptr.
    const ImageChannel* find(const std::string& name) const;
};

/// Writes all channels as 32-bit float OpenEXR (ZIP compression). Throws RuntimeError
/// naming `path` if the directory is missing or read-only or the disk is full; in that
/// case any existing file at `path` is left untouched.
void write_exr(const std::filesystem::path& path, const Image& image);

/// Reads every channel of an OpenEXR file as float, with the data window's origin in
/// x0, y0. Throws InputError naming `path` when the file is missing or not a readable EXR,
/// and before allocating when its data window exceeds limits::kImageSide per side or its
/// pixels times channels limits::kImageFloats (util/input_limits.h).
Image read_exr(const std::filesystem::path& path);

/// Writes an 8-bit sRGB PNG preview of channels R, G, B: each value is multiplied by
/// 2^exposure, clamped to [0, 1] and encoded with the sRGB transfer curve. Atomic, and
/// throws like write_exr.
void write_png(const std::filesystem::path& path, const Image& image, float exposure = 0.0f);

/// Writes `width` x `height` 8-bit RGBA pixels (rows top first, 4 bytes a pixel, already
/// sRGB-encoded: a window's capture) as a PNG, atomically. Throws RuntimeError naming
/// `path` for an empty image, a failed encoding, or as write_exr.
void write_png_rgba8(const std::filesystem::path& path, const std::uint8_t* rgba, int width, int height);

}  // namespace tessera
