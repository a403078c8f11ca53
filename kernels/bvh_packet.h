/* OpenCL any-hit traversal of a packet of up to 16 rays over the BVH4 of
 * shared/layout_scene.h, for CPU devices (docs/ray-batches.md §4).
 *
 * PoCL runs a work-group's work-items one after another and cannot vectorise the
 * per-ray loop of bvh_traverse.h across them; here one work-item holds 16 rays as
 * float16 lanes (one AVX-512 register, or two AVX2 halves) and walks the tree once for
 * all of them (Wald, Slusallek, Benthin & Wagner, "Interactive Rendering with Coherent
 * Ray Tracing", EG 2001): one shared stack, each node's four child boxes tested against
 * all lanes at once, a child visited when any lane's interval meets its box, each
 * triangle of a leaf tested against all lanes at once.
 *
 * Per-lane result = ts_bvh_occluded's for the same ray, exactly:
 *   - the lanes that visit a node are exactly those whose single-ray traversal visits it:
 *     each stack entry carries the lane mask of the lanes that hit its box (tested only
 *     for lanes that visit the parent), so a lane never tests a triangle its own
 *     traversal would not reach (the box test is conservative, the triangle test is
 *     not, so an extra visit could find an extra hit);
 *   - the slab test (TS_BOX_TFAR_SCALE, the zero-direction guard) and the watertight
 *     triangle test are the formulas of bvh_traverse.h evaluated lane-wise in the same
 *     order, so every lane rounds as the scalar code does (no contraction, compat.h);
 *   - any-hit: the single-ray box tests use tmax throughout (it returns at its first
 *     hit), so do these; the visiting order only changes how soon a lane finds a hit.
 * Occluded lanes drop out of every later test; the walk ends when all lanes are occluded.
 *
 * Stack bound: visiting an inner node pops one entry and pushes at most its four
 * children, as in the single-ray traversal, so at depth d the stack holds at most
 * 3 d + 1 entries and TS_BVH_STACK_SIZE (layout_scene.h, >= 3 TS_BVH_MAX_DEPTH + 1, depth
 * checked by the builder) bounds it.
 */
#ifndef TS_BVH_PACKET_H
#define TS_BVH_PACKET_H
#include "bvh_traverse.h"

/* 16 rays, structure of arrays: lane i is ray i. */
typedef struct TsRay16 {
    float16 ox, oy, oz;
    float16 dx, dy, dz;
    float16 tmin, tmax;
} TsRay16;

#define TS_LANE_BITS16 \
    ((int16)(1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096, 8192, 16384, 32768))

/* Bit i set where lane i of the comparison result m is true (-1). */
static inline uint ts_lane_bits16(int16 m) {
    int16 b = m & TS_LANE_BITS16;
    int8 a = b.lo | b.hi;
    int4 c = a.lo | a.hi;
    int2 d = c.lo | c.hi;
    return (uint)(d.x | d.y);
}

/* -1 in lane i where bit i of `bits` is set, else 0. */
static inline int16 ts_lane_mask16(uint bits) { return ((int16)((int)bits) & TS_LANE_BITS16) != (int16)(0); }

/* 1 when some lane of the mask m (-1 or 0 per lane) is set. The traversals keep their
 * lane masks as int16 and ask only this in their loops: with Clang's vector reduction
 * (PoCL) it is one test of the comparison's mask register, where forming the lane bits
 * (ts_lane_bits16, no movemask in OpenCL C) takes a dozen shuffles and ORs. */
#ifdef __has_builtin
#if __has_builtin(__builtin_reduce_or)
#define TS_HAVE_REDUCE_OR 1
#endif
#endif
static inline int ts_any16(int16 m) {
#ifdef TS_HAVE_REDUCE_OR
    return __builtin_reduce_or(m != (int16)(0)) != 0; /* "!= 0" lets LLVM fold a compare's mask into the test */
#else
    return ts_lane_bits16(m) != 0u;
#endif
}

