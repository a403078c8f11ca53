/* Instant caching on OpenCL devices (shared/ic.h): the interpolation kernel (octree lookup over the
 * records, set as named inputs), and the record-VPL pair and gather kernels; on CPU
 * devices the host launches the 16-ray packet variant of the pair kernel. Built with
 * doubles where the device has cl_khr_fp64 (shared/compat.h TS_HAS_DOUBLE). */
#include "shared/frame.h"
#include "shared/layout_ic.h"
#include "tracer.h"
#include "bvh_packet_query.h"
#include "shared/ic.h"

TS_PIXEL_KERNEL(ic_interpolate, ts_ic_interpolate_kernel_pixel, TS_IC_INTERP_FLOATS)

/* The record–VPL work of the cache (placement, the temporal update): item i is one pair's
 * shadow ray, or one record's gather sum over its visibility row. */
TS_ITEM_KERNEL(ic_pair_pass, ts_ic_pair_item, TS_IC_PAIR_FLOATS)

TS_ITEM_KERNEL(ic_gather_pass, ts_ic_gather_item, TS_IC_GATHER_FLOATS)

/* The pair items, 16 consecutive items per work-item (CPU devices; placement lists a
 * block of records per VPL, so a packet's rays mostly end at one point; the temporal
 * update lists a record's pairs together): the items' shadow rays (ts_ic_pair_ray) as one
 * ts_bvh_any_hit16 packet, which hits where ts_ic_pair_item's query does, the triangle
 * it reports being any on the ray; written as ic_pair_pass writes them.
 * work_items = the number of items. */
__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void ic_pair_packets(TS_KERNEL_ARGS) {
    uint first = get_global_id(0) * TS_PACKET_LANES;
    if (first >= work_items) return;
    TS_KERNEL_VIEWS
    uint lanes = min((uint)TS_PACKET_LANES, work_items - first), traced = 0u;
    float a[8][TS_PACKET_LANES];
    for (uint i = 0u; i < TS_PACKET_LANES; ++i) {
        TsRay shadow;
        shadow.org = shadow.dir = (float3)(0.0f);
        shadow.tmin = shadow.tmax = 0.0f; /* an idle lane: never traced */
        if (i < lanes && ts_ic_pair_ray(&sv, &frame, first + i, &shadow)) traced |= 1u << i;
        ts_ray16_put(a, (int)i, shadow);
    }
    TsRay16 r = ts_ray16_load(a);
    uint16 hit = (uint16)(TS_NO_HIT);
    ts_bvh_any_hit16(tracer.nodes, tracer.tris, &r, traced, &hit);
    uint prim[TS_PACKET_LANES];
    vstore16(hit, 0, prim);
    for (uint i = 0u; i < lanes; ++i)
        out[(size_t)(first + i) * TS_IC_PAIR_FLOATS + TS_IC_PAIR_HIT] =
            as_float((traced >> i & 1u) ? prim[i] : (uint)TS_IC_PAIR_FACING);
}
