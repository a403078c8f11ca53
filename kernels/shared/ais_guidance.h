/* AIS guidance and each pixel's sample sets (docs/ais.md §3-5): the per-pixel math of the
 * host's compute_guidance and make_schedule (host/gi/ais_schedule.cpp), written once so the
 * device's schedule kernel (KernelId::AisSchedule, shared/ais_resolve.h) gives the host's masks bit for bit where
 * the device has fp64 (else the CoV's sums are compensated float). The host keeps the
 * decisions that are not per pixel: the parameters (AisScheduleTable, layout_igi.h), and
 * the item list the masks become (gi/ais_schedule.h, schedule_items).
 *
 * Window positions i = (dy − lo)·n + (dx − lo) over tile edge n's window
 * (shared/discontinuity.h); `in_image` and `accepted` are p's window masks: positions in
 * the image, and those p's discontinuity test accepts (p itself included). */
#ifndef TS_AIS_GUIDANCE_H
#define TS_AIS_GUIDANCE_H
#include "shared/compat.h"
#include "shared/discontinuity.h"
#include "shared/geometry.h"
#include "shared/layout_igi.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

/* What the guidance reads per pixel q, in scene units and W/(sr·m²): depth[q · depth_stride],
 * normal and position at q · vec_stride (position null: the depth test), visibility at
 * q · surf_stride, E_id at q · surf_stride (its luminance: 3 floats where indirect_rgb, else
 * 1), the lit fraction, medium length and L_pm at q · media_stride (lit null: no medium;
 * media null or pm_cov 0: no g_var), L_pm's luminance likewise by media_rgb. */
typedef struct TsAisGuideView {
    TS_GLOBAL const float* depth;
    TS_GLOBAL const float* normal;
    TS_GLOBAL const float* position;
    TS_GLOBAL const float* visibility;
    TS_GLOBAL const float* indirect;
    TS_GLOBAL const float* lit;
    TS_GLOBAL const float* length;
    TS_GLOBAL const float* media;
    uint depth_stride, vec_stride, surf_stride, media_stride;
    int indirect_rgb, media_rgb;
    int width, height, tile;
    float cos_min, depth_rel;
} TsAisGuideView;

/* The guidance's thresholds (host: AisThresholds, id_cov already scaled to the paths). */
typedef struct TsAisParams {
    float trigger[3];
    float id_cov, pm_cov;
    int min_accepted; /* N_min */
    int complete;     /* A: distinct sets to complete to */
    int graded;       /* A: the graded term's set count G, ⌈a·(min(G, N)−1)⌉ more sets */
    int amax;         /* 1: A-MAX */
} TsAisParams;

/* g and A's grade of one component at one pixel. */
typedef struct TsAisValue {
    float g, grade;
} TsAisValue;

/* Pixel (x, y)'s window positions inside the w × h image (all of them unless the image is
 * narrower or lower than the window: ts_discontinuity_lo_at moves a window in at the
 * border). */
TS_INLINE ulong ts_ais_in_image(int x, int y, int w, int h, int n) {
    const ulong all = n * n == 64 ? ~(ulong)0 : ((ulong)1 << (n * n)) - (ulong)1;
    if (w >= n && h >= n) return all;
    const int lx = ts_discontinuity_lo_at(x, w, n), ly = ts_discontinuity_lo_at(y, h, n);
    ulong bits = 0;
    int i = 0;
    for (int dy = ly; dy < ly + n; ++dy)
        for (int dx = lx; dx < lx + n; ++dx, ++i) {
            const int qx = x + dx, qy = y + dy;
            if (qx >= 0 && qy >= 0 && qx < w && qy < h) bits |= (ulong)1 << i;
        }
    return bits;
}

/* The set column (or row) held by the first position of the window of pixel coordinate v
 * on an axis `size` pixels long, tile edge n (ts_discontinuity_lo_at's window). */
TS_INLINE int ts_ais_window_origin(int v, int size, int n) {
    return (v + ts_discontinuity_lo_at(v, size, n)) % n;
}

/* The interleave sets held by a pixel's window positions, its window's first position
 * holding set column sx and row sy (ts_ais_window_origin): *missing those in the image
 * that p's test rejects, *held those it accepts. A window row's positions hold one row of
 * sets rotated by sx, so each row's bits rotate into place (no division per position). */
