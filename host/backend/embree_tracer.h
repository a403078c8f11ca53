// The Embree backend's tracer for the shared shading code (kernels/shared/direct.h names
// the interface): single rays through rtcIntersect1 / rtcOccluded1, and the 16-ray
// occlusion packets the packet dispatch uses (embree_packets.h). Include before any
// kernels/shared header that traces rays.
#pragma once
#include <cstdint>

#include <embree3/rtcore.h>

#include "kernels/shared/geometry.h"

namespace tessera::ts {

struct TsTracer {
    RTCScene scene;
    /// The packet mode of ts_trace_occluded_lanes: Embree's coherent mode, for lanes whose
    /// rays start close together (ts_packet_context).
    bool coherent = false;
};

/// `ray` as Embree's single ray (id 0, all masks, time 0).
inline RTCRay ts_embree_ray(TsRay ray) {
    RTCRay r;
    r.org_x = ray.org.x;
    r.org_y = ray.org.y;
    r.org_z = ray.org.z;
    r.tnear = ray.tmin;
    r.dir_x = ray.dir.x;
    r.dir_y = ray.dir.y;
    r.dir_z = ray.dir.z;
    r.time = 0.0f;
    r.tfar = ray.tmax;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
    return r;
}

inline TsHit ts_trace_closest(const TsTracer* tr, TsRay ray) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray = ts_embree_ray(ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(tr->scene, &ctx, &rh);
    TsHit h;
    h.t = rh.ray.tfar;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    h.prim = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? TS_NO_HIT : rh.hit.primID;
    if (h.prim == TS_NO_HIT) h.u = h.v = 0.0f;
    return h;
}

inline int ts_trace_occluded(const TsTracer* tr, TsRay ray) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r = ts_embree_ray(ray);
    rtcOccluded1(tr->scene, &ctx, &r);
    return r.tfar < 0.0f ? 1 : 0;  // Embree sets tfar to -inf on occlusion
}

/// The context of a 16-ray packet query: Embree's coherent mode when the caller grouped
/// rays that start close together and head the same way (it then traverses the packet
/// as a whole longer before splitting it).
inline RTCIntersectContext ts_packet_context(bool coherent) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    return ctx;
}

/// The context of an any-hit query that also reports the triangle it found
/// (ts_trace_any_hit, ts_trace_any_hit16): Embree's occlusion query with a context filter
/// that, before accepting a hit, writes its primID to prim[id] (id = the ray's id field,
/// its lane). The scene is built with RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION for it
/// (bvh/embree_scene.cpp); other queries leave the filter unset.
struct TsAnyHitContext {
    RTCIntersectContext ctx;  // first: Embree hands the filter this pointer
    uint32_t* prim;
};

inline void ts_record_any_hit(const RTCFilterFunctionNArguments* args) {
    const auto* c = reinterpret_cast<const TsAnyHitContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i)
        if (args->valid[i]) c->prim[RTCRayN_id(args->ray, args->N, i)] = RTCHitN_primID(args->hit, args->N, i);
}

inline TsAnyHitContext ts_any_hit_context(bool coherent, uint32_t* prim) {
    TsAnyHitContext c{ts_packet_context(coherent), prim};
    c.ctx.filter = ts_record_any_hit;
    return c;
}

/// Any hit of `ray` in [tmin, tmax): the triangle of a hit Embree found first, not
/// necessarily the nearest (an occlusion query, which stops there), or TS_NO_HIT. Equal
/// to ts_trace_occluded in whether it hits.
inline uint32_t ts_trace_any_hit(const TsTracer* tr, TsRay ray) {
    uint32_t prim = TS_NO_HIT;
    TsAnyHitContext c = ts_any_hit_context(false, &prim);
    RTCRay r = ts_embree_ray(ray);
    rtcOccluded1(tr->scene, &c.ctx, &r);
    if (!(r.tfar < 0.0f)) return TS_NO_HIT;
    // Blocked without a triangle noted: an Embree built without filter functions. The
    // closest hit is an answer too.
    return prim != TS_NO_HIT ? prim : ts_trace_closest(tr, ray).prim;
}

