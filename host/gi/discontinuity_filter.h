// The discontinuity buffer (Keller's thesis 1998; used by IGI, Wald et al. 2002): an n×n
// box filter over interleaved estimates that averages a pixel only with neighbours on
// the same surface, so the structured noise of interleaved sampling goes away while
// edges stay sharp. Host code shared by every backend; the window and the acceptance
// test are kernels/shared/discontinuity.h's, which the device resolve
// (kernels/shared/igi_resolve.h) uses too.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/shared/discontinuity.h"

namespace tessera {

/// Thresholds: a neighbour q of pixel p is accepted when n_p · n_q >= normal_cos and q's
/// point lies within depth_rel · z_p of p's tangent plane, |n_p · (x_q - x_p)| (or, where
/// the buffer has no positions, |z_p - z_q|) <= depth_rel · z_p. The plane distance is 0
/// across a plane seen at any slant, where a depth difference grows with the slant and
/// would flag plain walls seen at grazing angles as edges; it separates parallel surfaces
/// at different depths as the depth test does. Defaults (ours, docs/igi.md §8): 0.9
/// (normals within about 26°, looser than a curved surface's change across a 3-pixel
/// window at typical distances, tighter than any crease) and 5% of the depth (below the
/// step of a contact edge seen from a few scene units).
struct DiscontinuitySettings {
    int tile = 3;             ///< window edge n: every n×n window holds each sample set once
    float normal_cos = 0.9f;
    float depth_rel = 0.05f;
};

/// Per-pixel geometry of the first diffuse hit: unit normal (3 floats), distance (+inf
/// where the camera ray escaped) and, optionally, the hit position (3 floats, world
/// space; empty: the filter falls back to the depth test). Row-major, width × height.
struct GeometryBuffer {
    int width = 0, height = 0;
    std::vector<float> normal;
    std::vector<float> depth;
    std::vector<float> position;
    /// Optional (discontinuity_precompute): per pixel, the positions of its window that it
    /// accepts, bit i = (dy − lo)·n + (dx − lo) (itself included, positions outside the
    /// image clear), for the settings in `accepted_for`. The filter of each component and
    /// AIS's guidance and reconstruction read it instead of repeating the test per pair.
    std::vector<uint64_t> accepted;
    DiscontinuitySettings accepted_for{0, 0.0f, 0.0f};
};

/// Fills g.accepted for `s` (s.tile ≤ 8: 64 window positions), one test per pair.
void discontinuity_precompute(GeometryBuffer& g, const DiscontinuitySettings& s);

/// Pixel (x, y)'s accepted window positions as in GeometryBuffer::accepted: the
/// precomputed mask when g holds one for `s`, else computed now.
uint64_t discontinuity_window_mask(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y);

/// Whether pixel p accepts neighbour q (the test above; pixels whose rays escaped accept
/// only each other). Inline: out of line, the edge guidance's pairs outside the masks
/// took 40% of its loop in the call.
inline bool discontinuity_accepts(const GeometryBuffer& g, const DiscontinuitySettings& s, size_t p, size_t q) {
    const bool plane = !g.position.empty();
    auto at = [](const std::vector<float>& v, size_t i) { return ts::ts_f3_load(&v[3 * i]); };
    const ts::float3 none = ts::make_float3(0.0f, 0.0f, 0.0f);
    return ts::ts_discontinuity_accepts(g.depth[p], at(g.normal, p), plane ? at(g.position, p) : none, g.depth[q],
                                        at(g.normal, q), plane ? at(g.position, q) : none, plane, s.normal_cos,
                                        s.depth_rel) != 0;
}

/// The window offsets lo..hi (inclusive, on each axis) for tile edge n.
void discontinuity_window(int n, int* lo, int* hi);

/// Window position i (row-major, (dy − lo)·n + (dx − lo), as in the window masks) as a
/// pixel index offset in an image `width` pixels wide: q = p + offset[i]. Positions past
/// n² are 0. Saves the loops over a mask's bits a division and a modulo by n per bit.
std::array<ptrdiff_t, 64> discontinuity_window_offsets(int n, int width);

/// Filters `channels` interleaved floats per pixel of `in` into `out`. Window: offsets
/// -(n-1)/2 .. (n-1)/2 for odd n, -n/2 .. n/2-1 for even n (each n×n window then holds
/// every set (x mod n, y mod n) exactly once). A pixel always accepts itself; pixels
/// whose rays escaped accept only other escaped pixels. `accepted`, if given, receives
/// |A(p)| per pixel (the guidance signal AIS uses). `channels` is 1 or 3 (else
/// std::invalid_argument); the means are those of double sums in window order (whole
/// windows whose values sum exactly in double, from n = 4, are summed by columns: the same
/// floats, fewer additions).
void discontinuity_filter(const GeometryBuffer& g, const DiscontinuitySettings& s, int channels,
                          const std::vector<float>& in, std::vector<float>& out,
                          std::vector<uint8_t>* accepted = nullptr);

}  // namespace tessera
