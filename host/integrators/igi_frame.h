// One frame of Instant Global Illumination (Wald et al. 2002) as the renderer runs it:
// VPLs (host), the per-pixel kernels (backend), the discontinuity filter and the
// composite (host). Everything but the kernels is host code shared by every backend.
// IgiFrame is the `igi` integrator and the base of the igi family: AisFrame
// (integrators/ais_frame.h) refines the components with extra sample sets, IcFrame
// (integrators/ic_frame.h) takes the indirect component from an instant cache; both through the
// protected stages below.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "backend/backend.h"
#include "gi/ais_edges.h"
#include "gi/ais_schedule.h"
#include "gi/discontinuity_filter.h"
#include "gi/vpl_generator.h"
#include "image/image_io.h"
#include "integrators/integrator.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"

namespace tessera {

/// IGI settings; docs/igi.md gives each default and its source.
struct IgiSettings {
    uint32_t tile = 3;             ///< interleave tile edge n, 1..8 (n² sample sets)
    uint32_t paths_per_set = VplSettings{}.paths_per_set;  ///< light paths (VPL sources) per set
    /// Segments per light path at most (surface hits and medium scattering events;
    /// kLightPathDepth gives the default's reason). ic/tic take it too (IcSettings).
    uint32_t light_path_depth = kLightPathDepth;
    uint32_t set_shadow_samples = 4;  ///< area-light samples per pixel (its set's share)
    uint32_t march_steps = 8;      ///< medium ray-march steps per pixel (the N sets stratify them)
    /// Geometry-term clamp b = 1 / (clamp_c · D)², D = SceneBuffers::clamp_length, the
    /// scene's bounding-box diagonal with outlying bits of surface left out
    /// (trimmed_diagonal, scene/extent.h; frame 0's in an animation whose objects move):
    /// scene-relative, so the same c gives the same image at any scale (docs/igi.md §4,
    /// default c = 0.1). clamp_c = 0 disables clamping (b = +inf).
    float clamp_c = 0.1f;
    /// Exponent a of the clamp's decay over passes: pass p uses c_p = clamp_c · (p + 1)^-a,
    /// so that an accumulation of passes converges to the unclamped (path-traced) image
    /// while every single frame keeps the clamp's low noise (docs/igi.md §4). 0: the same
    /// clamp in every pass.
    float clamp_decay = 0.25f;
    /// Return the clamp's loss where interleaved VPLs make ID (igi, ais, ais-max): the
    /// screen-space estimate of gi/clamp_screen.h, added to the reconstructed E_id
    /// (docs/igi.md §4). Where igi resolves on the device, so does the compensation
    /// (KernelId::IgiClampRecords, IgiClampGather; the same bits). false
    /// (`--no-clamp-compensation`): the clamped estimate alone.
    bool clamp_compensation = true;
    /// VPLs for the view (gi/vpl_importance.h, docs/igi.md §3b): K > 1 traces K times the
    /// light paths and keeps, on average, paths_per_set paths' worth of VPLs per set, by
    /// their importance for view_grid² view points of the frame's camera. 1: off. K = 4
    /// and 16² points: a single Cornell box frame's relMSE 21% lower and 0.1 JOD higher
    /// at 256² for ~4 ms (K = 8 gained 0.03 JOD more; 8² to 64² points measured alike).
    uint32_t vpl_importance = 4;
    uint32_t view_grid = 16;       ///< view points per image side for vpl_importance
    /// The viewer's view points across its frames (ViewPointHistory: kept while the camera
    /// moves a little, for temporal stability); null: traced for every pass, as `render`.
    std::shared_ptr<ViewPointHistory> view_history;
    bool filter = true;            ///< the discontinuity buffer (off: raw interleaved image)
    /// Media: light paths scatter in the medium and leave medium VPLs, which surfaces and
    /// the ray march gather (multiple scattering, converging to `pt`; docs/igi.md §6);
    /// false: single scattering from the lights only (converging to `pt --max-scatter 1`).
    /// Uses the ID component's VPLs.
    bool multiple_scattering = true;
    /// Media, with multiple_scattering: the ray march gathers virtual ray lights, one per
    /// light-path segment inside the medium, instead of the medium VPLs (Novák et al.
    /// 2012; docs/igi.md §6), with no clamp: a ray light spreads a point VPL's 1/d² spike
    /// along its segment. Surfaces still gather the medium VPLs. false
    /// (`--point-medium-vpls`): the march gathers the medium VPLs too, clamped to b/4.
    /// One AIS frame on five fog scenes: relMSE and FLIP lower on all five, HDR-VDP-3
    /// lower on three, for 1.1-1.3× the frame time (bench/results/ray_lights.md).
    bool ray_lights = true;
    /// Media: the ray march's light samples and VPL links at equiangular distances toward
    /// each light sample or VPL (Kulla and Fajardo 2012), the light samples combined by MIS
    /// with the phase samples at the march's points (docs/igi.md §6); false
    /// (`--uniform-march`): all of them at the march's own stratified points.
    bool equiangular = true;
    DiscontinuitySettings discontinuity;
    /// Components to compute (TS_COMPONENT_SS | _ID | _PM | _EDGE); the ones the scene does
    /// not call for are dropped anyway (no medium: no PM), and only AIS takes edge samples.
    uint32_t components = TS_COMPONENT_SS | TS_COMPONENT_ID | TS_COMPONENT_PM | TS_COMPONENT_EDGE;
    /// Bring the components to the host every frame, for the per-component AOVs
    /// (add_aov_channels) and the viewer's AOV display. false lets igi resolve its frame
    /// where the kernels ran (Backend::resolves_on_device: OpenCL's GPU variant), reading
    /// back only the pass image (AIS: also each pixel's set masks and edge-sample count); ic
    /// always reconstructs on the host.
    bool component_aovs = false;
    /// A frame resolved on the device (Backend::resolves_on_device) brings back the whole
    /// pass image, TS_PASS_FLOATS a pixel. false: the radiance alone, TS_PASS_RADIANCE_FLOATS
    /// a pixel (kernels/shared/pass_radiance.h; the same radiance bits), for a consumer that
    /// reads no albedo, normal or depth: 3.1 MB to read back at 512² instead of 10.5 MB.
    /// Frames reconstructed on the host always write the whole pass.
    bool pass_aovs = true;
    /// Adaptive Interleaved Sampling (AisFrame, ais_schedule.h): the mode and thresholds.
    AisMode ais_mode = AisMode::A;
    AisThresholds ais;
    /// AIS edge samples (TS_COMPONENT_EDGE; gi/ais_edges.h).
    EdgeSettings edges;
};

/// Timings and counts of the last frame, for the log and the benchmark. A frame resolved
/// on the device (Backend::resolves_on_device) queues its kernels without host waits: its
/// kernels' stages are their device times (Backend::kernel_seconds), its host parts wall
/// times between the reads, and filter_seconds the rest of the frame's wall time. The
/// stages do not overlap: filter_seconds (the log's "filter+composite") leaves out AIS's
/// edge samples, edge_seconds, which the log shows apart (it held them before 2026-12-02).
struct IgiFrameStats {
    double vpl_seconds = 0, surface_seconds = 0, media_seconds = 0, filter_seconds = 0;
    /// The VPL stage's parts: the view points (their camera rays), the light paths, the
    /// selection for the view, and the rest (the sets' concatenation and their upload).
    double view_seconds = 0, paths_seconds = 0, select_seconds = 0;
    /// Of paths_seconds and select_seconds, the device time of their kernels where they
    /// ran (VplList::trace_kernel_seconds, select_kernel_seconds; 0 on the host paths).
    double paths_kernel_seconds = 0, select_kernel_seconds = 0;
    /// Of filter_seconds, on a frame resolved on the device: the device time of the resolve
    /// and the clamp compensation's kernels (the rest: the image's read-back, TS_PASS_FLOATS
    /// a pixel or, without IgiSettings::pass_aovs, TS_PASS_RADIANCE_FLOATS, and the gaps);
    /// 0 on the host path.
    double resolve_kernel_seconds = 0;
    size_t vpls = 0;
    uint64_t vpl_rays = 0;   ///< light-path rays
    uint64_t pixel_rays = 0; ///< camera, shadow and VPL rays of the kernels (upper bound)
    /// PM was called for but skipped: no camera ray of the frame can meet the medium
    /// (camera_may_meet_medium, device/medium_view.h), so no ray march ran.
    bool medium_out_of_view = false;
    double ais_seconds = 0;  ///< guidance, schedule and the extra sets (AIS only)
    /// Its parts (AIS only): guidance and schedule (a device frame's: their kernels and
    /// the host's prefix sums with their upload), the extra sets' kernel launch with its
    /// read-back (on the device: kept there), and the host's merge of the extra sets into
    /// the pixels (0 on the device, which merges in the resolve).
    double ais_schedule_seconds = 0, ais_kernel_seconds = 0, ais_merge_seconds = 0;
    /// Of ais_schedule_seconds and edge_schedule_seconds, a device frame's schedule
    /// kernels (the rest: the host's prefix sums; 0 on the host path).
    double ais_schedule_kernel_seconds = 0, edge_schedule_kernel_seconds = 0;
    double cache_seconds = 0;  ///< the instant cache's indirect component (ic/tic only)
    size_t ais_items = 0;    ///< extra (pixel, set) evaluations (AIS only)
    size_t edge_samples = 0; ///< extra camera samples on edges (AIS only)
    double edge_seconds = 0; ///< edge guidance, samples and their merge (AIS only)
    double edge_schedule_seconds = 0, edge_kernel_seconds = 0;  ///< its guidance+schedule and samples parts
    std::array<double, kAisComponents> flagged{};  ///< fraction of pixels flagged (AIS only)
    double edge_flagged = 0;  ///< fraction of pixels given edge samples (AIS only)
};

class IgiFrame : public Integrator {
public:
    /// `scene` and `backend` must outlive this object.
    IgiFrame(Backend& backend, const SceneBuffers& scene, const EffectPlan& plan, const IgiSettings& settings);