/* Lane-wise ts_f3_get: component k (0 = x, 1 = y, 2 = z) of (x, y, z) per lane. */
static inline float16 ts_pick16(float16 x, float16 y, float16 z, int16 k) {
    return select(select(z, y, k == (int16)(1)), x, k == (int16)(0));
}

/* Writes ray r into lane i of the arrays a (TS_RAY_FLOATS arrays of 16 floats, in the
 * order of TsRay16's fields), for ts_ray16_load. */
static inline void ts_ray16_put(float a[8][16], int i, TsRay r) {
    a[0][i] = r.org.x, a[1][i] = r.org.y, a[2][i] = r.org.z;
    a[3][i] = r.dir.x, a[4][i] = r.dir.y, a[5][i] = r.dir.z;
    a[6][i] = r.tmin, a[7][i] = r.tmax;
}

static inline TsRay16 ts_ray16_load(float a[8][16]) {
    TsRay16 r;
    r.ox = vload16(0, a[0]), r.oy = vload16(0, a[1]), r.oz = vload16(0, a[2]);
    r.dx = vload16(0, a[3]), r.dy = vload16(0, a[4]), r.dz = vload16(0, a[5]);
    r.tmin = vload16(0, a[6]), r.tmax = vload16(0, a[7]);
    return r;
}

/* Per-lane constants of the traversal: ts_bvh_traverse's setup, lane-wise. */
typedef struct TsPacketSetup {
    float16 ix, iy, iz;       /* 1 / direction, zero components guarded */
    int16 nx, ny, nz;         /* direction component < 0 (-1) */
    int16 kx, ky, kz;         /* watertight axis permutation */
    float16 sx, sy, sz;       /* watertight shear */
} TsPacketSetup;

static inline float16 ts_guard_zero16(float16 d) {
    return select(d, copysign((float16)(1e-30f), d), fabs(d) < (float16)(1e-30f));
}

static inline TsPacketSetup ts_packet_setup(const TsRay16* r) {
    TsPacketSetup p;
    float16 gx = ts_guard_zero16(r->dx), gy = ts_guard_zero16(r->dy), gz = ts_guard_zero16(r->dz);
    p.ix = 1.0f / gx, p.iy = 1.0f / gy, p.iz = 1.0f / gz;
    p.nx = gx < 0.0f, p.ny = gy < 0.0f, p.nz = gz < 0.0f;
    /* ts_watertight_setup on the unguarded direction. */
    float16 ax = fabs(r->dx), ay = fabs(r->dy), az = fabs(r->dz);
    const int16 i0 = (int16)(0), i1 = (int16)(1), i2 = (int16)(2);
    int16 kz = select(select(i2, i1, ay > az), select(i2, i0, ax > az), ax > ay);
    int16 kx = select(kz + i1, i0, kz == i2);
    int16 ky = select(kx + i1, i0, kx == i2);
    float16 dz = ts_pick16(r->dx, r->dy, r->dz, kz);
    int16 swap = dz < 0.0f; /* keep the winding */
    p.kx = select(kx, ky, swap);
    p.ky = select(ky, kx, swap);
    p.kz = kz;
    p.sx = ts_pick16(r->dx, r->dy, r->dz, p.kx) / dz;
    p.sy = ts_pick16(r->dx, r->dy, r->dz, p.ky) / dz;
    p.sz = 1.0f / dz;
    return p;
}

/* Lanes (-1) whose interval meets child c's box of `node`: ts_node_hits lane-wise, with
 * each lane's entry distance in *tnear. */
