// 16 records per batch through ts_ic_gather16 (embree_ic_gather.h). Built with
// -fno-trapping-math, as embree_lanes.cpp and for the same reason (CMakeLists.txt).
#include "backend/embree_ic_gather.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "bvh/embree_device.h"
#include "kernels/shared/ic_gather.h"

namespace tessera {

void ic_gather_lanes(const ts::TsSceneView& sv, const TsFrame& frame, size_t count, std::vector<float>& out) {
    constexpr size_t kLanes = TS_PACKET_LANES;
    const size_t batches = (count + kLanes - 1) / kLanes;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batches, 1), [&](const tbb::blocked_range<size_t>& r) {
        set_ftz_daz();  // as the one-record dispatch: the same denormal handling, the same sums
        alignas(64) ts::TsIcLanes lanes;
        uint32_t row[kLanes];
        for (size_t batch = r.begin(); batch < r.end(); ++batch) {
            const size_t first = batch * kLanes, n = std::min(kLanes, count - first);
            uint32_t on = 0;
            for (size_t i = 0; i < kLanes; ++i) {
                // An idle lane repeats the first record: finite, and never written.
                const uint32_t* item = sv.items + TS_IC_GATHER_WORDS * (first + (i < n ? i : 0));
                ts::ts_ic_lanes_set(&lanes, static_cast<int>(i),
                                    sv.ic_record_surfaces + size_t(TS_IC_GBUF_FLOATS) * item[TS_IC_GATHER_RECORD]);
                row[i] = item[TS_IC_GATHER_ROW];
                if (i < n) on |= 1u << i;
            }
            ts::ts_ic_gather16(&lanes, on, sv.ic_visibility, row, sv.vpl_set_start[1], sv.vpls, frame.igi_g_clamp,
                               &out[first * TS_IC_GATHER_FLOATS]);
        }
    });
}

}  // namespace tessera
