/* The igi ray march of up to 16 pixels side by side (docs/ray-batches.md §2, §4), for the
 * backends that trace 16-ray packets: the Embree backend
 * (host/backend/embree_media_packets.cpp) and the OpenCL CPU kernels
 * (kernels/igi_packets.h). Each lane computes what ts_igi_media_set (shared/igi_media.h)
 * computes, through the same functions, in the same order for its own sums; where
 * ts_igi_media_set traces one shadow ray, the lanes of one sample set trace theirs
 * together, since at step i they all meet the same light sample and the same VPL share.
 * The links' branch-free parts (the box test of the phase samples, the VPL and ray-light
 * weights) run over the lanes in loops GCC vectorises. So every lane's values equal
 * ts_igi_media_set's bit for bit (tests/backend/media_packets_test.cpp,
 * tests/kernels/igi_march16_test.cpp).
 *
 * Besides the tracer interface of shared/direct.h, the tracer provides
 *   uint ts_trace_occluded_lanes(const TsTracer*, const TsRay rays[TS_PACKET_LANES],
 *                                uint valid)
 * which traces the rays of the lanes whose bit is set in `valid` as one packet and
 * returns the bit mask of those found blocked (the rays of other lanes are not read).
 *
 * Private memory: 16 marches (128 B each), one step's lane state (2.4 KB) and, within a
 * link's lanes function, up to 1.2 KB of the lanes' link values (ts_igi_march_vrl_links16;
 * the links' transmittances, ts_march16_transmittance, 192 B). */
#ifndef TS_IGI_MARCH16_H
#define TS_IGI_MARCH16_H
#include "shared/igi_media.h"

TS_NAMESPACE_BEGIN

/* One step of the lanes' marches: per lane the step's distance and point, its
 * in-scattered light, the link being traced (shadow ray, radiance, weight) and the VPL
 * share's sum. */
typedef struct TsMarchStep {
    float t[TS_PACKET_LANES], w[TS_PACKET_LANES];
    float3 x[TS_PACKET_LANES], light[TS_PACKET_LANES], radiance[TS_PACKET_LANES], vpl_sum[TS_PACKET_LANES],
        vrl_sum[TS_PACKET_LANES], tint[TS_PACKET_LANES];
    TsRay shadow[TS_PACKET_LANES];
} TsMarchStep;

/* The lanes of `valid` whose shadow ray is unoccluded. */
TS_INLINE uint ts_march16_visible(const TsTracer* tracer, const TsMarchStep* s, uint valid) {
    return valid == 0u ? 0u : valid & ~ts_trace_occluded_lanes(tracer, s->shadow, valid);
}

/* The medium's transmittance tr[c][l] along the shadow ray s->shadow[l] of the lanes in
 * `seen` (others 1), over (0, 1) where `unit` is set (the light sample's link,
 * ts_igi_march_light_add) or the ray's (tmin, tmax) (ts_shadow_transmittance, the VPL and
 * ray-light links): each one-lane function's bits, with the exponentials over the lanes
 * at once. */
TS_INLINE void ts_march16_transmittance(const TsMedium* med, const TsMarchStep* s, uint seen, int unit,
                                        float tr[3][TS_PACKET_LANES]) {
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        float3 x = make_float3(0.0f, 0.0f, 0.0f);
        if (seen >> l & 1u)
            x = unit ? ts_medium_log_transmittance(med, s->shadow[l].org, s->shadow[l].dir, 0.0f, 1.0f)
                     : ts_shadow_log_transmittance(med, s->shadow[l]);
        tr[0][l] = x.x, tr[1][l] = x.y, tr[2][l] = x.z;
    }
    ts_medium_exp_lanes(med, tr);
}

/* ts_igi_march_vpl_add of the lanes in `seen` to sums[l], for VPL (or ray light) `vpl`
 * and each lane's link in s, bit for bit. */
