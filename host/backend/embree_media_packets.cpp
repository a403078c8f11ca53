// The igi media pass in packets on Embree (embree_media_packets.h): the dispatch around the
// shared march of kernels/shared/igi_march16.h, whose packet query is the Embree tracer's
// ts_trace_occluded_lanes (rtcOccluded16). The phase-sampled rays and the camera rays stay
// single: their closest hits must equal rtcIntersect1's bit for bit.
#include <algorithm>
#include <array>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "backend/embree_media_packets.h"
#include "bvh/embree_device.h"

// After the tracer (embree_media_packets.h includes it): the shared code calls it.
#include "kernels/shared/igi_march16.h"

namespace tessera {
namespace {

// Block b of the frame (ts_packet_block, as igi_surface_packets): 4×4 pixels of one set,
// each written at its pixel's place. `tracer` is in coherent mode: the block's pixels lie
// close together.
void media_block(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, uint32_t b,
                 std::vector<float>& out) {
    uint32_t k, bx, by;
    if (!ts::ts_packet_block(&frame, b, &k, &bx, &by)) return;
    std::array<uint32_t, TS_PACKET_LANES> px{}, py{}, set{};
    uint32_t on = 0;
    for (uint32_t lane = 0; lane < TS_PACKET_LANES; ++lane) {
        if (!ts::ts_packet_block_pixel(&frame, k, bx, by, lane, &px[lane], &py[lane])) continue;
        on |= 1u << lane;
        set[lane] = ts::ts_igi_set(px[lane], py[lane], frame.igi_tile);
    }
    float values[TS_PACKET_LANES][TS_IGI_MEDIA_FLOATS];
    ts::ts_igi_march_packet(&sv, &tracer, &frame, on, px.data(), py.data(), set.data(), values);
    for (int l = 0; l < TS_PACKET_LANES; ++l)
        if (on >> l & 1u)
            std::copy(values[l], values[l] + TS_IGI_MEDIA_FLOATS,
                      &out[(size_t(py[l]) * frame.width + px[l]) * TS_IGI_MEDIA_FLOATS]);
}

}  // namespace

void igi_media_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                       std::vector<float>& out) {
    ts::TsTracer coherent = tracer;
    coherent.coherent = true;
    const uint32_t blocks = ts::ts_packet_block_count(&frame);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, blocks, 4), [&](const tbb::blocked_range<uint32_t>& r) {
        const FtzDazScope ftz_daz;
        for (uint32_t b = r.begin(); b < r.end(); ++b) media_block(sv, coherent, frame, b, out);
    });
}

}  // namespace tessera
