/* The emitters as the ray march's phase-sampled direction meets them (docs/igi.md §6):
 * a box test per emitter triangle that spares the trace of a direction that cannot meet
 * one, and the traced emitter's light with the pdf light sampling would have given it,
 * for the march's MIS (shared/igi_march.h). */
#ifndef TS_IGI_EMITTERS_H
#define TS_IGI_EMITTERS_H
#include "shared/igi.h"

TS_NAMESPACE_BEGIN

/* Emitter triangles up to which ts_igi_may_meet_emitter tests a ray against each one's
 * box before the ray is traced; with more, the test could cost what the trace saves
 * (the standard scenes have 2 and 8). */
#define TS_IGI_EMITTER_BOXES_MAX 16u

/* Emitter triangle i's box (sv->lights: every triangle with emission) for the box test
 * of ts_igi_may_meet_emitter, and the largest coordinate magnitude of its corners. */
typedef struct TsEmitterBox {
    float3 lo, hi;
    float mag;
} TsEmitterBox;

TS_INLINE TsEmitterBox ts_igi_emitter_box(const TsSceneView* sv, uint i) {
    TS_GLOBAL const float* L = sv->lights + i * TS_LIGHT_FLOATS;
    float3 p0 = ts_f3_load(L + TS_LIGHT_P0);
    float3 p1 = p0 + ts_f3_load(L + TS_LIGHT_E1), p2 = p0 + ts_f3_load(L + TS_LIGHT_E2);
    TsEmitterBox b;
    b.lo = fmin(p0, fmin(p1, p2));
    b.hi = fmax(p0, fmax(p1, p2));
    b.mag = fmax(ts_max_abs3(b.lo), ts_max_abs3(b.hi));
    return b;
}

/* The pad that grows an emitter's box for a ray from x (mx = ts_max_abs3(x)): 1e-4 of the
 * largest coordinate magnitude of the box and of x, far more than the rounding between
 * the table's p0 + e1 and the mesh's own vertex and that of the slab test (relative to the
 * coordinates and the distance travelled). */
TS_INLINE float ts_igi_emitter_pad(float mag, float mx) { return 1e-4f * (mx > mag ? mx : mag) + 1e-30f; }

/* Whether the ray from x (mx = ts_max_abs3(x)) with inverse direction inv (1/wi per
 * component) may meet `box` grown by ts_igi_emitter_pad: the slab test, with selects for
 * fmin and fmax (their values wherever no NaN enters; GCC vectorises selects over the
 * lanes of ts_igi_may_meet_emitter_lanes, shared/igi_march16.h). A zero component of wi
 * gives an infinite inverse, and the test still holds: ±inf where x lies outside that
 * slab (an empty interval), (-inf, inf) inside. A NaN slab distance (0·∞: x on a grown
 * face with wi parallel to it; or a NaN x or wi) passes: a ray passed needlessly is only
 * traced, and meets no emitter. */
TS_INLINE int ts_igi_emitter_box_may(TsEmitterBox box, float3 x, float3 inv, float mx) {
    float pad = ts_igi_emitter_pad(box.mag, mx);
    float ax = (box.lo.x - pad - x.x) * inv.x, bx = (box.hi.x + pad - x.x) * inv.x;
    float ay = (box.lo.y - pad - x.y) * inv.y, by = (box.hi.y + pad - x.y) * inv.y;
    float az = (box.lo.z - pad - x.z) * inv.z, bz = (box.hi.z + pad - x.z) * inv.z;
    float nx = ax < bx ? ax : bx, ny = ay < by ? ay : by, nz = az < bz ? az : bz;
    float fx = ax > bx ? ax : bx, fy = ay > by ? ay : by, fz = az > bz ? az : bz;
    float t0 = nx > ny ? nx : ny, t1 = fx < fy ? fx : fy;
    t0 = t0 > nz ? t0 : nz;
    t0 = t0 > 0.0f ? t0 : 0.0f;
    t1 = t1 < fz ? t1 : fz;
    int nan = (ax != ax) | (bx != bx) | (ay != ay) | (by != by) | (az != az) | (bz != bz);
    return (t0 <= t1) | nan;
}

/* Whether a ray from x along wi can hit an emitter: false only when it misses the
 * bounding box of every emitter triangle (ts_igi_emitter_box), each grown by
 * ts_igi_emitter_pad (ts_igi_emitter_box_may); such a ray's closest hit cannot be an emitter, so
 * ts_igi_emitter_traced's answer (nothing) needs no trace. Most phase-sampled rays of the
 * ray march miss the lights this way (a small light seen from the medium); the rest are
 * traced as before, so results do not change. The 16-lane march tests its lanes
 * together (ts_igi_may_meet_emitter_lanes, shared/igi_march16.h). */
TS_INLINE int ts_igi_may_meet_emitter(const TsSceneView* sv, float3 x, float3 wi) {
    if (sv->light_count > TS_IGI_EMITTER_BOXES_MAX) return 1;
    float3 inv = make_float3(1.0f / wi.x, 1.0f / wi.y, 1.0f / wi.z);
    float mx = ts_max_abs3(x);
    for (uint i = 0u; i < sv->light_count; ++i)
        if (ts_igi_emitter_box_may(ts_igi_emitter_box(sv, i), x, inv, mx)) return 1;
    return 0;
}

/* Light arriving at medium point x from direction `wi`, found by tracing a ray, and the
 * pdf (per steradian) with which light sampling would have picked that emitter point and
 * its distance *t_hit: for the phase-sampled half of the ray march's MIS. Zero when the
 * ray misses, hits a non-emitter or an emitter's back. */
TS_INLINE float3 ts_igi_emitter_traced(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                       const TsMedium* med, float3 x, float3 wi, float* pdf_light, float* t_hit) {
    TsRay r;
    r.org = x;
    r.dir = wi;
    r.tmin = 0.0f;
    r.tmax = TS_INF;
    *pdf_light = 0.0f;
    *t_hit = 0.0f;
    TsHit h = ts_trace_closest(tracer, r);
    if (h.prim == TS_NO_HIT) return make_float3(0.0f, 0.0f, 0.0f);
    TsSurface s = ts_surface_at(sv, r, h);
    float3 le = ts_material_emission(sv, &s);
    if (!(ts_max3(le) > 0.0f)) return le;
    float cos_y = -dot(s.geo_normal, wi);
    TS_GLOBAL const float* M = sv->materials + TS_MATERIAL_FLOATS * s.material;
    *pdf_light = ts_light_pdf_area(M[TS_MAT_SELECTION], f->light_power) * h.t * h.t / cos_y;
    *t_hit = h.t;
    return le * ts_medium_transmittance(med, x, wi, 0.0f, h.t);
}

TS_NAMESPACE_END
#endif /* TS_IGI_EMITTERS_H */
