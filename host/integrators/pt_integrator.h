// The `pt` method's integrator: one launch of the path-tracing kernel per pass
// (kernels/shared/pt.h; frame.max_depth and max_scatter bound the paths).
#pragma once
#include "backend/backend.h"
#include "integrators/integrator.h"

namespace tessera {

class PtIntegrator final : public Integrator {
public:
    /// `backend` must outlive this object.
    explicit PtIntegrator(Backend& backend) : backend_(backend) {}
    void render_pass(const TsFrame& frame, std::vector<float>& out) override {
        backend_.launch(KernelId::PathTrace, frame, out);
    }

private:
    Backend& backend_;
};

}  // namespace tessera
