// AIS reconstruction of one component after the adaptive pass (docs/ais.md §6;
// the set-completion rule is our assumption, stated below). Host code shared by every
// backend.
#pragma once
#include <cstdint>
#include <vector>

#include "gi/discontinuity_filter.h"

namespace tessera {

/// Reconstructs one component, 3 floats per pixel, row-major (g.width × g.height).
/// Every pixel's estimate holds each of the N = tile² sets at most once: the sets it
/// evaluated itself (`masks[p]` bit j: set j evaluated, own set included; `own_sum` the
/// sum of those evaluations in double, 3 per pixel) and, for each other set, the base
/// value (`base`, the pixel's own-set estimate) of the neighbour in its filter window
/// that holds that set, if the filter accepts it. So a pixel that evaluated only its own
/// set gets exactly the discontinuity filter's value, one that evaluated all N sets its
/// full-rate mean, and an edge pixel that evaluated its missing sets holds every set
/// once, as an interior pixel does after filtering. Rows run in parallel; deterministic.
void ais_reconstruct(const GeometryBuffer& g, const DiscontinuitySettings& s, const std::vector<float>& base,
                     const std::vector<double>& own_sum, const std::vector<uint64_t>& masks,
                     std::vector<float>& out);

}  // namespace tessera
