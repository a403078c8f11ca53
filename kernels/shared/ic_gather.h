/* Instant caching, the record-VPL work that needs no tracer (docs/instant-caching.md §3):
 * a record's surface and the gather sum of its E over the VPLs its visibility row marks
 * visible. The pair and gather kernels (shared/ic.h) call these; host code may too. */
#ifndef TS_IC_GATHER_H
#define TS_IC_GATHER_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout_ic.h"
#include "shared/layout_igi.h"
#include "shared/medium.h"
#include "shared/vpl.h"

TS_NAMESPACE_BEGIN

/* The surface a record was made at, from its G-buffer entry (TS_IC_GBUF_FLOATS): what
 * ts_vpl_geometry reads. */
TS_INLINE TsSurface ts_ic_record_surface(TS_GLOBAL const float* g) {
    TsSurface s;
    s.position = ts_f3_load(g + TS_IC_GBUF_POSITION);
    s.geo_normal = ts_f3_load(g + TS_IC_GBUF_GEO_NORMAL);
    s.shading_normal = ts_f3_load(g + TS_IC_GBUF_NORMAL);
    s.uv = make_float2(0.0f, 0.0f);
    s.material = 0u;
    s.front_face = 1;
    s.origin = ts_f3_load(g + TS_IC_GBUF_ORIGIN);
    s.pos_scale = g[TS_IC_GBUF_POS_SCALE];
    return s;
}

/* Writes a gather's TS_IC_GATHER_FLOATS outputs (layout_ic.h) from its sums: E and the
 * harmonic mean distance as ts_ic_gather has always formed them, then the sums themselves
 * as (hi, lo) pairs. A double d goes out as hi = (float)d, lo = (float)(d - hi), whose sum
 * holds d to about 2^-48 of it. */
TS_INLINE void ts_ic_gather_pair_out(float* out, uint at, float hi, float lo) {
    out[at] = hi;
    out[at + 1u] = lo;
}

#ifdef TS_HAS_DOUBLE
/* The harmonic mean distance from the sums: `seen` visible VPLs, Σ 1/distance; +inf for
 * none. The host forms it from its kept sums with this too (host/gi/ic_gather.h). */
TS_INLINE float ts_ic_harmonic_mean(double seen, double inv_dist) {
    return seen > 0.0 && inv_dist > 0 ? (float)(seen / inv_dist) : TS_INF;
}

TS_INLINE void ts_ic_gather_split_out(float* out, uint at, double d) {
    float hi = (float)d;
    ts_ic_gather_pair_out(out, at, hi, (float)(d - (double)hi));
}

TS_INLINE void ts_ic_gather_store_double(float* out, TsDouble3 sum, double inv_dist, uint seen) {
    ts_f3_store(out + TS_IC_GATHER_E, ts_vpl_gather_result_double(sum));
    out[TS_IC_GATHER_HARMONIC] = ts_ic_harmonic_mean((double)seen, inv_dist);
    ts_ic_gather_split_out(out, TS_IC_GATHER_SUM, sum.x);
    ts_ic_gather_split_out(out, TS_IC_GATHER_SUM + 2u, sum.y);
    ts_ic_gather_split_out(out, TS_IC_GATHER_SUM + 4u, sum.z);
    ts_ic_gather_split_out(out, TS_IC_GATHER_INV_DIST, inv_dist);
    out[TS_IC_GATHER_SEEN] = (float)seen;
}
#else
TS_INLINE void ts_ic_gather_store_compensated(float* out, TsSum3 sum, float inv_dist, float inv_dist_c, uint seen) {
    ts_f3_store(out + TS_IC_GATHER_E, ts_vpl_gather_result_compensated(sum));
    float total = inv_dist + inv_dist_c;
    out[TS_IC_GATHER_HARMONIC] = seen > 0u && total > 0 ? (float)(seen / total) : TS_INF;
    for (uint c = 0u; c < 3u; ++c) ts_ic_gather_pair_out(out, TS_IC_GATHER_SUM + 2u * c, sum.s[c], sum.c[c]);
    ts_ic_gather_pair_out(out, TS_IC_GATHER_INV_DIST, inv_dist, inv_dist_c);
    out[TS_IC_GATHER_SEEN] = (float)seen;
}
#endif

/* E = (1/π) Σ_j C_j T_j min(G_j, b) over the `count` VPLs (in order) whose bit in the
 * mask `visible` (TS_IC_VISIBLE_WORDS(count) uints, layout_ic.h) is set, and the harmonic
 * mean distance to them (+inf for none): the
 * radius estimate of docs/instant-caching.md §4 that needs no extra rays. Sums in double
 * where the device has it (bit-identical to the host's former double sums), else in
 * compensated float (shared/vpl.h). Writes TS_IC_GATHER_FLOATS to out. */