    /// Geometry-term clamp b of pass 0 in scene units^-2 (+inf without clamping).
    float g_clamp() const { return g_clamp_; }
    /// Geometry-term clamp b of `pass`: b · (pass + 1)^(2a), a = clamp_decay (scene
    /// units^-2, +inf without clamping). Every igi-family pass draws its own VPLs (tic's
    /// pass p always the same ones), so the loosening clamp converges.
    float g_clamp_for(uint32_t pass) const;

    /// `frame` with the igi fields filled in as render_pass() uses them (tile, set samples,
    /// march steps, clamp, components, the frame's Cranley–Patterson shift).
    TsFrame prepare(TsFrame frame) const;

    /// A component of the last frame before filtering, 3 floats per pixel (AIS: each
    /// refined pixel's mean over its sets). An AIS frame resolved on the device leaves
    /// none here (its components stay on the device).
    const std::vector<float>& component(AisComponent c) const { return raw_[c]; }

    /// Renders frame.pass: VPLs from path block `frame.pass`, the surface kernel, the media
    /// kernel when the scene has a medium, the filter, and the composite
    ///   L = T · throughput · (Le + albedo · (Ẽ_ss + Ẽ_id)) + L̃_pm
    /// into TS_PASS_FLOATS per pixel (layout_pass.h). Fills frame's igi fields itself. Filter
    /// and composite run on the host, or, where reconstructs_on_host() is false, as
    /// KernelId::IgiResolve where the kernels ran, after IgiClampRecords and IgiClampGather
    /// when the frame compensates the clamp (same formula and sums, same image); there,
    /// without IgiSettings::pass_aovs, `out` is TS_PASS_RADIANCE_FLOATS per pixel
    /// (KernelId::IgiResolveRadiance: the same radiance).
    void render_pass(const TsFrame& frame, std::vector<float>& out) override;

