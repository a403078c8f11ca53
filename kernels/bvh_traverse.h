/* OpenCL BVH4 traversal (layout in shared/layout_scene.h): closest hit and any hit.
 *
 * PoCL runs work-items of a work-group one after another and cannot vectorise a
 * traversal loop across them (its exit depends on the ray), so SIMD comes from inside
 * one ray: each node step tests the ray against the four child boxes with float4
 * arithmetic. No barriers: every work-item traverses on its own.
 *
 * Box test: slab test with the near/far plane chosen by the ray direction's sign (so
 * empty boxes, min = +inf and max = -inf, are never hit), and the far distance scaled
 * by 1 + 2γ3 (Ize, "Robust BVH Ray Traversal", JCGT 2013) so rounding cannot cull a box
 * the ray grazes. Triangle test: watertight (Woop, Benthin, Wald, "Watertight
 * Ray/Triangle Intersection", JCGT 2013), so rays cannot slip between triangles that
 * share an edge, with the distance from the triangle's plane (ts_intersect_triangle);
 * the double-precision fallback for exactly-zero edge functions is left out (doubles are
 * optional in OpenCL 1.2), which keeps watertightness and only resolves exact-edge ties
 * by a fixed rule.
 */
#ifndef TS_BVH_TRAVERSE_H
#define TS_BVH_TRAVERSE_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout_rays.h"
#include "shared/layout_scene.h"

/* 1 + 2γ(3) with γ(n) = n ε / (1 − n ε), ε = 2^-24: the slab distance (b − o) · (1/d)
 * takes three correctly rounded operations. A device without correctly rounded division
 * (-DTS_INEXACT_DIV_SQRT, host/opencl/program_cache.cpp) may be 2.5 ulp off in 1/d, five
 * half-ulps instead of one, so there the bound is 1 + 2γ(7) ≤ 1 + 8 · 2^-23. */
#ifdef TS_INEXACT_DIV_SQRT
#define TS_BOX_TFAR_SCALE 1.0000009536743164f
#else
#define TS_BOX_TFAR_SCALE 1.0000003576278687f
#endif

/* Larger and smaller of two slab distances, componentwise, as compare-selects: one
 * maxps/minps on x86, where OpenCL's fmax/fmin must also return the non-NaN operand and
 * cost two more instructions per call on PoCL. No slab distance is NaN for a ray with
 * finite origin and direction (1/d is finite and non-zero, ts_slab_setup; an empty
 * child's infinite bounds give ±inf), so the values equal fmax/fmin's; a ray with a NaN
 * component now misses every box where fmax/fmin let it enter all, a no-hit either way
 * (its triangle tests all fail). */
#define TS_SLAB_MAX(a, b) ((a) > (b) ? (a) : (b))
#define TS_SLAB_MIN(a, b) ((a) < (b) ? (a) : (b))

/* Per-ray constants of the watertight test: the axis permutation and the shear. */
typedef struct TsWatertight {
    int kx, ky, kz;
    float sx, sy, sz;
} TsWatertight;

static inline TsWatertight ts_watertight_setup(float3 d) {
    float3 a = fabs(d);
    int kz = (a.x > a.y) ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (ts_f3_get(d, kz) < 0.0f) { int t = kx; kx = ky; ky = t; } /* keep the winding */
    TsWatertight w;
    w.kx = kx; w.ky = ky; w.kz = kz;
    float dz = ts_f3_get(d, kz);
    w.sx = ts_f3_get(d, kx) / dz;
    w.sy = ts_f3_get(d, ky) / dz;
    w.sz = 1.0f / dz;
    return w;
}

