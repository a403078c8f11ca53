#include "render/accumulator.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/shared/layout_pass.h"

namespace tessera {

Accumulator::Accumulator(int width, int height)
    : width_(width), height_(height),
      sum_(size_t(width) * height * TS_PASS_FLOATS, 0.0),
      sum_sq_(size_t(width) * height * 3, 0.0),
      hits_(size_t(width) * height, 0) {}

void Accumulator::add(const std::vector<float>& pass) {
    const size_t n = size_t(width_) * height_;
    // A whole pass, or (n > 0) a radiance-only one: the same radiance sums either way.
    const size_t stride = pass.size() == n * TS_PASS_FLOATS ? TS_PASS_FLOATS : TS_PASS_RADIANCE_FLOATS;
    if (pass.size() != n * stride)
        throw std::invalid_argument("Accumulator::add: a pass of " + std::to_string(pass.size()) + " floats for " +
                                    std::to_string(width_) + "x" + std::to_string(height_) + " pixels");
    // Pixels are independent sums: in parallel (serial, a 512² pass took 3.5 ms of the
    // main thread while the workers waited), the same bits in any order.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t p = r.begin(); p < r.end(); ++p) {
            const float* in = &pass[p * stride];
            double* s = &sum_[p * TS_PASS_FLOATS];
            for (int c = 0; c < 3; ++c) {
                s[TS_PASS_RADIANCE + c] += in[TS_PASS_RADIANCE + c];
                sum_sq_[3 * p + c] += double(in[TS_PASS_RADIANCE + c]) * in[TS_PASS_RADIANCE + c];
            }
            if (stride == TS_PASS_RADIANCE_FLOATS) continue;
            for (int k = TS_PASS_ALBEDO; k < TS_PASS_DEPTH; ++k) s[k] += in[k];
            if (std::isfinite(in[TS_PASS_DEPTH])) {
                s[TS_PASS_DEPTH] += in[TS_PASS_DEPTH];
                ++hits_[p];
            }
        }
    });
    ++passes_;
}

void Accumulator::restore(uint32_t passes, std::vector<double> sums, std::vector<double> sums_of_squares,
                          std::vector<uint32_t> hit_counts) {
    if (sums.size() != sum_.size() || sums_of_squares.size() != sum_sq_.size() || hit_counts.size() != hits_.size())
        throw std::invalid_argument("Accumulator::restore: state of a different image size");
    passes_ = passes;
    sum_ = std::move(sums);
    sum_sq_ = std::move(sums_of_squares);
    hits_ = std::move(hit_counts);
}

Image Accumulator::mean_image(bool aovs, bool variance) const {
    Image img;
    img.width = width_;
    img.height = height_;
    const size_t n = size_t(width_) * height_;
    const double inv = passes_ ? 1.0 / passes_ : 0.0;
    auto channel = [&](const char* name, auto value) {
        ImageChannel c{name, std::vector<float>(n)};
        for (size_t p = 0; p < n; ++p) c.data[p] = static_cast<float>(value(p));
        img.channels.push_back(std::move(c));
    };
    const char* rgb[] = {"R", "G", "B"};
    for (int k = 0; k < 3; ++k) channel(rgb[k], [&](size_t p) { return sum_[p * TS_PASS_FLOATS + TS_PASS_RADIANCE + k] * inv; });
    if (aovs) {
        static_assert(TS_PASS_NORMAL == TS_PASS_ALBEDO + 3, "albedo and normal are adjacent");
        const char* names[] = {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z"};
        for (int k = 0; k < 6; ++k)
            channel(names[k], [&](size_t p) { return sum_[p * TS_PASS_FLOATS + TS_PASS_ALBEDO + k] * inv; });
        channel("Z", [&](size_t p) {
            return hits_[p] ? sum_[p * TS_PASS_FLOATS + TS_PASS_DEPTH] / hits_[p] : std::numeric_limits<double>::infinity();
        });
    }
    if (variance) {
        const char* names[] = {"variance.R", "variance.G", "variance.B"};
        for (int k = 0; k < 3; ++k)
            channel(names[k], [&](size_t p) {
                if (passes_ < 2) return 0.0;
                double mean = sum_[p * TS_PASS_FLOATS + TS_PASS_RADIANCE + k] * inv;
                double var = (sum_sq_[3 * p + k] * inv - mean * mean) * passes_ / (passes_ - 1.0);
                return std::max(var, 0.0) / passes_;
            });
    }
    return img;
}

}  // namespace tessera
