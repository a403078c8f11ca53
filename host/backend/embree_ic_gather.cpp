// 16 records per batch through ts_ic_gather16 (embree_ic_gather.h). Built with
// -fno-trapping-math, as embree_packets.cpp and for the same reason (CMakeLists.txt).
#include "backend/embree_ic_gather.h"

#include "backend/embree_packet_loop.h"
#include "kernels/shared/ic_gather.h"

namespace tessera {

void ic_gather_lanes(const ts::TsSceneView& sv, const TsFrame& frame, size_t count, std::vector<float>& out) {
    // The same denormal handling as the one-record dispatch (for_each_packet), the same sums.
    for_each_packet(count, [&](size_t first, size_t n) {
        const ts::TsMedium med = ts::ts_medium_load(sv.medium);  // as ts_ic_gather_item, under FTZ/DAZ
        alignas(64) ts::TsIcLanes lanes;
        uint32_t row[TS_PACKET_LANES];
        uint32_t on = 0;
        for (size_t i = 0; i < TS_PACKET_LANES; ++i) {
            // An idle lane repeats the first record: finite, and never written.
            const uint32_t* item = sv.items + TS_IC_GATHER_WORDS * (first + (i < n ? i : 0));
            ts::ts_ic_lanes_set(&lanes, static_cast<int>(i),
                                sv.ic_record_surfaces + size_t(TS_IC_GBUF_FLOATS) * item[TS_IC_GATHER_RECORD]);
            row[i] = item[TS_IC_GATHER_ROW];
            if (i < n) on |= 1u << i;
        }
        ts::ts_ic_gather16(&lanes, on, sv.ic_visibility, row, sv.vpl_set_start[1], sv.vpls, &med, frame.igi_g_clamp,
                           &out[first * TS_IC_GATHER_FLOATS]);
    });
}

}  // namespace tessera
