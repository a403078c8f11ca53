// Adaptive Interleaved Sampling (Dubla, Debattista & Chalmers; docs/ais.md): from
// the base interleaved pass, per-component guidance maps decide where interleaving fails,
// and a schedule assigns those pixels extra sample sets. Host code shared by every
// backend and free of device-specific branches: the same base buffers always give the
// same schedule, bit for bit.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "gi/discontinuity_filter.h"
#include "kernels/shared/sampling.h"

namespace tessera {

/// The components AIS guides separately: soft shadows, indirect diffuse, participating media.
enum AisComponent { kAisSS = 0, kAisID = 1, kAisPM = 2, kAisComponents = 3 };

/// A: a flagged pixel gets enough of the sets its filter window is missing to hold
/// ⌈N/2⌉, plus a number graded by the signal, ⌈a·(min(G, N)−1)⌉ (make_schedule). A-MAX: every
/// flagged pixel gets all N sets. (docs/ais.md §4-5: reading 1 of A-MAX; completing
/// missing sets at edges instead of saturating them is our assumption.)
enum class AisMode { A, AMax };

/// Guidance thresholds (ours). docs/ais.md §7 gives how each default was chosen and what
/// it measured.
struct AisThresholds {
    /// SS: flag when the visibility range over A(p) exceeds this. 0.5: with 4 light
    /// samples a set, ranges of 0.25-0.5 are sample noise the filter averages.
    float ss_trigger = 0.5f;
    /// ID: the coefficient of variation of E_id over A(p) that saturates g_var, at
    /// kIdCovPaths light paths per set (AisFrame scales it by √(kIdCovPaths / paths), as
    /// the CoV that VPL noise alone gives falls as 1/√paths). 2: CoVs of about 1 are VPL
    /// noise, which the filter's N-set mean already averages (a pixel's own N sets are no
    /// less noisy).
    float id_cov = 2.0f;
    static constexpr int kIdCovPaths = 32;
    /// ID: flag when g_ID exceeds this: edges (g_geo = 1) and CoV > id_trigger · id_cov = 1.
    float id_trigger = 0.5f;
    /// PM: flag when g_PM exceeds this. 0.3: the lit fraction comes in steps of 1/march
    /// steps (0.125 at 8) and neighbours march with different offsets, so a range of one
    /// or two steps is sampling noise.
    float pm_trigger = 0.3f;
    /// PM: the coefficient of variation of the set estimates of L_pm over A(p) that
    /// saturates g_var (where the interleaved media samples disagree: shafts, medium VPL
    /// spikes, march noise); 0 turns g_var off (the seed's g_len and g_shaft alone).
    float pm_cov = 0.0f;
    int min_accepted = 0;     ///< |A(p)| below this counts as an unfilterable edge; 0: ⌈N/2⌉
    /// A: a flagged pixel evaluates the sets its filter window misses until it holds this
    /// many distinct sets (own, accepted neighbours' and its own extra ones); 0: the edge
    /// test's min_accepted (⌈N/2⌉), N: every missing set. ⌈N/2⌉ because a pixel holding
    /// that many is one the filter counts as cleanable (N_min, docs/ais.md §3); all N
    /// buys error at a worse rate than extra passes do (docs/ais.md §7).
    int complete_sets = 0;
    /// A: the set count G of the graded term, ⌈a·(min(G, N)−1)⌉ sets beyond the completed
    /// ones; 0: N (every set, the rule before it was bounded). 9, the N of the default
    /// tile (3), so the default frame is the same and a larger tile costs no more per
    /// flagged pixel: with ⌈a·(N−1)⌉ the extra work grew with N (Cornell box 512², tile
    /// 8: 703k extra set evaluations against 39k at tile 3), and the sets past 9 bought
    /// ~0.1 points of HDR-VDP-3 P ≥ 75% for 1.3–1.4× the frame time (docs/ais.md §7).
    int graded_sets = 9;
};

/// What the base pass leaves per pixel (row-major, width × height), host side.
struct AisBaseBuffers {
    GeometryBuffer geometry;          ///< normal and depth of the first diffuse hit
    std::vector<float> visibility;    ///< SS: unoccluded fraction of the pixel's light samples
    std::vector<float> indirect;      ///< ID: luminance of the pixel's set estimate of E_id
    std::vector<float> lit_fraction;  ///< PM: lit fraction of the march steps (empty: no medium)
    std::vector<float> medium_length; ///< PM: camera-segment length inside the medium
    std::vector<float> media;         ///< PM: luminance of the pixel's set estimate of L_pm (W/(sr·m²))
};

/// Guidance per pixel and component (an empty map for a component not computed), all
/// row-major width × height.
struct AisGuidance {
    /// Flag strength in [0, 1]: a pixel is flagged where g > the component's trigger
    /// (A-MAX then gives it all N sets); the `--aov guidance` view.
    std::array<std::vector<float>, kAisComponents> g;
    /// A's grade in [0, 1], the signal part of g alone (SS: visibility range; ID: g_var;
    /// PM: g_shaft): how many own sets a flagged pixel takes beyond the missing ones
    /// (make_schedule).
    std::array<std::vector<float>, kAisComponents> grade;
    /// Bit k set where the filter window holds set k on a pixel the filter rejects (the
    /// sets the discontinuity filter is missing at p; 0 inside a surface). Empty when no
    /// component is computed.
    std::vector<uint64_t> missing;
    /// Bit k set where the filter window holds set k on a pixel the filter accepts (p's own
    /// set included): the sets p's filtered estimate already has. Empty as `missing`.
    std::vector<uint64_t> held;
};

/// Builds the guidance maps (no rays):
///   SS: g = range of visibility over the accepted neighbours A(p) (0 in full light and
///       umbra, > 0 on penumbrae), or 1 on an edge pixel the filter cannot clean
///       (|A(p)| < min_accepted because it rejects neighbours inside the image; a window
///       clipped by the image border is no edge) whose own visibility is fractional;
///   ID: g = max(g_geo, g_var): g_geo = 1 where the filter cannot clean p or a 3×3 neighbour
///       lies across a depth or normal edge; g_var = CoV of E_id over A(p) / id_cov,
///       clamped to 1 (large in indirect shadows, corners, near VPL spikes);
///   PM: g = max(g_len, g_shaft, g_var): g_len = 1 where a window pixel the filter rejects
///       has a medium path length differing by more than the filter's relative depth
///       threshold (a discontinuity; smooth change along a slanted surface is not flagged);
///       g_shaft = range of the lit fraction over the window (volumetric shadow
///       boundaries); g_var = CoV of L_pm over A(p) / pm_cov, clamped to 1 (0 when pm_cov
///       is 0 or base.media is empty).
/// grade is the signal part (visibility range, g_var, max(g_shaft, g_var)); `missing` comes from the
/// filter's accept test alone. Rows are computed in parallel; each pixel's values depend
/// on the inputs only, so the result is deterministic.
AisGuidance compute_guidance(const AisBaseBuffers& base, const DiscontinuitySettings& filter,
                             const AisThresholds& t, const std::array<bool, kAisComponents>& enabled);

/// The extra work: for each component, the sets each pixel evaluates, and the flat list
/// of (pixel, set) evaluations to dispatch. A flagged pixel p with own set k gets:
///   A-MAX: all N sets;
///   A: missing sets until it holds `complete_sets` distinct sets with its accepted
///      neighbours' (each set present at most once: ais_reconstruct.h), plus ⌈a·(G−1)⌉
///      more, G = min(`graded_sets`, N), a = (grade − trigger) / (1 − trigger)
///      clamped to [0, 1], the signal's strength above its trigger; taken from the
///      window's farthest accepted neighbours first (the nearest stay in the estimate:
///      least blur). At the trigger the filter's estimate is as good as the pixel's own;
///      far above it, G sets (all N where G ≥ N).
/// Unflagged pixels keep their own set only. Tile edge n ≤ 8, so a set fits in 64 bits.
/// A guidance without `grade` maps grades by g; one without `missing` misses no sets and
/// one without `held` counts only the pixel's own set as held.
/// Tile edge (pixels) of the items' order within a set. On Sibenik at 512² (AIS, 0.8 extra
/// sets per pixel) the items' pass took 25% less time on OpenCL (PoCL packets) and about
/// 8% less on Embree with 16-pixel tiles than in scanline order; 4 to 32 measured alike.
constexpr uint32_t kItemTile = 16;

struct AisSchedule {
    /// Per component and pixel: bit j set when the pixel evaluates set j (own set included).
    std::array<std::vector<uint64_t>, kAisComponents> masks;
    /// Per component and pixel: the number of sets evaluated (popcount of the mask).
    std::array<std::vector<uint8_t>, kAisComponents> sets;
    /// Work items: the pixel index and the set to evaluate, grouped by set (coherent
    /// dispatch: consecutive items share VPLs and light samples), then by kItemTile ×
    /// kItemTile pixel tile (rows of tiles), then by pixel (so 16 consecutive items lie
    /// close on screen: their packets' rays start close together).
    std::vector<uint32_t> item_pixels;
    std::vector<uint8_t> item_sets;
    /// Per item: bit c set when component c is evaluated for it.
    std::vector<uint8_t> item_components;
    /// Fraction of pixels flagged, per component.
    std::array<double, kAisComponents> flagged{};
};

/// The interleave set of pixel (x, y) (x, y ≥ 0) for tile edge n: the kernels' own
/// ts_igi_set, (x mod n) + n·(y mod n), for the host's int indices.
inline int interleave_set(int x, int y, int n) {
    return static_cast<int>(ts::ts_igi_set(static_cast<unsigned>(x), static_cast<unsigned>(y), static_cast<unsigned>(n)));
}

AisSchedule make_schedule(const AisGuidance& guidance, const AisThresholds& t, AisMode mode, int width,
                          int height, int tile);

/// Fills s.item_pixels, item_sets and item_components from s.masks (the per-pixel part of
/// make_schedule, or a device's AisSchedule kernel): the order make_schedule documents.
void schedule_items(AisSchedule& s, int width, int height, int tile);

struct EdgeSettings;

/// The named input AisScheduleTable (layout_igi.h TS_AIS_TABLE_*) for the device's
/// KernelId::AisSchedule and KernelId::EdgeSchedule: `t` as make_schedule reads it (N_min
/// and the completed set count resolved), `mode`, the far-first set orders of tile edge
/// `tile`, the TS_COMPONENT_* bits `components` guided, the edge settings `e` and the
/// edge contrast's ε `edge_epsilon` (W/(sr·m²); edge_epsilon in gi/ais_edges.h).
std::vector<uint32_t> ais_schedule_table(const AisThresholds& t, AisMode mode, int tile, uint32_t components,
                                         const EdgeSettings& e, float edge_epsilon);

}  // namespace tessera
