/* The 16-ray packet variants of the igi surface and AIS extra kernels for CPU OpenCL
 * devices (docs/ray-batches.md §4): the OpenCL counterpart of
 * host/backend/embree_packets.cpp. A work-item holds 16 lanes (pixels or AIS items);
 * each lane runs the shared per-pixel code of shared/igi.h up to its links, then the
 * lanes gather them set by set, each link of the set traced for all lanes as one packet
 * (shared/igi_gather16.h, the Embree backend's gather too; ts_bvh_occluded16,
 * bvh_packet.h). Every lane so sums exactly the terms ts_igi_surface_set sums one ray at
 * a time, in the same order, and ts_bvh_occluded16's per-lane result is ts_bvh_occluded's:
 * the images equal the per-pixel kernels' bit for bit (tests/backend/opencl_packets_test.cpp).
 *
 * The media pass (igi_media_packets) and the media part of the AIS items run the shared
 * 16-lane ray march of shared/igi_march16.h, whose packet query ts_trace_occluded_lanes is
 * defined here.
 *
 * Private memory per work-item: 16 lanes × (view ~190 B + albedo 16 B + gather 32 B) + the
 * gather's lanes (1.8 KB) + the packet rays (512 B) + the traversal stack
 * (TS_BVH_STACK_SIZE × 8 B) ≈ 6 KB.
 */
#ifndef TS_IGI_PACKETS_H
#define TS_IGI_PACKETS_H
#include "bvh_packet_query.h"
#include "tracer.h"
#include "shared/ais_item.h"

/* 16 lanes, each a surface seen through a pixel and the links it gathers. */
typedef struct TsIgiPacket {
    TsIgiView view[TS_PACKET_LANES];
    float3 albedo[TS_PACKET_LANES]; /* at the view's surface: looked up once (textures cost pow) */
    uint set[TS_PACKET_LANES], mask[TS_PACKET_LANES];
    uint links[TS_PACKET_LANES]; /* 0: nothing to gather (idle lane, no surface) */
    TsIgiGather gather[TS_PACKET_LANES];
} TsIgiPacket;

/* The tracer's closest-hit packet query for shared/igi_view16.h (which documents it): the
 * rays of the lanes in `valid` as one ts_bvh_closest16 packet. */
static inline void ts_trace_closest_lanes(const TsTracer* tracer, const TsRay* rays, uint valid, TsHit* hits) {
    float a[8][TS_PACKET_LANES];
    for (int l = 0; l < TS_PACKET_LANES; ++l) ts_ray16_put(a, l, rays[l]);
    TsRay16 r = ts_ray16_load(a);
    TsHit16 h = ts_bvh_closest16(tracer->nodes, tracer->tris, &r, valid);
    ts_hit16_unpack(&h, valid, hits);
}
#include "shared/igi_view16.h"

/* The 16-ray packet of shared/igi_gather16.h (which documents these calls): the arrays
 * ts_ray16_load reads. */
typedef struct TsRayLanes {
    float a[8][TS_PACKET_LANES];
} TsRayLanes;

/* Zeroes every lane: a lane that is never put is then a finite ray, never traced. */
static inline void ts_ray_lanes_init(TsRayLanes* r) {
    for (int c = 0; c < 8; ++c)
        for (int i = 0; i < TS_PACKET_LANES; ++i) r->a[c][i] = 0.0f;
}

static inline void ts_ray_lanes_put(TsRayLanes* r, int i, TsRay ray) { ts_ray16_put(r->a, i, ray); }

static inline TsRay ts_ray_lanes_get(const TsRayLanes* r, int i) {
    TsRay ray;
    ray.org = make_float3(r->a[0][i], r->a[1][i], r->a[2][i]);
    ray.dir = make_float3(r->a[3][i], r->a[4][i], r->a[5][i]);
    ray.tmin = r->a[6][i];
    ray.tmax = r->a[7][i];
    return ray;
}

/* One ts_bvh_occluded16 packet of the lanes with traced[i] = -1 (its per-lane answers
 * are ts_bvh_occluded's); visible[i] = -1 for those found unoccluded. */