    /// Per-component AOVs summed over the frames rendered so far, divided by `frames`:
    /// SS, ID (irradiance / π) and, when the scene has a medium, PM (radiance), each
    /// before and after filtering (channels SS.R, SS_filtered.R, ...).
    void add_aov_channels(Image& image, uint32_t frames) const override;
    std::vector<std::vector<double>*> aov_sums() override;

    const IgiFrameStats& stats() const { return stats_; }

    /// One line for the log: tile, VPLs, clamp and the last frame's stage times.
    std::string describe() const override;

    /// describe() and stats() into `stats` (integrators/factory.h).
    void report(IntegratorStats& stats) const override;

protected:
    /// Whether the components come to the host for reconstruction (raw_, final_, the AOV
    /// sums): always for ic, whose cache is host code; for igi and AIS unless the backend
    /// resolves on the device and no component AOVs are wanted. The device resolve
    /// compensates the clamp too (shared/igi_clamp_screen.h).
    virtual bool reconstructs_on_host() const {
        return settings_.component_aovs || !backend_.resolves_on_device();
    }
    /// Whether this frame adds the clamp's screen-space residual to E_id.
    bool compensates_clamp() const;
    /// True when the indirect component comes from the interleaved VPL sets (igi, ais);
    /// false: the surface kernel skips ID and refine() supplies it (the sets are still
    /// made when the media need them, needs_vpl_sets).
    virtual bool interleaved_indirect() const { return true; }
    /// Runs after the base pass, before reconstruction: may replace or refine the raw
    /// components (raw_). Its time is not counted as the filter's.
    virtual void refine(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media) {
        (void)frame, (void)surf, (void)media;
    }
    /// final_[c] from raw_[c]: the discontinuity filter (or a copy with the filter off).
    virtual void reconstruct_component(int c);
    /// Runs after the composite, on the pass image `out` (TS_PASS_FLOATS per pixel): may
    /// refine its radiance (AIS's edge samples). Counted as filter+composite time.
    virtual void finish(const TsFrame& frame, std::vector<float>& out) { (void)frame, (void)out; }
    /// Adds this frame's raw and final components to the AOV sums.
    virtual void add_to_sums();
    /// Appends `sum` / frames as channel `name` (channels 1) or name.R/G/B (channels 3).
    static void append_channels(Image& image, const std::vector<double>& sum, const std::string& name,
                                int channels, uint32_t frames);