TS_INLINE void ts_ic_gather(const TsSurface* s, TS_GLOBAL const uint* visible, uint count, TS_GLOBAL const float* vpls,
                            const TsMedium* med, float b, float* out) {
#ifdef TS_HAS_DOUBLE
    TsDouble3 sum = {0.0, 0.0, 0.0};
    double inv_dist = 0.0;
#else
    TsSum3 sum = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    float inv_dist = 0.0f, inv_dist_c = 0.0f;
#endif
    uint seen = 0u;
    /* The shadow ray matters only for the medium's transmittance: without a medium it is
     * not built, and the transmittance is 1 as ts_shadow_transmittance would return (same
     * sums; a tic re-sum of 18k records on the Cornell box, Embree: 28 → 24.5 ms). */
    float3 org = ts_offset_ray_origin(s->origin, s->geo_normal, s->pos_scale);
    for (uint j = 0; j < count; ++j) {
        /* A word without a visible VPL is skipped whole: the temporal update's re-sums
         * over a few changed VPLs pass masks that are mostly zero. */
        uint word = visible[j >> 5];
        if (word == 0u) {
            j |= 31u;
            continue;
        }
        if (!((word >> (j & 31u)) & 1u)) continue;
        TS_GLOBAL const float* v = vpls + (size_t)TS_VPL_FLOATS * j;
        float g = ts_vpl_geometry_term(s->position, s->shading_normal, s->geo_normal, v, b, med->g);
        if (!(g > 0.0f)) continue;
        float3 tr =
            med->present ? ts_vpl_shadow_transmittance(med, ts_vpl_shadow_ray(org, v), v) : make_float3(1.0f, 1.0f, 1.0f);
        float3 d = ts_f3_load(v + TS_VPL_POSITION) - s->position;
#ifdef TS_HAS_DOUBLE
        ts_vpl_gather_add_double(&sum, v, tr, g);
        inv_dist += 1.0 / sqrt((double)dot(d, d));
#else
        ts_vpl_gather_add_compensated(&sum, v, tr, g);
        ts_sum_compensated_add(&inv_dist, &inv_dist_c, 1.0f / sqrt(dot(d, d)));
#endif
        ++seen;
    }
#ifdef TS_HAS_DOUBLE
    ts_ic_gather_store_double(out, sum, inv_dist, seen);
#else
    ts_ic_gather_store_compensated(out, sum, inv_dist, inv_dist_c, seen);
#endif
}

#ifdef TS_HAS_DOUBLE
/* ts_ic_gather for the records of TS_PACKET_LANES lanes at once; the Embree backend
 * batches records this way (host/backend/embree_ic_gather.cpp). The loop runs over the
 * VPLs; its body, the same for every lane, runs over the lanes in loops GCC vectorises
 * (the one-record loop is bound by the latency of its divisions and square roots, about
 * 36 cycles a visible pair; a tic re-sum of 18k records × 400 VPLs on the Cornell box:
 * 24.5 → 16.5 ms). PoCL does not vectorise these loops: as an OpenCL kernel of 16 records
 * per work-item the same re-sum took 44 ms against 24 ms one record per work-item, so
 * the OpenCL backend keeps the latter. A hidden lane adds +0 to each sum, which leaves it
 * unchanged, so each lane's sums take the same terms in the same order as ts_ic_gather's:
 * the outputs are equal bit for bit, with a medium too (its transmittance below). */
typedef struct TsIcLanes {
    float x[3][TS_PACKET_LANES], n[3][TS_PACKET_LANES], ng[3][TS_PACKET_LANES]; /* the records' surfaces */
    float o[3][TS_PACKET_LANES];   /* their shadow rays' origin (ts_offset_ray_origin) */
    float pos_scale[TS_PACKET_LANES];
    int held[TS_PACKET_LANES];     /* the origin in the medium (ts_medium_holds) */
    uint word[TS_PACKET_LANES];    /* each lane's visibility bits of the current 32 VPLs */
    double e[3][TS_PACKET_LANES], inv_dist[TS_PACKET_LANES]; /* the sums of ts_ic_gather */
    uint seen[TS_PACKET_LANES];
} TsIcLanes;

/* Lane i's record surface (ts_ic_record_surface's position and normals, and the origin
 * of ts_ic_gather's shadow rays). */
TS_INLINE void ts_ic_lanes_set(TsIcLanes* L, int i, TS_GLOBAL const float* g) {
    const TsSurface s = ts_ic_record_surface(g);
    const float3 o = ts_offset_ray_origin(s.origin, s.geo_normal, s.pos_scale);
    for (int a = 0; a < 3; ++a) {
        L->x[a][i] = g[TS_IC_GBUF_POSITION + a];
        L->n[a][i] = g[TS_IC_GBUF_NORMAL + a];
        L->ng[a][i] = g[TS_IC_GBUF_GEO_NORMAL + a];
    }
    L->o[0][i] = o.x;
    L->o[1][i] = o.y;
    L->o[2][i] = o.z;
    L->pos_scale[i] = s.pos_scale;
}

