/* The igi surface gather of 16 lanes side by side (docs/ray-batches.md §3, §4), for the
 * backends that trace 16-ray packets: the Embree backend (host/backend/embree_packets.cpp)
 * and the OpenCL CPU kernels (kernels/igi_packets.h). Set by set, each link of the set (a
 * light sample, then a VPL: the same for every lane of the set, but for a light sample
 * near a lane's surface, ts_light_sample_from) is computed for the 16
 * lanes in loops GCC vectorises, its shadow rays written straight into the tracer's
 * packet, traced as one packet and gathered per lane. A lane takes part in the light
 * links if its mask has TS_COMPONENT_SS, in the VPL links if it has TS_COMPONENT_ID: the
 * links ts_igi_link (shared/igi.h) gives it, in the same order, so its sums equal
 * ts_igi_surface_set's bit for bit (tests/backend/embree_packets_test.cpp,
 * tests/backend/opencl_packets_test.cpp).
 *
 * Besides the tracer interface of shared/direct.h, the tracer provides a 16-ray packet
 * in its own layout, TsRayLanes (Embree's RTCRay16; an 8 × 16 float array on OpenCL), and
 *   void  ts_ray_lanes_init(TsRayLanes* r)              sets r's fields other than the rays
 *   void  ts_ray_lanes_put(TsRayLanes* r, int i, TsRay)  lane i's ray
 *   TsRay ts_ray_lanes_get(const TsRayLanes* r, int i)   lane i's ray (an unoccluded lane's
 *                                                        unchanged by tracing)
 *   void  ts_trace_occluded_ray_lanes(const TsTracer*, TsRayLanes* r, const int traced[16],
 *                                     int visible[16])
 * which traces the lanes with traced[i] = -1 as one packet (nothing when no lane is;
 * traced is 64-byte aligned, as rtcOccluded16 wants) and sets visible[i] = -1 for those
 * found unoccluded, 0 for the others.
 *
 * The loops vectorise because the shared functions they call are branch-free, their
 * outputs are local arrays or fields apart from their inputs, and the Embree file that
 * includes this is built with -fno-trapping-math (CMakeLists.txt says why that changes no
 * value). Private memory: the lanes' surfaces and sums (1.3 KB) and one link's masks and
 * terms (0.5 KB, 192 B of them the links' transmittances), besides the tracer's packet. */
#ifndef TS_IGI_GATHER16_H
#define TS_IGI_GATHER16_H
#include "shared/igi.h"

TS_NAMESPACE_BEGIN

/* The lanes' surfaces as a structure of arrays (the fields the links read: positions and
 * origins in scene units, unit normals, pos_scale as in TsSurface) and their running
 * gather sums (TsIgiGather's: E_ss and E_id before normalisation, visible light
 * samples). A lane without links holds a stand-in surface (another lane's) so that all
 * its rays are finite; its sums are never read. */
typedef struct TS_ALIGN64 TsIgiLanes {
    float position[3][TS_PACKET_LANES], geo_normal[3][TS_PACKET_LANES], shading_normal[3][TS_PACKET_LANES],
        origin[3][TS_PACKET_LANES];
    float pos_scale[TS_PACKET_LANES];
    float ss[3][TS_PACKET_LANES], id[3][TS_PACKET_LANES];
    uint facing[TS_PACKET_LANES], seen[TS_PACKET_LANES];
} TsIgiLanes;

/* One link against the lanes: which lanes take part (in_ss, in_id: -1 or 0), whose rays
 * are traced (traced: -1 or 0) and come back unoccluded (visible), and the link's
 * unoccluded terms (c: a light sample's contribution, RGB rows; g: a VPL's clamped
 * geometry term). Every int row is 64 bytes, so each is 64-byte aligned. */
typedef struct TS_ALIGN64 TsIgiLinkLanes {
    int in_ss[TS_PACKET_LANES], in_id[TS_PACKET_LANES], traced[TS_PACKET_LANES], visible[TS_PACKET_LANES];
    float c[3][TS_PACKET_LANES], g[TS_PACKET_LANES];
} TsIgiLinkLanes;

/* Lane i's surface, with the fields the links do not read set to constants (not
 * value-initialised: GCC then clears the struct with a memset and stops vectorising). */
