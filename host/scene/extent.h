// The scene's length for the VPL clamps: the trimmed diagonal of its triangles' bounds.
#pragma once
#include <cstddef>

#include "scene/scene.h"

namespace tessera {

/// The length D the VPL clamps are relative to (b = 1/(c·D)², docs/igi.md §4), scene units:
/// the diagonal of the triangles' bounds with their outlying 10^-4 of area trimmed from
/// each end of each axis, each triangle taken by its lowest (and highest) vertex.
/// `xyz`: 9 floats per triangle (its three vertices), `triangles` of them; `bounds`: the
/// bounds of every vertex. A stray triangle 1 km from a 0.5 m box made the whole bounds'
/// diagonal 1,000 times the box's and darkened igi's indirect light by up to 60%.
/// 10^-4, not more: every shipped scene keeps its whole bounds (1% took Sibenik's
/// outermost parts off, D 3.6% shorter), while a speck such as that triangle (2.5·10^-5
/// of the box's area) is left out. The bounds' diagonal where the triangles have no area
/// (or the trimmed bounds are a point); 0 without triangles. Only the outermost triangles
/// are sorted where they hold more than the trim (Sibenik: 1.95 ms against 18.7 ms for six
/// full sorts; bench/results/viewer_restart.md).
float trimmed_diagonal(const float* xyz, size_t triangles, const SceneBounds& bounds);

}  // namespace tessera
