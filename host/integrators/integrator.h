// The integrator seam: one integrator per method family behind this interface, each in
// its own file (direct and pt share the one-kernel KernelIntegrator; igi, ais, ic/tic);
// make_integrator (integrators/factory.h) picks one from the method. Integrators render
// through the generic Backend (rays, kernel launches, named inputs) and know nothing of
// the frame loop above them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/layout_pass.h"

namespace tessera {

struct IntegratorStats;  // integrators/settings.h

class Integrator {
public:
    virtual ~Integrator() = default;

    /// Renders pass frame.pass of `frame` into TS_PASS_FLOATS per pixel (layout_pass.h),
    /// row-major from the top-left pixel; the frame loop accumulates the passes. An igi-
    /// family integrator told to leave the AOVs out (IgiSettings::pass_aovs false) may write
    /// TS_PASS_RADIANCE_FLOATS per pixel instead; Accumulator::add takes either.
    virtual void render_pass(const TsFrame& frame, std::vector<float>& out) = 0;

    /// One line for the log about the last pass ("" for none).
    virtual std::string describe() const { return {}; }

    /// Writes describe() and the last pass's counts and stage times into `stats`; an
    /// integrator with none leaves it unchanged.
    virtual void report(IntegratorStats& stats) const { (void)stats; }

    /// Adds the method's own AOV channels (sums over the passes rendered so far divided by
    /// `passes`); none by default.
    virtual void add_aov_channels(Image& image, uint32_t passes) const {
        (void)image;
        (void)passes;
    }

    /// The sums add_aov_channels reads, in a fixed order, for a checkpoint to save and
    /// restore (render/checkpoint.h, MethodSums); none by default. Each is empty or holds
    /// 1 or 3 doubles per pixel.
    virtual std::vector<std::vector<double>*> aov_sums() { return {}; }
};

}  // namespace tessera
