// Adaptive Interleaved Sampling (modes A and A-MAX) as an igi-family integrator: the igi
// frame's base pass, then guidance maps and a schedule that give flagged pixels extra
// sample sets (gi/ais_schedule.h), and their reconstruction (gi/ais_reconstruct.h).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "gi/ais_schedule.h"
#include "integrators/igi_frame.h"

namespace tessera {

/// The `ais` / `ais-max` integrator; settings.ais_mode picks the mode.
class AisFrame final : public IgiFrame {
public:
    using IgiFrame::IgiFrame;

    /// IgiFrame's AOVs, then each component's guidance map and sample-set count
    /// (guidance.SS, sets.SS, ...), summed over the frames and divided by `frames`.
    void add_aov_channels(Image& image, uint32_t frames) const override;

    /// IgiFrame's line and the last frame's flagged fractions, extra sets and time.
    std::string describe() const override;

    /// The last frame's schedule.
    const AisSchedule& schedule() const { return schedule_; }
    /// The last frame's edge samples per pixel (empty without TS_COMPONENT_EDGE).
    const EdgeSchedule& edge_schedule() const { return edge_schedule_; }

protected:
    /// The schedule (AIS) and the cache (ic) are host code: components always come back.
    bool reconstructs_on_host() const override { return true; }
    void refine(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media) override;
    void reconstruct_component(int c) override;
    /// Edge samples (TS_COMPONENT_EDGE): guidance from the pass image and the G-buffer,
    /// the schedule, the samples' camera paths, their merge (gi/ais_edges.h).
    void finish(const TsFrame& frame, std::vector<float>& out) override;
    void add_to_sums() override;

private:
    void add_sets(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media);

    // Each pixel's own-set estimate and the sum over the sets it evaluated.
    std::array<std::vector<float>, kAisComponents> base_;
    std::array<std::vector<double>, kAisComponents> own_sum_;
    AisGuidance guidance_;
    AisSchedule schedule_;
    // Guidance (1 per pixel per component), then set counts, summed over frames; then the
    // edge guidance and each pixel's camera samples (1 + its edge samples).
    std::array<std::vector<double>, 8> guidance_sums_;
    std::vector<float> edge_guidance_;
    std::vector<uint8_t> emitter_;  // per pixel: the camera path ends on a light (edge_guidance)
    EdgeSchedule edge_schedule_;
    // The edge samples' kernel output, kept across passes as IgiFrame keeps surf_ (Sibenik
    // 512²: 11 MB a pass, whose fresh allocation would be zero-filled and faulted in anew).
    std::vector<float> edge_samples_;
};

}  // namespace tessera
