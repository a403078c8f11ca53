/* Homogeneous participating medium (layout in shared/layout_scene.h): extent, transmittance
 * and free-flight distance sampling with RGB coefficients. */
#ifndef TS_MEDIUM_H
#define TS_MEDIUM_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout_scene.h"
#include "shared/math_lanes.h"

TS_NAMESPACE_BEGIN

typedef struct TsMedium {
    float3 sigma_s;
    float3 sigma_t; /* sigma_a + sigma_s, per scene unit */
    float g;
    int bounded;
    float3 box_min, box_max;
    int present;
} TsMedium;

TS_INLINE TsMedium ts_medium_load(TS_GLOBAL const float* m) {
    TsMedium r;
    r.sigma_s = ts_f3_load(m + TS_MEDIUM_SIGMA_S);
    r.sigma_t = ts_f3_load(m + TS_MEDIUM_SIGMA_A) + r.sigma_s;
    r.g = m[TS_MEDIUM_G];
    r.bounded = m[TS_MEDIUM_BOUNDED] != 0.0f;
    r.box_min = ts_f3_load(m + TS_MEDIUM_BOX_MIN);
    r.box_max = ts_f3_load(m + TS_MEDIUM_BOX_MAX);
    r.present = m[TS_MEDIUM_PRESENT] != 0.0f;
    return r;
}

/* e^x per channel by ts_lanes_exp (shared/math_lanes.h, 8.2e-8 relative), not libm's or
 * OpenCL's exp: the 16-lane gathers take their links' exponentials in loops GCC
 * vectorises, and one link at a time must give them bit for bit (libm's expf was 6% of a
 * foggy igi frame's samples, one call per link); every backend's transmittance is then
 * the same bits too. A grey argument (every medium of the standard scenes) takes one
 * exponential, the same value three give. */
TS_INLINE float3 ts_exp3(float3 x) {
    if (x.x == x.y && x.y == x.z) {
        float e = ts_lanes_exp(x.x);
        return make_float3(e, e, e);
    }
    return make_float3(ts_lanes_exp(x.x), ts_lanes_exp(x.y), ts_lanes_exp(x.z));
}
/* ts_exp3 of 16 lanes' logs of transmittance x[c][i] in place, bit for bit, in loops GCC
 * vectorises. In a grey medium (the same sigma_t in every channel) each lane's three logs
 * are the same product, so one row's exponentials serve all three. */
TS_INLINE void ts_medium_exp_lanes(const TsMedium* m, float x[3][TS_PACKET_LANES]) {
    if (m->sigma_t.x == m->sigma_t.y && m->sigma_t.y == m->sigma_t.z) {
        ts_lanes_exp_n(x[0], TS_PACKET_LANES);
        for (int i = 0; i < TS_PACKET_LANES; ++i) x[1][i] = x[2][i] = x[0][i];
        return;
    }
    for (int c = 0; c < 3; ++c) ts_lanes_exp_n(x[c], TS_PACKET_LANES);
}
TS_INLINE float ts_mean3(float3 x) { return (x.x + x.y + x.z) * (1.0f / 3.0f); }

/* Clips the ray interval (*t0, *t1) to the part inside the medium; returns 0 if empty.
 * For a bounded medium this is a slab test against the box. */
TS_INLINE int ts_medium_clip(const TsMedium* m, float3 org, float3 dir, float* t0, float* t1) {
    if (!m->present) return 0;
    if (m->bounded) return ts_ray_box_clip(org, dir, m->box_min, m->box_max, t0, t1);
    return *t0 < *t1;
}

/* Whether no segment whose ends lie within `scale` · 1e-4 of the box [lo, hi] (scene
 * units) meets the medium, so that its transmittance is exactly 1 (ts_medium_clip fails
 * for it): no medium, or the boxes apart on some axis by more than 1e-4 of the largest
 * of `scale` and the coordinates of either. That is far above the slab test's rounding
 * (a few ulps of the coordinates) and a ray's end offsets (32 ulps of a point's
 * pos_scale, ts_offset_ray_origin, when `scale` holds the largest). A medium filling space
 * meets every segment; a NaN or infinite coordinate or scale is never apart. */