/* Returns 1 and sets (*t, *u, *v) if the ray hits the triangle with t in (tmin, tmax). */
static inline int ts_intersect_triangle(const TsWatertight* w, float3 org, float tmin, float tmax,
                                 __global const float* tri, float* t, float* u, float* v) {
    float3 A = vload3(0, tri + TS_BVH_TRI_VERTEX(0)) - org, B = vload3(0, tri + TS_BVH_TRI_VERTEX(1)) - org,
           C = vload3(0, tri + TS_BVH_TRI_VERTEX(2)) - org;
    float Az = ts_f3_get(A, w->kz), Bz = ts_f3_get(B, w->kz), Cz = ts_f3_get(C, w->kz);
    float Ax = ts_f3_get(A, w->kx) - w->sx * Az, Ay = ts_f3_get(A, w->ky) - w->sy * Az;
    float Bx = ts_f3_get(B, w->kx) - w->sx * Bz, By = ts_f3_get(B, w->ky) - w->sy * Bz;
    float Cx = ts_f3_get(C, w->kx) - w->sx * Cz, Cy = ts_f3_get(C, w->ky) - w->sy * Cz;
    float U = Cx * By - Cy * Bx;
    float V = Ax * Cy - Ay * Cx;
    float W = Bx * Ay - By * Ax;
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return 0;
    float det = U + V + W;
    if (det == 0.0f) return 0;
    /* t from the triangle's plane, (ng · (p0 − org)) / (ng · dir), as Embree's, not from
     * Woop's sheared sum U Az + V Bz + W Cz: its terms grow with the triangle, so on a
     * triangle 1e9 across they cancel to within ulps of 1e9, and a quad 1.5 units behind
     * a bounce ray's origin gave t = -0, a hit at the origin (tmin inclusive) that ended
     * the path (pt 11% dark on the OpenCL backend; AHugeTriangleBlocksNoRay). The
     * denominator is ng · dir / dz from ng itself: det = U + V + W equals it up to sign
     * in exact arithmetic, but it rounds apart from the numerator on grazing rays
     * (Sibenik: 2 of 100k distances off by more than 1e-4). */
    float3 P0 = vload3(0, tri + TS_BVH_TRI_VERTEX(0));
    float3 ng = cross(vload3(0, tri + TS_BVH_TRI_VERTEX(1)) - P0, vload3(0, tri + TS_BVH_TRI_VERTEX(2)) - P0);
    float den = ts_f3_get(ng, w->kx) * w->sx + ts_f3_get(ng, w->ky) * w->sy + ts_f3_get(ng, w->kz);
    if (den == 0.0f) return 0;
    /* (ng · (p0 − org)) / (ng · dir), written as the packet test writes it, term by
     * term, so both round alike (OpenCLPackets.*EqualsPerRay*). */
    float tt = (ng.x * A.x + ng.y * A.y + ng.z * A.z) * w->sz / den;
    float rcp = 1.0f / det;
    /* tmin inclusive, as in Embree: a surface exactly at a ray's origin blocks it (an
     * offset origin never lies on its own triangle, see ts_offset_ray_origin). */
    if (!(tt >= tmin && tt < tmax)) return 0;
    *t = tt;
    *u = V * rcp; /* weight of p1 */
    *v = W * rcp; /* weight of p2 */
    return 1;
}

/* Distances to the four child boxes of `node`; a child is hit where near <= far. */
static inline int4 ts_node_hits(__global const float* node, float3 org, float3 inv, int3 neg,
                         float tmin, float tmax, float4* tnear_out) {
    float4 lo_x = vload4(0, node + (neg.x ? TS_NODE_MAX(0) : TS_NODE_MIN(0)));
    float4 hi_x = vload4(0, node + (neg.x ? TS_NODE_MIN(0) : TS_NODE_MAX(0)));
    float4 lo_y = vload4(0, node + (neg.y ? TS_NODE_MAX(1) : TS_NODE_MIN(1)));
    float4 hi_y = vload4(0, node + (neg.y ? TS_NODE_MIN(1) : TS_NODE_MAX(1)));
    float4 lo_z = vload4(0, node + (neg.z ? TS_NODE_MAX(2) : TS_NODE_MIN(2)));
    float4 hi_z = vload4(0, node + (neg.z ? TS_NODE_MIN(2) : TS_NODE_MAX(2)));
    float4 n_x = (lo_x - org.x) * inv.x, f_x = (hi_x - org.x) * inv.x;
    float4 n_y = (lo_y - org.y) * inv.y, f_y = (hi_y - org.y) * inv.y;
    float4 n_z = (lo_z - org.z) * inv.z, f_z = (hi_z - org.z) * inv.z;
    float4 tn = TS_SLAB_MAX(TS_SLAB_MAX(n_x, n_y), TS_SLAB_MAX(n_z, (float4)(tmin)));
    float4 tf = TS_SLAB_MIN(TS_SLAB_MIN(f_x, f_y), TS_SLAB_MIN(f_z, (float4)(tmax))) * TS_BOX_TFAR_SCALE;
    *tnear_out = tn;
    return tn <= tf;
}

