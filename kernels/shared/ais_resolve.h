/* An AIS frame reconstructed where the kernels ran (docs/ais.md §6, docs/ray-batches.md §5):
 * the extra sets' merge and reconstruction (host: host/integrators/ais_frame.cpp and
 * host/gi/ais_reconstruct.cpp) and the edge samples' merge (host: host/gi/ais_edges.cpp),
 * step for step and sum for sum as the host runs them, over the surface and media passes'
 * outputs (TsSceneView.igi_surface, igi_media), the extra sets' output (ais_items) and the
 * edge samples' (edge_samples), so that the device's image is the host's bit for bit where
 * the device has fp64 (else the sums are compensated float). The schedule kernels are here
 * too (AisSchedule, EdgeRowSums, EdgeSchedule: the host's per-pixel code of
 * shared/ais_guidance.h and edge_guidance.h); their masks and counts stay where the kernels
 * ran, and the items are found from them and the tiles' prefix sums (shared/ais_compact.h). */
#ifndef TS_AIS_RESOLVE_H
#define TS_AIS_RESOLVE_H
#include "shared/ais_compact.h"
#include "shared/ais_guidance.h"
#include "shared/compat.h"
#include "shared/discontinuity.h"
#include "shared/edge_guidance.h"
#include "shared/frame.h"
#include "shared/geometry.h"
#include "shared/layout_igi.h"
#include "shared/layout_pass.h"
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
 * offsets from p, ts_discontinuity_offsets_at's), over the number of terms. Writes out (3 floats) and returns 1; returns 0 where
 * the pixel evaluated its own set only (the filter's value stands). The pixel's sets are
 * its masks (sv->ais_masks), its items found by ts_ais_compact_index. */
TS_INLINE int ts_ais_mean(const TsSceneView* sv, const TsFrame* f, uint x, uint y, int c, int n, ulong accepted,
                          const long* offset, float* out) {
    const size_t p = (size_t)y * f->width + x;
    const uint tile = f->igi_tile;
    TS_GLOBAL const float* m = sv->ais_masks + p * TS_AIS_MASK_FLOATS;
    const ulong own = (ulong)1 << ts_igi_set(x, y, tile);
    const ulong sets = ts_ais_component_mask(m, c);
    ulong mask = own;
    TsAisSum sum = ts_ais_sum_zero();
    ts_ais_sum_add(&sum, ts_ais_base(sv, c, p));
    for (ulong e = sets & ~own; e; e &= e - 1ul) {
        const uint k = (uint)ts_ctz64(e);
        mask |= (ulong)1 << k;
        ts_ais_sum_add(&sum, sv->ais_items + (size_t)ts_ais_compact_index(sv, f, x, y, k) * TS_AIS_ITEM_FLOATS +
                                 TS_AIS_ITEM_COMPONENT(c));
    }
    int count = ts_popcount64(mask);
    if (count < 2) return 0;
    const int lx = ts_discontinuity_lo_at((int)x, (int)f->width, n), ly = ts_discontinuity_lo_at((int)y, (int)f->height, n);
    for (int i = 0; i < n * n; ++i) {
        if (!((accepted >> i) & 1ul)) continue;  /* outside the image, or rejected */
        const uint qx = (uint)((int)x + lx + i % n), qy = (uint)((int)y + ly + i / n);
        if ((mask >> ts_igi_set(qx, qy, tile)) & 1ul) continue;  /* p has its own */
        ts_ais_sum_add(&sum, ts_ais_base(sv, c, (size_t)((long)p + offset[i])));
        ++count;
    }
    ts_ais_sum_mean(&sum, count, out);
    return 1;
}

/* Per-pixel kernel AisSchedule: pixel (x, y)'s set masks and flags (TS_AIS_MASK_*) from the
 * base pass's outputs where the kernels ran (TsSceneView.igi_surface, igi_media) and the
 * parameters (ais_schedule_table): the host's make_schedule(compute_guidance(...)) masks. */
TS_INLINE void ts_ais_schedule_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint x, uint y,
                                     float* out) {
    (void)tracer;
    TS_GLOBAL const uint* table = sv->ais_schedule_table;
    const TsAisParams t = ts_ais_params(table);
    const uint components = table[TS_AIS_TABLE_COMPONENTS];
    const int n = (int)f->igi_tile, sets = n * n, w = (int)f->width, h = (int)f->height;
    const int own = (int)ts_igi_set(x, y, (uint)n);
    TsAisGuideView v;
    v.depth = sv->igi_surface + TS_IGI_SURF_DISTANCE;
    v.normal = sv->igi_surface + TS_IGI_SURF_NORMAL;
    v.position = sv->igi_surface + TS_IGI_SURF_POSITION;
    v.visibility = sv->igi_surface + TS_IGI_SURF_VISIBLE;
    v.indirect = sv->igi_surface + TS_IGI_SURF_E_ID;
    v.depth_stride = v.vec_stride = v.surf_stride = TS_IGI_SURF_FLOATS;
    v.indirect_rgb = 1;
    const int media = (components & TS_COMPONENT_PM) != 0;
    v.lit = media ? sv->igi_media + TS_IGI_MEDIA_LIT : 0;
    v.length = media ? sv->igi_media + TS_IGI_MEDIA_LENGTH : 0;
    v.media = media ? sv->igi_media + TS_IGI_MEDIA_RADIANCE : 0;
    v.media_stride = TS_IGI_MEDIA_FLOATS;
    v.media_rgb = 1;
    v.width = w, v.height = h, v.tile = n;
    v.cos_min = f->igi_filter_cos, v.depth_rel = f->igi_filter_depth;
    long offset[64];
    ts_discontinuity_offsets_at((int)x, (int)y, w, h, n, offset);
    const ulong in_image = ts_ais_in_image((int)x, (int)y, w, h, n);
    const ulong accepted = ts_discontinuity_mask((int)x, (int)y, w, h, n, v.depth, v.normal, v.position,
                                                 TS_IGI_SURF_FLOATS, TS_IGI_SURF_FLOATS, 1, v.cos_min, v.depth_rel);
    ulong missing, held;
    ts_ais_window_sets(in_image, accepted, ts_ais_window_origin((int)x, w, n), ts_ais_window_origin((int)y, h, n), n,
                       &missing, &held);
    TS_GLOBAL const uint* order = table + TS_AIS_TABLE_ORDER + (size_t)own * (size_t)(sets - 1);
    uint flags = 0u;
    for (int c = 0; c < 3; ++c) {
        ulong mask = (ulong)1 << own;
        if (components & (1u << c)) {
            const TsAisValue g = ts_ais_guidance(&v, &t, offset, c, in_image, accepted, (int)x, (int)y);
            if (g.g > t.trigger[c]) flags |= 1u << c;
            mask = ts_ais_set_mask(g, t.trigger[c], &t, own, sets, held, missing, order);
        }
        out[TS_AIS_MASK_SETS(c)] = as_float((uint)(mask & 0xffffffffu));
        out[TS_AIS_MASK_SETS(c) + 1] = as_float((uint)(mask >> 32));
    }
    out[TS_AIS_MASK_FLAGS] = as_float(flags);
}

