// Progressive accumulation of per-pass outputs (TS_PASS_FLOATS per pixel) in double,
// so 2,500+ passes of float samples add up without losing precision, plus the sum of
// squares of radiance for a per-pixel variance estimate.
#pragma once
#include <cstdint>
#include <vector>

#include "image/image_io.h"

namespace tessera {

class Accumulator {
public:
    Accumulator(int width, int height);

    /// Adds one pass: width × height × TS_PASS_FLOATS floats (layout_pass.h), or a
    /// radiance-only pass of width × height × TS_PASS_RADIANCE_FLOATS (IgiSettings::pass_aovs
    /// false), which adds to the radiance sums alone: the AOV channels of mean_image are
    /// then meaningful only where every pass carried them. Throws std::invalid_argument
    /// for any other size.
    void add(const std::vector<float>& pass);

    uint32_t passes() const { return passes_; }
    int width() const { return width_; }
    int height() const { return height_; }

    /// The raw state, for checkpoints (render/checkpoint.h) and nothing else: per-pixel
    /// sums (TS_PASS_FLOATS each), sums of squared radiance (3 each) and hit counts (1
    /// each), row-major from the top-left pixel.
    const std::vector<double>& sums() const { return sum_; }
    const std::vector<double>& sums_of_squares() const { return sum_sq_; }
    const std::vector<uint32_t>& hit_counts() const { return hits_; }

    /// Replaces the whole state with one read back from a checkpoint, so that later
    /// add() calls continue exactly where the saved accumulator stopped. The vectors
    /// must have the sizes of this accumulator's (throws std::invalid_argument if not).
    void restore(uint32_t passes, std::vector<double> sums, std::vector<double> sums_of_squares,
                 std::vector<uint32_t> hit_counts);

    /// The mean image: channels R, G, B (radiance, W/(sr·m²)); with `aovs` also
    /// albedo.R/G/B, N.X/Y/Z (mean shading normal) and Z (mean first-hit distance over
    /// passes that hit, in scene units; +inf where no pass hit); with `variance`,
    /// variance.R/G/B: the sample variance of one pass's radiance divided by the pass
    /// count (the variance of the mean), 0 with fewer than 2 passes.
    Image mean_image(bool aovs, bool variance) const;

private:
    int width_, height_;
    uint32_t passes_ = 0;
    std::vector<double> sum_;      // TS_PASS_FLOATS per pixel; Z summed only over hits
    std::vector<double> sum_sq_;   // 3 per pixel: radiance squared
    std::vector<uint32_t> hits_;   // passes whose camera ray hit, per pixel
};

}  // namespace tessera