TS_INLINE void ts_ais_window_sets(ulong in_image, ulong accepted, int sx, int sy, int n, ulong* missing, ulong* held) {
    const ulong row = ((ulong)1 << n) - (ulong)1, rejected = in_image & ~accepted;
    ulong m = 0, h = 0;
    for (int r = 0; r < n; ++r) {
        const ulong a = (accepted >> (r * n)) & row, b = (rejected >> (r * n)) & row;
        h |= (((a << sx) | (a >> (n - sx))) & row) << (n * sy);
        m |= (((b << sx) | (b >> (n - sx))) & row) << (n * sy);
        sy = sy + 1 == n ? 0 : sy + 1;
    }
    *missing = m;
    *held = h;
}

/* Luminance at q of a buffer of 3 floats (rgb) or 1 float a pixel. */
TS_INLINE float ts_ais_luminance_at(TS_GLOBAL const float* v, uint stride, int rgb, size_t q) {
    return rgb ? ts_luminance(ts_f3_load(v + q * stride)) : v[q * stride];
}

/* Whether the filter cannot clean p: it accepts fewer than N_min neighbours because it
 * rejects some inside the image (a window clipped by the image border is no edge). */
TS_INLINE int ts_ais_unfilterable(ulong in_image, ulong accepted, int min_accepted) {
    return ts_popcount64(accepted) < min_accepted && accepted != in_image;
}

#ifdef TS_HAS_DOUBLE
/* The coefficient of variation from `count` luminances' sum and sum of squares (double,
 * summed in window order), over `cov`, clamped to 1 (0 where the mean is 0). */
TS_INLINE float ts_ais_cov_of_sums(double sum, double sum2, int count, float cov) {
    const double mean = sum / count;
    if (!(mean > 0.0)) return 0.0f;
    const double var = sum2 / count - mean * mean;
    const double c = sqrt(0.0 < var ? var : 0.0) / mean / cov;
    return (float)(c < 1.0 ? c : 1.0);
}
#endif

/* The coefficient of variation over p's accepted window positions of the luminance in v,
 * over `cov`, clamped to 1 (0 where the mean is 0): g_var of ID and PM. Sums in double in
 * window order where the device has it (the host's bits), else compensated float. */
TS_INLINE float ts_ais_window_cov(TS_GLOBAL const float* v, uint stride, int rgb, const long* offset, ulong accepted,
                                  size_t p, float cov) {
    int count = 0;
#ifdef TS_HAS_DOUBLE
    double sum = 0.0, sum2 = 0.0;
    for (ulong b = accepted; b != 0ul; b &= b - 1ul) {
        const double y = ts_ais_luminance_at(v, stride, rgb, (size_t)((long)p + offset[ts_ctz64(b)]));
        sum += y;
        sum2 += y * y;
        ++count;
    }
    return ts_ais_cov_of_sums(sum, sum2, count, cov);
#else
    float sum = 0.0f, sum_c = 0.0f, sum2 = 0.0f, sum2_c = 0.0f;
    for (ulong b = accepted; b != 0ul; b &= b - 1ul) {
        const float y = ts_ais_luminance_at(v, stride, rgb, (size_t)((long)p + offset[ts_ctz64(b)]));
        ts_sum_compensated_add(&sum, &sum_c, y);
        ts_sum_compensated_add(&sum2, &sum2_c, y * y);
        ++count;
    }
    const float mean = (sum + sum_c) / count;
    if (!(mean > 0.0f)) return 0.0f;
    const float var = (sum2 + sum2_c) / count - mean * mean;
    const float c = sqrt(0.0f < var ? var : 0.0f) / mean / cov;
    return c < 1.0f ? c : 1.0f;
#endif
}

/* SS from the visibility range lo..hi over A(p) and p's own visibility s: g = the range,
 * or 1 on an unfilterable pixel whose own visibility is fractional; grade the range. */
TS_INLINE TsAisValue ts_ais_ss_value(float lo, float hi, float s, ulong in_image, ulong accepted, int min_accepted) {
    const float range = hi - lo;
    const int edge = s > 0.0f && s < 1.0f && ts_ais_unfilterable(in_image, accepted, min_accepted);
    TsAisValue r = {edge ? 1.0f : range, range};
    return r;
}

/* SS: g = range of visibility over A(p), or 1 on an unfilterable pixel whose own
 * visibility is fractional; grade the range. */
