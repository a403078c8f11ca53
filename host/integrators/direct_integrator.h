// The `direct` method's integrator: one launch of the direct kernel per pass
// (kernels/shared/direct.h).
#pragma once
#include "backend/backend.h"
#include "integrators/integrator.h"

namespace tessera {

class DirectIntegrator final : public Integrator {
public:
    /// `backend` must outlive this object.
    explicit DirectIntegrator(Backend& backend) : backend_(backend) {}
    void render_pass(const TsFrame& frame, std::vector<float>& out) override {
        backend_.launch(KernelId::Direct, frame, out);
    }

private:
    Backend& backend_;
};

}  // namespace tessera