TS_INLINE TsSurface ts_igi_lanes_surface(const TsIgiLanes* ls, int i) {
    TsSurface s;
    s.position = make_float3(ls->position[0][i], ls->position[1][i], ls->position[2][i]);
    s.geo_normal = make_float3(ls->geo_normal[0][i], ls->geo_normal[1][i], ls->geo_normal[2][i]);
    s.shading_normal = make_float3(ls->shading_normal[0][i], ls->shading_normal[1][i], ls->shading_normal[2][i]);
    s.origin = make_float3(ls->origin[0][i], ls->origin[1][i], ls->origin[2][i]);
    s.pos_scale = ls->pos_scale[i];
    s.uv = make_float2(0.0f, 0.0f);
    s.material = 0;
    s.front_face = 1;
    s.uv_footprint = 0.0f;
    return s;
}

/* Sets lane i's surface and clears its sums. */
TS_INLINE void ts_igi_lanes_set(TsIgiLanes* ls, int i, const TsSurface* s) {
    ls->position[0][i] = s->position.x, ls->position[1][i] = s->position.y, ls->position[2][i] = s->position.z;
    ls->geo_normal[0][i] = s->geo_normal.x, ls->geo_normal[1][i] = s->geo_normal.y;
    ls->geo_normal[2][i] = s->geo_normal.z;
    ls->shading_normal[0][i] = s->shading_normal.x, ls->shading_normal[1][i] = s->shading_normal.y;
    ls->shading_normal[2][i] = s->shading_normal.z;
    ls->origin[0][i] = s->origin.x, ls->origin[1][i] = s->origin.y, ls->origin[2][i] = s->origin.z;
    ls->pos_scale[i] = s->pos_scale;
    for (int a = 0; a < 3; ++a) ls->ss[a][i] = ls->id[a][i] = 0.0f;
    ls->facing[i] = ls->seen[i] = 0u;
}

/* x where mask is -1, +0 where it is 0: a select GCC 12 vectorises (it does not for
 * `mask ? x : 0.0f` or x · (float)(mask != 0)). Adding the +0 of a hidden lane to a sum
 * >= +0 leaves it unchanged bit for bit, so masked sums equal the sums of the visible
 * terms alone (terms are finite: contributions and VPL flux are, and so is G' <= b or,
 * with the clamp off, cosθ cosθ' / d² at d > 0). */
TS_INLINE float ts_lanes_masked(float x, int mask) { return as_float(as_int(x) & mask); }

/* Whether any lane's surface is near light sample q's triangle (ts_light_near), so that
 * its sample is drawn in solid angle. */
TS_INLINE int ts_igi_lanes_light_near(TS_GLOBAL const float* lights, const TsIgiLanes* TS_RESTRICT ls,
                                      TsLightSample q) {
    TS_GLOBAL const float* Lq = lights + q.light * TS_LIGHT_FLOATS;
    const float3 p0 = ts_f3_load(Lq + TS_LIGHT_P0), e1 = ts_f3_load(Lq + TS_LIGHT_E1), e2 = ts_f3_load(Lq + TS_LIGHT_E2);
    int near = 0;
    for (int i = 0; i < TS_PACKET_LANES; ++i)
        near |= ts_light_near(p0, e1, e2, make_float3(ls->position[0][i], ls->position[1][i], ls->position[2][i]));
    return near;
}

/* Lane i's light-sample link: contribution ci and shadow ray sh. */
TS_INLINE void ts_igi_lanes_light_put(TsIgiLinkLanes* TS_RESTRICT L, TsRayLanes* TS_RESTRICT r, int i, float3 ci,
                                      TsRay sh) {
    L->c[0][i] = ci.x;
    L->c[1][i] = ci.y;
    L->c[2][i] = ci.z;
    L->traced[i] = (ts_igi_light_link_traced(ci) ? -1 : 0) & L->in_ss[i];
    ts_ray_lanes_put(r, i, sh);
}

/* ts_igi_lanes_light_links where a lane is near q's light: each lane takes q as seen
 * from it (ts_light_contribution_from). */