TS_INLINE void ts_march16_vpl_add(const TsMedium* med, const TsMarchStep* s, uint seen, TS_GLOBAL const float* vpl,
                                  float3* sums) {
    if (seen == 0u) return;
    float tr[3][TS_PACKET_LANES];
    ts_march16_transmittance(med, s, seen, 0, tr);
    for (int l = 0; l < TS_PACKET_LANES; ++l)
        if (seen >> l & 1u)
            sums[l] += ts_igi_march_vpl_term(vpl, make_float3(tr[0][l], tr[1][l], tr[2][l]), s->w[l], s->tint[l]);
}

/* ts_igi_may_meet_emitter for the rays of the lanes in `in`, lane l's from x[l] along
 * wi[l] (other lanes' entries are not read): the bit mask of those that may meet an
 * emitter. Each emitter's box is computed once for all the lanes, and its test
 * (ts_igi_emitter_box_may, selects only) runs over the lanes in a loop GCC vectorises. Most
 * phase-sampled rays of a foggy frame miss the lights, and this test was 7% of its time
 * one lane at a time. */
TS_INLINE uint ts_igi_may_meet_emitter_lanes(const TsSceneView* sv, const float3* x, const float3* wi, uint in) {
    if (in == 0u || sv->light_count > TS_IGI_EMITTER_BOXES_MAX) return in;
    float o[3][TS_PACKET_LANES], inv[3][TS_PACKET_LANES], mx[TS_PACKET_LANES];
    int may[TS_PACKET_LANES];
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        int on = (int)(in >> l & 1u);
        float3 ol = on ? x[l] : make_float3(0.0f, 0.0f, 0.0f), w = on ? wi[l] : make_float3(1.0f, 1.0f, 1.0f);
        o[0][l] = ol.x, o[1][l] = ol.y, o[2][l] = ol.z;
        inv[0][l] = 1.0f / w.x, inv[1][l] = 1.0f / w.y, inv[2][l] = 1.0f / w.z;
        mx[l] = ts_max_abs3(ol);
        may[l] = 0;
    }
    for (uint i = 0u; i < sv->light_count; ++i) {
        TsEmitterBox box = ts_igi_emitter_box(sv, i);
        for (int l = 0; l < TS_PACKET_LANES; ++l)
            may[l] |= ts_igi_emitter_box_may(box, make_float3(o[0][l], o[1][l], o[2][l]),
                                             make_float3(inv[0][l], inv[1][l], inv[2][l]), mx[l]);
    }
    uint mask = 0u;
    for (int l = 0; l < TS_PACKET_LANES; ++l) mask |= (uint)may[l] << l;
    return mask & in;
}

/* The phase-sampled half of the MIS at step i of the marches in `in`
 * (ts_igi_march_phase_add, lane by lane): each lane draws its direction, the lanes' box
 * tests run together, and the lanes that may meet an emitter trace theirs. */
TS_INLINE void ts_igi_march_phase16(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                    const TsMedium* med, uint in, TsIgiMarch* m, TsMarchStep* s) {
    float3 wp[TS_PACKET_LANES];
    for (int l = 0; l < TS_PACKET_LANES; ++l)
        if (in >> l & 1u) wp[l] = ts_igi_march_phase_dir(med, &m[l]);
    uint may = ts_igi_may_meet_emitter_lanes(sv, s->x, wp, in);
    for (int l = 0; l < TS_PACKET_LANES; ++l)
        if (may >> l & 1u) ts_igi_march_phase_gather(sv, tracer, f, med, &m[l], s->x[l], s->t[l], wp[l], &s->light[l]);
}

/* ts_igi_march_vpl_weight over the lanes for VPLs of one kind (medium: 1 for a medium
 * VPL): the kind test folds away once this is inlined with a constant `medium`, so the
 * loop computes only that kind's emission factor and GCC vectorises it. */
