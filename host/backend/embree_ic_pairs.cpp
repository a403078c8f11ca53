// Record–VPL pairs in packets on the Embree backend (embree_ic_pairs.h).
#include "backend/embree_ic_pairs.h"

#include <algorithm>
#include <cstring>

#include "backend/embree_packet_loop.h"
#include "kernels/shared/ic.h"

namespace tessera {

void ic_pair_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, size_t count,
                     std::vector<float>& out) {
    static_assert(TS_IC_PAIR_FLOATS == 1 && TS_IC_PAIR_HIT == 0, "one hit code per pair");
    for_each_packet(count, [&](size_t first, size_t n) {
        ts::TsRay rays[TS_PACKET_LANES] = {};
        uint32_t prim[TS_PACKET_LANES] = {};
        int valid[TS_PACKET_LANES] = {};
        bool one_vpl = true;
        for (size_t i = 0; i < n; ++i) {
            valid[i] = ts::ts_ic_pair_ray(&sv, &frame, static_cast<uint32_t>(first + i), &rays[i]) ? -1 : 0;
            one_vpl = one_vpl && ts::ts_ic_pair_vpl(&sv, &frame, static_cast<uint32_t>(first + i)) ==
                                     ts::ts_ic_pair_vpl(&sv, &frame, static_cast<uint32_t>(first));
        }
        if (std::any_of(valid, valid + n, [](int v) { return v != 0; }))
            ts::ts_trace_any_hit16(&tracer, rays, valid, one_vpl, prim);
        for (size_t i = 0; i < n; ++i) {
            const uint32_t hit = valid[i] ? prim[i] : uint32_t(TS_IC_PAIR_FACING);
            std::memcpy(&out[first + i], &hit, sizeof hit);
        }
    });
}

}  // namespace tessera