TS_INLINE int ts_medium_misses_box(const TsMedium* m, float3 lo, float3 hi, float scale) {
    if (!m->present) return 1;
    if (!m->bounded || !(scale < TS_INF)) return 0; /* fmax below would drop a NaN scale */
    float s = fmax(fmax(fmax(fabs(lo.x), fabs(lo.y)), fmax(fabs(lo.z), fabs(hi.x))), fmax(fabs(hi.y), fabs(hi.z)));
    s = fmax(s, scale);
    s = fmax(s, fmax(fmax(fabs(m->box_min.x), fabs(m->box_min.y)), fabs(m->box_min.z)));
    s = fmax(s, fmax(fmax(fabs(m->box_max.x), fabs(m->box_max.y)), fabs(m->box_max.z)));
    float e = 1e-4f * s;
    if (!(e < TS_INF) || !(lo.x + lo.y + lo.z + hi.x + hi.y + hi.z < TS_INF)) return 0;
    return lo.x > m->box_max.x + e || lo.y > m->box_max.y + e || lo.z > m->box_max.z + e ||
           hi.x < m->box_min.x - e || hi.y < m->box_min.y - e || hi.z < m->box_min.z - e;
}

/* ts_medium_misses_box for the links from points in [from_lo, from_hi] (pos_scale up to
 * from_scale) to far ends in [lo, hi] (pos_scale up to scale), scene units: whether none
 * meets the medium, so that each one's transmittance is exactly 1. A far end that is not
 * finite, or a NaN far scale, is never apart (the larger scale is taken without fmax,
 * which would drop the NaN). The lane gathers of igi and ic ask this per link target. */
TS_INLINE int ts_medium_misses_links(const TsMedium* m, float3 from_lo, float3 from_hi, float from_scale, float3 lo,
                                     float3 hi, float scale) {
    if (!((lo.x + lo.y + lo.z + hi.x + hi.y + hi.z) * 0.0f == 0.0f)) return 0;
    scale = from_scale > scale ? from_scale : scale;
    return ts_medium_misses_box(m, fmin(from_lo, lo), fmax(from_hi, hi), scale);
}

/* Whether the medium scatters light in some channel (sigma_s > 0): else it only absorbs,
 * and in-scattered light is 0 everywhere. */
TS_INLINE int ts_medium_scatters(const TsMedium* m) {
    return m->sigma_s.x > 0.0f || m->sigma_s.y > 0.0f || m->sigma_s.z > 0.0f;
}

/* How far (scene units) in-scattered light carries in the medium: 20 mean free paths of
 * its thinnest scattering channel, past which e^-20 (2e-9) of it is left; +inf where
 * nothing scatters. A channel with sigma_s = 0 scatters no light however far it sees, so
 * it does not lift the cut for the others. The igi family's march and ray lights end
 * there (shared/igi_march.h, light_path.h): a medium box far larger than the scene (1e9
 * units) spread their points over all of it, where no light is left (13-33% dark). */
TS_INLINE float ts_medium_reach(const TsMedium* m) {
    float x = m->sigma_s.x > 0.0f ? m->sigma_t.x : TS_INF;
    float y = m->sigma_s.y > 0.0f ? m->sigma_t.y : TS_INF;
    float z = m->sigma_s.z > 0.0f ? m->sigma_t.z : TS_INF;
    float thinnest = fmin(fmin(x, y), z); /* sigma_t >= sigma_s > 0 where finite */
    return isfinite(thinnest) ? 20.0f / thinnest : TS_INF;
}

/* The log of the Beer–Lambert transmittance over a ray's span (t0, t1), all of it inside
 * the medium, len = |dir| (scene units): -sigma_t · (t1 - t0) · len per channel (<= 0,
 * the optical depth's negative). Its ts_exp3 is ts_medium_span_transmittance; callers
 * over lanes take the exponentials together (ts_medium_exp_lanes). */
TS_INLINE float3 ts_medium_span_log_transmittance(const TsMedium* m, float len, float t0, float t1) {
    return m->sigma_t * (-(t1 - t0) * len);
}

/* Beer–Lambert transmittance exp(-sigma_t · (t1 - t0) · len) over a ray's span (t0, t1),
 * all of it inside the medium, len = |dir| (scene units): ts_medium_transmittance's value
 * once clipped. */
TS_INLINE float3 ts_medium_span_transmittance(const TsMedium* m, float len, float t0, float t1) {
    return ts_exp3(ts_medium_span_log_transmittance(m, len, t0, t1));
}

/* The log of ts_medium_transmittance (its ts_exp3 is that, bit for bit): 0 where the ray
 * misses the medium, whose exponential is exactly 1. */