TS_INLINE TsAisValue ts_ais_ss(const TsAisGuideView* v, const TsAisParams* t, const long* offset, ulong in_image,
                               ulong accepted, size_t p) {
    float lo = TS_INF, hi = -TS_INF;
    for (ulong b = accepted; b != 0ul; b &= b - 1ul) {
        const float s = v->visibility[(size_t)((long)p + offset[ts_ctz64(b)]) * v->surf_stride];
        lo = s < lo ? s : lo;
        hi = hi < s ? s : hi;
    }
    return ts_ais_ss_value(lo, hi, v->visibility[p * v->surf_stride], in_image, accepted, t->min_accepted);
}

/* Whether a pixel of p's 3×3 neighbourhood (in the image) lies across p's discontinuity
 * test: read from the window masks where the window holds the 3×3 (n ≥ 3, off the image's border), else tested. */
TS_INLINE int ts_ais_geometric_edge(const TsAisGuideView* v, ulong in_image, ulong accepted, int x, int y) {
    const int n = v->tile;
    if (ts_discontinuity_position(x, y, v->width, v->height, n, -1, -1) >= 0 &&
        ts_discontinuity_position(x, y, v->width, v->height, n, 1, 1) >= 0) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const ulong bit = (ulong)1 << ts_discontinuity_position(x, y, v->width, v->height, n, dx, dy);
                if ((in_image & bit) && !(accepted & bit)) return 1;
            }
        return 0;
    }
    const size_t p = (size_t)y * (size_t)v->width + (size_t)x;
    const int plane = v->position != 0;
    const float3 none = make_float3(0.0f, 0.0f, 0.0f);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= v->width || qy >= v->height) continue;
            const size_t q = (size_t)qy * (size_t)v->width + (size_t)qx;
            if (!ts_discontinuity_accepts(v->depth[p * v->depth_stride], ts_f3_load(v->normal + p * v->vec_stride),
                                          plane ? ts_f3_load(v->position + p * v->vec_stride) : none,
                                          v->depth[q * v->depth_stride], ts_f3_load(v->normal + q * v->vec_stride),
                                          plane ? ts_f3_load(v->position + q * v->vec_stride) : none, plane,
                                          v->cos_min, v->depth_rel))
                return 1;
        }
    return 0;
}

/* ID from g_var = `var` (ts_ais_window_cov): g = max(g_geo, g_var) as 1 on an
 * unfilterable or geometric-edge pixel, else g_var; grade g_var. */
TS_INLINE TsAisValue ts_ais_id_value(const TsAisGuideView* v, const TsAisParams* t, float var, ulong in_image,
                                     ulong accepted, int x, int y) {
    const int edge =
        ts_ais_unfilterable(in_image, accepted, t->min_accepted) || ts_ais_geometric_edge(v, in_image, accepted, x, y);
    TsAisValue r = {edge ? 1.0f : var, var};
    return r;
}

/* ID: ts_ais_id_value of the CoV of E_id over A(p). */
TS_INLINE TsAisValue ts_ais_id(const TsAisGuideView* v, const TsAisParams* t, const long* offset, ulong in_image,
                               ulong accepted, int x, int y) {
    const size_t p = (size_t)y * (size_t)v->width + (size_t)x;
    const float var = ts_ais_window_cov(v->indirect, v->surf_stride, v->indirect_rgb, offset, accepted, p, t->id_cov);
    return ts_ais_id_value(v, t, var, in_image, accepted, x, y);
}

/* PM: g = 1 where a window pixel the filter rejects has a medium length differing by more
 * than depth_rel of p's (g_len), else max(g_shaft, g_var): the lit fraction's range over
 * the window, the CoV of L_pm over A(p); grade max(g_shaft, g_var). g_len looks only at
 * rejected neighbours: a slanted wall's smooth change is no failure (docs/ais.md §3). */