TS_COLD void ts_igi_lanes_light_links_near(TS_GLOBAL const float* lights, const TsIgiLanes* TS_RESTRICT ls,
                                           TsLightSample q, TsIgiLinkLanes* TS_RESTRICT L,
                                           TsRayLanes* TS_RESTRICT r) {
    TsRay sh;
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        const TsSurface s = ts_igi_lanes_surface(ls, i);
        const float3 ci = ts_light_contribution_from(lights, &s, q, &sh);
        ts_igi_lanes_light_put(L, r, i, ci, sh);
    }
}

/* Light sample q against every lane: L->c and the shadow rays in r; L->traced[i] = -1
 * where lane i takes part (L->in_ss) and the ray must be traced (ts_igi_light_link_traced).
 * The lanes share q's point (one SIMD loop) unless one is near the light; then each lane
 * takes q as seen from it (ts_light_contribution_from). */
TS_INLINE void ts_igi_lanes_light_links(TS_GLOBAL const float* lights, const TsIgiLanes* TS_RESTRICT ls,
                                         TsLightSample q, TsIgiLinkLanes* TS_RESTRICT L,
                                         TsRayLanes* TS_RESTRICT r) {
    if (ts_igi_lanes_light_near(lights, ls, q)) {
        ts_igi_lanes_light_links_near(lights, ls, q, L, r);
        return;
    }
    TsRay sh;
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        const TsSurface s = ts_igi_lanes_surface(ls, i);
        const float3 ci = ts_light_contribution(&s, q, &sh);
        ts_igi_lanes_light_put(L, r, i, ci, sh);
    }
}

/* Adds the light-sample terms of the lanes with L->visible[i] = -1 to their E_ss and
 * counts them as seen, with the medium's transmittance along each lane's ray in r; counts
 * the traced ones (L->traced[i] = -1) as facing. */
TS_INLINE void ts_igi_lanes_light_gather(TsIgiLanes* TS_RESTRICT ls, const TsIgiLinkLanes* TS_RESTRICT L,
                                          const TsMedium* med, const TsRayLanes* TS_RESTRICT r) {
    if (!med->present) {
        const float3 clear = make_float3(1.0f, 1.0f, 1.0f); /* ts_shadow_transmittance without a medium */
        for (int i = 0; i < TS_PACKET_LANES; ++i) {
            const int v = L->visible[i];
            const float3 ci =
                make_float3(ts_lanes_masked(L->c[0][i], v), ts_lanes_masked(L->c[1][i], v), ts_lanes_masked(L->c[2][i], v));
            const float3 t = ts_igi_light_term(ci, clear);
            ls->ss[0][i] += t.x;
            ls->ss[1][i] += t.y;
            ls->ss[2][i] += t.z;
            ls->facing[i] += (uint)L->traced[i] & 1u;
            ls->seen[i] += (uint)v & 1u;
        }
        return;
    }
    float tr[3][TS_PACKET_LANES];
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        const float3 x =
            L->visible[i] ? ts_shadow_log_transmittance(med, ts_ray_lanes_get(r, i)) : make_float3(0.0f, 0.0f, 0.0f);
        tr[0][i] = x.x, tr[1][i] = x.y, tr[2][i] = x.z;
    }
    ts_medium_exp_lanes(med, tr); /* ts_shadow_transmittance's bits */
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        ls->facing[i] += (uint)L->traced[i] & 1u;
        if (!L->visible[i]) continue;
        const float3 ci = make_float3(L->c[0][i], L->c[1][i], L->c[2][i]);
        const float3 t = ts_igi_light_term(ci, make_float3(tr[0][i], tr[1][i], tr[2][i]));
        ls->ss[0][i] += t.x;
        ls->ss[1][i] += t.y;
        ls->ss[2][i] += t.z;
        ++ls->seen[i];
    }
}

/* ts_igi_lanes_vpl_links for VPLs of one kind (medium: 1 for a medium VPL): the kind
 * test in the shared code folds away once this is inlined with a constant `medium`, so
 * the vector loop computes only that kind's emission factor. */
