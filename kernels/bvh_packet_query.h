/* The 16-ray packet queries the kernels call: ts_bvh_occluded16 (bvh_packet.h) and
 * ts_bvh_closest16, which traces a packet that fits a frustum (a camera tile) by the
 * frustum traversal of bvh_frustum.h and any other lane-wise (bvh_packet.h); both give each
 * lane the hit of ts_bvh_closest for its ray. Kept apart so that bvh_packet.h and
 * bvh_frustum.h each compile by themselves (tests/kernels/standalone_headers_test.cpp). */
#ifndef TS_BVH_PACKET_QUERY_H
#define TS_BVH_PACKET_QUERY_H
#include "bvh_frustum.h"
#include "bvh_packet.h"

/* Closest hit of each lane in `active` (bit i = lane i), equal to ts_bvh_closest for that
 * lane's ray; lanes outside `active` get TS_NO_HIT. */
static inline TsHit16 ts_bvh_closest16(__global const float* nodes, __global const float* tris, const TsRay16* ray,
                                       uint active) {
    TsRay16 r = *ray;
    if (active == 0u) {
        TsHit16 h;
        h.t = r.tmax;
        h.u = h.v = (float16)(0.0f);
        h.prim = (uint16)(TS_NO_HIT);
        return h;
    }
    TsPacketSetup p = ts_packet_setup(&r);
    TsFrustum f;
    if (ts_packet_frustum(&r, &p, ts_lane_mask16(active), &f))
        return ts_bvh_closest16_frustum(nodes, tris, r, &p, &f, ts_lane_mask16(active));
    return ts_bvh_closest16_lanes(nodes, tris, r, &p, active);
}

#endif /* TS_BVH_PACKET_QUERY_H */
