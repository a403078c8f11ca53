/* Ray-batch kernels: trace rays given by the host and return hits. Used by the
 * traversal tests (against Embree) and the ray-throughput benchmark.
 * rays: TS_RAY_FLOATS floats per ray (layout_rays.h: org.xyz, tmin, dir.xyz, tmax).
 * trace_closest writes TS_HIT_FLOATS words per ray: t, u, v (floats), prim (uint bits).
 * trace_occluded writes 1 uint per ray: 1 if anything lies in (tmin, tmax);
 * trace_occluded_packets and trace_closest_packets the same as trace_occluded and
 * trace_closest, tracing 16 consecutive rays per work-item as one packet (bvh_packet.h;
 * the OpenCL backend's batches on CPU devices). */
#include "shared/frame.h"
#include "shared/layout_rays.h"
#include "bvh_packet_query.h"
#include "bvh_query.h"

static inline TsRay ts_load_ray(__global const float* rays, uint i) {
    __global const float* r = rays + TS_RAY_FLOATS * i;
    TsRay ray;
    ray.org = vload3(0, r + TS_RAY_ORG);
    ray.tmin = r[TS_RAY_TMIN];
    ray.dir = vload3(0, r + TS_RAY_DIR);
    ray.tmax = r[TS_RAY_TMAX];
    return ray;
}

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void trace_closest(__global const float* nodes, __global const float* tris,
                   __global const float* rays, uint count, __global float* hits) {
    uint i = get_global_id(0);
    if (i >= count) return;
    TsHit h = ts_bvh_closest(nodes, tris, ts_load_ray(rays, i));
    __global float* o = hits + TS_HIT_FLOATS * i;
    o[TS_HIT_T] = h.t;
    o[TS_HIT_U] = h.u;
    o[TS_HIT_V] = h.v;
    o[TS_HIT_PRIM] = as_float(h.prim);
}

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void trace_occluded(__global const float* nodes, __global const float* tris,
                    __global const float* rays, uint count, __global uint* occluded) {
    uint i = get_global_id(0);
    if (i >= count) return;
    occluded[i] = (uint)ts_bvh_occluded(nodes, tris, ts_load_ray(rays, i));
}

/* The packet of rays first .. first + 15 (those below count; the bits of `active`). */
static inline TsRay16 ts_load_ray16(__global const float* rays, uint first, uint count, uint* active) {
    uint lanes = min((uint)TS_PACKET_LANES, count - first);
    float a[8][TS_PACKET_LANES];
    *active = 0u;
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        TsRay r;
        r.org = r.dir = (float3)(0.0f);
        r.tmin = r.tmax = 0.0f; /* an idle lane: zeroed, never traced */
        if ((uint)i < lanes) {
            r = ts_load_ray(rays, first + (uint)i);
            *active |= 1u << i;
        }
        ts_ray16_put(a, i, r);
    }
    return ts_ray16_load(a);
}

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void trace_occluded_packets(__global const float* nodes, __global const float* tris,
                            __global const float* rays, uint count, __global uint* occluded) {
    uint first = get_global_id(0) * TS_PACKET_LANES;
    if (first >= count) return;
    uint active;
    TsRay16 r = ts_load_ray16(rays, first, count, &active);
    uint hit = ts_bvh_occluded16(nodes, tris, &r, active);
    for (uint i = 0u; first + i < count && i < TS_PACKET_LANES; ++i) occluded[first + i] = hit >> i & 1u;
}

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void trace_closest_packets(__global const float* nodes, __global const float* tris,
                           __global const float* rays, uint count, __global float* hits) {
    uint first = get_global_id(0) * TS_PACKET_LANES;
    if (first >= count) return;
    uint active;
    TsRay16 r = ts_load_ray16(rays, first, count, &active);
    TsHit16 h = ts_bvh_closest16(nodes, tris, &r, active);
    TsHit lane[TS_PACKET_LANES];
    ts_hit16_unpack(&h, active, lane);
    for (uint i = 0u; first + i < count && i < TS_PACKET_LANES; ++i) {
        __global float* o = hits + TS_HIT_FLOATS * (first + i);
        o[TS_HIT_T] = lane[i].t;
        o[TS_HIT_U] = lane[i].u;
        o[TS_HIT_V] = lane[i].v;
        o[TS_HIT_PRIM] = as_float(lane[i].prim);
    }
}