/* The medium's transmittance tr[c][i] along lane i's shadow ray to VPL v, for the lanes
 * with use[i] set (others keep 1), as ts_ic_gather takes it (ts_shadow_transmittance of
 * ts_vpl_shadow_ray), bit for bit. A ray whose two ends lie in the medium skips the slab
 * test (ts_medium_keeps_span): its length runs over the lanes; any other takes the
 * one-ray function's slab test. In the foggy Cornell box, whose fog fills the room, that
 * is every ray. The exponentials run over the lanes at once (ts_medium_exp_lanes). */
TS_INLINE void ts_ic_lanes_transmittance(const TsIcLanes* TS_RESTRICT L, TS_GLOBAL const float* v,
                                         const TsMedium* med, const int* use, float tr[3][TS_PACKET_LANES]) {
    const TsRay end = ts_vpl_shadow_ray(make_float3(0.0f, 0.0f, 0.0f), v); /* dir: ts_vpl_shadow_end */
    const int end_held = ts_medium_holds(med, end.dir);
    float len[TS_PACKET_LANES];
    int keeps[TS_PACKET_LANES];
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        const float3 dir = end.dir - make_float3(L->o[0][i], L->o[1][i], L->o[2][i]); /* ts_shadow_ray's */
        len[i] = length(dir);
        keeps[i] = ts_medium_keeps_span(L->held[i] & end_held, dir, end.tmin, end.tmax);
    }
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        float3 x = make_float3(0.0f, 0.0f, 0.0f); /* e^0 = 1 exactly */
        if (use[i] && keeps[i])
            x = ts_medium_span_log_transmittance(med, len[i], end.tmin, end.tmax);
        else if (use[i])
            x = ts_shadow_log_transmittance(med, ts_vpl_shadow_ray(make_float3(L->o[0][i], L->o[1][i], L->o[2][i]), v));
        tr[0][i] = x.x;
        tr[1][i] = x.y;
        tr[2][i] = x.z;
    }
    ts_medium_exp_lanes(med, tr);
}

/* VPL v (bit `bit` of the lanes' current words) added to every lane that sees it; `kind`
 * is ts_vpl_in_medium(v), a constant once inlined (ts_ic_lanes_add), hg the medium's
 * Henyey–Greenstein g, med the medium the links cross (NULL: none, transmittance 1). */
TS_INLINE void ts_ic_lanes_add_of(TsIcLanes* L, TS_GLOBAL const float* v, uint bit, float b, float hg, int kind,
                                  const TsMedium* med) {
    const float3 y = ts_f3_load(v + TS_VPL_POSITION), c = ts_f3_load(v + TS_VPL_FLUX);
    /* Separate loops (G', the masks, the double sums): GCC vectorises each alone, not fused
     * (it threads the select of G' into branches, and one loop of floats and doubles finds
     * no vector type). Their outputs are local arrays: a store through L could alias v, and
     * the reload of v would stop the vectoriser. A hidden lane gets G' = +0 and a finite
     * stand-in distance (1) whose inverse is then multiplied by 0. */
    float g[TS_PACKET_LANES], gm[TS_PACKET_LANES], dist2[TS_PACKET_LANES], tr[3][TS_PACKET_LANES];
    uint seen[TS_PACKET_LANES];
    int use[TS_PACKET_LANES];
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        float3 x = make_float3(L->x[0][i], L->x[1][i], L->x[2][i]);
        float3 n = make_float3(L->n[0][i], L->n[1][i], L->n[2][i]);
        float3 ng = make_float3(L->ng[0][i], L->ng[1][i], L->ng[2][i]);
        g[i] = ts_vpl_geometry_term_of(x, n, ng, v, b, hg, kind);
    }
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        float3 x = make_float3(L->x[0][i], L->x[1][i], L->x[2][i]);
        use[i] = (g[i] > 0.0f ? -1 : 0) & -(int)((L->word[i] >> bit) & 1u);
        float3 d = y - x;
        gm[i] = as_float(as_int(g[i]) & use[i]);
        dist2[i] = as_float((as_int(dot(d, d)) & use[i]) | (as_int(1.0f) & ~use[i]));
        seen[i] = (uint)use[i] & 1u;
    }
    if (med) {
        ts_ic_lanes_transmittance(L, v, med, use, tr);
        for (int i = 0; i < TS_PACKET_LANES; ++i) {
            L->e[0][i] += ts_vpl_gather_term_double(c.x, tr[0][i], gm[i]);
            L->e[1][i] += ts_vpl_gather_term_double(c.y, tr[1][i], gm[i]);
            L->e[2][i] += ts_vpl_gather_term_double(c.z, tr[2][i], gm[i]);
        }
    } else {
        for (int i = 0; i < TS_PACKET_LANES; ++i) {
            L->e[0][i] += ts_vpl_gather_term_double(c.x, 1.0f, gm[i]);
            L->e[1][i] += ts_vpl_gather_term_double(c.y, 1.0f, gm[i]);
            L->e[2][i] += ts_vpl_gather_term_double(c.z, 1.0f, gm[i]);
        }
    }
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        L->inv_dist[i] += (double)seen[i] * (1.0 / sqrt((double)dist2[i]));
        L->seen[i] += seen[i];
    }
}