/* A hit child of a node: entry distance, reference, and a tie-break rank (its slot
 * 0..3; -1 for a missed child, which is also given t = +inf). */
typedef struct TsChild {
    float t;
    int ref;
    int rank;
} TsChild;

/* Compare-exchange: after it *a comes first in visit order (nearer entry first; at
 * equal entry distance the higher slot first, which is the order the earlier
 * insertion sort and push loop gave, so traversal order and ties are unchanged). */
static inline void ts_child_exchange(TsChild* a, TsChild* b) {
    int swap = b->t < a->t || (b->t == a->t && b->rank > a->rank);
    TsChild x = *a;
    *a = swap ? *b : *a;
    *b = swap ? x : *b;
}

/* The children of a node in visit order, hit children first: a five-exchange sorting
 * network on four values held in registers (Knuth, TAOCP vol. 3 §5.3.4), for the GPU
 * variant (bvh_short_stack.h) instead of the insertion sort over dynamically indexed
 * private arrays below, which GPU compilers place in slow scratch memory. Every key is
 * distinct among hit children, so any correct network gives the insertion sort's order.
 * The full-stack traversal keeps the insertion sort: on PoCL the network, which always
 * does five exchanges where most nodes have one or two hit children, made per-ray
 * traversal ~15% slower (docs/ray-batches.md §5). Returns the number of hit children. */
static inline int ts_order_children(int4 m, float4 tn, int4 refs, TsChild* c0, TsChild* c1, TsChild* c2,
                                    TsChild* c3) {
    c0->t = m.x ? tn.x : INFINITY; c0->ref = refs.x; c0->rank = m.x ? 0 : -1;
    c1->t = m.y ? tn.y : INFINITY; c1->ref = refs.y; c1->rank = m.y ? 1 : -1;
    c2->t = m.z ? tn.z : INFINITY; c2->ref = refs.z; c2->rank = m.z ? 2 : -1;
    c3->t = m.w ? tn.w : INFINITY; c3->ref = refs.w; c3->rank = m.w ? 3 : -1;
    ts_child_exchange(c0, c1);
    ts_child_exchange(c2, c3);
    ts_child_exchange(c0, c2);
    ts_child_exchange(c1, c3);
    ts_child_exchange(c1, c2);
    return (m.x ? 1 : 0) + (m.y ? 1 : 0) + (m.z ? 1 : 0) + (m.w ? 1 : 0);
}

/* Tests the triangles of leaf `ref` in order, shortening *hit to each nearer one.
 * Returns 1 when `any` and a triangle was hit (the any-hit query is then answered). */
static inline int ts_leaf_intersect(__global const float* tris, int ref, const TsWatertight* w, TsRay ray,
                                    TsHit* hit, int any) {
    uint v = ~(uint)ref;
    uint first = v >> 3, count = v & 7u;
    for (uint i = 0u; i < count; ++i) {
        __global const float* tri = tris + (first + i) * TS_BVH_TRI_FLOATS;
        float t, u, vv;
        if (ts_intersect_triangle(w, ray.org, ray.tmin, hit->t, tri, &t, &u, &vv)) {
            hit->t = t;
            hit->u = u;
            hit->v = vv;
            hit->prim = as_uint(tri[TS_BVH_TRI_PRIM]);
            if (any) return 1;
        }
    }
    return 0;
}

