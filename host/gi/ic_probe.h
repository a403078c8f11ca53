// The hemisphere probe of instant-cache records (kernels/shared/ic_probe.h,
// docs/instant-caching.md §4): the distance to the nearest surface over each record, which
// bounds its validity radius so that no record serves a point behind an occluder.
#pragma once
#include <cstdint>
#include <vector>

#include "backend/backend.h"
#include "gi/irradiance_cache.h"

namespace tessera {

/// For each records[which[k]]: the distance (scene units) along the nearest of its
/// TS_IC_PROBE_RAYS probe rays to a surface, capped at `reach[k]` (also when no ray hits).
/// The rays are traced through Backend::trace_closest, so every backend finds the same
/// distances. Returns one float per entry of `which`; `rays` (if given) gets the count.
std::vector<float> ic_probe_distances(Backend& backend, const std::vector<IcRecord>& records,
                                      const std::vector<uint32_t>& which, const std::vector<float>& reach,
                                      uint64_t* rays = nullptr);

}  // namespace tessera
