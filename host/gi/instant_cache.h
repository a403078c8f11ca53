// Instant caching (Debattista, Dubla et al., CGF 2009) and its temporal form: the
// indirect diffuse component of an igi frame read from an irradiance cache whose records
// gather from the VPLs of one path subset (docs/instant-caching.md). Host code shared by
// every backend: record placement, the visibility bookkeeping and the temporal update's
// decisions run here; the G-buffer, the record–VPL shadow rays and gather sums
// (KernelId::IcPair and IcGather, launched through gi/ic_gather.h) and the interpolation
// (KernelId::IcInterpolate) run on the backend.
//
// Choices the paper does not fix for us (docs/instant-caching.md marks them ours), and why:
// - Radius: the harmonic mean distance to the VPLs a record sees, clamped to 1.5–20 pixel
//   footprints; it needs no rays beyond the gather (Ward's hemisphere probe would add 32 a
//   record), and the clamp dominates in open areas anyway.
// - Weight: Ward's, shifted by 1/a so records fade out at their validity edge (no seams);
//   no gradients (records are dense enough at a = 0.3; measured error in the tests).
// - Records keep the occluding object of every record–VPL pair (not one visibility bit):
//   the temporal update then knows which pairs a moving object can change (exact, see
//   temporal_update.cpp). 4 bytes a pair: 20k records × 400 VPLs = 32 MB.
// - Temporal invalidation re-traces a whole light path (same Halton point) rather than from
//   the first invalid vertex, and re-traces suspect shadow rays in the full scene rather
//   than against the moved object alone: simpler, still exact, and it costs light-path rays
//   (hundreds a frame) and only the shadow rays the bounding-box test lets through.
// - Every backend sees the same records: placement reads the G-buffer on the host and the
//   octree lookup is one function (shared/ic_lookup.h) for host and kernels.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "backend/backend.h"
#include "gi/ic_gather.h"
#include "gi/irradiance_cache.h"
#include "gi/light_paths.h"
#include "gi/vpl_importance.h"
#include "device/scene_buffers.h"
#include "scene/scene.h"

