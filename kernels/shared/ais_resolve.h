/* An AIS frame reconstructed where the kernels ran (docs/ais.md §6, docs/ray-batches.md §5):
 * the extra sets' merge and reconstruction (host: host/integrators/ais_frame.cpp and
 * host/gi/ais_reconstruct.cpp) and the edge samples' merge (host: host/gi/ais_edges.cpp),
 * step for step and sum for sum as the host runs them, over the surface and media passes'
 * outputs (TsSceneView.igi_surface, igi_media), the extra sets' output (ais_items) and the
 * edge samples' (edge_samples), so that the device's image is the host's bit for bit where
 * the device has fp64 (else the sums are compensated float). The schedule stays the host's:
 * it sends, per pixel, which items are its own (ais_pixel_items, edge_pixel_samples). */
#ifndef TS_AIS_RESOLVE_H
#define TS_AIS_RESOLVE_H
#include "shared/compat.h"
#include "shared/discontinuity.h"
#include "shared/frame.h"
#include "shared/geometry.h"
#include "shared/layout_igi.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

/* Component c's (0 SS, 1 ID, 2 PM) base estimate at pixel q: its own set's, as the surface
 * and media passes left it (3 floats). */
TS_INLINE TS_GLOBAL const float* ts_ais_base(const TsSceneView* sv, int c, size_t q) {
    if (c == 2) return sv->igi_media + q * TS_IGI_MEDIA_FLOATS + TS_IGI_MEDIA_RADIANCE;
    return sv->igi_surface + q * TS_IGI_SURF_FLOATS + (c == 0 ? TS_IGI_SURF_E_SS : TS_IGI_SURF_E_ID);
}

/* A running sum of 3 channels: double where the device has it, else compensated float. */
typedef struct TsAisSum {
#ifdef TS_HAS_DOUBLE
    double s[3];
#else
    float s[3], c[3];
#endif
} TsAisSum;

TS_INLINE TsAisSum ts_ais_sum_zero(void) {
    TsAisSum a;
    for (int j = 0; j < 3; ++j) {
        a.s[j] = 0;
#ifndef TS_HAS_DOUBLE
        a.c[j] = 0.0f;
#endif
    }
    return a;
}

TS_INLINE void ts_ais_sum_add3(TsAisSum* a, float3 v) {
    const float x[3] = {v.x, v.y, v.z};
    for (int j = 0; j < 3; ++j) {
#ifdef TS_HAS_DOUBLE
        a->s[j] += (double)x[j];
#else
        ts_sum_compensated_add(&a->s[j], &a->c[j], x[j]);
#endif
    }
}

TS_INLINE void ts_ais_sum_add(TsAisSum* a, TS_GLOBAL const float* v) { ts_ais_sum_add3(a, ts_f3_load(v)); }

TS_INLINE void ts_ais_sum_mean(const TsAisSum* a, int count, float* out) {
    for (int j = 0; j < 3; ++j) {
#ifdef TS_HAS_DOUBLE
        out[j] = (float)(a->s[j] / (double)count);
#else
        out[j] = (a->s[j] + a->c[j]) / (float)count;
#endif
    }
}

/* Component c of an AIS frame at pixel (x, y), where it evaluated sets beyond its own: the
 * sum of its own estimate and its extra sets' (sv->ais_items, in increasing set order: the
 * host's own_sum), plus, for each set it did not evaluate, the base estimate of the
 * neighbour in its filter window that holds it, if the filter accepts it (`accepted`, the
 * window's bits as ts_discontinuity_mask gives them for window edge n, `offset` their pixel
 * offsets), over the number of terms. Writes out (3 floats) and returns 1; returns 0 where
 * the pixel evaluated its own set only (the filter's value stands). Layout of
 * sv->ais_pixel_items: TS_AIS_PIXEL_ITEMS. */
TS_INLINE int ts_ais_mean(const TsSceneView* sv, const TsFrame* f, uint x, uint y, int c, int n, ulong accepted,
                          const long* offset, float* out) {
    const size_t p = (size_t)y * f->width + x;
    const size_t pixels = (size_t)f->width * f->height;
    TS_GLOBAL const uint* table = sv->ais_pixel_items;
    const uint begin = table[p], end = table[p + 1u];
    const uint tile = f->igi_tile;
    ulong mask = (ulong)1 << ts_igi_set(x, y, tile);
    TsAisSum sum = ts_ais_sum_zero();
    ts_ais_sum_add(&sum, ts_ais_base(sv, c, p));
    for (uint k = begin; k < end; ++k) {
        TS_GLOBAL const uint* entry = table + pixels + 1u + TS_AIS_ENTRY_WORDS * (size_t)k;
        const uint code = entry[TS_AIS_ENTRY_CODE];
        if (!((code >> 8) & (1u << c))) continue;
        mask |= (ulong)1 << (code & 0xffu);
        ts_ais_sum_add(&sum, sv->ais_items + (size_t)entry[TS_AIS_ENTRY_ITEM] * TS_AIS_ITEM_FLOATS +
                                 TS_AIS_ITEM_COMPONENT(c));
    }
    int count = ts_popcount64(mask);
    if (count < 2) return 0;
    int lo, hi;
    ts_discontinuity_window(n, &lo, &hi);
    for (int i = 0; i < n * n; ++i) {
        if (!((accepted >> i) & 1ul)) continue;  /* outside the image, or rejected */
        const uint qx = (uint)((int)x + lo + i % n), qy = (uint)((int)y + lo + i / n);
        if ((mask >> ts_igi_set(qx, qy, tile)) & 1ul) continue;  /* p has its own */
        ts_ais_sum_add(&sum, ts_ais_base(sv, c, (size_t)((long)p + offset[i])));
        ++count;
    }
    ts_ais_sum_mean(&sum, count, out);
    return 1;
}

