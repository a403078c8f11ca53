// Edge samples, AIS's fourth component (docs/ais.md §9): where the base frame's pixel
// straddles a geometric edge with contrast across it, one camera sample per pixel decides
// the pixel's whole footprint and the edge stair-steps. Flagged pixels get extra camera
// samples inside the frame (selective rendering applied to pixel coverage); each sample is
// shaded with the reconstructed components of the neighbour on its surface (shading reuse,
// as subpixel reconstruction antialiasing does: Chajed and Luebke 2011), so a sample costs
// one camera path and no light or VPL rays. Host code shared by every backend: the same
// base frame gives the same schedule, bit for bit.
#pragma once
#include <cstdint>
#include <vector>

#include "gi/ais_schedule.h"
#include "gi/discontinuity_filter.h"

namespace tessera {

/// Edge settings (ours; docs/ais.md §9 gives how each was chosen).
struct EdgeSettings {
    /// Flag a pixel when the contrast across an edge in its 3×3 window exceeds this.
    /// Contrast is |Y_a − Y_b| / (Y_a + Y_b + ε) (Michelson's, in [0, 1]) for a pair of
    /// p's neighbours that a's discontinuity test rejects (edge_guidance); 0.05 is a
    /// luminance ratio of 1.1, about the visible step of a flat edge in HDR-VDP-3's model
    /// at our display luminances.
    float trigger = 0.05f;
    /// Contrast at which A gives a flagged pixel all `samples` (ratio 3:1); below it A
    /// grades the count linearly from the trigger.
    float full = 0.5f;
    /// Extra camera samples a flagged pixel takes at most (A-MAX: all of them), 1..15. 4: on
    /// Sibenik (45% of its pixels flagged, 256²) 2, 4 and 8 marked 3.34%, 3.10% and 2.93% of
    /// the pixels (HDR-VDP-3, P ≥ 75%) for 23, 35 and 75 ms of samples; on the Cornell box,
    /// office and conference 4 and 8 measured alike (docs/ais.md §9).
    uint32_t samples = 4;
    /// ε of the contrast as a fraction of the frame's mean luminance: differences in the
    /// dark, far below the frame's level, are not visible edges (scene-relative, so the
    /// same at any exposure).
    float dark = 0.01f;
};

/// Per pixel (row-major width × height) the largest contrast across an edge in its 3×3
/// window, in [0, 1]: over the pairs a, b of p's neighbours in ts_edge_pairs (both inside
/// the image; never p itself, whose own sample the merge averages) where a's
/// discontinuity test `s` rejects b (normals, plane distance, escaped rays) or the two
/// differ in `emitter`, |Y_a − Y_b| / (Y_a + Y_b + ε) with Y the luminance of `radiance`
/// (TS_PASS_FLOATS per pixel, its TS_PASS_RADIANCE) and ε = `dark` × the frame's mean Y.
/// 0 where all of p's neighbours lie on one surface. `emitter` (one byte a pixel, nonzero
/// where the camera path ends on an emitter; empty: none) adds the edges of lights that
/// lie in the plane of what holds them, which geometry does not show: a ceiling panel's
/// edge, pixels a fraction of whose footprint is a light thousands of times brighter
/// (docs/ais.md §9).
std::vector<float> edge_guidance(const GeometryBuffer& g, const DiscontinuitySettings& s,
                                 const std::vector<float>& radiance, float dark,
                                 const std::vector<uint8_t>& emitter = {});

/// ε of the edge contrast: `dark` × the mean luminance of `radiance` (TS_PASS_FLOATS per
/// pixel, its TS_PASS_RADIANCE; an image `width` pixels wide): each row summed in double in
/// pixel order (ts_edge_row_luminance, shared with the device's KernelId::EdgeRowSums),
/// the rows' sums in row order. (Until 2026-11 one double sum ran over all pixels: the two
/// can differ in a last bit on rows of very different magnitudes, and so, rarely, a
/// contrast at its trigger.) Throws std::invalid_argument unless `radiance` holds whole
/// rows of `width` pixels.
float edge_epsilon(const std::vector<float>& radiance, int width, float dark);

/// The same ε from KernelId::EdgeRowSums's output over every row of a `pixels`-pixel
/// frame (TS_EDGE_ROW_FLOATS a row, in row order): edge_epsilon's bits where the device
/// summed in double.
float edge_epsilon_of_rows(const std::vector<float>& rows, size_t pixels, float dark);

/// Which pixels take extra samples, and the flat list of samples to trace.
struct EdgeSchedule {
    /// Per pixel: extra samples taken (0 unless flagged).
    std::vector<uint8_t> samples;
    /// TS_EDGE_ITEM_WORDS uints per sample (layout_igi.h): pixel, sample index j = 1..n, n;
    /// pixels in row-major order, each pixel's samples together.
    std::vector<uint32_t> items;
    double flagged = 0;  ///< fraction of pixels flagged
};

/// Flags pixels with guidance > trigger. A-MAX: each takes `samples`; A: ⌈samples · a⌉,
/// a = (g − trigger) / (full − trigger) clamped to [0, 1] (at least one sample).
EdgeSchedule make_edge_schedule(const std::vector<float>& guidance, const EdgeSettings& e, AisMode mode);

/// Fills s.items and s.flagged from s.samples (make_edge_schedule's, or a device's
/// KernelId::EdgeSchedule counts).
void edge_schedule_items(EdgeSchedule& s);

/// The reconstructed components the samples are shaded with, 3 floats per pixel each:
/// E_ss, E_id (irradiance / π), L_pm (W/(sr·m²)) and the camera segment's transmittance.
struct EdgeShading {
    const std::vector<float>* e_ss;
    const std::vector<float>* e_id;
    const std::vector<float>* l_pm;
    const std::vector<float>* transmittance;
};

/// The window pixel whose surface sample `sample` (TS_EDGE_SAMPLE_FLOATS) lies on, for
/// pixel (x, y): among p's 3×3 neighbours (p first, then the 4 sides, then the corners)
/// those whose discontinuity test accepts the sample's surface, the one nearest to it in
/// space; none accepting, the one nearest in depth (an escaped sample: p). Returns its
/// row-major index.
size_t edge_sample_match(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y,
                         const float* sample);

/// Replaces each flagged pixel's radiance in `out` (TS_PASS_FLOATS per pixel) by the mean
/// of its base sample and its edge samples (`samples`, TS_EDGE_SAMPLE_FLOATS per item of
/// `schedule`), each shaded as L = Tr · β · (Le + ρ · (E_ss + E_id)) + L_pm with its own
/// β, Le and ρ and the matching pixel's (edge_sample_match) Tr, E_ss, E_id and L_pm:
/// the box-filtered pixel, as `pt`'s jittered samples give. Sums in double.
void merge_edge_samples(const GeometryBuffer& g, const DiscontinuitySettings& s, const EdgeSchedule& schedule,
                        const std::vector<float>& samples, const EdgeShading& shading, std::vector<float>& out);

}  // namespace tessera