namespace tessera {

/// Settings; defaults from docs/instant-caching.md (ours, not the paper's).
struct IcSettings {
    uint32_t paths = 256;        ///< N_p light paths a record gathers from
    /// M path subsets a pass draws (M·N_p paths); each record gathers from one, chosen by a
    /// hash of its 16×16-pixel block and placement level (docs/instant-caching.md §2b).
    /// 0 = 1 here; the renderer sets it from the spp and image size (resolve_ic_subsets)
    /// unless --ic-subsets gives it.
    uint32_t subsets = 0;
    /// K: a pass draws K·N_p candidate paths a subset and keeps N_p paths' worth of VPLs
    /// for the view (select_paths; 1: the paths as drawn). 8, twice igi's VPL K, because
    /// the view rays below make more candidates pay (docs/instant-caching.md §2).
    uint32_t path_importance = 8;
    /// S: shadow rays a candidate VPL traces toward the view points it would light, so a
    /// path whose VPLs the view cannot see weighs nothing (vpl_view_importance; 0: off).
    uint32_t view_rays = 2;
    float error_bound = 0.3f;    ///< Ward's a: a record serves points with ε < a (shared/ic_lookup.h)
    float min_radius_px = 1.5f;  ///< record radius bounds in pixel footprints (ic_record_radius); the
                                 ///< probe's bound goes below the lower one (InstantCache::radius_of)
    float max_radius_px = 20.0f;
    bool temporal = false;       ///< tic: keep VPL paths, records and visibility across frames
    /// tic: a record outside the view frustum for this many frames in a row is evicted
    /// (docs/instant-caching.md §8): without it a moving camera
    /// grows the cache, and the per-frame update with it, without bound.
    uint32_t evict_after_frames = 30;
    bool multiple_scattering = true;   ///< light paths scatter in the medium (IgiSettings)
    uint32_t light_path_depth = kLightPathDepth;  ///< segments per light path (IgiSettings)
    /// Add to each pixel an estimate of what the geometry-term clamp removed from its
    /// indirect light (kernels/shared/ic_residual.h, docs/instant-caching.md §9): up to two
    /// rays and two shadow rays a pixel and pass. Without it the clamp darkens corners
    /// (two-rooms at 16 spp: 5% in a corner region, averaged over seeds).
    bool clamp_compensation = true;
};

/// How the cache draws fresh light paths (docs/instant-caching.md §2): as they come, or
/// kept for the view (IcSettings::path_importance).
struct IcPathSelection {
    /// K > 1 (with `view`): K·paths candidate paths, of which select_paths keeps paths'
    /// worth on average; 1: the paths as drawn.
    uint32_t oversampling = 1;
    const ViewPoints* view = nullptr;  ///< the frame's view points (trace_view_points)
    float importance_clamp = 0.0f;     ///< vpl_view_importance's g_clamp, scene units^-2
    uint32_t view_rays = 0;            ///< IcSettings::view_rays
};

/// Counts and times of the last indirect() call (one pass), or summed over a frame's
/// passes (IcFrame; records then counts each pass's cache).
struct IcFrameStats {
    size_t records = 0, created = 0, removed = 0, resummed = 0;
    size_t resummed_by_change = 0;  ///< of resummed: over the changed VPLs only (tic; IcGatherSums)
    size_t evicted = 0;  ///< records dropped for being out of view (tic)
    /// tic: records whose rows were re-made from runs of kept columns (a re-traced path
    /// changed its VPL count), not moved over as they were
    size_t rows_remade = 0;
    size_t vpls = 0, paths_retraced = 0, vpls_changed = 0;
    uint64_t light_path_rays = 0;  ///< rays of (re-)traced light paths
    uint64_t shadow_rays = 0;      ///< record–VPL shadow rays
    uint64_t probe_rays = 0;       ///< the new records' hemisphere probes (gi/ic_probe.h)
    uint64_t view_rays = 0;        ///< the path selection's VPL–view point shadow rays (IcSettings::view_rays)
    size_t fallback_pixels = 0;    ///< pixels the kernel found uncovered (rounding), shaded on the host
    double update_seconds = 0, place_seconds = 0, interpolate_seconds = 0;
    /// Of update and placement: the record–VPL shadow rays (the pair lists, the pair
    /// kernel and the rows' write-back), of it the kernel's launch with its transfers; the
    /// new records' probes; the gathers (visibility packed, the gather kernel), of it the
    /// kernel's launch. What a GPU still leaves to the host is the difference.
    double pair_seconds = 0, pair_kernel_seconds = 0, probe_seconds = 0, gather_seconds = 0,
           gather_kernel_seconds = 0;
    /// Of placement: the octree's rebuild, and the coverage tests of its four levels.
    double octree_seconds = 0, coverage_seconds = 0;
    uint64_t indirect_rays() const { return light_path_rays + view_rays + shadow_rays + probe_rays; }
    IcFrameStats& operator+=(const IcFrameStats& o);
};

/// The path subsets M the renderer gives ic and tic at `spp` passes on an image of `pixels`
/// when --ic-subsets is 0 (docs/instant-caching.md §2b): 1 below 4 spp, where each
/// record's own VPL noise would show as record-shaped blotches, 2 below 16 spp; from 16
/// spp 16 on images of at least kIcManySubsetsPixels, else 4.
uint32_t ic_subsets_for(uint32_t spp, uint64_t pixels);

/// The path subset, of `subsets` M ≥ 1, that the records of image block `block` (the
/// Morton code of a 16×16-pixel block) at placement level `level` (its grid stride) gather
/// from in pass `pass` with seed `seed` (docs/instant-caching.md §2b). Each run of M
/// consecutive blocks (block / M equal: a 4×4 square of blocks at M = 16, 2×2 at M = 4)
/// holds every subset once, in an order drawn per run, level, pass and seed; 0 when M is 1.
uint32_t ic_record_subset(uint32_t subsets, uint32_t level, uint32_t block, uint32_t pass, uint32_t seed);
/// The smallest image on which M = 16 pays (2^16 pixels: 256²; the two rooms' 384×256
/// has 1.5× that): a 4×3 region of it holds ~20 or more of the 16-pixel blocks that share
/// a subset, and the records outweigh the light paths. At 128×96 M = 16 cost 1.3-1.6×
/// M = 4 for a region error barely lower (bench/results/ic_subsets_128x96.md).
inline constexpr uint64_t kIcManySubsetsPixels = uint64_t(1) << 16;

/// One log line: the cache's settings and `stats` (one pass, or summed over `passes`).
std::string describe_ic(const IcSettings& settings, const IcFrameStats& stats, uint32_t passes);

/// Visibility of one record–VPL pair, as kept per record (one int32 per VPL; the bits of
/// the pair kernel's TS_IC_PAIR_FACING and TS_IC_PAIR_VISIBLE, layout_ic.h):
/// kIcFacing = the geometry term is 0 (no ray needed), kIcVisible = unoccluded, ≥ 0 the
/// object (Scene::objects index) the shadow ray hits, the one its any-hit query found
/// (any occluder serves the temporal update: docs/instant-caching.md §3).
constexpr int32_t kIcFacing = -2;
constexpr int32_t kIcVisible = -1;

/// Sets `gbuffer` to the ic G-buffer (TS_IC_GBUF_FLOATS per pixel, layout_ic.h) of the igi
/// surface pass's output `surf` (TS_IGI_SURF_FLOATS per pixel): each pixel's first
/// diffuse surface, or TS_NO_HIT where the camera path found none or one of albedo 0 (no
/// record serves it). The surface pass has traced the camera rays already; the cache
/// reads its surfaces instead of tracing them again.
void ic_gbuffer_from_surface(const std::vector<float>& surf, std::vector<float>& gbuffer);

class InstantCache {
public:
    /// `objects` are the scene's (stable over an animation); empty = one object.
    InstantCache(const IcSettings& settings, const std::vector<SceneObject>& objects);