static inline int16 ts_packet_box_near(__global const float* node, int c, const TsRay16* r, const TsPacketSetup* p,
                                       float16* tnear) {
    float16 mnx = (float16)(node[TS_NODE_MIN(0) + c]), mxx = (float16)(node[TS_NODE_MAX(0) + c]);
    float16 mny = (float16)(node[TS_NODE_MIN(1) + c]), mxy = (float16)(node[TS_NODE_MAX(1) + c]);
    float16 mnz = (float16)(node[TS_NODE_MIN(2) + c]), mxz = (float16)(node[TS_NODE_MAX(2) + c]);
    float16 n_x = (select(mnx, mxx, p->nx) - r->ox) * p->ix, f_x = (select(mxx, mnx, p->nx) - r->ox) * p->ix;
    float16 n_y = (select(mny, mxy, p->ny) - r->oy) * p->iy, f_y = (select(mxy, mny, p->ny) - r->oy) * p->iy;
    float16 n_z = (select(mnz, mxz, p->nz) - r->oz) * p->iz, f_z = (select(mxz, mnz, p->nz) - r->oz) * p->iz;
    float16 tn = TS_SLAB_MAX(TS_SLAB_MAX(n_x, n_y), TS_SLAB_MAX(n_z, r->tmin));
    float16 tf = TS_SLAB_MIN(TS_SLAB_MIN(f_x, f_y), TS_SLAB_MIN(f_z, r->tmax)) * TS_BOX_TFAR_SCALE;
    *tnear = tn;
    return tn <= tf;
}

/* ts_packet_box_near without the distances (the any-hit traversal's test). */
static inline int16 ts_packet_box(__global const float* node, int c, const TsRay16* r, const TsPacketSetup* p) {
    float16 tnear;
    return ts_packet_box_near(node, c, r, p, &tnear);
}

/* Lanes (-1) that hit triangle `tri` with t in [tmin, tmax): ts_intersect_triangle
 * lane-wise (the caller masks the lanes that test it), with each lane's t, u (weight of
 * p1) and v (weight of p2) as it computes them; meaningful only in hit lanes. */
static inline int16 ts_packet_triangle_uv(__global const float* tri, const TsRay16* r, const TsPacketSetup* p,
                                          float16* t, float16* u, float16* v) {
    float3 a = vload3(0, tri + TS_BVH_TRI_VERTEX(0)), b = vload3(0, tri + TS_BVH_TRI_VERTEX(1)),
           c = vload3(0, tri + TS_BVH_TRI_VERTEX(2));
    float16 Ax0 = a.x - r->ox, Ay0 = a.y - r->oy, Az0 = a.z - r->oz;
    float16 Bx0 = b.x - r->ox, By0 = b.y - r->oy, Bz0 = b.z - r->oz;
    float16 Cx0 = c.x - r->ox, Cy0 = c.y - r->oy, Cz0 = c.z - r->oz;
    float16 Az = ts_pick16(Ax0, Ay0, Az0, p->kz), Bz = ts_pick16(Bx0, By0, Bz0, p->kz),
            Cz = ts_pick16(Cx0, Cy0, Cz0, p->kz);
    float16 Ax = ts_pick16(Ax0, Ay0, Az0, p->kx) - p->sx * Az, Ay = ts_pick16(Ax0, Ay0, Az0, p->ky) - p->sy * Az;
    float16 Bx = ts_pick16(Bx0, By0, Bz0, p->kx) - p->sx * Bz, By = ts_pick16(Bx0, By0, Bz0, p->ky) - p->sy * Bz;
    float16 Cx = ts_pick16(Cx0, Cy0, Cz0, p->kx) - p->sx * Cz, Cy = ts_pick16(Cx0, Cy0, Cz0, p->ky) - p->sy * Cz;
    float16 U = Cx * By - Cy * Bx;
    float16 V = Ax * Cy - Ay * Cx;
    float16 W = Bx * Ay - By * Ax;
    const float16 z = (float16)(0.0f);
    int16 outside = ((U < z) | (V < z) | (W < z)) & ((U > z) | (V > z) | (W > z));
    float16 det = U + V + W;
    int16 inside = ~outside & (det != z);
    /* t from the triangle's plane, as ts_intersect_triangle (a second division: igi and
     * ais frames 2-4% slower on PoCL, bench/results/huge_triangles.md; an early return
     * where no lane is inside measured no better). */
    float3 ng = cross(b - a, c - a);
    float16 den = ts_pick16((float16)(ng.x), (float16)(ng.y), (float16)(ng.z), p->kx) * p->sx +
                  ts_pick16((float16)(ng.x), (float16)(ng.y), (float16)(ng.z), p->ky) * p->sy +
                  ts_pick16((float16)(ng.x), (float16)(ng.y), (float16)(ng.z), p->kz);
    float16 tt = (ng.x * Ax0 + ng.y * Ay0 + ng.z * Az0) * p->sz / den;
    float16 rcp = 1.0f / det;
    *t = tt;
    *u = V * rcp;
    *v = W * rcp;
    return inside & (den != z) & (tt >= r->tmin) & (tt < r->tmax);
}