static inline void ts_trace_occluded_ray_lanes(const TsTracer* tracer, TsRayLanes* r, const int* traced,
                                               int* visible) {
    uint valid = 0u, blocked = 0u;
    for (int i = 0; i < TS_PACKET_LANES; ++i)
        if (traced[i]) valid |= 1u << i;
    if (valid != 0u) {
        TsRay16 p = ts_ray16_load(r->a);
        blocked = ts_bvh_occluded16(tracer->nodes, tracer->tris, &p, valid);
    }
    for (int i = 0; i < TS_PACKET_LANES; ++i) visible[i] = traced[i] & (blocked >> i & 1u ? 0 : -1);
}
#include "shared/igi_gather16.h"

/* The lanes in `want` see pixels (px[i], py[i]), their camera rays traced as one packet;
 * returns the lanes whose camera path found a surface, and sets each lane's links for
 * its set and components (p->set, p->mask; a black surface's too, as in
 * ts_igi_surface_set, and none for lanes outside `want`). */
static inline uint ts_igi_packet_views(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                       TsIgiPacket* p, uint want, const uint* px, const uint* py) {
    ts_igi_view16(sv, tracer, f, want, px, py, p->view);
    return ts_igi_view16_links(sv, f, want, p->view, p->set, p->mask, p->albedo, p->links);
}

/* The links of the first `lanes` lanes, gathered set by set (shared/igi_gather16.h). */
static inline void ts_igi_packet_gather(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                        TsIgiPacket* p, int lanes) {
    ts_igi_gather16(sv, tracer, f, lanes, p->view, p->set, p->mask, p->links, p->gather);
}

/* The igi surface pass, one work-item per packet block (ts_packet_block, shared/
 * geometry.h): ts_igi_surface_pixel for the block's 16 pixels, each written at its
 * pixel's place (TS_IGI_SURF_FLOATS floats). */
__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void igi_surface_packets(TS_KERNEL_ARGS) {
    uint k, bx, by;
    if (!ts_packet_block(&frame, get_global_id(0), &k, &bx, &by)) return;
    TS_KERNEL_VIEWS
    TsIgiPacket p;
    uint px[TS_PACKET_LANES], py[TS_PACKET_LANES], used = 0u;
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        p.set[i] = p.mask[i] = 0u;
        if (!ts_packet_block_pixel(&frame, k, bx, by, (uint)i, &px[i], &py[i])) continue;
        used |= 1u << i;
        p.set[i] = ts_igi_set(px[i], py[i], frame.igi_tile);
        p.mask[i] = frame.igi_components;
    }
    uint seen = ts_igi_packet_views(&sv, &tracer, &frame, &p, used, px, py);
    ts_igi_packet_gather(&sv, &tracer, &frame, &p, TS_PACKET_LANES);
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        if (!(used >> i & 1u)) continue;
        float v[TS_IGI_SURF_FLOATS];
        ts_igi_surface_clear(v);
        if (seen >> i & 1u) {
            float3 e_ss, e_id;
            float visible;
            ts_igi_gather_end(&p.gather[i], &frame, &e_ss, &e_id, &visible);
            const TsSurface* s = &p.view[i].s;
            ts_igi_surface_store(&p.view[i], p.albedo[i], ts_material_emission(&sv, s), e_ss, e_id, visible, v);
        }
        size_t o = ((size_t)py[i] * frame.width + px[i]) * TS_IGI_SURF_FLOATS;
        for (int c = 0; c < TS_IGI_SURF_FLOATS; ++c) out[o + c] = v[c];
    }
}

/* The tracer's packet query for shared/igi_march16.h (which documents it): the rays of
 * the lanes in `valid` as one ts_bvh_occluded16 packet. Every lane's ray is copied (the
 * march keeps them finite); only the valid lanes are traced. */
static inline uint ts_trace_occluded_lanes(const TsTracer* tracer, const TsRay* rays, uint valid) {
    float a[8][TS_PACKET_LANES];
    for (int l = 0; l < TS_PACKET_LANES; ++l) ts_ray16_put(a, l, rays[l]);
    TsRay16 r = ts_ray16_load(a);
    return ts_bvh_occluded16(tracer->nodes, tracer->tris, &r, valid);
}
#include "shared/igi_march16.h"

