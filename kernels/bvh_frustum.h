/* Frustum traversal of a 16-ray packet over the BVH4 of shared/layout_scene.h, for packets
 * whose rays share one origin, the sign of each direction component and nearly one
 * direction: tiles of camera rays (docs/ray-batches.md §4).
 *
 * The lane-wise traversals of bvh_packet.h test every child box against all 16 lanes:
 * four 16-wide slab tests per node. A coherent packet mostly agrees on every box, so
 * here a node's four boxes are tested once, with float4 arithmetic, against interval
 * bounds of the packet (Reshetov, Soupikov & Hurley, "Multi-level ray tracing
 * algorithm", SIGGRAPH 2005; Embree's coherent packets do likewise): the lanes' shared
 * origin and per axis the least and greatest 1/d. Leaves test every live lane,
 * lane-wise as before.
 *
 * Why each lane's answer is unchanged: the bounds hold for the lane's own computed slab
 * distances, not only for exact ones. A lane's distance to a box plane P is
 * round(a · i) with a = round(P − o), the same a for every lane (one origin), and i its
 * 1/d in [imin, imax] (all of one sign). Correctly rounded multiplication is monotone in
 * each operand, so round(a · imin) and round(a · imax) bound it: the lower bound is the
 * one with imin for a ≥ 0 and with imax for a < 0, the upper bound the other. max, min
 * and the TS_BOX_TFAR_SCALE product are monotone too, so when the packet's interval
 * misses a box, every lane's own test (bvh_traverse.h's) misses it: the frustum visits
 * a superset of the nodes each lane's traversal visits. Visiting extra leaves cannot
 * change a lane's answer: the triangle test is exact for the lane's ray (a triangle it
 * reports is hit in [tmin, tmax)), the closest-hit query keeps the least t of the hits it
 * finds, and the superset contains every triangle the lane's own traversal would find.
 * As in ts_bvh_closest16, only triangles hit at exactly the same t could be chosen
 * differently (the visiting order differs).
 *
 * Stack bound: one pop, at most four pushes per node, as the single-ray traversal:
 * TS_BVH_STACK_SIZE (layout_scene.h) holds.
 */
#ifndef TS_BVH_FRUSTUM_H
#define TS_BVH_FRUSTUM_H
#include "bvh_packet.h"

/* A packet's interval bounds, per axis (x, y, z of each field), over its live lanes. */
typedef struct TsFrustum {
    float3 org;    /* the lanes' shared origin */
    float3 imin, imax; /* least and greatest 1/d (guarded as in ts_packet_setup) */
    int3 neg;      /* -1 where every live lane's direction is negative, else 0 */
    float tmin;    /* least tmin */
} TsFrustum;

/* Largest difference of a lane's unit direction from lane 0's, per component, for which
 * a packet goes by its frustum. A 4×4 pixel tile at 512² spans 0.007 on Sibenik (60°
 * field of view) and passes. The igi camera packets, 4×4 pixels of one interleave set
 * (9 pixels across at tile 3), span about 0.020 there and 0.013 on the Cornell box, and
 * may pass: their frames measured the same with and without the frustum (512², medians
 * of 3 alternating runs: Cornell box 183.4 against 185.0 ms, Sibenik 493.9 against
 * 495.5). 16 scattered AIS items do not pass: taken by the frustum (the first version,
 * no gate), whose leaves test all 16 lanes, ais frames on the Cornell box were ~5%
 * slower. Only the choice of traversal depends on it, never a result. */
#define TS_FRUSTUM_SPREAD 0.02f

/* 1 when the live lanes share one origin, agree on all three direction signs and their
 * directions lie within TS_FRUSTUM_SPREAD of one another (then *f holds their bounds),
 * else 0 and *f is unset.
 *
 * Why a shared origin: with origins spread over a region (shadow rays from 16 surface
 * points to one light sample), the interval product [P − omax, P − omin] · [imin, imax]
 * (the bound for spread origins) is loose
 * wherever one lane's direction component is small (imax ~ 1/|d| grows without bound),
 * and the leaves of nearly every node the region's rays pass were tested for all 16
 * lanes: Sibenik light-sample shadow rays ran at 4.7 Mrays/s against 37 lane-wise
 * (bench/results/ray_bench.md). Camera rays of a pinhole camera share their origin,
 * and for them the bounds are the tile's own frustum. */
