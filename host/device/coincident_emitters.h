// Emitters that lie in the plane of another surface, overlapping it.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace tessera {

/// What separate_coincident_emitters found, in emissive triangles.
struct CoincidentEmitters {
    size_t moved = 0;    ///< moved off another surface's plane
    /// Lying on a light that faces the same way, their interiors overlapping (a light
    /// listed twice): both are sampled, so their light counts twice where they overlap,
    /// while a ray that meets them sees one. Left in place; reported by `info` and `render`.
    size_t stacked = 0;
};

/// Moves every emissive triangle (a light of make_scene_buffers) that lies in the plane
/// of another triangle, their interiors overlapping, off that plane along its emitting
/// normal (cross(e1, e2), the side it lights), so that its nearest vertex lies
/// kCoincidentEmitterUlps ulps of the pair's largest absolute coordinate in front. "In the plane": every vertex of the emitter within
/// kCoplanarEmitterUlps such ulps of the other's plane (measured in double), the normals
/// parallel. The other triangle is any surface, or a light facing the other way (a
/// two-sided light made of two back to back); a light facing the same way would move as
/// far and is left, counted as stacked. `positions` is 3 per triangle, the scene's posed vertices, changed in
/// place; every test reads them as given, so the order of the triangles does not matter.
/// Returns how many emissive triangles moved and how many are stacked.
///
/// Why: every ray that reaches such a pair meets both at the same distance, and the
/// backends break that tie differently (our traversal keeps the first triangle tested,
/// Embree's robust intersector the last) and round t differently, so on one backend the
/// light shows and on the other the surface does; pt's and igi's images then differ by
/// 10-200% (docs/ray-tracing.md §4). A light placed flat on a ceiling is the usual case.
/// Moved by a distance above both intersectors' rounding, the emitter is strictly nearer
/// from the side it lights and hidden from the other on both. Triangles that only touch
/// (a light filling a hole in the ceiling) are left as they are, as is every scene
/// without such a pair (bit for bit). Cost: a uniform grid over the emitters' boxes, so
/// about linear in the triangles that come near an emitter.
CoincidentEmitters separate_coincident_emitters(const Scene& scene, std::vector<glm::vec3>& positions);

/// What `info`, `render` and `view` say of `stacked` (CoincidentEmitters::stacked > 0):
/// "N emissive triangles lie on another light facing the same way (...)".
std::string stacked_emitters_text(size_t stacked);

/// The coplanarity tolerance, in ulps of the pair's largest absolute coordinate: a light
/// modelled in a wall's plane and written with 6 decimals, or rotated at load, lies up to
/// about 2.4 of them off the plane (measured); 4 covers that. A light set on purpose that
/// close to a surface is within the intersectors' rounding of it and moves too.
inline constexpr double kCoplanarEmitterUlps = 4.0;

/// The separation a moved light ends at, in the same ulps: beyond the tolerance, so the
/// light is clear of it, and three times the 2 ulps that already made the images of both
/// backends agree bit for bit; 7·10⁻⁷ of the coordinates (3.6 mm at 5 km). A light just in
/// front of a surface moves only the rest of the way, so a scene's image barely changes.
inline constexpr double kCoincidentEmitterUlps = 6.0;

}  // namespace tessera