    /// E_id (irradiance / π, 3 floats per pixel) for `frame` (prepared by the igi frame).
    /// The light paths are path block frame.pass drawn with frame.seed. Non-temporal: a
    /// fresh cache every call. Temporal: on the first call a fresh cache, later the changes
    /// since the previous call (moved objects, materials, lights) are applied first
    /// (docs/instant-caching.md §8); every call must then be for the same pass and seed
    /// (one cache per pass: IcPassCaches), or std::logic_error is thrown.
    /// `surf` is the igi surface pass's output for `frame` (TS_IGI_SURF_FLOATS per pixel,
    /// row-major): the surfaces records are made at and looked up for. `g_clamp` is the
    /// igi geometry-term bound b. `selection` says how fresh light paths are drawn (read
    /// only when draws_paths()); a temporal cache keeps the kept paths and their weights.
    /// `gbuffer` is scratch (its contents are overwritten). `residual` gets, 3 floats per
    /// pixel, the estimate of what the clamp removed (irradiance / π, kernels/shared/
    /// ic_residual.h; zeros with IcSettings::clamp_compensation off): E_id + residual is
    /// the pixel's estimate; the residual alone is noisy per pixel, and a caller may filter it.
    void indirect(Backend& backend, const SceneBuffers& scene, const TsFrame& frame, const std::vector<float>& surf,
                  float g_clamp, const IcPathSelection& selection, std::vector<float>& gbuffer,
                  std::vector<float>& e_id, std::vector<float>& residual);

    /// Whether the next indirect() draws fresh light paths (every call but a temporal
    /// cache's updates): only then is its IcPathSelection read.
    bool draws_paths() const { return !settings_.temporal || !have_previous_; }

    /// The current records (same surfaces) with E and R recomputed from scratch on
    /// `scene`: fresh light paths (same indices), every shadow ray traced. The temporal
    /// update must equal this.
    std::vector<IcRecord> rebuilt_records(Backend& backend, const SceneBuffers& scene, float g_clamp) const;

