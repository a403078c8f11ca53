// A tracer that traces nothing, for tests of shared shading functions that take a
// tracer but are exercised without geometry. Include after kernels/shared/geometry.h and
// before the shared header under test. Its unnamed namespace gives it internal linkage:
// the Embree backend's TsTracer is another type, so the shared inline functions taking a
// TsTracer* cannot be merged across the two (ODR).
#pragma once
#include "kernels/shared/geometry.h"

namespace tessera::ts {
namespace {
struct TsTracer {};
[[maybe_unused]] TsHit ts_trace_closest(const TsTracer*, TsRay) { return TsHit{0, 0, 0, TS_NO_HIT}; }
[[maybe_unused]] int ts_trace_occluded(const TsTracer*, TsRay) { return 0; }
[[maybe_unused]] uint ts_trace_any_hit(const TsTracer*, TsRay) { return TS_NO_HIT; }
// The packet interface of shared/igi_view16.h and igi_march16.h: nothing hit, nothing blocked.
[[maybe_unused]] void ts_trace_closest_lanes(const TsTracer*, const TsRay*, uint valid, TsHit* hits) {
    for (int i = 0; i < TS_PACKET_LANES; ++i)
        if (valid >> i & 1u) hits[i] = TsHit{0, 0, 0, TS_NO_HIT};
}
[[maybe_unused]] uint ts_trace_occluded_lanes(const TsTracer*, const TsRay*, uint) { return 0u; }
// The packet of shared/igi_gather16.h: kept rays, nothing blocked.
struct TsRayLanes {
    TsRay ray[TS_PACKET_LANES];
};
[[maybe_unused]] void ts_ray_lanes_init(TsRayLanes*) {}
[[maybe_unused]] void ts_ray_lanes_put(TsRayLanes* r, int i, TsRay ray) { r->ray[i] = ray; }
[[maybe_unused]] TsRay ts_ray_lanes_get(const TsRayLanes* r, int i) { return r->ray[i]; }
[[maybe_unused]] void ts_trace_occluded_ray_lanes(const TsTracer*, TsRayLanes*, const int* traced, int* visible) {
    for (int i = 0; i < TS_PACKET_LANES; ++i) visible[i] = traced[i];
}
}  // namespace
}  // namespace tessera::ts