    uint32_t effective_components() const;
    /// The view points of the VPL selection for `frame` (settings_.view_history's, else
    /// traced afresh).
    ViewPoints view_points(const TsFrame& frame);
    /// Whether a frame computing `components` makes the interleaved VPL sets: for ID where
    /// interleaved_indirect(), and for PM's multiple scattering (the ray march gathers the
    /// sets' VPLs, docs/igi.md §6) in every igi-family method, ic and tic included.
    bool needs_vpl_sets(uint32_t components) const;

    Backend& backend_;
    const SceneBuffers& scene_;
    EffectPlan plan_;
    IgiSettings settings_;
    float g_clamp_ = 0.0f;
    float importance_clamp_ = 0.0f;  ///< VplSettings::importance_clamp of this scene
    float march_far_ = 0.0f;
    IgiFrameStats stats_;
    // Raw and reconstructed components (3 floats per pixel each), summed over frames.
    std::array<std::vector<double>, 6> component_sums_;
    std::array<std::vector<float>, kAisComponents> raw_, final_;
    std::vector<float> transmittance_;
    std::vector<float> clamp_residual_;  ///< E_res of the last frame (compensate_clamp)
    /// compensate_clamp's scratch (the records' planes, ~10 floats a pixel), kept between
    /// frames so each reuses it rather than allocating and zeroing it again.
    std::vector<float> clamp_planes_;
    // The surface and media kernels' outputs, kept across passes: a fresh 32 MB (512², 31
    // floats a pixel) each pass cost its zero fill and page faults, ~5 ms.
    std::vector<float> surf_, media_;
    GeometryBuffer geometry_;

    /// The kernels' outputs stay where they ran; IgiResolve filters and composites there
    /// (AisFrame: its schedule's extra sets and edge samples too).
    virtual void resolve_on_device(const TsFrame& frame, const TsFrame& surface_frame, std::vector<float>& out);
    /// The device time of the last resolve of `frame` (kernel `resolve`: IgiResolve or
    /// IgiResolveRadiance) and, where the frame compensates the clamp, of its two kernels:
    /// IgiFrameStats::resolve_kernel_seconds.
    double resolve_kernels_seconds(const TsFrame& frame, KernelId resolve);
    /// The resolve that writes the frame's read-back: IgiResolve, or IgiResolveRadiance
    /// without the pass's AOVs (IgiSettings::pass_aovs).
    KernelId resolve_kernel() const {
        return settings_.pass_aovs ? KernelId::IgiResolve : KernelId::IgiResolveRadiance;
    }
    /// raw_, transmittance_ and geometry_ from the surface and media kernels' outputs.
    void extract(int width, const std::vector<float>& surf, const std::vector<float>& media);

private:
    void composite(const std::vector<float>& surf, std::vector<float>& out);
    /// Adds the clamp's screen-space residual (gi/clamp_screen.h) to final_[kAisID].
    void compensate_clamp(const TsFrame& frame, const std::vector<float>& surf);
};

}  // namespace tessera
