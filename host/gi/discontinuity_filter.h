// The discontinuity buffer (Keller's thesis 1998; used by IGI, Wald et al. 2002): an n×n
// box filter over interleaved estimates that averages a pixel only with neighbours on
// the same surface, so the structured noise of interleaved sampling goes away while
// edges stay sharp. Host code shared by every backend.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera {

/// Thresholds: a neighbour q of pixel p is accepted when n_p · n_q >= normal_cos and
/// |z_p - z_q| <= depth_rel · z_p. Defaults from ALGORITHMS.md §1.2 [A]: 0.9 (normals
/// within about 26°, looser than a curved surface's change across a 3-pixel window at
/// typical distances, tighter than any crease) and 5% relative depth (below the depth
/// step of a contact edge seen from a few scene units, above a slanted plane's change
/// across the window at angles up to about 70°).
struct DiscontinuitySettings {
    int tile = 3;             ///< window edge n: every n×n window holds each sample set once
    float normal_cos = 0.9f;
    float depth_rel = 0.05f;
};

/// Per-pixel geometry of the first diffuse hit: unit normal (3 floats) and distance
/// (+inf where the camera ray escaped). Row-major, width × height.
struct GeometryBuffer {
    int width = 0, height = 0;
    std::vector<float> normal;
    std::vector<float> depth;
};

/// Whether pixel p accepts neighbour q (the test above; pixels whose rays escaped accept
/// only each other).
bool discontinuity_accepts(const GeometryBuffer& g, const DiscontinuitySettings& s, size_t p, size_t q);

/// The window offsets lo..hi (inclusive, on each axis) for tile edge n.
void discontinuity_window(int n, int* lo, int* hi);

/// Filters `channels` interleaved floats per pixel of `in` into `out`. Window: offsets
/// -(n-1)/2 .. (n-1)/2 for odd n, -n/2 .. n/2-1 for even n (each n×n window then holds
/// every set (x mod n, y mod n) exactly once). A pixel always accepts itself; pixels
/// whose rays escaped accept only other escaped pixels. `accepted`, if given, receives
/// |A(p)| per pixel (the guidance signal AIS uses).
void discontinuity_filter(const GeometryBuffer& g, const DiscontinuitySettings& s, int channels,
                          const std::vector<float>& in, std::vector<float>& out,
                          std::vector<uint8_t>* accepted = nullptr);

}  // namespace tessera