/* Per-pixel kernel EdgeSchedule: pixel (x, y)'s edge samples (one float, a count 0..15)
 * from the resolved pass (TsSceneView.igi_pass), the base pass's G-buffer and emission
 * (igi_surface) and the edge settings and ε (ais_schedule_table): the host's
 * make_edge_schedule(edge_guidance(...)) count, bit for bit. */
TS_INLINE void ts_edge_schedule_pixel(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint x, uint y,
                                      float* out) {
    (void)tracer;
    TS_GLOBAL const uint* table = sv->ais_schedule_table;
    const int w = (int)f->width, h = (int)f->height;
    const float eps = as_float(table[TS_AIS_TABLE_EDGE_EPSILON]);
    float best = 0.0f;
    /* The neighbour pairs of ts_edge_pairs, never p itself. */
    for (int i = 0; i < 10; ++i) {
        size_t qa, qb;
        if (!ts_edge_pair_pixels((int)x, (int)y, w, h, i, &qa, &qb)) continue;
        TS_GLOBAL const float* sa = sv->igi_surface + qa * TS_IGI_SURF_FLOATS;
        TS_GLOBAL const float* sb = sv->igi_surface + qb * TS_IGI_SURF_FLOATS;
        const int accepted = ts_discontinuity_accepts(
            sa[TS_IGI_SURF_DISTANCE], ts_f3_load(sa + TS_IGI_SURF_NORMAL), ts_f3_load(sa + TS_IGI_SURF_POSITION),
            sb[TS_IGI_SURF_DISTANCE], ts_f3_load(sb + TS_IGI_SURF_NORMAL), ts_f3_load(sb + TS_IGI_SURF_POSITION), 1,
            f->igi_filter_cos, f->igi_filter_depth);
        const int emitter_a =
            sa[TS_IGI_SURF_EMISSION] + sa[TS_IGI_SURF_EMISSION + 1] + sa[TS_IGI_SURF_EMISSION + 2] > 0.0f;
        const int emitter_b =
            sb[TS_IGI_SURF_EMISSION] + sb[TS_IGI_SURF_EMISSION + 1] + sb[TS_IGI_SURF_EMISSION + 2] > 0.0f;
        if (accepted && emitter_a == emitter_b) continue;
        const float ya = ts_luminance(ts_f3_load(sv->igi_pass + qa * TS_PASS_FLOATS + TS_PASS_RADIANCE));
        const float yb = ts_luminance(ts_f3_load(sv->igi_pass + qb * TS_PASS_FLOATS + TS_PASS_RADIANCE));
        best = ts_edge_max(best, ts_edge_contrast(ya, yb, eps));
    }
    out[0] = (float)ts_edge_sample_count(best, as_float(table[TS_AIS_TABLE_EDGE_TRIGGER]),
                                         as_float(table[TS_AIS_TABLE_EDGE_FULL]), table[TS_AIS_TABLE_EDGE_SAMPLES],
                                         (int)table[TS_AIS_TABLE_MODE]);
}

/* Item kernel EdgeRowSums, launched without a list: item i is row i of the resolved pass
 * (TsSceneView.igi_pass); writes its luminance sum (ts_edge_row_luminance) as
 * TS_EDGE_ROW_FLOATS (layout_igi.h), from which the host takes the edge contrast's ε
 * (edge_epsilon_of_rows, host/gi/ais_edges.h) without reading the image back. */
TS_INLINE void ts_edge_row_sum_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                    float* out) {
    (void)tracer;
    const uint y = i;
    out[TS_EDGE_ROW_DOUBLE] = out[TS_EDGE_ROW_DOUBLE + 1] = out[TS_EDGE_ROW_FLOAT] = 0.0f;
#ifdef TS_HAS_DOUBLE
    uint lo, hi;
    ts_double_words(ts_edge_row_luminance(sv->igi_pass, f->width, y), &lo, &hi);
    out[TS_EDGE_ROW_DOUBLE] = as_float(lo);
    out[TS_EDGE_ROW_DOUBLE + 1] = as_float(hi);
    out[TS_EDGE_ROW_HAS_DOUBLE] = 1.0f;
#else
    out[TS_EDGE_ROW_FLOAT] = ts_edge_row_luminance(sv->igi_pass, f->width, y);
    out[TS_EDGE_ROW_HAS_DOUBLE] = 0.0f;
#endif
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