TS_INLINE float3 ts_medium_log_transmittance(const TsMedium* m, float3 org, float3 dir, float t0, float t1) {
    if (!ts_medium_clip(m, org, dir, &t0, &t1)) return make_float3(0.0f, 0.0f, 0.0f);
    return ts_medium_span_log_transmittance(m, length(dir), t0, t1);
}

/* Beer–Lambert transmittance exp(-sigma_t · length) along the ray over (t0, t1); the
 * length counts only the part inside the medium. */
TS_INLINE float3 ts_medium_transmittance(const TsMedium* m, float3 org, float3 dir, float t0, float t1) {
    if (!ts_medium_clip(m, org, dir, &t0, &t1)) return make_float3(1.0f, 1.0f, 1.0f); /* no exponential */
    return ts_medium_span_transmittance(m, length(dir), t0, t1);
}

/* Whether p lies in the medium's closed box (scene units), or the medium fills space;
 * 0 for a NaN coordinate or no medium. */
TS_INLINE int ts_medium_holds(const TsMedium* m, float3 p) {
    if (!m->present) return 0;
    if (!m->bounded) return 1;
    return (m->box_min.x <= p.x) & (p.x <= m->box_max.x) & (m->box_min.y <= p.y) & (p.y <= m->box_max.y) &
           (m->box_min.z <= p.z) & (p.z <= m->box_max.z);
}

/* Whether ts_medium_transmittance(m, org, dir, t0, t1) equals
 * ts_medium_span_transmittance(m, length(dir), t0, t1), bit for bit, without its slab
 * test: where both ends org and org + dir lie in the medium (ts_medium_holds:
 * `ends_held`), t0 is 0, 0 < t1 <= 1 - 1e-6 and every component of dir is 0 or a normal
 * float of magnitude at most 2^126. Then on each axis the slab's entry parameter rounds
 * to <= 0 (the box's near side minus org has the sign of -dir, and rounding keeps it) and
 * its exit to >= (1 - d)(1 - 2^-24), d the division's relative error (|far side - org| >=
 * |dir| rounds the same way; 1/dir is a normal float, also under flush-to-zero, for
 * |dir| <= 2^126): above 1 - 1e-6 for d up to ~8 ulp (OpenCL allows 2.5). So the clip
 * keeps (0, t1) whole, and an axis with dir 0 passes its test as org lies in the box.
 * Every shadow ray (t1 = 0.99999, ts_shadow_ray) between two points in fog qualifies; a
 * box with an infinite side holds infinite points, whose dir is refused. */
TS_INLINE int ts_medium_keeps_span(int ends_held, float3 dir, float t0, float t1) {
    const float tiny = 1.17549435e-38f, huge = 8.50705917e37f; /* 2^-126, 2^126: 1/dir normal */
    const float3 a = fabs(dir);
    const int normal = (a.x == 0.0f || (a.x >= tiny && a.x <= huge)) & (a.y == 0.0f || (a.y >= tiny && a.y <= huge)) &
                       (a.z == 0.0f || (a.z >= tiny && a.z <= huge));
    return ends_held & normal & (t0 == 0.0f) & (0.0f < t1) & (t1 <= 0.999999f);
}

/* The far roulette (docs/path-tracing.md §3): where a path's medium vertices need a
 * roulette beyond the throughput's. A medium that scatters without absorbing ends no path
 * by that roulette (a scattering event's weight is 1), and where it extends past the
 * scene (a medium filling space, a box with an open side) a path walks away from
 * everything it could light until its cap: `pt` to 8,192 vertices (90x the time of a
 * 64-vertex cap on an open Cornell box in such fog), the igi family's light paths to
 * 1,024 segments and as many VPLs and ray lights (10x the frame time). The region is the
 * box [lo, hi] (scene units: the scene's surfaces, and for camera paths the camera) grown
 * by `margin` (the box's diagonal); margin 0 (a zeroed frame or table) turns it off. */
typedef struct TsFarRegion {
    float3 lo, hi;
    float margin;
} TsFarRegion;

