// Instant caching (ic) and temporal instant caching (tic) as an igi-family integrator:
// the igi frame with its indirect component from an InstantCache (gi/instant_cache.h)
// instead of the interleaved VPL sets, unfiltered (the cache's interpolation already
// smooths it). Direct light and media are igi's.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "gi/igi_frame.h"
#include "gi/instant_cache.h"

namespace tessera {

class IcFrame final : public IgiFrame {
public:
    /// `cache` is shared so that tic can keep it across the frames of a sequence; it
    /// must belong to the scene being rendered (its object table).
    IcFrame(Backend& backend, const SceneBuffers& scene, const EffectPlan& plan, const IgiSettings& settings,
            std::shared_ptr<InstantCache> cache)
        : IgiFrame(backend, scene, plan, settings), cache_(std::move(cache)) {}

    /// IgiFrame's line and the cache's.
    std::string describe() const override;
    /// IgiFrame's stats and the cache's.
    void report(IntegratorStats& stats) const override;

protected:
    /// The schedule (AIS) and the cache (ic) are host code: components always come back.
    bool reconstructs_on_host() const override { return true; }
    bool interleaved_indirect() const override { return false; }
    /// ic draws a new VPL set each pass; tic keeps one (and its records would go stale).
    bool clamp_decays() const override { return !cache_->temporal(); }
    void refine(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media) override;
    void reconstruct_component(int c) override;

private:
    std::shared_ptr<InstantCache> cache_;
};

}  // namespace tessera