#ifdef TS_HAS_MEDIUM
/* The igi media pass, one work-item per packet block (as igi_surface_packets):
 * ts_igi_media_pixel for the block's 16 pixels, each written at its pixel's place. */
__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void igi_media_packets(TS_KERNEL_ARGS) {
    uint k, bx, by;
    if (!ts_packet_block(&frame, get_global_id(0), &k, &bx, &by)) return;
    TS_KERNEL_VIEWS
    uint px[TS_PACKET_LANES], py[TS_PACKET_LANES], set[TS_PACKET_LANES], used = 0u;
    float v[TS_PACKET_LANES][TS_IGI_MEDIA_FLOATS];
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        set[i] = 0u;
        if (!ts_packet_block_pixel(&frame, k, bx, by, (uint)i, &px[i], &py[i])) continue;
        used |= 1u << i;
        set[i] = ts_igi_set(px[i], py[i], frame.igi_tile);
    }
    ts_igi_march_packet(&sv, &tracer, &frame, used, px, py, set, v);
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        if (!(used >> i & 1u)) continue;
        size_t o = ((size_t)py[i] * frame.width + px[i]) * TS_IGI_MEDIA_FLOATS;
        for (int c = 0; c < TS_IGI_MEDIA_FLOATS; ++c) out[o + c] = v[i][c];
    }
}
#endif

/* The AIS extra items, 16 consecutive items of the list per work-item (the host lists
 * them grouped by set): ts_ais_extra_item for each, written in list order
 * (TS_AIS_ITEM_FLOATS floats). work_items = the number of items. */
__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void ais_extra_packets(TS_KERNEL_ARGS) {
    uint first = get_global_id(0) * TS_PACKET_LANES;
    if (first >= work_items) return;
    TS_KERNEL_VIEWS
    TsIgiPacket p;
    uint px[TS_PACKET_LANES], py[TS_PACKET_LANES], want = 0u;
    int lanes = (int)min((uint)TS_PACKET_LANES, work_items - first);
    for (int i = 0; i < lanes; ++i) {
        uint k, mask;
        ts_ais_item_decode(&sv, &frame, first + (uint)i, &px[i], &py[i], &k, &mask);
        p.set[i] = k;
        p.mask[i] = mask;
        if (ts_ais_item_has_surface(mask)) want |= 1u << i;
    }
    uint seen = ts_igi_packet_views(&sv, &tracer, &frame, &p, want, px, py);
    ts_igi_packet_gather(&sv, &tracer, &frame, &p, lanes);
#ifdef TS_HAS_MEDIUM
    /* The items with PM march side by side, set by set. */
    uint pm = 0u;
    float media[TS_PACKET_LANES][TS_IGI_MEDIA_FLOATS];
    for (int i = 0; i < lanes; ++i)
        if (p.mask[i] & TS_COMPONENT_PM) pm |= 1u << i;
    if (pm != 0u) ts_igi_march_packet(&sv, &tracer, &frame, pm, px, py, p.set, media);
#endif
    for (int i = 0; i < lanes; ++i) {
        float v[TS_AIS_ITEM_FLOATS];
        for (int c = 0; c < TS_AIS_ITEM_FLOATS; ++c) v[c] = 0.0f;
        if (seen >> i & 1u) {
            float3 e_ss, e_id;
            float visible;
            ts_igi_gather_end(&p.gather[i], &frame, &e_ss, &e_id, &visible);
            ts_ais_item_store_surface(e_ss, e_id, v);
        }
#ifdef TS_HAS_MEDIUM
        if (pm >> i & 1u)
            for (int c = 0; c < 3; ++c) v[TS_AIS_ITEM_PM + c] = media[i][TS_IGI_MEDIA_RADIANCE + c];
#endif
        size_t o = (size_t)(first + (uint)i) * TS_AIS_ITEM_FLOATS;
        for (int c = 0; c < TS_AIS_ITEM_FLOATS; ++c) out[o + c] = v[c];
    }
}

#endif /* TS_IGI_PACKETS_H */
