// A TsRay into the tracer's ray layout and a hit out of its hit layout (layout_rays.h
// TS_RAY_FLOATS, TS_HIT_FLOATS), for host code that batches rays through
// Backend::trace_closest.
#pragma once
#include <cstring>

#include "kernels/shared/geometry.h"
#include "kernels/shared/layout_rays.h"

namespace tessera {

/// Writes `r` as TS_RAY_FLOATS floats at `out`.
inline void store_ray(const ts::TsRay& r, float* out) {
    ts::ts_f3_store(out + TS_RAY_ORG, r.org);
    out[TS_RAY_TMIN] = r.tmin;
    ts::ts_f3_store(out + TS_RAY_DIR, r.dir);
    out[TS_RAY_TMAX] = r.tmax;
}

/// The hit stored as TS_HIT_FLOATS floats at `h` (the primitive as uint bits).
inline ts::TsHit load_hit(const float* h) {
    ts::TsHit hit{h[TS_HIT_T], h[TS_HIT_U], h[TS_HIT_V], 0u};
    std::memcpy(&hit.prim, &h[TS_HIT_PRIM], 4);
    return hit;
}

}  // namespace tessera