/* ts_packet_triangle_uv's hit lanes alone (the any-hit test; u and v go unused). */
static inline int16 ts_packet_triangle(__global const float* tri, const TsRay16* r, const TsPacketSetup* p) {
    float16 t, u, v;
    return ts_packet_triangle_uv(tri, r, p, &t, &u, &v);
}

/* The least (greatest) lane of x (no lane NaN). */
static inline float ts_min16(float16 x) {
    float8 a = TS_SLAB_MIN(x.lo, x.hi);
    float4 b = TS_SLAB_MIN(a.lo, a.hi);
    float2 c = TS_SLAB_MIN(b.lo, b.hi);
    return TS_SLAB_MIN(c.x, c.y);
}

/* The least lane of each of a, b, c and d (no lane NaN), as (min a, min b, min c, min d):
 * the four reductions share their steps (halves, then even against odd lanes). */
static inline float4 ts_min16x4(float16 a, float16 b, float16 c, float16 d) {
    float16 ab = (float16)(TS_SLAB_MIN(a.lo, a.hi), TS_SLAB_MIN(b.lo, b.hi)); /* a: 8 | b: 8 */
    float16 cd = (float16)(TS_SLAB_MIN(c.lo, c.hi), TS_SLAB_MIN(d.lo, d.hi));
    float16 q = (float16)(TS_SLAB_MIN(ab.even, ab.odd), TS_SLAB_MIN(cd.even, cd.odd)); /* 4 each */
    float8 e = TS_SLAB_MIN(q.even, q.odd);                                           /* 2 each */
    return TS_SLAB_MIN(e.even, e.odd);
}

static inline float ts_max16(float16 x) {
    float8 a = TS_SLAB_MAX(x.lo, x.hi);
    float4 b = TS_SLAB_MAX(a.lo, a.hi);
    float2 c = TS_SLAB_MAX(b.lo, b.hi);
    return TS_SLAB_MAX(c.x, c.y);
}

/* Closest hits of 16 rays, structure of arrays (TsHit per lane): t (tmax where nothing
 * is hit), u, v and prim (TS_NO_HIT where nothing is hit). */
typedef struct TsHit16 {
    float16 t, u, v;
    uint16 prim;
} TsHit16;

/* Tests the triangles of leaf `ref` against the lanes in `lanes`, shortening each lane's
 * interval (r->tmax) to its nearest hit and recording t's triangle, u and v in *h (h->t
 * is left to the caller: r->tmax holds it). Returns the lanes that found a nearer hit. */
static inline int16 ts_packet_leaf_closest(__global const float* tris, int ref, TsRay16* r, const TsPacketSetup* p,
                                           int16 lanes, TsHit16* h) {
    uint v = ~(uint)ref;
    uint first = v >> 3, count = v & 7u;
    int16 any_hit = (int16)(0);
    for (uint i = 0u; i < count; ++i) {
        __global const float* tri = tris + (first + i) * TS_BVH_TRI_FLOATS;
        float16 t, u, w;
        int16 hit = ts_packet_triangle_uv(tri, r, p, &t, &u, &w) & lanes;
        if (!ts_any16(hit)) continue;
        any_hit |= hit;
        r->tmax = select(r->tmax, t, hit);
        h->u = select(h->u, u, hit);
        h->v = select(h->v, w, hit);
        h->prim = select(h->prim, (uint16)(as_uint(tri[TS_BVH_TRI_PRIM])), as_uint16(hit));
    }
    return any_hit;
}