TS_INLINE void ts_igi_march_vpl_weights16(float (*x)[TS_PACKET_LANES], float (*dir)[TS_PACKET_LANES],
                                          float3 y, TS_GLOBAL const float* vpl, int medium, float g, float b,
                                          float* w, int* ok) {
    if (ts_vpl_in_medium(vpl) != medium) TS_UNREACHABLE();
    for (int l = 0; l < TS_PACKET_LANES; ++l)
        w[l] = ts_igi_march_vpl_weight(make_float3(x[0][l], x[1][l], x[2][l]),
                                       make_float3(dir[0][l], dir[1][l], dir[2][l]), y, vpl, medium, g, b, &ok[l]);
}

/* ts_igi_march_vpl_link for the marches of the lanes in `in`, from the step's own
 * distances s->t: the links' points (ts_igi_march_vpl_point, lane by lane), their weights
 * (ts_igi_march_vpl_weight, over the lanes at once: the phase values and divisions were
 * most of a VPL link's time one lane at a time), then the shadow rays of the lanes with a
 * link. Sets s->shadow, s->w and s->tint of those lanes, as ts_igi_march_vpl_link would,
 * and returns their mask. */
TS_INLINE uint ts_igi_march_vpl_links16(const TsFrame* f, const TsMedium* med, const TsIgiMarch* m, uint in,
                                        TS_GLOBAL const float* vpl, TsMarchStep* s) {
    float b;
    if (in == 0u || !ts_igi_march_vpl_clamp(f, vpl, &b)) return 0u;
    float3 y = ts_f3_load(vpl + TS_VPL_POSITION);
    float x[3][TS_PACKET_LANES], dir[3][TS_PACKET_LANES], w[TS_PACKET_LANES];
    int ok[TS_PACKET_LANES];
    uint pointed = 0u;
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        float3 xl = make_float3(0.0f, 0.0f, 0.0f), dl = make_float3(0.0f, 0.0f, 1.0f);
        if ((in >> l & 1u) && ts_igi_march_vpl_point(med, &m[l], s->t[l], y, b, &xl, &s->tint[l])) {
            pointed |= 1u << l;
            dl = m[l].ray.dir;
        }
        x[0][l] = xl.x, x[1][l] = xl.y, x[2][l] = xl.z;
        dir[0][l] = dl.x, dir[1][l] = dl.y, dir[2][l] = dl.z;
    }
    if (ts_vpl_in_medium(vpl))
        ts_igi_march_vpl_weights16(x, dir, y, vpl, 1, med->g, b, w, ok);
    else
        ts_igi_march_vpl_weights16(x, dir, y, vpl, 0, med->g, b, w, ok);
    uint valid = 0u;
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        if (!(pointed >> l & 1u) || !ok[l]) continue;
        s->shadow[l] = ts_vpl_shadow_ray(make_float3(x[0][l], x[1][l], x[2][l]), vpl);
        s->w[l] = w[l];
        valid |= 1u << l;
    }
    return valid;
}

/* ts_igi_march_vrl_link for the marches of the lanes in `in`, from the step's own
 * distances s->t, for ray light j of the set (`vrl`) and the share's stride: the camera
 * side (ts_igi_march_vrl_point and the ray light's number ts_igi_vrl_u, lane by lane),
 * the ray light's side (ts_igi_march_vrl_weight, over the lanes at once), then the shadow
 * rays of the lanes with a link. Sets s->shadow, s->w and s->tint of those lanes, as
 * ts_igi_march_vrl_link would, and returns their mask. */