static inline int ts_packet_frustum(const TsRay16* r, const TsPacketSetup* p, int16 live, TsFrustum* f) {
    /* Cheap tests first: the shadow-ray packets of IGI fail the first one, once per link
     * of every packet. A packet whose lane 0 is idle goes lane-wise (none of ours does). */
    if (!live.s0) return 0;
    float3 o = make_float3(r->ox.s0, r->oy.s0, r->oz.s0);
    int16 moved = (r->ox != (float16)(o.x)) | (r->oy != (float16)(o.y)) | (r->oz != (float16)(o.z));
    if (ts_any16(live & moved)) return 0;
    /* Directions within TS_FRUSTUM_SPREAD of lane 0's (unit vectors, per component). */
    float16 rl = rsqrt(r->dx * r->dx + r->dy * r->dy + r->dz * r->dz);
    float16 ux = r->dx * rl, uy = r->dy * rl, uz = r->dz * rl;
    float16 spread = TS_SLAB_MAX(TS_SLAB_MAX(fabs(ux - (float16)(ux.s0)), fabs(uy - (float16)(uy.s0))),
                                 fabs(uz - (float16)(uz.s0)));
    if (ts_any16(live & ~(spread <= (float16)(TS_FRUSTUM_SPREAD)))) return 0;
    int3 neg = (int3)(p->nx.s0, p->ny.s0, p->nz.s0);
    int16 differs = (p->nx ^ (int16)(neg.x)) | (p->ny ^ (int16)(neg.y)) | (p->nz ^ (int16)(neg.z));
    if (ts_any16(live & differs)) return 0;
    const float16 inf = (float16)(INFINITY), ninf = (float16)(-INFINITY);
    f->org = o;
    f->imin = make_float3(ts_min16(select(inf, p->ix, live)), ts_min16(select(inf, p->iy, live)),
                          ts_min16(select(inf, p->iz, live)));
    f->imax = make_float3(ts_max16(select(ninf, p->ix, live)), ts_max16(select(ninf, p->iy, live)),
                          ts_max16(select(ninf, p->iz, live)));
    f->neg = neg;
    f->tmin = ts_min16(select(inf, r->tmin, live));
    return 1;
}

/* Lower bound of the lanes' distances to near planes P (see the header). */
static inline float4 ts_frustum_near(float4 plane, float org, float imin, float imax) {
    float4 a = plane - org;
    return select(a * imax, a * imin, a >= (float4)(0.0f));
}

/* Upper bound of the lanes' distances to far planes P. */
static inline float4 ts_frustum_far(float4 plane, float org, float imin, float imax) {
    float4 b = plane - org;
    return select(b * imin, b * imax, b >= (float4)(0.0f));
}

/* Bounds of the lanes' distances to the near and far planes of the four child boxes of
 * `node` on one axis (neg: the lanes' direction is negative there). */
static inline void ts_frustum_slab(__global const float* node, int axis, int neg, float org, float imin, float imax,
                                   float4* tnear, float4* tfar) {
    *tnear = ts_frustum_near(vload4(0, node + (neg ? TS_NODE_MAX(axis) : TS_NODE_MIN(axis))), org, imin, imax);
    *tfar = ts_frustum_far(vload4(0, node + (neg ? TS_NODE_MIN(axis) : TS_NODE_MAX(axis))), org, imin, imax);
}

/* Children of `node` whose box the packet's interval meets before tmax (the greatest
 * lane tmax), with the lower bound of the lanes' entry distances in *tnear. */
static inline int4 ts_frustum_node(__global const float* node, const TsFrustum* f, float tmax, float4* tnear) {
    float4 nx, fx, ny, fy, nz, fz;
    ts_frustum_slab(node, 0, f->neg.x, f->org.x, f->imin.x, f->imax.x, &nx, &fx);
    ts_frustum_slab(node, 1, f->neg.y, f->org.y, f->imin.y, f->imax.y, &ny, &fy);
    ts_frustum_slab(node, 2, f->neg.z, f->org.z, f->imin.z, f->imax.z, &nz, &fz);
    float4 tn = TS_SLAB_MAX(TS_SLAB_MAX(nx, ny), TS_SLAB_MAX(nz, (float4)(f->tmin)));
    float4 tf = TS_SLAB_MIN(TS_SLAB_MIN(fx, fy), TS_SLAB_MIN(fz, (float4)(tmax))) * TS_BOX_TFAR_SCALE;
    *tnear = tn;
    return tn <= tf;
}

/* ts_bvh_closest16 for a packet with a frustum (ts_packet_frustum): the same per-lane
 * result. The frustum's far bound shrinks with the greatest lane hit so far. */
static inline TsHit16 ts_bvh_closest16_frustum(__global const float* nodes, __global const float* tris, TsRay16 r,
                                               const TsPacketSetup* p, const TsFrustum* f, int16 live) {
    TsHit16 h;
    h.u = h.v = (float16)(0.0f);
    h.prim = (uint16)(TS_NO_HIT);
    float tfar = ts_max16(select((float16)(-INFINITY), r.tmax, live));
    int stack[TS_BVH_STACK_SIZE];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        int ref = stack[--sp];
        if (ref >= 0) {
            __global const float* node = nodes + (uint)ref * TS_NODE_FLOATS;
            float4 tn;
            int4 m = ts_frustum_node(node, f, tfar, &tn);
            sp = ts_push_hit_children(m, tn, as_int4(vload4(0, node + TS_NODE_REFS)), stack, sp);
        } else {
            if (ts_any16(ts_packet_leaf_closest(tris, ref, &r, p, live, &h))) tfar = ts_max16(select((float16)(-INFINITY), r.tmax, live));
        }
    }
    h.t = r.tmax;
    return h;
}

#endif /* TS_BVH_FRUSTUM_H */