TS_INLINE void ts_igi_lanes_vpl_links_of(const TsIgiLanes* TS_RESTRICT ls, TS_GLOBAL const float* vpl, float b,
                                          float hg, int medium, TsIgiLinkLanes* TS_RESTRICT L,
                                          TsRayLanes* TS_RESTRICT r) {
    if (ts_vpl_in_medium(vpl) != medium) TS_UNREACHABLE();
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        const TsSurface s = ts_igi_lanes_surface(ls, i);
        TsRay sh;
        L->g[i] = ts_vpl_geometry(&s, vpl, b, hg, &sh);
        ts_ray_lanes_put(r, i, sh);
    }
    for (int i = 0; i < TS_PACKET_LANES; ++i) L->traced[i] = (L->g[i] > 0.0f ? -1 : 0) & L->in_id[i];
}

/* VPL `vpl` against every lane: clamped geometry terms L->g (ts_vpl_geometry; b the
 * clamp, hg the medium's Henyey–Greenstein g) and shadow rays in r; L->traced[i] = -1
 * where L->in_id[i] = -1 and g > 0. */
TS_INLINE void ts_igi_lanes_vpl_links(const TsIgiLanes* ls, TS_GLOBAL const float* vpl, float b, float hg,
                                      TsIgiLinkLanes* L, TsRayLanes* r) {
    if (ts_vpl_in_medium(vpl))
        ts_igi_lanes_vpl_links_of(ls, vpl, b, hg, 1, L, r);
    else
        ts_igi_lanes_vpl_links_of(ls, vpl, b, hg, 0, L, r);
}

/* Adds the VPL's terms to E_id of the lanes with L->visible[i] = -1, as
 * ts_igi_lanes_light_gather. */
TS_INLINE void ts_igi_lanes_vpl_gather(TsIgiLanes* TS_RESTRICT ls, TS_GLOBAL const float* vpl,
                                        const TsIgiLinkLanes* TS_RESTRICT L, const TsMedium* med,
                                        const TsRayLanes* TS_RESTRICT r) {
    if (!med->present) {
        const float3 clear = make_float3(1.0f, 1.0f, 1.0f); /* ts_shadow_transmittance without a medium */
        for (int i = 0; i < TS_PACKET_LANES; ++i) {
            const float3 t = ts_vpl_gather_term(vpl, clear, ts_lanes_masked(L->g[i], L->visible[i]));
            ls->id[0][i] += t.x;
            ls->id[1][i] += t.y;
            ls->id[2][i] += t.z;
        }
        return;
    }
    float tr[3][TS_PACKET_LANES];
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        const float3 x = L->visible[i] ? ts_vpl_shadow_log_transmittance(med, ts_ray_lanes_get(r, i), vpl)
                                       : make_float3(0.0f, 0.0f, 0.0f);
        tr[0][i] = x.x, tr[1][i] = x.y, tr[2][i] = x.z;
    }
    ts_medium_exp_lanes(med, tr); /* ts_vpl_shadow_transmittance's bits */
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        if (!L->visible[i]) continue;
        const float3 t = ts_vpl_gather_term(vpl, make_float3(tr[0][i], tr[1][i], tr[2][i]), L->g[i]);
        ls->id[0][i] += t.x;
        ls->id[1][i] += t.y;
        ls->id[2][i] += t.z;
    }
}

/* The box around the lanes' surfaces (positions and origins, scene units) in *lo, *hi,
 * and their largest pos_scale in *scale, for ts_igi_vpl_medium: every lane holds a
 * finite surface (a stand-in's at worst), so including them all only grows the box. */
TS_INLINE void ts_igi_lanes_bounds(const TsIgiLanes* TS_RESTRICT ls, float3* lo, float3* hi, float* scale) {
    float b[7] = {TS_INF, TS_INF, TS_INF, -TS_INF, -TS_INF, -TS_INF, 0.0f}, check = 0.0f;
    for (int i = 0; i < TS_PACKET_LANES; ++i)
        for (int a = 0; a < 3; ++a) {
            const float p = ls->position[a][i], o = ls->origin[a][i];
            check += p * 0.0f + o * 0.0f; /* NaN where a coordinate is not finite */
            b[a] = b[a] < p ? b[a] : p;
            b[a] = b[a] < o ? b[a] : o;
            b[3 + a] = b[3 + a] > p ? b[3 + a] : p;
            b[3 + a] = b[3 + a] > o ? b[3 + a] : o;
        }
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        b[6] = b[6] > ls->pos_scale[i] ? b[6] : ls->pos_scale[i];
        check += ls->pos_scale[i] * 0.0f;
    }
    *lo = make_float3(b[0], b[1], b[2]);
    *hi = make_float3(b[3], b[4], b[5]);
    *scale = check == 0.0f ? b[6] : TS_INF; /* never apart (ts_medium_misses_box) */
}