TS_INLINE uint ts_igi_march_vrl_links16(const TsFrame* f, const TsMedium* med, const TsIgiMarch* m, uint in, uint j,
                                        float stride, TS_GLOBAL const float* vrl, TsMarchStep* s) {
    if (in == 0u) return 0u;
    float3 start = ts_f3_load(vrl + TS_VRL_START), omega = ts_f3_load(vrl + TS_VRL_DIR);
    float vlen = vrl[TS_VRL_LENGTH];
    float x[3][TS_PACKET_LANES], dir[3][TS_PACKET_LANES], cam[3][TS_PACKET_LANES], u[TS_PACKET_LANES];
    float y[3][TS_PACKET_LANES], tint[3][TS_PACKET_LANES], w[TS_PACKET_LANES];
    int ok[TS_PACKET_LANES];
    uint pointed = 0u;
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        float3 xl = make_float3(0.0f, 0.0f, 0.0f), dl = make_float3(0.0f, 0.0f, 1.0f), cl = xl;
        float ul = 0.5f;
        if ((in >> l & 1u) && ts_igi_march_vrl_point(med, &m[l], s->t[l], vrl, &xl, &cl)) {
            pointed |= 1u << l;
            dl = m[l].ray.dir;
            ul = ts_igi_vrl_u(f, &m[l], j);
        }
        x[0][l] = xl.x, x[1][l] = xl.y, x[2][l] = xl.z;
        dir[0][l] = dl.x, dir[1][l] = dl.y, dir[2][l] = dl.z;
        cam[0][l] = cl.x, cam[1][l] = cl.y, cam[2][l] = cl.z;
        u[l] = ul;
    }
    if (pointed == 0u) return 0u;
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        float3 yl, tl;
        w[l] = ts_igi_march_vrl_weight(med, make_float3(x[0][l], x[1][l], x[2][l]),
                                       make_float3(dir[0][l], dir[1][l], dir[2][l]), start, omega, vlen, u[l],
                                       make_float3(cam[0][l], cam[1][l], cam[2][l]), stride, &yl, &tl, &ok[l]);
        y[0][l] = yl.x, y[1][l] = yl.y, y[2][l] = yl.z;
        tint[0][l] = tl.x, tint[1][l] = tl.y, tint[2][l] = tl.z;
    }
    uint valid = 0u;
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        if (!(pointed >> l & 1u) || !ok[l]) continue;
        s->shadow[l] = ts_shadow_ray(make_float3(x[0][l], x[1][l], x[2][l]), make_float3(y[0][l], y[1][l], y[2][l]),
                                     make_float3(0.0f, 0.0f, 0.0f), 0.0f);
        s->w[l] = w[l];
        s->tint[l] = make_float3(tint[0][l], tint[1][l], tint[2][l]);
        valid |= 1u << l;
    }
    return valid;
}

/* Step i of the marches in `in` (bit l: lane l), all of set k: the light link (one light
 * sample for all the lanes), the phase sample, the VPL share, then each lane's step end. */
