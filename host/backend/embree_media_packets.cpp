// The igi ray march in packets (embree_media_packets.h). The lanes of one sample set step
// together: at step i each lane makes the calls of ts_igi_media_set in its order (light
// link, phase sample, the VPL share, the step's end), and where ts_igi_media_set traces
// one shadow ray the lanes trace theirs as one packet. The phase-sampled rays and the
// camera rays stay single: their closest hits must equal rtcIntersect1's bit for bit.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "backend/embree_lanes.h"
#include "backend/embree_media_packets.h"
#include "bvh/embree_device.h"

// After the tracer (embree_media_packets.h includes it): the shared code calls it.
#include "kernels/shared/igi.h"

namespace tessera {
namespace {

using ts::float3;
using ts::TsIgiMarch;

// The lanes of one step: marching (in[l] = -1), their points and in-scattered light, and
// the rays of the link being traced.
struct Step {
    alignas(64) int in[kLanes];
    alignas(64) int traced[kLanes];
    ts::TsRay rays[kLanes] = {};  // lanes not traced keep a finite ray Embree never reads
    float t[kLanes], w[kLanes];
    float3 x[kLanes], light[kLanes], radiance[kLanes], vpl_sum[kLanes];
};

// Traces the lanes with s.traced[l] = -1 as one packet; clears traced[l] where blocked.
void trace(const ts::TsTracer& tracer, Step& s, bool coherent) {
    bool any = false;
    for (int l = 0; l < kLanes; ++l) any |= s.traced[l] != 0;
    if (!any) return;
    const uint32_t blocked = ts::ts_trace_occluded16(&tracer, s.rays, s.traced, coherent);
    for (int l = 0; l < kLanes; ++l)
        if (blocked >> l & 1u) s.traced[l] = 0;
}

// Step i of the marches in s.in, all of set k: the light link, the phase sample, the
// VPL share, then each lane's step end, in ts_igi_media_set's order.
void march_step(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                const ts::TsMedium& med, uint32_t k, uint32_t i, bool coherent, std::array<TsIgiMarch, kLanes>& m,
                Step& s) {
    for (int l = 0; l < kLanes; ++l) {
        s.traced[l] = 0;
        if (!s.in[l]) continue;
        s.t[l] = ts::ts_igi_march_t(&frame, &m[l], k, i);
        s.x[l] = m[l].ray.org + m[l].ray.dir * s.t[l];
        s.light[l] = ts::make_float3(0.0f, 0.0f, 0.0f);
        if (ts::ts_igi_march_light_link(&sv, &frame, &med, &m[l], s.x[l], k, i, &s.rays[l], &s.radiance[l], &s.w[l]))
            s.traced[l] = -1;
    }
    trace(tracer, s, coherent);
    for (int l = 0; l < kLanes; ++l)
        if (s.traced[l]) ts::ts_igi_march_light_add(&m[l], &med, s.rays[l], s.radiance[l], s.w[l], &s.light[l]);
    for (int l = 0; l < kLanes; ++l)
        if (s.in[l]) ts::ts_igi_march_phase_add(&sv, &tracer, &frame, &med, &m[l], s.x[l], &s.light[l]);
    if (frame.igi_media_vpls) {
        uint32_t first, stride;
        ts::ts_igi_march_vpl_share(&sv, &frame, k, i, &first, &stride);
        for (int l = 0; l < kLanes; ++l) s.vpl_sum[l] = ts::make_float3(0.0f, 0.0f, 0.0f);
        for (uint32_t j = first; j < sv.vpl_set_start[k + 1]; j += stride) {
            const float* vpl = sv.vpls + size_t(j) * TS_VPL_FLOATS;
            for (int l = 0; l < kLanes; ++l)
                s.traced[l] = s.in[l] && ts::ts_igi_march_vpl_link(&frame, &med, s.x[l], m[l].ray.dir, vpl,
                                                                    &s.rays[l], &s.w[l])
                                  ? -1
                                  : 0;
            trace(tracer, s, coherent);
            for (int l = 0; l < kLanes; ++l)
                if (s.traced[l]) ts::ts_vpl_gather_add(&s.vpl_sum[l], vpl, &med, s.rays[l], s.w[l]);
        }
        for (int l = 0; l < kLanes; ++l)
            if (s.in[l]) s.light[l] += s.vpl_sum[l] * static_cast<float>(stride);
    }
    for (int l = 0; l < kLanes; ++l)
        if (s.in[l]) ts::ts_igi_march_step_end(&m[l], &med, s.t[l], s.light[l]);
}

// Block b of the frame (ts_packet_block, as igi_surface_packets): 4×4 pixels of one set.
void media_block(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, uint32_t b,
                 std::vector<float>& out) {
    uint32_t k, bx, by;
    if (!ts::ts_packet_block(&frame, b, &k, &bx, &by)) return;
    MarchLanes lanes;
    std::array<float*, kLanes> o{};
    for (uint32_t lane = 0; lane < kLanes; ++lane) {
        uint32_t px, py;
        if (!ts::ts_packet_block_pixel(&frame, k, bx, by, lane, &px, &py)) continue;
        const int i = lanes.lanes++;
        o[i] = &out[(size_t(py) * frame.width + px) * TS_IGI_MEDIA_FLOATS];
        o[i][TS_IGI_MEDIA_LIT] = o[i][TS_IGI_MEDIA_LENGTH] = 0.0f;
        lanes.px[i] = px;
        lanes.py[i] = py;
        lanes.k[i] = ts::ts_igi_set(px, py, frame.igi_tile);
        lanes.on[i] = true;
    }
    march_packet(sv, tracer, frame, lanes, true, o);
}

}  // namespace

void march_packet(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                  const MarchLanes& lanes, bool coherent, const std::array<float*, kLanes>& out) {
    const ts::TsMedium med = ts::ts_medium_load(sv.medium);
    std::array<TsIgiMarch, kLanes> m;
    uint32_t done = 0;  // bit l: lane l marched, off, or outside the medium
    for (int l = 0; l < lanes.lanes; ++l) {
        if (lanes.on[l]) m[l] = ts::ts_igi_march_begin(&tracer, &frame, &med, lanes.px[l], lanes.py[l], lanes.k[l]);
        if (!lanes.on[l] || !m[l].active) done |= 1u << l;
    }
    Step s;
    for (int first = 0; first < lanes.lanes; ++first) {
        if (done >> first & 1u) continue;
        const uint32_t k = lanes.k[first];
        for (int l = 0; l < kLanes; ++l) {
            s.in[l] = l < lanes.lanes && !(done >> l & 1u) && lanes.k[l] == k ? -1 : 0;
            if (s.in[l]) done |= 1u << l;
        }
        for (uint32_t i = 0; i < frame.igi_steps; ++i) march_step(sv, tracer, frame, med, k, i, coherent, m, s);
    }
    for (int l = 0; l < lanes.lanes; ++l)
        if (lanes.on[l]) ts::ts_igi_march_end(&frame, &m[l], &med, out[l]);
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