/* The medium the lanes' links to a far end within [lo, hi] (pos_scale up to `scale`)
 * cross: `clear` (no medium) where the box around the lanes' surfaces
 * (ts_igi_lanes_bounds) and the far end lies apart from the medium's
 * (ts_medium_misses_links), so that every link's transmittance is exactly 1 and the gathers
 * take their vector loops, with the same sums bit for bit; else med. A medium box in one
 * part of a scene (or where no link goes) then costs the links elsewhere nothing: one far
 * from every surface of the Cornell box made its igi frame 1.7× as long. */
TS_INLINE const TsMedium* ts_igi_link_medium(const TsMedium* med, const TsMedium* clear, float3 lanes_lo,
                                             float3 lanes_hi, float lanes_scale, float3 lo, float3 hi, float scale) {
    return ts_medium_misses_links(med, lanes_lo, lanes_hi, lanes_scale, lo, hi, scale) ? clear : med;
}

/* ts_igi_link_medium for the links to `vpl` (its position). */
TS_INLINE const TsMedium* ts_igi_vpl_medium(const TsMedium* med, const TsMedium* clear, float3 lanes_lo,
                                            float3 lanes_hi, float lanes_scale, TS_GLOBAL const float* vpl) {
    const float3 p = ts_f3_load(vpl + TS_VPL_POSITION);
    return ts_igi_link_medium(med, clear, lanes_lo, lanes_hi, lanes_scale, p, p, vpl[TS_VPL_POS_SCALE]);
}

/* ts_igi_link_medium for the links to light sample q, with the box around q's whole light
 * (the parallelogram p0 + u·e1 + v·e2, u, v in [0, 1], holds its triangle): a lane near
 * the light draws its own point on it (ts_light_sample_from). */
TS_INLINE const TsMedium* ts_igi_light_medium(const TsMedium* med, const TsMedium* clear, float3 lanes_lo,
                                              float3 lanes_hi, float lanes_scale, TS_GLOBAL const float* lights,
                                              const TsLightSample* q) {
    TS_GLOBAL const float* l = lights + (size_t)q->light * TS_LIGHT_FLOATS;
    const float3 p0 = ts_f3_load(l + TS_LIGHT_P0), e1 = ts_f3_load(l + TS_LIGHT_E1), e2 = ts_f3_load(l + TS_LIGHT_E2);
    const float3 lo = fmin(fmin(p0, p0 + e1), fmin(p0 + e2, p0 + e1 + e2));
    const float3 hi = fmax(fmax(p0, p0 + e1), fmax(p0 + e2, p0 + e1 + e2));
    return ts_igi_link_medium(med, clear, lanes_lo, lanes_hi, lanes_scale, lo, hi, q->pos_scale);
}

/* Gathers the links of the lanes of sample set k among the first `lanes` (those with
 * links[i] > 0 and set[i] == k; at least one): the set's light samples, then its VPLs.
 * view[i].s is lane i's surface; the sums go to gather[i] of those lanes only. */