/* Per-ray set-up of the slab test: 1/d with a zero component replaced by ±1e-30 (a
 * zero would give 0 · inf = NaN) and the direction's sign per axis. */
static inline void ts_slab_setup(float3 d, float3* inv, int3* neg) {
    float3 ds = make_float3(fabs(d.x) < 1e-30f ? copysign(1e-30f, d.x) : d.x,
                            fabs(d.y) < 1e-30f ? copysign(1e-30f, d.y) : d.y,
                            fabs(d.z) < 1e-30f ? copysign(1e-30f, d.z) : d.z);
    *inv = 1.0f / ds;
    *neg = (int3)(ds.x < 0.0f, ds.y < 0.0f, ds.z < 0.0f);
}

/* The state every traversal starts from: no hit yet (t = tmax), the slab test's
 * reciprocal direction and signs, and the watertight test's shear. */
static inline TsWatertight ts_traversal_begin(TsRay ray, TsHit* hit, float3* inv, int3* neg) {
    hit->prim = TS_NO_HIT;
    hit->t = ray.tmax;
    hit->u = hit->v = 0.0f;
    ts_slab_setup(ray.dir, inv, neg);
    return ts_watertight_setup(ray.dir);
}

/* Pushes the hit children (m) of a node with references `refs` onto stack[sp..] far to
 * near by entry distance tn, so the nearest is popped first; returns the new sp. No
 * bound check: the builder refuses trees deeper than TS_BVH_MAX_DEPTH, and
 * TS_BVH_STACK_SIZE >= 3 · TS_BVH_MAX_DEPTH + 1 is checked at compile time
 * (shared/layout_scene.h), so a push cannot overflow and no node is ever dropped. */
static inline int ts_push_hit_children(int4 m, float4 tn, int4 refs, int* stack, int sp) {
    int cr[4];
    float ct[4];
    int n = 0;
    if (m.x) { cr[n] = refs.x; ct[n++] = tn.x; }
    if (m.y) { cr[n] = refs.y; ct[n++] = tn.y; }
    if (m.z) { cr[n] = refs.z; ct[n++] = tn.z; }
    if (m.w) { cr[n] = refs.w; ct[n++] = tn.w; }
    for (int i = 1; i < n; ++i) { /* insertion sort, descending distance */
        int r = cr[i];
        float t = ct[i];
        int j = i - 1;
        while (j >= 0 && ct[j] < t) { cr[j + 1] = cr[j]; ct[j + 1] = ct[j]; --j; }
        cr[j + 1] = r;
        ct[j + 1] = t;
    }
    for (int i = 0; i < n; ++i) stack[sp++] = cr[i];
    return sp;
}

/* Traversal shared by closest and any hit. `any` is a compile-time constant at each
 * call site, so the compiler specialises the loop. */
static inline TsHit ts_bvh_traverse(__global const float* nodes, __global const float* tris, TsRay ray,
                             int any) {
    TsHit hit;
    float3 inv;
    int3 neg;
    TsWatertight w = ts_traversal_begin(ray, &hit, &inv, &neg);

    int stack[TS_BVH_STACK_SIZE];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        int ref = stack[--sp];
        if (ref >= 0) {
            __global const float* node = nodes + (uint)ref * TS_NODE_FLOATS;
            float4 tn;
            int4 m = ts_node_hits(node, ray.org, inv, neg, ray.tmin, hit.t, &tn);
            sp = ts_push_hit_children(m, tn, as_int4(vload4(0, node + TS_NODE_REFS)), stack, sp);
        } else if (ts_leaf_intersect(tris, ref, &w, ray, &hit, any)) {
            return hit;
        }
    }
    return hit;
}

#endif /* TS_BVH_TRAVERSE_H */
