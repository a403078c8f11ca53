// Adaptive Interleaved Sampling (Dubla, Debattista & Chalmers; ALGORITHMS.md §2): from
// the base interleaved pass, per-component guidance maps decide where interleaving fails,
// and a schedule assigns those pixels extra sample sets. Host code shared by every
// backend and free of device-specific branches: the same base buffers always give the
// same schedule, bit for bit.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "gi/discontinuity_filter.h"

namespace tessera {

/// The components AIS guides separately: soft shadows, indirect diffuse, participating media.
enum AisComponent { kAisSS = 0, kAisID = 1, kAisPM = 2, kAisComponents = 3 };

/// A: a flagged pixel gets a number of sets graded by its guidance, s = 1 + ⌈g·(N−1)⌉.
/// A-MAX: every flagged pixel gets all N sets. (ALGORITHMS.md §2.5, reading 1.)
enum class AisMode { A, AMax };

/// Guidance thresholds; defaults from ALGORITHMS.md §2.4 [A], starting points to tune.
struct AisThresholds {
    float ss_trigger = 0.0f;  ///< SS: flag when the visibility range over A(p) exceeds this
    float id_cov = 1.0f;      ///< ID: coefficient of variation of E_id over A(p) that saturates g
    /// ID: flag when g_ID exceeds this. 0.9 (measured on the Cornell box at 512²): 0.25
    /// flagged 64% of the pixels, for set-to-set variation the filter removes anyway;
    /// 0.9 flags 10%, geometric edges and strong variation.
    float id_trigger = 0.9f;
    float pm_trigger = 0.1f;  ///< PM: flag when g_PM exceeds this
    int min_accepted = 0;     ///< |A(p)| below this counts as an unfilterable edge; 0: ⌈N/2⌉
};

/// What the base pass leaves per pixel (row-major, width × height), host side.
struct AisBaseBuffers {
    GeometryBuffer geometry;          ///< normal and depth of the first diffuse hit
    std::vector<float> visibility;    ///< SS: unoccluded fraction of the pixel's light samples
    std::vector<float> indirect;      ///< ID: luminance of the pixel's set estimate of E_id
    std::vector<float> lit_fraction;  ///< PM: lit fraction of the march steps (empty: no medium)
    std::vector<float> medium_length; ///< PM: camera-segment length inside the medium
};

/// Guidance in [0, 1] per pixel and component (an empty map for a component not computed).
struct AisGuidance {
    std::array<std::vector<float>, kAisComponents> g;
};

/// Builds the guidance maps (no rays):
///   SS: g = range of visibility over the accepted neighbours A(p) (0 in full light and
///       umbra, > 0 on penumbrae), or 1 on an edge pixel the filter cannot clean
///       (|A(p)| < min_accepted because it rejects neighbours inside the image; a window
///       clipped by the image border is no edge) whose own visibility is fractional;
///   ID: g = max(g_geo, g_var): g_geo = 1 where the filter cannot clean p or a 3×3 neighbour
///       lies across a depth or normal edge; g_var = CoV of E_id over A(p) / id_cov,
///       clamped to 1 (large in indirect shadows, corners, near VPL spikes);
///   PM: g = max(g_len, g_shaft): g_len = 1 where medium path lengths in the window
///       differ by more than the filter's relative depth threshold; g_shaft = range of the
///       lit fraction over the window (volumetric shadow boundaries).
AisGuidance compute_guidance(const AisBaseBuffers& base, const DiscontinuitySettings& filter,
                             const AisThresholds& t, const std::array<bool, kAisComponents>& enabled);

/// The extra work: for each component, each pixel's total set count (1 = the base pass
/// only, N = full rate), and the flat list of (pixel, set) evaluations to dispatch. A
/// pixel of own set k that needs s sets takes k+1, …, k+s−1 (mod N).
struct AisSchedule {
    std::array<std::vector<uint8_t>, kAisComponents> sets;
    /// Work items: the pixel index and the set to evaluate, grouped by set (coherent
    /// dispatch: consecutive items share VPLs and light samples), then by pixel.
    std::vector<uint32_t> item_pixels;
    std::vector<uint8_t> item_sets;
    /// Per item: bit c set when component c is evaluated for it.
    std::vector<uint8_t> item_components;
    /// Fraction of pixels flagged, per component.
    std::array<double, kAisComponents> flagged{};
};

AisSchedule make_schedule(const AisGuidance& guidance, const AisThresholds& t, AisMode mode, int width,
                          int height, int tile);

}  // namespace tessera