/* The far roulette's importance of a medium vertex at x: 1 within the region's margin of
 * its box (or without a region, or for a NaN x), (margin / d)² beyond it, d the distance
 * from the box; 0 (the path ends) past 1e10 margins, where the importance would fall
 * toward float's denormals and the survivors' weights, up to 1 / importance, toward its
 * overflow. A path there survives with probability min(1, w × this), its weight divided
 * by that (ts_roulette in shared/pt.h: w the throughput; ts_light_path_medium in
 * shared/light_path.h: w the product of the path's earlier far factors' inverses):
 * unbiased, and a path within the margin keeps its numbers and bits. The survivals
 * telescope, so a walk reaches distance d with probability (margin / d)², and the far
 * roulette raises a weight to at most (d / margin)² (a constant factor per event would
 * compound instead); the square, not the first power, because a random walk takes ~d²
 * events to wander to d, and with it each doubling of d costs about as many events as
 * the last rather than twice as many. */
TS_INLINE float ts_far_importance(const TsFarRegion* r, float3 x) {
    if (!(r->margin > 0.0f)) return 1.0f;
    float3 out = fmax(fmax(r->lo - x, x - r->hi), make_float3(0.0f, 0.0f, 0.0f));
    float d = length(out);
    if (!(d > r->margin)) return 1.0f;
    float f = r->margin / d;
    float importance = f * f;
    return importance < 1e-20f ? 0.0f : importance;
}

/* A path's state for free-flight sampling in a chromatic medium: path-level one-sample MIS
 * over the RGB channels (the "hero" channel of Wilkie et al. 2014, "Hero wavelength
 * spectral sampling"; pbrt-v4 §14.2.2 and Mitsuba 3's volpathmis keep the same ratio). The
 * channel whose exponential draws the distances is picked once per path (hero, 0-2;
 * TS_HERO_UNSET until the path's first segment in the medium picks it), and `ratio` holds
 * the three channels' pdfs of the path's distances so far, over their mean: a path's
 * weight is f / mean_c(p_c(path)), where each channel's pdf is a product over its
 * segments. Bounded: a channel's weight is at most 3 times the product of its
 * single-scattering albedos over the path's events (f_c / mean ≤ 3 f_c / p_c). Dividing each segment by
 * its own channel mean instead (one channel per segment) is unbiased too, but its weights
 * multiply, up to 3 an event: rare paths of huge weight, and images of a chromatic fog
 * dark in most runs (docs/path-tracing.md §4). */
#define TS_HERO_UNSET 3u
typedef struct TsSpectralMis {
    float3 ratio; /* the channels' path pdfs over their mean: (1, 1, 1) at the start */
    uint hero;    /* the channel that samples distances, or TS_HERO_UNSET */
} TsSpectralMis;

TS_INLINE TsSpectralMis ts_spectral_mis_start(void) {
    TsSpectralMis s;
    s.ratio = make_float3(1.0f, 1.0f, 1.0f);
    s.hero = TS_HERO_UNSET;
    return s;
}

/* Free-flight sampling over a segment of length `len` (scene units) inside the medium, for
 * a path whose spectral state is *sm (updated). The path's first segment picks the hero
 * channel c with `u_channel` (later segments ignore it); the distance is drawn from c's
 * exponential, t = -ln(1 - u) / sigma_t[c]. Returns the distance, or `len` when the sample
 * passes the whole segment. *weight is the throughput factor f / mean_c(ratio_c · p_c),
 *   scatter: f = sigma_s · Tr(t), p = sigma_t · Tr(t)
 *   pass:    f = p = Tr(len),
 * and ratio becomes ratio · p / mean_c(ratio_c · p_c); in a grey medium ratio stays 1 and
 * the weight is sigma_s / sigma_t or 1. A weight the float range cannot hold (channel
 * pdfs 1e38 apart) is 0: the path is dropped, not given an infinite weight. *scattered is
 * set to 1 for a scattering event. */
TS_INLINE float ts_medium_sample_distance(const TsMedium* m, float len, float u_channel, float u, TsSpectralMis* sm,
                                          float3* weight, int* scattered) {
    float3 st = m->sigma_t;
    if (sm->hero > 2u) sm->hero = u_channel < (1.0f / 3.0f) ? 0u : (u_channel < (2.0f / 3.0f) ? 1u : 2u);
    float sc = sm->hero == 0u ? st.x : (sm->hero == 1u ? st.y : st.z);
    float t = sc > 0.0f ? -log(1.0f - u) / sc : TS_INF;
    *scattered = t < len;
    if (!*scattered) t = len;
    float3 tr = ts_exp3(st * (-t));
    float3 f = *scattered ? m->sigma_s * tr : tr, p = *scattered ? st * tr : tr;
    if (st.x == st.y && st.y == st.z) {
        *weight = f / p.x; /* grey: every channel's pdf is p.x, and ratio stays (1, 1, 1) */
        return t;
    }
    float3 rp = sm->ratio * p;
    float mp = ts_mean3(rp);
    if (!(mp > 0.0f) || !isfinite(mp)) {
        *weight = make_float3(0.0f, 0.0f, 0.0f);
        return t;
    }
    *weight = f / mp;
    sm->ratio = rp / mp;
    return t;
}