/* Occlusion of the lanes in `active` (bit i = lane i): returns the bits of those whose
 * ray hits a triangle with t in [tmin, tmax), each equal to ts_bvh_occluded for that
 * lane's ray. Lanes outside `active` are neither read as rays nor reported. When `prim`
 * is not 0, each occluded lane's entry becomes the triangle (TS_BVH_TRI_PRIM) that
 * occluded it: the first the packet's walk found, not necessarily the nearest, and not
 * always the one the lane's single-ray walk finds (the walk's order depends on the other
 * lanes); the other entries are left as they are. `prim` is a constant at each call
 * site, so the compiler drops its work where it is 0. */
static inline uint ts_bvh_any_hit16(__global const float* nodes, __global const float* tris, const TsRay16* r,
                                    uint active, uint16* prim) {
    if (active == 0u) return 0u;
    TsPacketSetup p = ts_packet_setup(r);
    const int16 live = ts_lane_mask16(active);
    int16 occluded = (int16)(0);
    int stack[TS_BVH_STACK_SIZE];
    int16 lanes[TS_BVH_STACK_SIZE]; /* the lanes visiting each entry */
    int sp = 0;
    stack[sp] = 0;
    lanes[sp++] = live;
    while (sp > 0) {
        --sp;
        int ref = stack[sp];
        int16 m = lanes[sp] & ~occluded;
        if (!ts_any16(m)) continue;
        if (ref >= 0) {
            __global const float* node = nodes + (uint)ref * TS_NODE_FLOATS;
            /* Children are pushed in slot order, not sorted near to far: for IGI's
             * shadow rays, mostly unoccluded, every hit child is visited anyway, and
             * sorting by the lanes' entry distances cost 10% of the pass on Sibenik. */
            int16 h[4] = {ts_packet_box(node, 0, r, &p) & m, ts_packet_box(node, 1, r, &p) & m,
                          ts_packet_box(node, 2, r, &p) & m, ts_packet_box(node, 3, r, &p) & m};
            for (int c = 0; c < 4; ++c) {
                if (!ts_any16(h[c])) continue;
                stack[sp] = as_int(node[TS_NODE_REFS + c]);
                lanes[sp++] = h[c];
            }
        } else {
            uint v = ~(uint)ref;
            uint first = v >> 3, count = v & 7u;
            for (uint i = 0u; i < count; ++i) {
                __global const float* tri = tris + (first + i) * TS_BVH_TRI_FLOATS;
                int16 hit = ts_packet_triangle(tri, r, &p) & m;
                if (prim) *prim = select(*prim, (uint16)(as_uint(tri[TS_BVH_TRI_PRIM])), as_uint16(hit));
                occluded |= hit;
                m &= ~hit;
                if (!ts_any16(m)) break;
            }
            if (!ts_any16(live & ~occluded)) break;
        }
    }
    return ts_lane_bits16(occluded) & active;
}

/* Occlusion of the lanes in `active`: ts_bvh_any_hit16 without the triangles. */
static inline uint ts_bvh_occluded16(__global const float* nodes, __global const float* tris, const TsRay16* r,
                                     uint active) {
    return ts_bvh_any_hit16(nodes, tris, r, active, 0);
}

/* hits[i] = lane i of h for each lane i in `valid` (bit i); the other entries untouched. */
static inline void ts_hit16_unpack(const TsHit16* h, uint valid, TsHit* hits) {
    float t[TS_PACKET_LANES], u[TS_PACKET_LANES], v[TS_PACKET_LANES];
    uint prim[TS_PACKET_LANES];
    vstore16(h->t, 0, t);
    vstore16(h->u, 0, u);
    vstore16(h->v, 0, v);
    vstore16(h->prim, 0, prim);
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        if (!(valid >> i & 1u)) continue;
        hits[i].t = t[i];
        hits[i].u = u[i];
        hits[i].v = v[i];
        hits[i].prim = prim[i];
    }
}