/// The 16-ray packet of kernels/shared/igi_gather16.h (which documents the calls below):
/// Embree's own layout, so the gather's vector loops write the rays straight into it.
using TsRayLanes = RTCRay16;

inline void ts_ray_lanes_init(TsRayLanes* r) {
    for (int i = 0; i < 16; ++i) {
        r->time[i] = 0.0f;
        r->mask[i] = 0xffffffffu;
        r->id[i] = static_cast<unsigned>(i);
        r->flags[i] = 0;
    }
}

inline void ts_ray_lanes_put(TsRayLanes* __restrict r, int i, const TsRay& ray) {
    r->org_x[i] = ray.org.x;
    r->org_y[i] = ray.org.y;
    r->org_z[i] = ray.org.z;
    r->dir_x[i] = ray.dir.x;
    r->dir_y[i] = ray.dir.y;
    r->dir_z[i] = ray.dir.z;
    r->tnear[i] = ray.tmin;
    r->tfar[i] = ray.tmax;
}

/// Copies ray `ray` into lane i of an Embree packet of 16, with the lane's other fields.
inline void ts_packet_set(RTCRay16& r, int i, const TsRay& ray) {
    ts_ray_lanes_put(&r, i, ray);
    r.time[i] = 0.0f;
    r.mask[i] = 0xffffffffu;
    r.id[i] = static_cast<unsigned>(i);
    r.flags[i] = 0;
}

/// Occlusion of a packet already laid out for Embree (its caller wrote the rays straight
/// into the structure of arrays): `valid` as for ts_trace_occluded16, 64-byte aligned, as
/// rtcOccluded16 requires. Returns the bit mask of the traced lanes found blocked.
inline uint32_t ts_occluded16(const TsTracer* tr, RTCRay16& r, const int* valid, bool coherent) {
    RTCIntersectContext ctx = ts_packet_context(coherent);
    rtcOccluded16(valid, tr->scene, &ctx, &r);
    uint32_t blocked = 0;
    for (int i = 0; i < 16; ++i)
        if (valid[i] && r.tfar[i] < 0.0f) blocked |= 1u << i;
    return blocked;
}

/// Occlusion of up to 16 rays as one packet (rtcOccluded16). `valid[i]` is -1 for a lane
/// to trace, 0 to skip (its ray is not read); returns a bit mask of the traced lanes
/// found blocked. Embree sets a blocked ray's tfar to -inf, as rtcOccluded1 does.
inline uint32_t ts_trace_occluded16(const TsTracer* tr, const TsRay* rays, const int* valid, bool coherent) {
    alignas(64) RTCRay16 r;
    alignas(64) int v[16];
    for (int i = 0; i < 16; ++i) {
        v[i] = valid[i];
        ts_packet_set(r, i, valid[i] ? rays[i] : rays[0]);
    }
    return ts_occluded16(tr, r, v, coherent);
}

/// ts_trace_any_hit of up to 16 rays as one packet (rtcOccluded16): prim[i] for each lane
/// with valid[i] != 0 (as for ts_trace_occluded16); the other entries are left as they are.
inline void ts_trace_any_hit16(const TsTracer* tr, const TsRay* rays, const int* valid, bool coherent,
                               uint32_t* prim) {
    alignas(64) RTCRay16 r;
    alignas(64) int v[16];
    uint32_t found[16];
    for (int i = 0; i < 16; ++i) {
        v[i] = valid[i];
        found[i] = TS_NO_HIT;
        ts_packet_set(r, i, valid[i] ? rays[i] : rays[0]);
    }
    TsAnyHitContext c = ts_any_hit_context(coherent, found);
    rtcOccluded16(v, tr->scene, &c.ctx, &r);
    for (int i = 0; i < 16; ++i) {
        if (!valid[i]) continue;
        prim[i] = r.tfar[i] < 0.0f ? found[i] : TS_NO_HIT;
        // Blocked without a triangle noted (an Embree without filter functions): the
        // closest hit is an answer too.
        if (r.tfar[i] < 0.0f && found[i] == TS_NO_HIT) prim[i] = ts_trace_closest(tr, rays[i]).prim;
    }
}