TS_INLINE TsAisValue ts_ais_pm(const TsAisGuideView* v, const TsAisParams* t, const long* offset, ulong in_image,
                               ulong accepted, size_t p) {
    const float lp = v->length[p * v->media_stride];
    float lo = TS_INF, hi = -TS_INF;
    for (ulong b = in_image; b != 0ul; b &= b - 1ul) {
        const float s = v->lit[(size_t)((long)p + offset[ts_ctz64(b)]) * v->media_stride];
        lo = s < lo ? s : lo;
        hi = hi < s ? s : hi;
    }
    int length_edge = 0;
    for (ulong b = in_image & ~accepted; b != 0ul; b &= b - 1ul) {
        const float lq = v->length[(size_t)((long)p + offset[ts_ctz64(b)]) * v->media_stride];
        length_edge |= fabs(lq - lp) > v->depth_rel * lp;
    }
    const float cov = t->pm_cov > 0.0f && v->media != 0
                          ? ts_ais_window_cov(v->media, v->media_stride, v->media_rgb, offset, accepted, p, t->pm_cov)
                          : 0.0f;
    const float shaft = hi - lo, grade = shaft < cov ? cov : shaft;
    TsAisValue r = {length_edge ? 1.0f : grade, grade};
    return r;
}

/* Component c's guidance at pixel (x, y): SS and ID are 0 where the camera ray escaped
 * (nothing to shade), PM is computed everywhere. */
TS_INLINE TsAisValue ts_ais_guidance(const TsAisGuideView* v, const TsAisParams* t, const long* offset, int c,
                                     ulong in_image, ulong accepted, int x, int y) {
    const size_t p = (size_t)y * (size_t)v->width + (size_t)x;
    if (c == 2) return ts_ais_pm(v, t, offset, in_image, accepted, p);
    if (!isfinite(v->depth[p * v->depth_stride])) {
        TsAisValue none = {0.0f, 0.0f};
        return none;
    }
    return c == 0 ? ts_ais_ss(v, t, offset, in_image, accepted, p) : ts_ais_id(v, t, offset, in_image, accepted, x, y);
}

/* The sets pixel p (own set `own`) evaluates for a component of guidance `value`
 * (make_schedule, gi/ais_schedule.h): its own set where g ≤ trigger; else A-MAX all
 * `sets`, A the missing sets (bits of `missing`, taken in `order`: the other sets
 * far-first) until p holds `complete` distinct sets with `held`, then ⌈a·(G−1)⌉ more in
 * `order`, a = (grade − trigger) / (1 − trigger) clamped to [0, 1], G = min(`graded`, N). */
TS_INLINE ulong ts_ais_set_mask(TsAisValue value, float trigger, const TsAisParams* t, int own, int sets, ulong held,
                                ulong missing, TS_GLOBAL const uint* order) {
    ulong mask = (ulong)1 << own;
    if (!(value.g > trigger)) return mask;
    if (t->amax) return sets == 64 ? ~(ulong)0 : ((ulong)1 << sets) - (ulong)1;
    int need = t->complete - ts_popcount64(held | mask);
    for (int r = 0; r < sets - 1 && need > 0; ++r)
        if ((missing >> order[r]) & 1ul) {
            mask |= (ulong)1 << order[r];
            --need;
        }
    float a = (value.grade - trigger) / (1.0f - trigger);
    a = a < 0.0f ? 0.0f : (1.0f < a ? 1.0f : a);
    const int graded = t->graded < sets ? t->graded : sets;
    int more = (int)ceil(a * (float)(graded - 1));
    for (int r = 0; r < sets - 1 && more > 0; ++r)
        if (!((mask >> order[r]) & 1ul)) {
            mask |= (ulong)1 << order[r];
            --more;
        }
    return mask;
}

/* The parameters from an AisScheduleTable (layout_igi.h TS_AIS_TABLE_*). */
TS_INLINE TsAisParams ts_ais_params(TS_GLOBAL const uint* table) {
    TsAisParams t;
    for (int c = 0; c < 3; ++c) t.trigger[c] = as_float(table[TS_AIS_TABLE_TRIGGER + c]);
    t.id_cov = as_float(table[TS_AIS_TABLE_ID_COV]);
    t.pm_cov = as_float(table[TS_AIS_TABLE_PM_COV]);
    t.min_accepted = (int)table[TS_AIS_TABLE_MIN_ACCEPTED];
    t.complete = (int)table[TS_AIS_TABLE_COMPLETE];
    t.graded = (int)table[TS_AIS_TABLE_GRADED];
    t.amax = (int)table[TS_AIS_TABLE_MODE];
    return t;
}

TS_NAMESPACE_END
#endif /* TS_AIS_GUIDANCE_H */
