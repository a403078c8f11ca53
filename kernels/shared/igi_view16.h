/* The views (ts_igi_view, shared/igi.h) of up to 16 pixels with their camera rays traced
 * as one closest-hit packet (docs/ray-batches.md §2, §4), for the backends that trace
 * 16-ray packets: the Embree backend (host/backend/embree_packets.cpp) and the OpenCL CPU
 * kernels (kernels/igi_packets.h). Each lane makes ts_igi_view's calls in the same order
 * and only its first trace is shared, so a lane's view equals ts_igi_view's wherever the
 * packet query returns the single-ray query's hit (bit for bit on the OpenCL backend,
 * tests/backend/opencl_packets_test.cpp).
 *
 * Besides the tracer interface of shared/direct.h, the tracer provides
 *   void ts_trace_closest_lanes(const TsTracer*, const TsRay rays[TS_PACKET_LANES],
 *                               uint valid, TsHit hits[TS_PACKET_LANES])
 * which traces the rays of the lanes whose bit is set in `valid` as one packet and writes
 * their closest hits (the other lanes' rays are not read, their hits not written).
 *
 * Private memory: 16 rays, random streams and hits (≈ 1 KB) besides the views. */
#ifndef TS_IGI_VIEW16_H
#define TS_IGI_VIEW16_H
#include "shared/igi.h"

TS_NAMESPACE_BEGIN

/* views[i] = ts_igi_view(sv, tracer, f, px[i], py[i]) for each lane i in `on` (bit i:
 * lane i); the other lanes' views are left as they were. */
TS_INLINE void ts_igi_view16(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint on,
                             const uint* px, const uint* py, TsIgiView* views) {
    if (on == 0u) return;
    TsRng rng[TS_PACKET_LANES];
    TsRay ray[TS_PACKET_LANES];
    TsHit hit[TS_PACKET_LANES];
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        ray[i].org = ray[i].dir = make_float3(0.0f, 0.0f, 0.0f); /* an idle lane: never traced */
        ray[i].tmin = ray[i].tmax = 0.0f;
        if (on >> i & 1u) ray[i] = ts_igi_view_ray(f, px[i], py[i], &rng[i]);
    }
    ts_trace_closest_lanes(tracer, ray, on, hit);
    for (int i = 0; i < TS_PACKET_LANES; ++i)
        if (on >> i & 1u) views[i] = ts_igi_view_from(sv, tracer, f, ray[i], hit[i], &rng[i]);
}

/* After ts_igi_view16: for each lane i in `want` whose camera path found a surface, its
 * albedo and the number of links it gathers for set[i] and components mask[i] (a black
 * surface's too, as in ts_igi_surface_set); links[i] = 0 for every other lane.
 * Returns the lanes that found a surface. */
TS_INLINE uint ts_igi_view16_links(const TsSceneView* sv, const TsFrame* f, uint want, const TsIgiView* views,
                                   const uint* set, const uint* mask, float3* albedo, uint* links) {
    uint seen = 0u;
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        links[i] = 0u;
        if (!(want >> i & 1u) || views[i].hit.prim == TS_NO_HIT) continue;
        seen |= 1u << i;
        albedo[i] = ts_material_albedo(sv, &views[i].s);
        links[i] = ts_igi_link_count(sv, f, set[i], mask[i]);
    }
    return seen;
}

TS_NAMESPACE_END

#endif /* TS_IGI_VIEW16_H */
