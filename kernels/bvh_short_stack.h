/* BVH4 traversal with a short stack and a restart trail, for GPU devices (built with
 * -DTS_GPU_TRAVERSAL; bvh_query.h picks it; it uses bvh_traverse.h's node and leaf tests).
 *
 * Why: the full-stack traversal keeps TS_BVH_STACK_SIZE = 160 ints (640 bytes) of
 * dynamically indexed private memory per work-item, one copy per inlined call site; GPUs
 * put that in slow scratch memory and it limits how many work-items run at once. Here
 * the stack holds TS_BVH_SHORT_STACK entries (5 bytes each) as a ring: a push onto a
 * full ring overwrites its oldest entry. Nothing is lost, because a restart trail
 * (Laine, "Restart trail for stackless BVH traversal", HPG 2010, §3, generalised from
 * binary to 4-wide nodes) records the path from the root: for each level l (root 0,
 * its children 1, ..., at most TS_BVH_MAX_DEPTH), the index k_l of the path's node among
 * its parent's hit children in visit order (2 bits) and whether it is the last of them.
 * When the ring is empty, the deepest level on the path that is not last is advanced
 * (k_l + 1, deeper levels cleared) and the traversal restarts at the root, descending
 * along the trail and refilling the ring with the siblings it passes; it ends when every
 * level of the path is last. Short stack plus restart: Horn, Sugerman, Houston and
 * Hanrahan, "Interactive k-D tree GPU raytracing", I3D 2007, §4.
 *
 * Same hits as the full stack: nodes are visited in the same depth-first order (hit
 * children by entry distance, ties by slot, ts_order_children). A descent after a
 * restart re-tests the boxes on the path with the current, possibly shorter hit distance
 * t*; a child culled by that re-test has entry distance > t* (the far bound only
 * shrinks), so its box holds no point of the ray before t* (the box test is
 * conservative, TS_BOX_TFAR_SCALE) and skipping it loses no nearer hit; the children
 * still hit keep their order and form a prefix of the earlier list, so the indices of
 * the trail still name the same children. The any-hit query returns at its first hit
 * and never shortens t*, so it visits exactly the full stack's nodes up to that hit. */
#ifndef TS_BVH_SHORT_STACK_H
#define TS_BVH_SHORT_STACK_H
#include "bvh_traverse.h"

/* Ring entries. 8 keeps the private state at 8 · 5 bytes plus three 64-bit trail words;
 * tests build with 1 (restart after every pop) to exercise the trail. A power of two. */
#ifndef TS_BVH_SHORT_STACK
#define TS_BVH_SHORT_STACK 8
#endif
#if TS_BVH_SHORT_STACK < 1 || (TS_BVH_SHORT_STACK & (TS_BVH_SHORT_STACK - 1)) != 0
#error "TS_BVH_SHORT_STACK must be a power of two"
#endif
#if TS_BVH_MAX_DEPTH > 62
#error "the restart trail keeps one bit per level in 64-bit words"
#endif

/* The trail: level l's index k_l is bit l of lo (low bit) and hi (high bit); `last` bit l
 * says the path's node at level l is its parent's last hit child. */
typedef struct TsTrail {
    ulong lo, hi, last;
} TsTrail;

static inline uint ts_trail_index(const TsTrail* tr, uint l) {
    return (uint)(tr->lo >> l & 1ul) | (uint)(tr->hi >> l & 1ul) << 1;
}

/* Records that the path enters child k of its node at level l − 1 (`last`: k is the last
 * hit child). Deeper levels are left as they are: zero on a first descent, the trail to
 * follow on a descent after a restart. */
static inline void ts_trail_enter(TsTrail* tr, uint l, uint k, uint last) {
    ulong bit = 1ul << l;
    tr->lo = (tr->lo & ~bit) | ((k & 1u) ? bit : 0ul);
    tr->hi = (tr->hi & ~bit) | ((k & 2u) ? bit : 0ul);
    tr->last = (tr->last & ~bit) | (last ? bit : 0ul);
}

/* Moves level l on to the next hit child (`last`: it is the last one) and clears every
 * deeper level: the subtree below is entered fresh. */
static inline void ts_trail_advance(TsTrail* tr, uint l, uint last) {
    uint k = ts_trail_index(tr, l) + 1u;
    ulong keep = (2ul << l) - 1ul;
    tr->lo &= keep;
    tr->hi &= keep;
    tr->last &= keep;
    ts_trail_enter(tr, l, k, last);
}

static inline TsHit ts_bvh_traverse_short(__global const float* nodes, __global const float* tris, TsRay ray,
                                          int any) {
    TsHit hit;
    float3 inv;
    int3 neg;
    TsWatertight w = ts_traversal_begin(ray, &hit, &inv, &neg);

    int ring_ref[TS_BVH_SHORT_STACK];
    uchar ring_level[TS_BVH_SHORT_STACK]; /* level | last << 7 */
    uint base = 0u, count = 0u;
    TsTrail tr;
    tr.lo = tr.hi = tr.last = 0ul;
    int ref = 0; /* the root */
    uint level = 0u;
    for (;;) {
        if (ref >= 0) {
            __global const float* node = nodes + (uint)ref * TS_NODE_FLOATS;
            float4 tn;
            int4 m = ts_node_hits(node, ray.org, inv, neg, ray.tmin, hit.t, &tn);
            TsChild c0, c1, c2, c3;
            uint n = (uint)ts_order_children(m, tn, as_int4(vload4(0, node + TS_NODE_REFS)), &c0, &c1, &c2, &c3);
            uint l = level + 1u;
            uint k = ts_trail_index(&tr, l); /* 0 on a first visit; the trail's child on a restart */
            if (k < n) {
                /* Enter child k; its later siblings go on the ring, farthest first. */
                for (uint i = 3u; i > k; --i) {
                    if (i >= n) continue;
                    int r = i == 3u ? c3.ref : i == 2u ? c2.ref : c1.ref;
                    uint slot = (base + count) & (TS_BVH_SHORT_STACK - 1u);
                    ring_ref[slot] = r;
                    ring_level[slot] = (uchar)(l | (i == n - 1u ? 0x80u : 0u));
                    if (count == TS_BVH_SHORT_STACK) base = (base + 1u) & (TS_BVH_SHORT_STACK - 1u);
                    else ++count;
                }
                ref = k == 0u ? c0.ref : k == 1u ? c1.ref : k == 2u ? c2.ref : c3.ref;
                ts_trail_enter(&tr, l, k, k == n - 1u);
                level = l;
                continue;
            }
            /* No child left to enter (none hit, or the trail's child is culled now):
             * this node is done. */
        } else if (ts_leaf_intersect(tris, ref, &w, ray, &hit, any)) {
            return hit;
        }
        if (count > 0u) { /* the next sibling of the deepest unfinished level */
            --count;
            uint slot = (base + count) & (TS_BVH_SHORT_STACK - 1u);
            ref = ring_ref[slot];
            level = ring_level[slot] & 0x7fu;
            ts_trail_advance(&tr, level, ring_level[slot] >> 7);
            continue;
        }
        /* Ring empty: restart at the deepest level of the path with a sibling left. */
        ulong open = ~tr.last & ((2ul << level) - 1ul) & ~1ul;
        if (open == 0ul) break;
        uint l = 63u - (uint)clz(open);
        ts_trail_advance(&tr, l, 0u);
        ref = 0;
        level = 0u;
    }
    return hit;
}

#endif /* TS_BVH_SHORT_STACK_H */
