/* Edge guidance and each pixel's edge-sample count (docs/ais.md §9): the per-pixel math of
 * the host's edge_guidance and make_edge_schedule (host/gi/ais_edges.cpp), written once so
 * the device's KernelId::EdgeSchedule (shared/ais_resolve.h) gives the host's counts bit
 * for bit. The caller finds which neighbours lie across an edge (its discontinuity test,
 * or the emitter flags differ); the contrast and the count are here. */
#ifndef TS_EDGE_GUIDANCE_H
#define TS_EDGE_GUIDANCE_H
#include "shared/compat.h"
#include "shared/layout_pass.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

/* p's 3×3 window: itself, the 4 sides, then the corners (the order ties are broken in). */
TS_CONSTANT_TABLE int ts_edge_window[9][2] = {{0, 0},  {-1, 0}, {1, 0},  {0, -1}, {0, 1},
                                              {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};

/* The pairs of p's neighbours the guidance compares, as offsets (ax, ay, bx, by) from p:
 * each of the 8 around p with the next on the ring, then left with right and above with
 * below (the only pairs an image one pixel wide or high has). Never p itself: a flag that
 * read p's own sample would be biased, for the merge averages that sample with the edge
 * samples, so a sample that alone met something (a light or a bar thinner than a pixel,
 * a reflection a dielectric chose) flagged its pixel, and its share of the pixel fell to
 * 1/(n + 1) (docs/ais.md §9). Any edge across p's 3×3 window parts the ring. */
TS_CONSTANT_TABLE int ts_edge_pairs[10][4] = {{-1, -1, 0, -1}, {0, -1, 1, -1}, {1, -1, 1, 0}, {1, 0, 1, 1},
                                              {1, 1, 0, 1},    {0, 1, -1, 1},  {-1, 1, -1, 0}, {-1, 0, -1, -1},
                                              {-1, 0, 1, 0},   {0, -1, 0, 1}};

/* Pair i of ts_edge_pairs around pixel (x, y) of a w × h image: 0 when a member lies
 * outside the image; else 1, with the members' row-major indices *qa and *qb. */
TS_INLINE int ts_edge_pair_pixels(int x, int y, int w, int h, int i, size_t* qa, size_t* qb) {
    const int ax = x + ts_edge_pairs[i][0], ay = y + ts_edge_pairs[i][1];
    const int bx = x + ts_edge_pairs[i][2], by = y + ts_edge_pairs[i][3];
    if (ax < 0 || ay < 0 || bx < 0 || by < 0 || ax >= w || bx >= w || ay >= h || by >= h) return 0;
    *qa = (size_t)ay * (size_t)w + (size_t)ax;
    *qb = (size_t)by * (size_t)w + (size_t)bx;
    return 1;
}

/* The contrast across the edge between luminances yp and yq (Michelson's with ε `eps`,
 * in [0, 1]); 0 where the denominator is not positive. */
TS_INLINE float ts_edge_contrast(float yp, float yq, float eps) {
    const float denominator = yp + yq + eps;
    return denominator > 0.0f ? fabs(yp - yq) / denominator : 0.0f;
}

/* Folds one neighbour's contrast into the pixel's running maximum `best`, clamped to 1. A
 * NaN or infinite luminance flags nothing (the comparison fails). */
TS_INLINE float ts_edge_max(float best, float contrast) {
    return contrast > best ? (1.0f < contrast ? 1.0f : contrast) : best;
}

/* Edge samples of a pixel of guidance g (0: not flagged): A-MAX `most`; A ⌈most · a⌉,
 * a = (g − trigger) / (full − trigger) clamped to [0, 1], at least 1 (where full >
 * trigger; else `most`). */
TS_INLINE uint ts_edge_sample_count(float g, float trigger, float full, uint most, int amax) {
    if (!(g > trigger)) return 0u;
    if (amax || !(full > trigger)) return most;
    float a = (g - trigger) / (full - trigger);
    a = a < 0.0f ? 0.0f : (1.0f < a ? 1.0f : a);
    const uint n = (uint)ceil(a * (float)most);
    return n < 1u ? 1u : (most < n ? most : n);
}

/* The luminance of row y's radiance in a pass image `width` pixels wide (TS_PASS_FLOATS a
 * pixel, TS_PASS_RADIANCE), summed in pixel order: in double where the device has it
 * (host: edge_epsilon sums the rows' sums in row order, so host and device agree bit for
 * bit), else in compensated float. */
#ifdef TS_HAS_DOUBLE
TS_INLINE double ts_edge_row_luminance(TS_GLOBAL const float* pass, uint width, uint y) {
    double sum = 0.0;
    for (uint x = 0; x < width; ++x)
        sum += ts_luminance(ts_f3_load(pass + ((size_t)y * width + x) * TS_PASS_FLOATS + TS_PASS_RADIANCE));
    return sum;
}
#else
TS_INLINE float ts_edge_row_luminance(TS_GLOBAL const float* pass, uint width, uint y) {
    float sum = 0.0f, c = 0.0f;
    for (uint x = 0; x < width; ++x)
        ts_sum_compensated_add(&sum, &c,
                               ts_luminance(ts_f3_load(pass + ((size_t)y * width + x) * TS_PASS_FLOATS + TS_PASS_RADIANCE)));
    return sum + c;
}
#endif

TS_NAMESPACE_END
#endif /* TS_EDGE_GUIDANCE_H */