    /// The light paths the VPLs come from (the kept ones, with their weights).
    const std::vector<LightPath>& paths() const { return paths_; }
    /// The VPLs the records gather from (TS_VPL_FLOATS each, in path order).
    const std::vector<float>& vpls() const { return vpls_; }
    const IrradianceCache& cache() const { return cache_; }
    const IcFrameStats& stats() const { return stats_; }
    bool temporal() const { return settings_.temporal; }
    const IcSettings& settings() const { return settings_; }
    /// M: the path subsets of each pass (IcSettings::subsets, at least 1).
    uint32_t subsets() const { return settings_.subsets > 1 ? settings_.subsets : 1u; }
    /// The VPL columns of subset s of the current light paths: [offsets[s], offsets[s + 1]).
    const std::vector<size_t>& subset_vpls() const { return subset_vpls_; }
    /// Record–VPL visibilities kept (4 bytes each): each record's row spans its subset's
    /// VPLs only.
    size_t pairs_kept() const;
    std::string describe() const { return describe_ic(settings_, stats_, 1); }

private:
    struct Pair {
        uint32_t record, vpl;
    };
    using Row = std::vector<int32_t>;
    struct Change;  // what differs from the previous frame (temporal_update.cpp)
    struct ChangedVpls;  // the VPLs that changed in a temporal update (temporal_update.cpp)
    static ChangedVpls changed_vpls(const std::vector<float>& old_vpls, const std::vector<float>& vpls,
                                    const std::vector<int64_t>& old_column);
    void resum_by_change(Backend& backend, const std::vector<float>& old_vpls, const ChangedVpls& changed,
                         const std::vector<uint32_t>& minus, const std::vector<std::vector<Pair>>& per_record,
                         float g_clamp);

