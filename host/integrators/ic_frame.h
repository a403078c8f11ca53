// Instant caching (ic) and temporal instant caching (tic) as an igi-family integrator:
// the igi frame with its indirect component from an instant cache (gi/instant_cache.h),
// one per pass (gi/ic_passes.h), instead of the interleaved VPL sets: the cache's E
// unfiltered (its interpolation already smooths it), plus the clamp's residual through the
// discontinuity filter (one ray a pixel, docs/instant-caching.md §9). Direct light and
// media are igi's (the media gather igi's VPL sets for multiple scattering, as in every
// igi-family method).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "gi/ic_passes.h"
#include "integrators/igi_frame.h"

namespace tessera {

class IcFrame final : public IgiFrame {
public:
    /// `caches` is shared so that tic can keep them across the frames of a sequence; they
    /// must belong to the scene being rendered (its object table).
    IcFrame(Backend& backend, const SceneBuffers& scene, const EffectPlan& plan, const IgiSettings& settings,
            std::shared_ptr<IcPassCaches> caches)
        : IgiFrame(backend, scene, plan, settings), caches_(std::move(caches)) {}

    /// IgiFrame's line and the caches', summed over the passes this frame rendered.
    std::string describe() const override;
    /// IgiFrame's stats and the caches' (summed over this frame's passes).
    void report(IntegratorStats& stats) const override;

protected:
    /// The schedule (AIS) and the cache (ic) are host code: components always come back.
    bool reconstructs_on_host() const override { return true; }
    bool interleaved_indirect() const override { return false; }
    void refine(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media) override;
    void reconstruct_component(int c) override;

private:
    std::shared_ptr<IcPassCaches> caches_;
    IcFrameStats frame_stats_;  // summed over the passes rendered
    // The last pass's ID parts (3 floats per pixel): the cache's E, the clamp's residual
    // (raw_[kAisID] is their sum) and the residual filtered.
    std::vector<float> cached_, residual_, filtered_;
    uint32_t passes_ = 0, released_ = 0;
};

}  // namespace tessera
