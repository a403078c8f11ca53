// Emitters that lie in the plane of another surface, overlapping it.
#pragma once
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace tessera {

/// Moves every emissive triangle (a light of make_scene_buffers) that lies in the plane
/// of a non-emissive triangle (within 1 ulp of the coordinates), their interiors
/// overlapping, off that plane along its
/// emitting normal (cross(e1, e2), the side it lights) by kCoincidentEmitterUlps ulps of
/// the pair's largest coordinate. `positions` is 3 per triangle, the scene's posed
/// vertices, changed in place; returns how many triangles moved.
///
/// Why: every ray that reaches such a pair meets both at the same distance, and the
/// backends break that tie differently (our traversal keeps the first triangle tested,
/// Embree's robust intersector the last) and round t differently, so on one backend the
/// light shows and on the other the wall does; pt's and igi's images then differ by
/// 10-200% (docs/ray-tracing.md §4). A light placed flat on a ceiling is the usual case.
/// Moved by a distance far above both intersectors' rounding, the emitter is strictly
/// nearer from the side it lights and hidden from the other on both. Triangles that
/// only touch (a light filling a hole in the ceiling) are left as they are, as is every
/// scene without such a pair (bit for bit). Cost: O(emitters × triangles) box tests.
size_t separate_coincident_emitters(const Scene& scene, std::vector<glm::vec3>& positions);

/// The separation, in ulps of the largest absolute coordinate of the pair: 2 ulps was
/// measured to be enough for axis-aligned and rotated pairs alike; 64 leaves a wide margin
/// and is still 8e-6 of the coordinates (0.04 mm at 5 m).
inline constexpr float kCoincidentEmitterUlps = 64.0f;

}  // namespace tessera