TS_INLINE void ts_igi_gather16_set(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, int lanes,
                                   const TsIgiView* view, const uint* set, const uint* mask, const uint* links,
                                   uint k, TsIgiGather* gather) {
    const TsMedium med = ts_medium_load(sv->medium);
    TsMedium clear = med;
    clear.present = 0;
    TsIgiLanes ls;
    TsIgiLinkLanes L;
    TsRayLanes r;
    int stand_in = 0, any_ss = 0, any_id = 0;
    for (int i = 0; i < lanes; ++i)
        if (set[i] == k && links[i] > 0u) stand_in = i;
    for (int i = 0; i < TS_PACKET_LANES; ++i) {
        const int lane = i < lanes && set[i] == k && links[i] > 0u;
        L.in_ss[i] = lane && ts_igi_light_links(sv, f, mask[i]) > 0u ? -1 : 0;
        L.in_id[i] = lane && (mask[i] & TS_COMPONENT_ID) ? -1 : 0;
        any_ss |= L.in_ss[i] != 0;
        any_id |= L.in_id[i] != 0;
        ts_igi_lanes_set(&ls, i, &view[lane ? i : stand_in].s);
    }
    float3 lanes_lo, lanes_hi;
    float lanes_scale;
    ts_igi_lanes_bounds(&ls, &lanes_lo, &lanes_hi, &lanes_scale);
    /* Lanes whose own box meets the medium's (all of them in a fog-filled room): any link
     * may cross it, and no link's box need be looked at. Without a medium, med itself
     * takes the loops without one. */
    const int lanes_apart = med.present && ts_medium_misses_box(&med, lanes_lo, lanes_hi, lanes_scale);
    ts_ray_lanes_init(&r);
    for (uint j = 0u; any_ss && j < f->shadow_samples; ++j) {
        const TsLightSample q = ts_igi_light_sample(sv, f, k, j);
        ts_igi_lanes_light_links(sv->lights, &ls, q, &L, &r);
        const TsMedium* m =
            lanes_apart ? ts_igi_light_medium(&med, &clear, lanes_lo, lanes_hi, lanes_scale, sv->lights, &q) : &med;
        ts_trace_occluded_ray_lanes(tracer, &r, L.traced, L.visible);
        ts_igi_lanes_light_gather(&ls, &L, m, &r);
    }
    for (uint v = sv->vpl_set_start[k]; any_id && v < sv->vpl_set_start[k + 1u]; ++v) {
#ifdef __OPENCL_VERSION__
        TS_GLOBAL const float* vpl = sv->vpls + (size_t)v * TS_VPL_FLOATS;
#else
        /* A local copy: the compiler then knows the lanes' stores leave it unchanged and
         * keeps its fields out of the vector loops. */
        float vpl[TS_VPL_FLOATS];
        for (int c = 0; c < TS_VPL_FLOATS; ++c) vpl[c] = sv->vpls[(size_t)v * TS_VPL_FLOATS + c];
#endif
        ts_igi_lanes_vpl_links(&ls, vpl, f->igi_g_clamp, sv->medium[TS_MEDIUM_G], &L, &r);
        const TsMedium* m =
            lanes_apart ? ts_igi_vpl_medium(&med, &clear, lanes_lo, lanes_hi, lanes_scale, vpl) : &med;
        ts_trace_occluded_ray_lanes(tracer, &r, L.traced, L.visible);
        ts_igi_lanes_vpl_gather(&ls, vpl, &L, m, &r);
    }
    for (int i = 0; i < lanes; ++i) {
        if (set[i] != k || links[i] == 0u) continue;
        gather[i].ss = make_float3(ls.ss[0][i], ls.ss[1][i], ls.ss[2][i]);
        gather[i].id = make_float3(ls.id[0][i], ls.id[1][i], ls.id[2][i]);
        gather[i].facing = ls.facing[i];
        gather[i].seen = ls.seen[i];
    }
}

/* The gathers of the first `lanes` lanes (lane i sees view[i].s, of sample set set[i],
 * components mask[i], links[i] links: 0 for nothing to gather), set by set: a surface
 * block is one set; AIS items, listed by set, span one or two sets per packet. gather[i]
 * ends as ts_igi_surface_set's sums for lane i (begun empty where links[i] is 0). */
TS_INLINE void ts_igi_gather16(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, int lanes,
                               const TsIgiView* view, const uint* set, const uint* mask, const uint* links,
                               TsIgiGather* gather) {
    uint done = 0u; /* bit i: lane i gathered or without links */
    for (int i = 0; i < lanes; ++i) {
        gather[i] = ts_igi_gather_begin();
        if (links[i] == 0u) done |= 1u << i;
    }
    for (int i = 0; i < lanes; ++i) {
        if (done >> i & 1u) continue;
        ts_igi_gather16_set(sv, tracer, f, lanes, view, set, mask, links, set[i], gather);
        for (int l = i; l < lanes; ++l)
            if (set[l] == set[i]) done |= 1u << l;
    }
}

TS_NAMESPACE_END
#endif /* TS_IGI_GATHER16_H */