/* Closest hit of each lane in `active` (bit i = lane i), equal to ts_bvh_closest for
 * that lane's ray: both return the triangle with the least t in [tmin, tmax) among those
 * the ray hits, with t, u and v computed by the same formulas (ts_packet_triangle_uv).
 * Each lane's interval shrinks to its own nearest hit so far, and the boxes are tested
 * against it, as in the single-ray traversal; the box test is conservative, so no lane
 * skips a triangle nearer than its hit. Only the visiting order differs (children near
 * to far by the nearest entry of any lane that hits them), which could change the
 * answer only between two triangles hit at exactly the same t. (Skipping a popped
 * entry whose lanes all have a hit nearer than its entry measured no faster: the child
 * box tests cull such nodes one level later.) Lanes outside `active` get TS_NO_HIT.
 * The lane-wise traversal of ts_bvh_closest16 (bvh_packet_query.h), which sends a camera
 * tile (ts_packet_frustum) to ts_bvh_closest16_frustum instead, with the same per-lane
 * result (bvh_frustum.h). `p` is ts_packet_setup of `r`; `active` is not 0.
 * Stack bound as ts_bvh_occluded16. */
static inline TsHit16 ts_bvh_closest16_lanes(__global const float* nodes, __global const float* tris, TsRay16 r,
                                             const TsPacketSetup* p, uint active) {
    /* r.tmax: each lane's nearest hit so far */
    TsHit16 h;
    h.t = r.tmax;
    h.u = h.v = (float16)(0.0f);
    h.prim = (uint16)(TS_NO_HIT);
    int stack[TS_BVH_STACK_SIZE];
    int16 lanes[TS_BVH_STACK_SIZE]; /* the lanes visiting each entry */
    int sp = 0;
    stack[sp] = 0;
    lanes[sp++] = ts_lane_mask16(active);
    while (sp > 0) {
        --sp;
        int ref = stack[sp];
        int16 act = lanes[sp];
        if (ref >= 0) {
            __global const float* node = nodes + (uint)ref * TS_NODE_FLOATS;
            /* The four tests written out and their keys reduced together (ts_min16x4): a
             * loop over c reducing each child's lanes in turn kept distances and masks in
             * memory and chained four latency-bound reductions. */
            float16 t0, t1, t2, t3;
            int16 hc[4];
            hc[0] = ts_packet_box_near(node, 0, &r, p, &t0) & act;
            hc[1] = ts_packet_box_near(node, 1, &r, p, &t1) & act;
            hc[2] = ts_packet_box_near(node, 2, &r, p, &t2) & act;
            hc[3] = ts_packet_box_near(node, 3, &r, p, &t3) & act;
            /* Push far to near, so the child some lane enters first is visited first. */
            const float16 inf = (float16)(INFINITY);
            float key[4];
            vstore4(ts_min16x4(select(inf, t0, hc[0]), select(inf, t1, hc[1]), select(inf, t2, hc[2]),
                               select(inf, t3, hc[3])),
                    0, key);
            int order[4], n = 0;
            for (int c = 0; c < 4; ++c) {
                if (!ts_any16(hc[c])) continue;
                int j = n++;
                while (j > 0 && key[order[j - 1]] < key[c]) {
                    order[j] = order[j - 1];
                    --j;
                }
                order[j] = c;
            }
            for (int j = 0; j < n; ++j) {
                stack[sp] = as_int(node[TS_NODE_REFS + order[j]]);
                lanes[sp++] = hc[order[j]];
            }
        } else {
            ts_packet_leaf_closest(tris, ref, &r, p, act, &h);
        }
    }
    h.t = r.tmax;
    return h;
}

#endif /* TS_BVH_PACKET_H */