/* Equiangular sampling of a distance along a ray toward a point p (Kulla and Fajardo
 * 2012, "Importance sampling techniques for path tracing in participating media", §4.1):
 * t = delta + D tan(theta), theta uniform in [theta_a, theta_b], so the density
 *   pdf(t) = D / ((theta_b - theta_a) (D^2 + (t - delta)^2))   (per scene unit)
 * follows the 1/distance^2 fall-off of light from p. delta: p's projection on the ray,
 * D: p's distance from the ray's line, floored at d_min and at 1e-5 of the segment's
 * extent from the origin, so that a point on the line gives a finite (narrow) density,
 * not a NaN. A larger floor only widens the density (any D > 0 gives an unbiased
 * estimate): callers whose integrand is clamped near p set d_min to the clamp's radius,
 * where 1/distance^2 stops describing it (shared/igi_march.h, ts_igi_march_vpl_link). */
typedef struct TsEquiangular {
    float delta, D, theta_a, theta_b;
} TsEquiangular;

/* The sampler's geometry for a segment ending at b of the ray (org, unit dir) toward p:
 * delta and D, at least d_min (scene units; 0: no floor beyond the rounding one). The
 * angles come apart (ts_equiangular_angles), so a caller can look at D before paying for
 * the inverse trigonometry. */
TS_INLINE TsEquiangular ts_equiangular_setup(float3 org, float3 dir, float b, float3 p, float d_min) {
    TsEquiangular e;
    float3 op = p - org;
    e.delta = dot(op, dir);
    float3 perp = op - dir * e.delta;
    float lp = length(perp), fb = fabs(b), fd = fabs(e.delta);
    float floor_d = 1e-5f * (fb > fd ? fb : fd) + 1e-30f;
    float D = lp > d_min ? lp : d_min;
    e.D = D > floor_d ? D : floor_d;
    e.theta_a = e.theta_b = 0.0f;
    return e;
}

/* The angles of the segment [a, b]'s ends seen from p (after ts_equiangular_setup):
 * atan((a - delta) / D), D > 0 (floored), with the branch-free arctangent of
 * shared/math_lanes.h, so that the 16-lane ray march vectorises the ray lights' draws
 * (shared/igi_march16.h). */
TS_INLINE TsEquiangular ts_equiangular_angles(TsEquiangular e, float a, float b) {
    e.theta_a = ts_lanes_atan((a - e.delta) / e.D);
    e.theta_b = ts_lanes_atan((b - e.delta) / e.D);
    return e;
}

/* The distance for uniform u in [0, 1), clamped to [a, b] against rounding of the tangent
 * (shared/math_lanes.h's, as the angles). Without branches: the selects give fmin and
 * fmax's values, a NaN t too (it gives a). */
TS_INLINE float ts_equiangular_sample(const TsEquiangular* e, float a, float b, float u) {
    float t = e->delta + e->D * ts_lanes_tan(e->theta_a + u * (e->theta_b - e->theta_a));
    t = t > a ? t : a;
    return t < b ? t : b;
}

/* The density of ts_equiangular_sample at t (per scene unit). */
TS_INLINE float ts_equiangular_pdf(const TsEquiangular* e, float t) {
    float x = t - e->delta;
    return e->D / ((e->theta_b - e->theta_a) * (e->D * e->D + x * x));
}

/* Distance sampling along a segment [a, b] of a ray (org, unit dir) toward a line (a
 * virtual ray light: p + s·w, w unit), with density ∝ 1/D(t), D(t) the distance from the
 * ray's point at t to the line (Novák, Nowrouzezahrai, Dachsbacher and Jarosz 2012,
 * "Virtual ray lights for rendering scenes with participating media", §5). The light a
 * ray light sends to a point falls as 1/d² over its length, which integrates to
 * (angle it spans)/D(t); sampling t ∝ 1/D(t) cancels that, so the pair's estimate stays
 * bounded up to a logarithm where the two lines pass close, where a point light's 1/d²
 * would not. With h the lines' closest distance, at ray parameter tc, and a = sin of the
 * angle between them, D(t)² = h² + a²(t − tc)², and
 *   t = tc + (h/a) sinh(A),  A uniform in [asinh(a(a' − tc)/h), asinh(a(b − tc)/h)],
 *   pdf(t) = a / ((A_b − A_a) · D(t))   (per scene unit).
 * h is floored at 1e-5 of the extent (as ts_equiangular_setup floors D); nearly parallel
 * lines (a < 1e-4) fall back to the uniform density 1/(b − a). */
