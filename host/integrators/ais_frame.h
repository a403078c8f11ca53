// Adaptive Interleaved Sampling (modes A and A-MAX) as an igi-family integrator: the igi
// frame's base pass, then guidance maps and a schedule that give flagged pixels extra
// sample sets (gi/ais_schedule.h), and their reconstruction (gi/ais_reconstruct.h).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "gi/ais_items.h"
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
    std::vector<std::vector<double>*> aov_sums() override;

    /// IgiFrame's line and the last frame's flagged fractions, extra sets and time.
    std::string describe() const override;

    /// The last frame's schedule (empty where the kernels scheduled it: resolve_on_device).
    const AisSchedule& schedule() const { return schedule_; }
    /// The last frame's edge samples per pixel (empty without TS_COMPONENT_EDGE, and where
    /// the kernels scheduled them).
    const EdgeSchedule& edge_schedule() const { return edge_schedule_; }

protected:
    /// As igi: on the device where the backend resolves there (the GPU variant) and no
    /// component AOVs are wanted. Which passes run, the thresholds and the item lists stay
    /// host decisions either way.
    bool reconstructs_on_host() const override {
        return settings_.component_aovs || !backend_.resolves_on_device();
    }
    /// The device's AIS frame: the set masks (KernelId::AisSchedule) and edge-sample counts
    /// (KernelId::EdgeSchedule) computed and kept where the kernels ran (the host's masks
    /// and counts, bit for bit), per-tile counts read back and their prefix sums sent
    /// (gi/ais_items.h), the extra sets and edge samples over exactly their items
    /// (kernels/shared/ais_compact.h, in the host list's order); the extra sets, their
    /// merge, the reconstruction, the clamp's compensation, the composite and the edge
    /// samples' merge where the kernels ran (shared/ais_resolve.h, KernelId::AisEdgeMerge):
    /// the host's image, bit for bit where the device has fp64 and rounds exp as the host
    /// does.
    void resolve_on_device(const TsFrame& frame, const TsFrame& surface_frame, std::vector<float>& out) override;
    void refine(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media) override;
    void reconstruct_component(int c) override;
    /// Edge samples (TS_COMPONENT_EDGE): guidance from the pass image and the G-buffer,
    /// the schedule, the samples' camera paths, their merge (gi/ais_edges.h).
    void finish(const TsFrame& frame, std::vector<float>& out) override;
    void add_to_sums() override;

private:
    void add_sets(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media);
    /// The guidance's inputs from the surface and media kernels' outputs (host frames).
    AisBaseBuffers base_of(const std::vector<float>& surf, const std::vector<float>& media) const;
    /// settings_.ais with id_cov scaled to the frame's paths per set.
    AisThresholds thresholds() const;
    /// Guidance and schedule from the base pass's `base` (guidance_, schedule_, stats),
    /// which lends geometry_ for the time: the extra sets' item list (TS_AIS_ITEM_WORDS
    /// per item).
    std::vector<uint32_t> schedule_sets(AisBaseBuffers base);
    /// schedule_'s item list (TS_AIS_ITEM_WORDS per item) in dispatch order (dispatch_);
    /// sets the flagged and item stats.
    std::vector<uint32_t> item_list();
    /// Edge guidance and schedule from the pass image `out` and emitter_ (edge_guidance_,
    /// edge_schedule_).
    void schedule_edges(const std::vector<float>& out);
    /// The device frame's edge samples, merged where the kernels ran into the resolved
    /// pass (IgiPass), read back into `out`.
    void edges_on_device(const TsFrame& frame, const TsFrame& ais, std::vector<float>& out);

    // Each pixel's own-set estimate and the sum over the sets it evaluated.
    std::array<std::vector<float>, kAisComponents> base_;
    std::array<std::vector<double>, kAisComponents> own_sum_;
    AisGuidance guidance_;
    AisSchedule schedule_;
    std::vector<uint32_t> dispatch_;  // the items' dispatch order (ais_dispatch_order)
    // Guidance (1 per pixel per component), then set counts, summed over frames; then the
    // edge guidance and each pixel's camera samples (1 + its edge samples).
    std::array<std::vector<double>, 8> guidance_sums_;
    std::vector<float> edge_guidance_;
    std::vector<uint8_t> emitter_;  // per pixel: the camera path ends on a light (edge_guidance)
    EdgeSchedule edge_schedule_;
    // The edge samples' kernel output, kept across passes as IgiFrame keeps surf_ (Sibenik
    // 512²: 11 MB a pass, whose fresh allocation would be zero-filled and faulted in anew).
    std::vector<float> edge_samples_;
    // A device frame's schedule: the AisScheduleTable input, KernelId::AisTileSets's
    // output read back and its offsets, KernelId::EdgeSegmentCounts's and its offsets.
    std::vector<uint32_t> schedule_table_;
    std::vector<float> tile_sets_;
    AisItemOffsets item_offsets_;
    std::vector<float> row_sums_;  // KernelId::EdgeRowSums's output, one item a row
    std::vector<float> edge_segments_;
    EdgeSegmentOffsets edge_offsets_;
};

}  // namespace tessera