/* ts_ic_lanes_add_of for VPL v of either kind. */
TS_INLINE void ts_ic_lanes_add(TsIcLanes* L, TS_GLOBAL const float* v, uint bit, float b, float hg,
                               const TsMedium* med) {
    if (ts_vpl_in_medium(v))
        ts_ic_lanes_add_of(L, v, bit, b, hg, 1, med);
    else
        ts_ic_lanes_add_of(L, v, bit, b, hg, 0, med);
}

/* The medium the lanes' links to VPL v cross: NULL where none does, so that every link's
 * transmittance is exactly 1: no medium, or the box around the lanes' shadow-ray origins
 * (lo, hi; largest pos_scale `scale`) and v apart from the medium's
 * (ts_medium_misses_links, whose margin covers the offset of v's end). A medium in one
 * part of a scene then costs the records elsewhere nothing. */
TS_INLINE const TsMedium* ts_ic_lanes_medium(const TsMedium* med, float3 lo, float3 hi, float scale,
                                             TS_GLOBAL const float* v) {
    if (!med->present) return 0;
    const float3 p = ts_f3_load(v + TS_VPL_POSITION);
    return ts_medium_misses_links(med, lo, hi, scale, p, p, fabs(v[TS_VPL_POS_SCALE])) ? 0 : med;
}

/* The gathers of lanes 0..TS_PACKET_LANES-1 (surfaces set with ts_ic_lanes_set; a lane
 * without a record holds any finite surface and is not written): lane i's visibility row
 * is row[i] of `visibility` (TS_IC_VISIBLE_WORDS(count) uints per row), its output
 * (TS_IC_GATHER_FLOATS, as ts_ic_gather's) goes to out + i · TS_IC_GATHER_FLOATS where bit
 * i of `on` is set. b: the geometry-term bound; med: the scene's medium. */
TS_INLINE void ts_ic_gather16(TsIcLanes* L, uint on, TS_GLOBAL const uint* visibility, const uint* row, uint count,
                              TS_GLOBAL const float* vpls, const TsMedium* med, float b, float* out) {
    const size_t words = TS_IC_VISIBLE_WORDS(count);
    float3 lo = make_float3(TS_INF, TS_INF, TS_INF), hi = -lo;
    float scale = 0.0f;
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        L->e[0][i] = L->e[1][i] = L->e[2][i] = L->inv_dist[i] = 0.0;
        L->seen[i] = 0u;
        const float3 o = make_float3(L->o[0][i], L->o[1][i], L->o[2][i]);
        L->held[i] = -ts_medium_holds(med, o);
        /* The box around the shadow rays' origins; a NaN one leaves no box (never apart). */
        lo = fmin(lo, o);
        hi = fmax(hi, o);
        scale = fmax(scale, L->pos_scale[i]);
        if (!((o.x + o.y + o.z) * 0.0f == 0.0f)) scale = TS_INF;
    }
    for (size_t w = 0; w < words; ++w) {
        uint any = 0u;
        for (int i = 0; i < TS_PACKET_LANES; ++i) {
            L->word[i] = on >> i & 1u ? visibility[words * row[i] + w] : 0u;
            any |= L->word[i];
        }
        /* Only the VPLs some lane sees, in increasing order: one no lane sees would add +0
         * to every sum, so the sums are the same, and the temporal update's re-sums over a
         * few changed VPLs cost a few VPLs, not their words' 32. */
        while (any != 0u) {
            uint bit = (uint)ts_ctz64((ulong)any);
            any &= any - 1u;
            TS_GLOBAL const float* v = vpls + (size_t)TS_VPL_FLOATS * (32u * w + bit);
            ts_ic_lanes_add(L, v, bit, b, med->g, ts_ic_lanes_medium(med, lo, hi, scale, v));
        }
    }
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        if (!(on >> i & 1u)) continue;
        TsDouble3 sum = {L->e[0][i], L->e[1][i], L->e[2][i]};
        ts_ic_gather_store_double(out + (size_t)TS_IC_GATHER_FLOATS * i, sum, L->inv_dist[i], L->seen[i]);
    }
}
#endif

TS_NAMESPACE_END

#endif /* TS_IC_GATHER_H */