/* Per-pixel kernel AisGuideInputs: what the host's guidance reads of pixel (x, y)'s base
 * pass (TS_AIS_GUIDE_*, layout_igi.h), the same values the host takes from the whole
 * outputs (luminances by ts_luminance, as the host computes them). */
TS_INLINE void ts_ais_guide_inputs_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint x,
                                         uint y, float* out) {
    (void)tracer;
    const size_t p = (size_t)y * f->width + x;
    TS_GLOBAL const float* s = sv->igi_surface + p * TS_IGI_SURF_FLOATS;
    for (int j = 0; j < 3; ++j) {
        out[TS_AIS_GUIDE_NORMAL + j] = s[TS_IGI_SURF_NORMAL + j];
        out[TS_AIS_GUIDE_POSITION + j] = s[TS_IGI_SURF_POSITION + j];
    }
    out[TS_AIS_GUIDE_DISTANCE] = s[TS_IGI_SURF_DISTANCE];
    out[TS_AIS_GUIDE_VISIBLE] = s[TS_IGI_SURF_VISIBLE];
    out[TS_AIS_GUIDE_INDIRECT] = ts_luminance(ts_f3_load(s + TS_IGI_SURF_E_ID));
    out[TS_AIS_GUIDE_EMITTER] = s[TS_IGI_SURF_EMISSION] + s[TS_IGI_SURF_EMISSION + 1] + s[TS_IGI_SURF_EMISSION + 2] > 0.0f
                                    ? 1.0f : 0.0f;
    out[TS_AIS_GUIDE_LIT] = out[TS_AIS_GUIDE_LENGTH] = out[TS_AIS_GUIDE_MEDIA] = 0.0f;
    if (!(f->igi_components & TS_COMPONENT_PM)) return;
    TS_GLOBAL const float* m = sv->igi_media + p * TS_IGI_MEDIA_FLOATS;
    out[TS_AIS_GUIDE_LIT] = m[TS_IGI_MEDIA_LIT];
    out[TS_AIS_GUIDE_LENGTH] = m[TS_IGI_MEDIA_LENGTH];
    out[TS_AIS_GUIDE_MEDIA] = ts_luminance(ts_f3_load(m + TS_IGI_MEDIA_RADIANCE));
}

/* The window pixel whose surface the edge sample `sample` (TS_EDGE_SAMPLE_FLOATS) lies on,
 * for pixel (x, y) (host: edge_sample_match, host/gi/ais_edges.h): among p's 3×3
 * neighbours (p first, then the 4 sides, then the corners) those whose discontinuity test
 * accepts the sample's surface, the one nearest to it in space; none accepting, the one
 * nearest in depth (an escaped sample: p). Returns its row-major index. */
TS_INLINE size_t ts_edge_sample_match(const TsSceneView* sv, const TsFrame* f, int x, int y, const float* sample) {
    const int order[9][2] = {{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    const int w = (int)f->width, h = (int)f->height;
    const float zs = sample[TS_EDGE_SAMPLE_DISTANCE];
    const float3 ns = make_float3(sample[TS_EDGE_SAMPLE_NORMAL], sample[TS_EDGE_SAMPLE_NORMAL + 1],
                                  sample[TS_EDGE_SAMPLE_NORMAL + 2]);
    const float3 xs = make_float3(sample[TS_EDGE_SAMPLE_POSITION], sample[TS_EDGE_SAMPLE_POSITION + 1],
                                  sample[TS_EDGE_SAMPLE_POSITION + 2]);
    const size_t p = (size_t)y * w + x;
    size_t accepted = p, nearest = p;
    float accepted_d = TS_INF, depth_d = TS_INF;
    int any = 0;
    for (int i = 0; i < 9; ++i) {
        const int qx = x + order[i][0], qy = y + order[i][1];
        if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
        const size_t q = (size_t)qy * w + qx;
        TS_GLOBAL const float* sq = sv->igi_surface + q * TS_IGI_SURF_FLOATS;
        const float zq = sq[TS_IGI_SURF_DISTANCE];
        const float3 xq = ts_f3_load(sq + TS_IGI_SURF_POSITION);
        if (ts_discontinuity_accepts(zs, ns, xs, zq, ts_f3_load(sq + TS_IGI_SURF_NORMAL), xq, 1, f->igi_filter_cos,
                                     f->igi_filter_depth)) {
            /* Escaped samples match the first escaped pixel; surfaces the nearest point. */
            const float3 d = xq - xs;
            const float d2 = !isfinite(zs) ? 0.0f : d.x * d.x + d.y * d.y + d.z * d.z;  /* the host's dot */
            if (!any || d2 < accepted_d) accepted = q, accepted_d = d2;
            any = 1;
        } else if (isfinite(zs) && isfinite(zq)) {
            const float dz = fabs(zq - zs);
            if (dz < depth_d) nearest = q, depth_d = dz;
        }
    }
    if (!isfinite(zs) && !any) return p;
    return any ? accepted : nearest;
}

TS_NAMESPACE_END
#endif /* TS_AIS_RESOLVE_H */