/// The packet query of kernels/shared/igi_march16.h: the rays of the lanes whose bit is set
/// in `valid` as one rtcOccluded16 packet, in the tracer's packet mode; returns the bit
/// mask of those found blocked.
inline uint32_t ts_trace_occluded_lanes(const TsTracer* tr, const TsRay* rays, uint32_t valid) {
    int v[16];
    for (int i = 0; i < 16; ++i) v[i] = valid >> i & 1u ? -1 : 0;
    return ts_trace_occluded16(tr, rays, v, tr->coherent);
}

/// Closest hits of up to 16 rays as one packet (rtcIntersect16); lanes with valid[i] == 0
/// are skipped and hits[i] is left as it was.
inline void ts_trace_closest16(const TsTracer* tr, const TsRay* rays, const int* valid, bool coherent, TsHit* hits) {
    RTCIntersectContext ctx = ts_packet_context(coherent);
    alignas(64) RTCRayHit16 rh;
    alignas(64) int v[16];
    for (int i = 0; i < 16; ++i) {
        v[i] = valid[i];
        ts_packet_set(rh.ray, i, valid[i] ? rays[i] : rays[0]);
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(v, tr->scene, &ctx, &rh);
    for (int i = 0; i < 16; ++i) {
        if (!valid[i]) continue;
        TsHit& h = hits[i];
        const bool miss = rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID;
        h.t = rh.ray.tfar[i];
        h.prim = miss ? TS_NO_HIT : rh.hit.primID[i];
        h.u = miss ? 0.0f : rh.hit.u[i];
        h.v = miss ? 0.0f : rh.hit.v[i];
    }
}

/// The closest-hit packet query of kernels/shared/igi_view16.h: the rays of the lanes whose
/// bit is set in `valid` as one rtcIntersect16 packet, in the tracer's packet mode.
inline void ts_trace_closest_lanes(const TsTracer* tr, const TsRay* rays, uint32_t valid, TsHit* hits) {
    int v[16];
    for (int i = 0; i < 16; ++i) v[i] = valid >> i & 1u ? -1 : 0;
    ts_trace_closest16(tr, rays, v, tr->coherent, hits);
}

/// Lane i's ray; Embree changes only an occluded lane's tfar.
inline TsRay ts_ray_lanes_get(const TsRayLanes* r, int i) {
    TsRay ray;
    ray.org = make_float3(r->org_x[i], r->org_y[i], r->org_z[i]);
    ray.dir = make_float3(r->dir_x[i], r->dir_y[i], r->dir_z[i]);
    ray.tmin = r->tnear[i];
    ray.tmax = r->tfar[i];
    return ray;
}

/// One rtcOccluded16 of the lanes with traced[i] = -1 (none when no lane is), in the
/// tracer's packet mode; Embree sets a blocked lane's tfar to -inf (ts_occluded16).
inline void ts_trace_occluded_ray_lanes(const TsTracer* tr, TsRayLanes* r, const int* __restrict traced,
                                        int* __restrict visible) {
    int any = 0;
    for (int i = 0; i < 16; ++i) any |= traced[i];
    if (any) {
        RTCIntersectContext ctx = ts_packet_context(tr->coherent);
        rtcOccluded16(traced, tr->scene, &ctx, r);
    }
    for (int i = 0; i < 16; ++i) visible[i] = traced[i] & (r->tfar[i] < 0.0f ? 0 : -1);
}

}  // namespace tessera::ts
