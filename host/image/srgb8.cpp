#include "image/srgb8.h"

#include <array>
#include <bit>
#include <cmath>
#include <limits>

namespace tessera {
namespace {

// The codes' steps and a coarse index into them (srgb8). The code rises at most 3295 per
// unit of v (255 · 12.92 on the curve's linear part; 255 · 1.055/2.4 · v^(1/2.4 − 1) just
// above it is less), so a bucket of width 1/4096 holds at most one step.
constexpr int kBuckets = 4096;

struct Steps {
    // t[k], k = 1..255: the least double whose code is at least k; t[256] = +inf.
    std::array<double, 257> t{};
    // base[i]: the code of i / kBuckets, the least v of bucket i = [i, i + 1) / kBuckets.
    std::array<std::uint8_t, kBuckets> base{};
};

Steps make_steps() {
    Steps s;
    s.t[0] = -std::numeric_limits<double>::infinity();
    s.t[256] = std::numeric_limits<double>::infinity();
    // Non-negative doubles order as their bit patterns do; code(0) = 0 < k <= code(1) = 255.
    for (int k = 1; k <= 255; ++k) {
        std::uint64_t lo = std::bit_cast<std::uint64_t>(0.0), hi = std::bit_cast<std::uint64_t>(1.0);
        while (hi - lo > 1) {
            const std::uint64_t mid = lo + (hi - lo) / 2;
            (srgb8_exact(std::bit_cast<double>(mid)) >= k ? hi : lo) = mid;
        }
        s.t[k] = std::bit_cast<double>(hi);
    }
    int k = 0;
    for (int i = 0; i < kBuckets; ++i) {
        const double v = double(i) / kBuckets;
        while (s.t[k + 1] <= v) ++k;
        s.base[i] = static_cast<std::uint8_t>(k);
    }
    return s;
}

}  // namespace

std::uint8_t srgb8_exact(double v) {
    if (!(v > 0.0)) return 0;  // also NaN
    if (v >= 1.0) return 255;
    const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(e * 255.0));
}

namespace {

const Steps& steps() {
    static const Steps s = make_steps();
    return s;
}

inline std::uint8_t code_of(const Steps& s, double v) {
    // Clamped to [0, 1) by selects, not early returns (a preview's values cross 0 and 1 at
    // random, which branches would mispredict):
    // NaN and v <= 0 to 0, v >= 1 to the double below 1, whose code is 255 as 1's is.
    const double below_one = 0x1.fffffffffffffp-1;
    const double c = v > 0.0 ? (v < 1.0 ? v : below_one) : 0.0;
    // c · 4096 is exact (a power of two) and its integer part names c's bucket, whose one
    // step, if any, is the next after its base code.
    const unsigned k = s.base[static_cast<unsigned>(c * kBuckets)];
    return static_cast<std::uint8_t>(k + (s.t[k + 1] <= c ? 1u : 0u));
}

}  // namespace

std::uint8_t srgb8(double v) { return code_of(steps(), v); }

void srgb8_encode(const float* in, std::size_t n, double scale, std::uint8_t* out, std::size_t out_stride) {
    const Steps& s = steps();
    for (std::size_t i = 0; i < n; ++i) out[i * out_stride] = code_of(s, static_cast<double>(in[i]) * scale);
}

void srgb8_encode(const double* in, std::size_t in_stride, std::size_t n, double scale, std::uint8_t* out,
                  std::size_t out_stride) {
    const Steps& s = steps();
    for (std::size_t i = 0; i < n; ++i) out[i * out_stride] = code_of(s, in[i * in_stride] * scale);
}

}  // namespace tessera