typedef struct TsLineSampler {
    float tc, h, a, A0, A1;
    int uniform;
} TsLineSampler;

/* The sampler's geometry (tc, h, a) for the segment [ta, tb] of the ray (org, unit dir)
 * toward the line (p, unit w); the bounds come apart (ts_line_bounds), so a caller can look
 * at h before paying for the inverse hyperbolic functions. */
TS_INLINE TsLineSampler ts_line_setup(float3 org, float3 dir, float ta, float tb, float3 p, float3 w) {
    TsLineSampler ls;
    float3 r = org - p;
    float b = dot(dir, w), c = dot(dir, r), e = dot(w, r);
    float s2 = fmax(1.0f - b * b, 0.0f);
    ls.a = sqrt(s2);
    ls.uniform = !(ls.a >= 1e-4f);
    ls.tc = ls.uniform ? 0.0f : (b * e - c) / s2;
    float sc = e + ls.tc * b;
    float3 gap = r + dir * ls.tc - w * sc;
    ls.h = fmax(length(gap), 1e-5f * fmax(fmax(fabs(ta), fabs(tb)), fabs(ls.tc)) + 1e-30f);
    ls.A0 = ls.A1 = 0.0f;
    return ls;
}

TS_INLINE TsLineSampler ts_line_bounds(TsLineSampler ls, float ta, float tb) {
    ls.A0 = ls.uniform ? ta : asinh(ls.a * (ta - ls.tc) / ls.h);
    ls.A1 = ls.uniform ? tb : asinh(ls.a * (tb - ls.tc) / ls.h);
    return ls;
}

TS_INLINE TsLineSampler ts_line_sampler(float3 org, float3 dir, float ta, float tb, float3 p, float3 w) {
    return ts_line_bounds(ts_line_setup(org, dir, ta, tb, p, w), ta, tb);
}

/* The distance for uniform u in [0, 1), clamped to [ta, tb] against rounding of sinh. */
TS_INLINE float ts_line_sample(const TsLineSampler* ls, float ta, float tb, float u) {
    float A = ls->A0 + u * (ls->A1 - ls->A0);
    float t = ls->uniform ? A : ls->tc + ls->h / ls->a * sinh(A);
    return fmin(fmax(t, ta), tb);
}

/* The density of ts_line_sample at t (per scene unit). */
TS_INLINE float ts_line_pdf(const TsLineSampler* ls, float t) {
    if (ls->uniform) return 1.0f / (ls->A1 - ls->A0);
    float x = ls->a * (t - ls->tc);
    return ls->a / ((ls->A1 - ls->A0) * sqrt(ls->h * ls->h + x * x));
}

/* Transmittance along a shadow ray over its (tmin, tmax); 1 where the medium is compiled
 * out (OpenCL builds without TS_HAS_MEDIUM; every C++ build has it, and a scene without a
 * medium gives 1 through ts_medium_clip). */
TS_INLINE float3 ts_shadow_transmittance(const TsMedium* med, TsRay shadow) {
#ifdef TS_HAS_MEDIUM
    return ts_medium_transmittance(med, shadow.org, shadow.dir, shadow.tmin, shadow.tmax);
#else
    (void)med;
    (void)shadow;
    return make_float3(1.0f, 1.0f, 1.0f);
#endif
}

/* The log of ts_shadow_transmittance (ts_medium_log_transmittance): 0 where the medium is
 * compiled out. */
TS_INLINE float3 ts_shadow_log_transmittance(const TsMedium* med, TsRay shadow) {
#ifdef TS_HAS_MEDIUM
    return ts_medium_log_transmittance(med, shadow.org, shadow.dir, shadow.tmin, shadow.tmax);
#else
    (void)med;
    (void)shadow;
    return make_float3(0.0f, 0.0f, 0.0f);
#endif
}

TS_NAMESPACE_END
#endif /* TS_MEDIUM_H */
