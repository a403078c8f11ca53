// One frame of Instant Global Illumination (Wald et al. 2002) as the renderer runs it:
// VPLs (host), the per-pixel kernels (backend), the discontinuity filter and the
// composite (host). Everything but the kernels is host code shared by every backend.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "backend/backend.h"
#include "gi/ais_schedule.h"
#include "gi/discontinuity_filter.h"
#include "gi/instant_cache.h"
#include "gi/vpl_generator.h"
#include "image/image_io.h"
#include "render/effect_plan.h"
#include "render/scene_buffers.h"

namespace tessera {

/// IGI settings; docs/igi.md gives each default and its source.
struct IgiSettings {
    uint32_t tile = 3;             ///< interleave tile edge n, 1..8 (n² sample sets)
    uint32_t paths_per_set = 32;   ///< light paths (VPL sources) per set
    uint32_t set_shadow_samples = 4;  ///< area-light samples per pixel (its set's share)
    uint32_t march_steps = 8;      ///< medium ray-march steps per pixel (the N sets stratify them)
    /// Geometry-term clamp b = 1 / (clamp_c · D)², D the scene's bounding-box diagonal:
    /// scene-relative, so the same c gives the same image at any scale (docs/igi.md §4,
    /// default c = 0.05). clamp_c = 0 disables clamping (b = +inf).
    float clamp_c = 0.05f;
    bool filter = true;            ///< the discontinuity buffer (off: raw interleaved image)
    DiscontinuitySettings discontinuity;
    /// Components to compute (TS_COMPONENT_SS | _ID | _PM); the ones the scene does not
    /// call for are dropped anyway (no medium: no PM).
    uint32_t components = 7u;
    /// Adaptive Interleaved Sampling: after the base pass, guidance maps and a schedule
    /// give flagged pixels extra sample sets (ais_schedule.h); off for plain IGI.
    bool adaptive = false;
    AisMode ais_mode = AisMode::A;
    AisThresholds ais;
};

/// Timings and counts of the last frame, for the log and the benchmark.
struct IgiFrameStats {
    double vpl_seconds = 0, surface_seconds = 0, media_seconds = 0, filter_seconds = 0;
    size_t vpls = 0;
    uint64_t vpl_rays = 0;   ///< light-path rays
    uint64_t pixel_rays = 0; ///< camera, shadow and VPL rays of the kernels (upper bound)
    double ais_seconds = 0;  ///< guidance, schedule and the extra sets (AIS only)
    double cache_seconds = 0;  ///< the instant cache's indirect component (ic/tic only)
    size_t ais_items = 0;    ///< extra (pixel, set) evaluations (AIS only)
    std::array<double, kAisComponents> flagged{};  ///< fraction of pixels flagged (AIS only)
};

class IgiFrame {
public:
    /// `scene` and `backend` must outlive this object.
    IgiFrame(Backend& backend, const SceneBuffers& scene, const EffectPlan& plan, const IgiSettings& settings);

    /// Geometry-term clamp b in scene units^-2 (+inf without clamping).
    float g_clamp() const { return g_clamp_; }

    /// `frame` with the igi fields filled in as render() uses them (tile, set samples,
    /// march steps, clamp, components, the frame's Cranley–Patterson shift).
    TsFrame prepare(TsFrame frame) const;

    /// A component of the last frame before filtering, 3 floats per pixel (AIS: each
    /// refined pixel's mean over its sets).
    const std::vector<float>& component(AisComponent c) const { return raw_[c]; }

    /// Renders frame.pass: VPLs from path block `frame.pass`, the surface kernel, the media
    /// kernel when the scene has a medium, the filter, and the composite
    ///   L = T · throughput · (Le + albedo · (Ẽ_ss + Ẽ_id)) + L̃_pm
    /// into TS_PASS_FLOATS per pixel (layout.h). Fills frame's igi fields itself.
    void render(TsFrame frame, std::vector<float>& out);

    /// Per-component AOVs summed over the frames rendered so far, divided by `frames`:
    /// SS, ID (irradiance / π) and, when the scene has a medium, PM (radiance), each
    /// before and after filtering (channels SS.R, SS_filtered.R, ...); with AIS also
    /// each component's guidance map and sample-set count (guidance.SS, sets.SS, ...).
    void add_component_channels(Image& image, uint32_t frames) const;

    const IgiFrameStats& stats() const { return stats_; }

    /// One line for the log: tile, VPLs, clamp and the last frame's stage times.
    std::string describe() const;

    /// Instant caching: the indirect component comes from `cache` (not owned; it must
    /// outlive this object) instead of the interleaved VPL sets, and is not filtered (the
    /// cache's interpolation already smooths it). nullptr restores plain igi.
    void set_instant_cache(InstantCache* cache) { cache_ = cache; }

    /// The last frame's schedule (AIS only; empty otherwise).
    const AisSchedule& schedule() const { return schedule_; }

private:
    uint32_t effective_components() const;
    void extract(int width, const std::vector<float>& surf, const std::vector<float>& media);
    void refine(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media);
    void reconstruct();
    void composite(const std::vector<float>& surf, std::vector<float>& out);
    void add_to_sums();

    Backend& backend_;
    const SceneBuffers& scene_;
    EffectPlan plan_;
    IgiSettings settings_;
    float g_clamp_ = 0.0f;
    float march_far_ = 0.0f;
    IgiFrameStats stats_;
    // Raw and reconstructed components (3 floats per pixel each), summed over frames;
    // then guidance (1 per pixel per component) and set counts.
    std::array<std::vector<double>, 12> component_sums_;
    std::array<std::vector<float>, kAisComponents> raw_, final_;
    // AIS: each pixel's own-set estimate and the sum over the sets it evaluated.
    std::array<std::vector<float>, kAisComponents> base_;
    std::array<std::vector<double>, kAisComponents> own_sum_;
    std::vector<float> transmittance_;
    GeometryBuffer geometry_;
    AisGuidance guidance_;
    AisSchedule schedule_;
    InstantCache* cache_ = nullptr;
};

}  // namespace tessera
