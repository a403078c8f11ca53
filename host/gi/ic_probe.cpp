#include "gi/ic_probe.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "device/ray_records.h"
#include "kernels/shared/ic_probe.h"

namespace tessera {
namespace {

// Records per trace_closest call: bounds the ray and hit buffers (32 rays of 8 + 4 floats).
constexpr size_t kProbeBatch = size_t(1) << 15;

}  // namespace

std::vector<float> ic_probe_distances(Backend& backend, const std::vector<IcRecord>& records,
                                      const std::vector<uint32_t>& which, const std::vector<float>& reach,
                                      uint64_t* rays) {
    std::vector<float> nearest(reach.begin(), reach.end());
    std::vector<float> ray_buf, hits;
    for (size_t begin = 0; begin < which.size(); begin += kProbeBatch) {
        const size_t n = std::min(kProbeBatch, which.size() - begin);
        ray_buf.resize(size_t(TS_RAY_FLOATS) * TS_IC_PROBE_RAYS * n);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const ts::TsSurface s = ic_record_surface(records[which[begin + i]]);
                for (uint32_t k = 0; k < TS_IC_PROBE_RAYS; ++k)
                    store_ray(ts::ts_ic_probe_ray(&s, records[which[begin + i]].probe_key, k, reach[begin + i]),
                              &ray_buf[TS_RAY_FLOATS * (TS_IC_PROBE_RAYS * i + k)]);
            }
        });
        backend.trace_closest(ray_buf, hits);
        for (size_t i = 0; i < n; ++i)
            for (uint32_t k = 0; k < TS_IC_PROBE_RAYS; ++k) {
                const ts::TsHit h = load_hit(&hits[TS_HIT_FLOATS * (TS_IC_PROBE_RAYS * i + k)]);
                if (h.prim != TS_NO_HIT) nearest[begin + i] = std::min(nearest[begin + i], h.t);  // unit directions
            }
        if (rays) *rays += uint64_t(TS_IC_PROBE_RAYS) * n;
    }
    return nearest;
}

}  // namespace tessera