TS_INLINE void ts_igi_march_step16(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                   const TsMedium* med, uint k, uint i, uint in, TsIgiMarch* m, TsMarchStep* s) {
    uint valid = 0u;
    TsLightSample ls = ts_igi_light_sample(sv, f, k, i % f->shadow_samples);
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        if (!(in >> l & 1u)) continue;
        s->t[l] = ts_igi_march_t(f, &m[l], k, i);
        ts_igi_march_step_begin(&m[l], med, s->t[l]);
        s->x[l] = m[l].ray.org + m[l].ray.dir * s->t[l];
        s->light[l] = make_float3(0.0f, 0.0f, 0.0f);
        if (ts_igi_march_light_link(med, &m[l], s->t[l], &ls, &s->shadow[l], &s->radiance[l], &s->w[l]))
            valid |= 1u << l;
    }
    uint seen = ts_march16_visible(tracer, s, valid);
    if (seen != 0u) {
        float tr[3][TS_PACKET_LANES];
        ts_march16_transmittance(med, s, seen, 1, tr);
        for (int l = 0; l < TS_PACKET_LANES; ++l)
            if (seen >> l & 1u)
                ts_igi_march_light_add_tr(&m[l], make_float3(tr[0][l], tr[1][l], tr[2][l]), s->radiance[l], s->w[l],
                                          &s->light[l]);
    }
    ts_igi_march_phase16(sv, tracer, f, med, in, m, s);
    if (f->igi_media_vpls) {
        uint first, stride;
        ts_igi_march_vpl_share(sv, f, k, i, &first, &stride);
        for (int l = 0; l < TS_PACKET_LANES; ++l) s->vpl_sum[l] = make_float3(0.0f, 0.0f, 0.0f);
        for (uint j = first; j < sv->vpl_set_start[k + 1u]; j += stride) {
            TS_GLOBAL const float* vpl = sv->vpls + j * TS_VPL_FLOATS;
            valid = ts_igi_march_vpl_links16(f, med, m, in, vpl, s);
            ts_march16_vpl_add(med, s, ts_march16_visible(tracer, s, valid), vpl, s->vpl_sum);
        }
        for (int l = 0; l < TS_PACKET_LANES; ++l) s->vpl_sum[l] = s->vpl_sum[l] * (float)stride;
        if (f->igi_media_vpls == TS_MEDIA_VPLS_RAYS) {
            for (int l = 0; l < TS_PACKET_LANES; ++l) s->vrl_sum[l] = make_float3(0.0f, 0.0f, 0.0f);
            ts_igi_march_vrl_share(sv, f, k, i, &first, &stride);
            for (uint j = first; j < sv->vrl_set_start[k + 1u]; j += stride) {
                TS_GLOBAL const float* vrl = sv->vrls + j * TS_VRL_FLOATS;
                valid = ts_igi_march_vrl_links16(f, med, m, in, j, (float)stride, vrl, s);
                ts_march16_vpl_add(med, s, ts_march16_visible(tracer, s, valid), vrl, s->vrl_sum);
            }
            for (int l = 0; l < TS_PACKET_LANES; ++l) s->vpl_sum[l] += s->vrl_sum[l];
        }
        for (int l = 0; l < TS_PACKET_LANES; ++l)
            if (in >> l & 1u) ts_igi_march_vpls_add(&m[l], s->vpl_sum[l], &s->light[l]);
    }
    for (int l = 0; l < TS_PACKET_LANES; ++l)
        if (in >> l & 1u) ts_igi_march_step_end(&m[l], med, s->t[l], s->light[l]);
}

/* The ray marches (ts_igi_media_set) of the lanes in `on`: lane l marches pixel
 * (px[l], py[l]) for set k[l], the lanes of one set side by side, the sets one after
 * another. Writes lane l's TS_IGI_MEDIA_FLOATS values to out[l] (LIT and LENGTH as
 * ts_igi_media_pixel writes them: 0 where the camera segment misses the medium). */
TS_INLINE void ts_igi_march_packet(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint on,
                                   const uint* px, const uint* py, const uint* k,
                                   float out[TS_PACKET_LANES][TS_IGI_MEDIA_FLOATS]) {
    TsMedium med = ts_medium_load(sv->medium);
    TsIgiMarch m[TS_PACKET_LANES];
    TsMarchStep s;
    for (int l = 0; l < TS_PACKET_LANES; ++l) s.shadow[l] = ts_shadow_ray(make_float3(0.0f, 0.0f, 0.0f),
                                                                           make_float3(0.0f, 0.0f, 1.0f),
                                                                           make_float3(0.0f, 0.0f, 1.0f), 1.0f);
    uint todo = 0u;
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        if (!(on >> l & 1u)) continue;
        m[l] = ts_igi_march_begin(tracer, f, &med, px[l], py[l], k[l]);
        if (m[l].marched) todo |= 1u << l;
    }
    for (int first = 0; first < TS_PACKET_LANES; ++first) {
        if (!(todo >> first & 1u)) continue;
        uint in = 0u;
        for (int l = 0; l < TS_PACKET_LANES; ++l)
            if ((todo >> l & 1u) && k[l] == k[first]) in |= 1u << l;
        todo &= ~in;
        for (uint i = 0u; i < f->igi_steps; ++i) ts_igi_march_step16(sv, tracer, f, &med, k[first], i, in, m, &s);
    }
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        if (!(on >> l & 1u)) continue;
        out[l][TS_IGI_MEDIA_LIT] = out[l][TS_IGI_MEDIA_LENGTH] = 0.0f;
        ts_igi_march_end(f, &m[l], &med, out[l]);
    }
}

TS_NAMESPACE_END
#endif /* TS_IGI_MARCH16_H */
