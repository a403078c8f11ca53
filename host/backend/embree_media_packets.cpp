// The igi ray march in packets on Embree (embree_media_packets.h): the dispatch around the
// shared march of kernels/shared/igi_march16.h, whose packet query is the Embree tracer's
// ts_trace_occluded_lanes (rtcOccluded16). The phase-sampled rays and the camera rays stay
// single: their closest hits must equal rtcIntersect1's bit for bit.
#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "backend/embree_media_packets.h"
#include "bvh/embree_device.h"

// After the tracer (embree_media_packets.h includes it): the shared code calls it.
#include "kernels/shared/igi_march16.h"

namespace tessera {
namespace {

// Block b of the frame (ts_packet_block, as igi_surface_packets): 4×4 pixels of one set.
void media_block(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, uint32_t b,
                 std::vector<float>& out) {
    uint32_t k, bx, by;
    if (!ts::ts_packet_block(&frame, b, &k, &bx, &by)) return;
    MarchLanes lanes;
    std::array<float*, TS_PACKET_LANES> o{};
    for (uint32_t lane = 0; lane < TS_PACKET_LANES; ++lane) {
        uint32_t px, py;
        if (!ts::ts_packet_block_pixel(&frame, k, bx, by, lane, &px, &py)) continue;
        const int i = lanes.lanes++;
        o[i] = &out[(size_t(py) * frame.width + px) * TS_IGI_MEDIA_FLOATS];
        lanes.px[i] = px;
        lanes.py[i] = py;
        lanes.k[i] = ts::ts_igi_set(px, py, frame.igi_tile);
        lanes.on[i] = true;
    }
    march_packet(sv, tracer, frame, lanes, true, o);
}

}  // namespace

void march_packet(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                  const MarchLanes& lanes, bool coherent, const std::array<float*, TS_PACKET_LANES>& out) {
    ts::TsTracer t = tracer;
    t.coherent = coherent;
    uint32_t on = 0;
    for (int l = 0; l < lanes.lanes; ++l) on |= lanes.on[l] ? 1u << l : 0u;
    float values[TS_PACKET_LANES][TS_IGI_MEDIA_FLOATS];
    ts::ts_igi_march_packet(&sv, &t, &frame, on, lanes.px.data(), lanes.py.data(), lanes.k.data(), values);
    for (int l = 0; l < lanes.lanes; ++l)
        if (lanes.on[l]) std::copy(values[l], values[l] + TS_IGI_MEDIA_FLOATS, out[l]);
}

void igi_media_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                       std::vector<float>& out) {
    const uint32_t blocks = ts::ts_packet_block_count(&frame);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, blocks, 4), [&](const tbb::blocked_range<uint32_t>& r) {
        set_ftz_daz();
        for (uint32_t b = r.begin(); b < r.end(); ++b) media_block(sv, tracer, frame, b, out);
    });
}

}  // namespace tessera
