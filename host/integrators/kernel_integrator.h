// The integrator of the methods that are one kernel launch per pass: `direct`
// (KernelId::Direct, kernels/shared/direct.h) and `pt` (KernelId::PathTrace,
// kernels/shared/pt.h; frame.max_depth and max_scatter bound the paths). Everything they
// compute is in the kernel; the frame loop accumulates the passes.
#pragma once
#include "backend/backend.h"
#include "integrators/integrator.h"

namespace tessera {

class KernelIntegrator final : public Integrator {
public:
    /// `backend` must outlive this object; `kernel` is a pixel kernel writing
    /// TS_PASS_FLOATS per pixel.
    KernelIntegrator(Backend& backend, KernelId kernel) : backend_(backend), kernel_(kernel) {}
    void render_pass(const TsFrame& frame, std::vector<float>& out) override { backend_.launch(kernel_, frame, out); }

private:
    Backend& backend_;
    KernelId kernel_;
};

}  // namespace tessera
