// Linear values to 8-bit sRGB codes for the PNG preview (write_png): the exact curve, and
// the same codes from the places where the code steps up.
#pragma once
#include <cstddef>
#include <cstdint>

namespace tessera {

/// The 8-bit sRGB code of a linear value v (already scaled by the exposure): 0 for v <= 0
/// and NaN, 255 for v >= 1, else round(255 · OETF(v)) with the exact IEC 61966-2-1 curve
/// (12.92 v up to 0.0031308, 1.055 v^(1/2.4) − 0.055 above) in double.
std::uint8_t srgb8_exact(double v);

/// srgb8_exact(v) without a pow: the code is the number of steps t_k <= v, where t_k
/// (k = 1..255) is the least double whose code is at least k, read from a 4096-bucket
/// index of [0, 1) and one comparison (a bucket holds at most one step). The steps are
/// found once, by bisection over the bit patterns of the doubles in [0, 1], on first use
/// (thread-safe). Equal to srgb8_exact wherever that is non-decreasing:
/// tests/image/srgb8_test.cpp checks around every step, and every float of [0, 1] was
/// checked once (2026-12-02).
std::uint8_t srgb8(double v);

/// out[i · out_stride] = srgb8(double(in[i]) · scale) for i < n: one channel of a preview.
/// A 512² RGB preview's encoding: ~25 ms with srgb8_exact, 2-3 ms so
/// (bench/results/frame_output.md).
void srgb8_encode(const float* in, std::size_t n, double scale, std::uint8_t* out, std::size_t out_stride);

/// out[i · out_stride] = srgb8(in[i · in_stride] · scale) for i < n: one channel read from
/// interleaved doubles (the viewer's display of its accumulated sums).
void srgb8_encode(const double* in, std::size_t in_stride, std::size_t n, double scale, std::uint8_t* out,
                  std::size_t out_stride);

}  // namespace tessera
