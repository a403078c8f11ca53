// Packet dispatch for the Embree backend (embree_packets.h). Each lane runs the shared
// per-pixel code of kernels/shared/igi.h up to its links; then, set by set, each link (a
// light sample or a VPL) is computed for the 16 lanes in SIMD, traced as one
// rtcOccluded16 packet and gathered per lane in link order (kernels/shared/igi_gather16.h,
// which the OpenCL packet kernels run too), so every lane sums exactly what
// ts_igi_surface_set sums one ray at a time. Built with -fno-trapping-math for the
// gather's vector loops (CMakeLists.txt).
#include <algorithm>
#include <array>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "backend/embree_packets.h"
#include "bvh/embree_device.h"

// After the tracer (embree_packets.h includes it): the shared code calls it.
#include "kernels/shared/ais_item.h"
#include "kernels/shared/igi_gather16.h"
#include "kernels/shared/igi_march16.h"
#include "kernels/shared/igi_view16.h"

namespace tessera {
namespace {

constexpr int kLanes = TS_PACKET_LANES;

// Up to 16 lanes, each a surface seen through a pixel and the links it gathers.
struct Packet {
    int lanes = 0;
    std::array<ts::TsIgiView, kLanes> view;
    std::array<ts::float3, kLanes> albedo;  // looked up once: a textured albedo costs a pow per texel
    std::array<uint32_t, kLanes> set{}, mask{}, links{};  // links = 0: nothing to gather
    std::array<ts::TsIgiGather, kLanes> gather;
};

// Each lane's links, gathered set by set as 16-ray packets (kernels/shared/igi_gather16.h).
// `coherent`: the lanes' surfaces lie close together (a pixel block), so Embree's coherent
// mode pays; for lanes scattered over the image it costs (docs/ray-batches.md §3).
void gather_links(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, Packet& p,
                  bool coherent) {
    ts::TsTracer t = tracer;
    t.coherent = coherent;
    ts::ts_igi_gather16(&sv, &t, &frame, p.lanes, p.view.data(), p.set.data(), p.mask.data(), p.links.data(),
                        p.gather.data());
}

// The lanes in `want` see pixels (px[i], py[i]), their camera rays traced as one packet
// (kernels/shared/igi_view16.h); sets each such lane's links for its set and components
// (p.set, p.mask; a black surface's too) and returns the lanes whose camera path
// found a surface. `coherent`: the tracer's packet mode for the camera rays.
uint32_t view_lanes(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, Packet& p,
                    uint32_t want, const uint32_t* px, const uint32_t* py, bool coherent) {
    ts::TsTracer t = tracer;
    t.coherent = coherent;
    ts::ts_igi_view16(&sv, &t, &frame, want, px, py, p.view.data());
    return ts::ts_igi_view16_links(&sv, &frame, want, p.view.data(), p.set.data(), p.mask.data(), p.albedo.data(),
                                   p.links.data());
}

// Block b of the frame (ts_packet_block, kernels/shared/geometry.h: the enumeration the
// OpenCL packet kernel uses too): 4×4 pixels of one sample set's sub-image.
void surface_block(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, uint32_t b,
                   std::vector<float>& out) {
    uint32_t k, bx, by;
    if (!ts::ts_packet_block(&frame, b, &k, &bx, &by)) return;
    Packet p;
    std::array<float*, kLanes> o{};
    std::array<uint32_t, kLanes> px{}, py{};
    for (uint32_t lane = 0; lane < kLanes; ++lane) {
        const int i = p.lanes;
        if (!ts::ts_packet_block_pixel(&frame, k, bx, by, lane, &px[i], &py[i])) continue;
        ++p.lanes;
        o[i] = &out[(size_t(py[i]) * frame.width + px[i]) * TS_IGI_SURF_FLOATS];
        ts::ts_igi_surface_clear(o[i]);
        p.set[i] = ts::ts_igi_set(px[i], py[i], frame.igi_tile);
        p.mask[i] = frame.igi_components;
    }
    const uint32_t all = (1u << p.lanes) - 1u;
    const uint32_t hit = view_lanes(sv, tracer, frame, p, all, px.data(), py.data(), true);
    gather_links(sv, tracer, frame, p, true);
    for (int i = 0; i < p.lanes; ++i) {
        if (!(hit >> i & 1u)) continue;
        ts::float3 e_ss, e_id;
        float visible;
        ts::ts_igi_gather_end(&p.gather[i], &frame, &e_ss, &e_id, &visible);
        const ts::TsSurface& s = p.view[i].s;
        ts::ts_igi_surface_store(&p.view[i], p.albedo[i], ts::ts_material_emission(&sv, &s), e_ss, e_id, visible,
                                 o[i]);
    }
}

// The media part of the packet's AIS items (ts_ais_item_media): the items with
// TS_COMPONENT_PM march side by side, set by set (kernels/shared/igi_march16.h; the
// tracer's packet mode incoherent: items lie scattered over edges). `out`: the packet's
// first item's output.
void ais_media(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, const Packet& p,
               const std::array<uint32_t, kLanes>& px, const std::array<uint32_t, kLanes>& py, float* out) {
    uint32_t on = 0;
    for (int i = 0; i < p.lanes; ++i)
        if (p.mask[i] & TS_COMPONENT_PM) on |= 1u << i;
    if (on == 0) return;
    float media[kLanes][TS_IGI_MEDIA_FLOATS];
    ts::ts_igi_march_packet(&sv, &tracer, &frame, on, px.data(), py.data(), p.set.data(), media);
    for (int i = 0; i < p.lanes; ++i)
        for (int c = 0; (on >> i & 1u) && c < 3; ++c)
            out[i * TS_AIS_ITEM_FLOATS + TS_AIS_ITEM_PM + c] = media[i][TS_IGI_MEDIA_RADIANCE + c];
}

void ais_packet(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, size_t first,
                size_t count, std::vector<float>& out) {
    Packet p;
    std::array<uint32_t, kLanes> px{}, py{};
    uint32_t want = 0;
    for (size_t item = first; item < std::min(count, first + kLanes); ++item) {
        const int i = p.lanes++;
        float* o = &out[item * TS_AIS_ITEM_FLOATS];
        std::fill(o, o + TS_AIS_ITEM_FLOATS, 0.0f);
        uint32_t k, mask;
        ts::ts_ais_item_decode(&sv, &frame, static_cast<uint32_t>(item), &px[i], &py[i], &k, &mask);
        p.set[i] = k;
        p.mask[i] = mask;
        if (ts::ts_ais_item_has_surface(mask)) want |= 1u << i;
    }
    // AIS items: pixels scattered over edges (incoherent packets).
    const uint32_t hit = view_lanes(sv, tracer, frame, p, want, px.data(), py.data(), false);
    gather_links(sv, tracer, frame, p, false);
    for (int i = 0; i < p.lanes; ++i) {
        if (!(hit >> i & 1u)) continue;
        ts::float3 e_ss, e_id;
        float visible;
        ts::ts_igi_gather_end(&p.gather[i], &frame, &e_ss, &e_id, &visible);
        ts::ts_ais_item_store_surface(e_ss, e_id, &out[(first + i) * TS_AIS_ITEM_FLOATS]);
    }
    ais_media(sv, tracer, frame, p, px, py, &out[first * TS_AIS_ITEM_FLOATS]);
}

}  // namespace

void igi_surface_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                         std::vector<float>& out) {
    const uint32_t blocks = ts::ts_packet_block_count(&frame);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, blocks, 4), [&](const tbb::blocked_range<uint32_t>& r) {
        const FtzDazScope ftz_daz;
        for (uint32_t b = r.begin(); b < r.end(); ++b) surface_block(sv, tracer, frame, b, out);
    });
}

void ais_item_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, size_t count,
                      std::vector<float>& out) {
    const size_t packets = (count + kLanes - 1) / kLanes;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, packets, 4), [&](const tbb::blocked_range<size_t>& r) {
        const FtzDazScope ftz_daz;
        for (size_t q = r.begin(); q < r.end(); ++q) ais_packet(sv, tracer, frame, q * kLanes, count, out);
    });
}

}  // namespace tessera