    void start_paths(Backend& backend, const SceneBuffers& scene, uint32_t block, const IcPathSelection& selection);
    LightPathSettings path_settings() const;
    /// Probes records[which[k]] (their pixel_size set) into their `probe` field; returns rays.
    uint64_t probe(Backend& backend, std::vector<IcRecord>& records, const std::vector<uint32_t>& which) const;
    /// R_i of `r` from the harmonic mean distance to its visible VPLs and its probe
    /// (docs/instant-caching.md §4).
    float radius_of(const IcRecord& r, float harmonic_mean) const;
    void concat_vpls();
    /// The VPL column offsets of the M subsets of `paths` (subset_vpls), the paths of pass
    /// block pass_ with oversampling_ candidates a path.
    std::vector<size_t> subset_offsets(const std::vector<LightPath>& paths) const;
    /// ic_record_subset with this cache's M, pass and seed.
    uint32_t record_subset(uint32_t level, uint32_t block) const {
        return ic_record_subset(subsets(), level, block, pass_, seed_);
    }
    /// The first VPL column of the subset of `r` among the subsets `offsets`
    /// (subset_offsets): its row's entry k is the visibility of column first + k.
    static size_t row_first(const IcRecord& r, const std::vector<size_t>& offsets) { return offsets.at(r.subset); }
    /// The VPL columns of the subset of `r`: its row's length.
    static size_t row_size(const IcRecord& r, const std::vector<size_t>& offsets) {
        return offsets.at(r.subset + 1) - offsets.at(r.subset);
    }
    /// The most VPLs a subset of `offsets` has: what a row may hold.
    static size_t widest_subset(const std::vector<size_t>& offsets);
    void place(Backend& backend, const std::vector<float>& gbuffer, const TsFrame& frame, float g_clamp,
               const SceneBounds& bounds);
    std::vector<uint8_t> covered(IrradianceCache& cache, const std::vector<float>& gbuffer,
                                 const std::vector<uint32_t>& pixels) const;
    uint64_t trace_pairs(Backend& backend, const std::vector<float>& vpls, const std::vector<Pair>& pairs,
                         float g_clamp, std::vector<std::vector<int32_t>>& rows) const;
    /// The pairs of `records` with the VPLs of each one's subset (`offsets`, subset_offsets).
    uint64_t trace_pair_grid(Backend& backend, const std::vector<float>& vpls, const std::vector<size_t>& offsets,
                             const std::vector<uint32_t>& records, float g_clamp,
                             std::vector<std::vector<int32_t>>& rows) const;
    /// trace_pair_grid for the records of one subset and its VPL columns [first, end).
    uint64_t trace_subset_grid(Backend& backend, const std::vector<float>& vpls, size_t first, size_t end,
                               const std::vector<uint32_t>& records, float g_clamp,
                               std::vector<std::vector<int32_t>>& rows) const;
    template <class Launch, class Write>
    uint64_t trace_in_batches(size_t total, Launch&& launch, Write&& write) const;
    int32_t row_code(uint32_t hit) const;
    /// Writes the gather kernel's visibility mask of item k (TS_IC_VISIBLE_WORDS(VPLs) uints, zeroed).
    using MaskFill = std::function<void(size_t k, uint32_t* mask)>;
    /// The gather kernel over records[which[k]] with the masks `fill` writes:
    /// TS_IC_GATHER_FLOATS outputs per k (layout_ic.h).
    std::vector<float> gather_outputs(Backend& backend, const std::vector<float>& vpls,
                                      const std::vector<IcRecord>& records, const std::vector<uint32_t>& which,
                                      float g_clamp, const MaskFill& fill) const;
    /// Gathers records[which[k]] over the VPLs their rows (over the subsets `offsets`) mark
    /// visible, in launches grouped by subset: sets their E and
    /// returns their harmonic mean distances; their sums go to (*sums)[which[k]] if given.
    std::vector<float> gather(Backend& backend, const std::vector<float>& vpls, const std::vector<size_t>& offsets,
                              const std::vector<Row>& rows, std::vector<IcRecord>& records,
                              const std::vector<uint32_t>& which, float g_clamp,
                              std::vector<IcGatherSums>* sums = nullptr) const;
    void update(Backend& backend, const SceneBuffers& scene, float g_clamp);
    void snapshot(const SceneBuffers& scene, float g_clamp);
    void mark_in_view(const TsFrame& frame);
    void evict_out_of_view();
    uint32_t object_of(uint32_t triangle) const;
    /// Throws RuntimeError when records × vpls visibilities exceed kMaxPairs (with vpls
    /// the widest subset's VPLs: a bound on what the rows hold).
    static void check_pairs(size_t records, size_t vpls);
    /// Record–VPL visibilities the cache may keep: 4 bytes each, so 2 GiB (ten times what
    /// 512² at the default settings needs; a guard against --ic-paths in the tens of thousands).
    static constexpr size_t kMaxPairs = size_t(1) << 29;

    IcSettings settings_;
    std::vector<uint32_t> object_first_;  // first triangle of each object, increasing
    IrradianceCache cache_;
    std::vector<LightPath> paths_;
    std::vector<float> vpls_;
    std::vector<size_t> subset_vpls_;          // subset_vpls()
    std::vector<std::vector<int32_t>> rows_;  // per record, one entry per VPL of its subset (row_first)
    std::vector<IcGatherSums> sums_;          // per record, its gather's sums (the temporal update adds to them)
    IcFrameStats stats_;
    // The stage times of the const helpers (trace_pairs, probe, gather), copied into stats_.
    struct StageTimes {
        double pairs = 0, pair_kernel = 0, probe = 0, gather = 0, gather_kernel = 0;
    };
    mutable StageTimes times_;
    uint32_t pass_ = 0, seed_ = 1;  // the path block and seed of the current light paths
    uint32_t oversampling_ = 1;     // K of the current light paths: each candidate weighs 1/(K·paths)
    // The previous frame, for the temporal update.
    bool have_previous_ = false;
    uint32_t frame_count_ = 0;  // indirect() calls so far
    std::vector<float> prev_tri_pos_, prev_materials_, prev_lights_, prev_light_cdf_;
    float prev_g_clamp_ = 0.0f;
};

}  // namespace tessera
