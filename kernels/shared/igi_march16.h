/* The igi ray march of up to 16 pixels side by side (docs/ray-batches.md §2, §4), for the
 * backends that trace 16-ray packets: the Embree backend
 * (host/backend/embree_media_packets.cpp) and the OpenCL CPU kernels
 * (kernels/igi_packets.h). Each lane makes the calls ts_igi_media_set (shared/igi.h)
 * makes, in the same order; where ts_igi_media_set traces one shadow ray, the lanes of
 * one sample set trace theirs together, since at step i they all meet the same light
 * sample and the same VPL share. So every lane's values equal ts_igi_media_set's bit for
 * bit (tests/backend/media_packets_test.cpp).
 *
 * Besides the tracer interface of shared/direct.h, the tracer provides
 *   uint ts_trace_occluded_lanes(const TsTracer*, const TsRay rays[TS_PACKET_LANES],
 *                                uint valid)
 * which traces the rays of the lanes whose bit is set in `valid` as one packet and
 * returns the bit mask of those found blocked (the rays of other lanes are not read).
 *
 * Private memory: 16 marches (≈ 100 B each) and one step's lane state (≈ 2.2 KB). */
#ifndef TS_IGI_MARCH16_H
#define TS_IGI_MARCH16_H
#include "shared/igi.h"

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

/* Step i of the marches in `in` (bit l: lane l), all of set k: the light link, the phase
 * sample, the VPL share, then each lane's step end. */
TS_INLINE void ts_igi_march_step16(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f,
                                   const TsMedium* med, uint k, uint i, uint in, TsIgiMarch* m, TsMarchStep* s) {
    uint valid = 0u;
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        if (!(in >> l & 1u)) continue;
        s->t[l] = ts_igi_march_t(f, &m[l], k, i);
        s->x[l] = m[l].ray.org + m[l].ray.dir * s->t[l];
        s->light[l] = make_float3(0.0f, 0.0f, 0.0f);
        if (ts_igi_march_light_link(sv, f, med, &m[l], s->t[l], k, i, &s->shadow[l], &s->radiance[l], &s->w[l]))
            valid |= 1u << l;
    }
    uint seen = ts_march16_visible(tracer, s, valid);
    for (int l = 0; l < TS_PACKET_LANES; ++l)
        if (seen >> l & 1u) ts_igi_march_light_add(&m[l], med, s->shadow[l], s->radiance[l], s->w[l], &s->light[l]);
    for (int l = 0; l < TS_PACKET_LANES; ++l)
        if (in >> l & 1u) ts_igi_march_phase_add(sv, tracer, f, med, &m[l], s->x[l], s->t[l], &s->light[l]);
    if (f->igi_media_vpls) {
        uint first, stride;
        ts_igi_march_vpl_share(sv, f, k, i, &first, &stride);
        for (int l = 0; l < TS_PACKET_LANES; ++l) s->vpl_sum[l] = make_float3(0.0f, 0.0f, 0.0f);
        for (uint j = first; j < sv->vpl_set_start[k + 1u]; j += stride) {
            TS_GLOBAL const float* vpl = sv->vpls + j * TS_VPL_FLOATS;
            valid = 0u;
            for (int l = 0; l < TS_PACKET_LANES; ++l)
                if ((in >> l & 1u) &&
                    ts_igi_march_vpl_link(f, med, &m[l], s->t[l], vpl, &s->shadow[l], &s->w[l], &s->tint[l]))
                    valid |= 1u << l;
            seen = ts_march16_visible(tracer, s, valid);
            for (int l = 0; l < TS_PACKET_LANES; ++l)
                if (seen >> l & 1u) ts_igi_march_vpl_add(&s->vpl_sum[l], vpl, med, s->shadow[l], s->w[l], s->tint[l]);
        }
        for (int l = 0; l < TS_PACKET_LANES; ++l) s->vpl_sum[l] = s->vpl_sum[l] * (float)stride;
        if (f->igi_media_vpls == TS_MEDIA_VPLS_RAYS) {
            for (int l = 0; l < TS_PACKET_LANES; ++l) s->vrl_sum[l] = make_float3(0.0f, 0.0f, 0.0f);
            ts_igi_march_vrl_share(sv, f, k, i, &first, &stride);
            for (uint j = first; j < sv->vrl_set_start[k + 1u]; j += stride) {
                TS_GLOBAL const float* vrl = sv->vrls + j * TS_VRL_FLOATS;
                valid = 0u;
                for (int l = 0; l < TS_PACKET_LANES; ++l)
                    if ((in >> l & 1u) && ts_igi_march_vrl_link(med, &m[l], s->t[l], ts_igi_vrl_u(f, &m[l], j),
                                                                (float)stride, vrl, &s->shadow[l], &s->w[l],
                                                                &s->tint[l]))
                        valid |= 1u << l;
                seen = ts_march16_visible(tracer, s, valid);
                for (int l = 0; l < TS_PACKET_LANES; ++l)
                    if (seen >> l & 1u)
                        ts_igi_march_vpl_add(&s->vrl_sum[l], vrl, med, s->shadow[l], s->w[l], s->tint[l]);
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
        if (m[l].active) todo |= 1u << l;
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
