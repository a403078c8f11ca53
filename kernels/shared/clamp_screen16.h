/* The screen-space clamp compensation's gather (shared/clamp_screen.h, docs/igi.md §4) for
 * 16 pixels of one row at once, x0, x0 + 2, ..., x0 + 30: the host's gather
 * (host/gi/clamp_screen.cpp) runs it over the even grid, whose pixels are two apart. Each
 * lane takes the samples ts_clamp_screen_pixel takes, in the same order, through the same
 * functions, and adds a term only where that function adds it, so its E_res equals
 * ts_clamp_screen_pixel's bit for bit (tests/kernels/clamp_screen16_test.cpp; the host's
 * whole estimate against one built from ts_clamp_screen_pixel: tests/gi/clamp_screen_test.cpp;
 * a device resolving an igi frame runs ts_clamp_screen_pixel:
 * tests/kernels/igi_resolve_test.cpp).
 *
 * Why 16 lanes: one pixel's gather is ~90 samples of branches and scattered loads (14%
 * of a default AIS frame on Embree). The lanes' samples at one offset lie side by side in
 * the records' planes below (pixels two apart, one parity), so a sample is a few vector
 * loads and a loop GCC vectorises; every file that includes this is built with
 * -fno-trapping-math (CMakeLists.txt says why that changes no value), and its functions
 * have internal linkage in C++ (TS_LANES_INLINE), so no file's copy stands in for
 * another's at link time.
 *
 * The records' planes (TsClampScreenPlanes): each of a record's TS_CLAMP_SCREEN_FLOATS
 * fields (layout_igi.h: field k is a device record's float k) is stored as two planes, the
 * even columns and the odd, each of `height` rows of `pitch` floats (ts_clamp_planes_at
 * gives the planes' order), pixel (x, y) at
 * column TS_CLAMP_PLANE_PAD + (x >> 1) of parity x & 1 (>> rounds down, so a column left
 * of the image is a pad). The pads, zero, hold the columns that the lanes read beyond the
 * image's sides (ring offsets stay within ±TS_CLAMP_SCREEN_MAX_RADIUS, and lanes 30 pixels to
 * the right of x0), so the loads need no test; their terms are masked. C and OpenCL C
 * compatible in form, used by the host only. */
#ifndef TS_CLAMP_SCREEN16_H
#define TS_CLAMP_SCREEN16_H
#include "shared/clamp_screen.h"
#include "shared/geometry.h"

TS_NAMESPACE_BEGIN

#define TS_CLAMP_LANES TS_PACKET_LANES
#ifdef __cplusplus
#define TS_LANES_INLINE static inline
#else
#define TS_LANES_INLINE TS_INLINE
#endif
/* Columns of pad left of each plane row: ring offsets stay within ±TS_CLAMP_SCREEN_MAX_RADIUS
 * pixels (about ±56: a ring's middle radius is below r ≤ 64), 32 columns. */
#define TS_CLAMP_PLANE_PAD 32
/* Columns right of the image's: +64 pixels of offset and lanes up to 30 pixels right of a
 * pixel in the image, (64 + 30) / 2 + 1 columns (with the same margin). */
#define TS_CLAMP_PLANE_PAD_RIGHT 48
#ifdef __cplusplus
static_assert(TS_CLAMP_PLANE_PAD * 2 >= TS_CLAMP_SCREEN_MAX_RADIUS &&
                  (TS_CLAMP_PLANE_PAD_RIGHT - 1) * 2 >= TS_CLAMP_SCREEN_MAX_RADIUS + 2 * (TS_CLAMP_LANES - 1),
              "clamp_screen16.h: the pads must hold the columns of the largest ring offset");
#endif

typedef struct TsClampScreenPlanes {
    const float* data; /* host memory: the planes are the host's alone */
    int width, height;
    int pitch; /* floats a plane row: ts_clamp_planes_pitch(width) */
} TsClampScreenPlanes;

/* Floats left between the two parities' planes and between fields beyond their size: one
 * cache line. Planes whose size is a multiple of 4 KB (at 512², 512 · 336 floats) would
 * otherwise put a sample's ten fields in one set of the L1 cache (and their stores 4 KB
 * apart alias): writing the records took twice as long (3.0% of a default AIS frame
 * on Embree against 1.5%). */
#define TS_CLAMP_PLANE_SKEW 16

TS_LANES_INLINE int ts_clamp_planes_pitch(int width) {
    return (width + 1) / 2 + TS_CLAMP_PLANE_PAD + TS_CLAMP_PLANE_PAD_RIGHT;
}
/* Floats from a field's even plane to its odd one, and from one field to the next. */
TS_LANES_INLINE size_t ts_clamp_planes_parity(const TsClampScreenPlanes* P) {
    return (size_t)P->height * P->pitch + TS_CLAMP_PLANE_SKEW;
}
TS_LANES_INLINE size_t ts_clamp_planes_field(const TsClampScreenPlanes* P) {
    return 2 * ts_clamp_planes_parity(P) + TS_CLAMP_PLANE_SKEW;
}
/* Floats in the planes of a width × height image. */
TS_LANES_INLINE size_t ts_clamp_planes_floats(int width, int height) {
    TsClampScreenPlanes P;
    P.data = 0;
    P.width = width;
    P.height = height;
    P.pitch = ts_clamp_planes_pitch(width);
    return (size_t)TS_CLAMP_SCREEN_FLOATS * ts_clamp_planes_field(&P);
}

/* Index of field 0 of pixel (x, y) (x may be a pad's column); field k is k ·
 * ts_clamp_planes_field further on. */
TS_LANES_INLINE size_t ts_clamp_planes_at(const TsClampScreenPlanes* P, int x, int y) {
    return (size_t)(x & 1) * ts_clamp_planes_parity(P) + (size_t)y * P->pitch + TS_CLAMP_PLANE_PAD + (x >> 1);
}

/* The lanes: each one's surface (position, unit normal: its record's), window radius r
 * (pixels, ts_clamp_screen_radius), whether it gathers (on: -1, else 0, with r = 0), and
 * its running sum (irradiance / π times π, as ts_clamp_screen_pixel's `sum`). */
typedef struct TS_ALIGN64 TsClampScreenLanes {
    float p[3][TS_CLAMP_LANES], n[3][TS_CLAMP_LANES], r[TS_CLAMP_LANES], sum[3][TS_CLAMP_LANES];
    int on[TS_CLAMP_LANES];
} TsClampScreenLanes;

/* One sample per lane in `use` (-1 or 0) with weight w[i], into the lanes' sums:
 * ts_clamp_screen_add's tests and term. Lane i's record is field k at
 * src[k · field + i] (side by side: a plane row, or a copy). The hot fields are read
 * first; where no lane is in reach the cold fields are not read. */
TS_LANES_INLINE void ts_clamp_lanes_add(TsClampScreenLanes* L, const float* TS_RESTRICT src, size_t field,
                                        const int* use, const float* w, float b, float inv_b, const TsMedium* med) {
    float d[3][TS_CLAMP_LANES], d2[TS_CLAMP_LANES], cos_x[TS_CLAMP_LANES], e[TS_CLAMP_LANES];
    float s[3][TS_CLAMP_LANES];
    int ok[TS_CLAMP_LANES], any = 0;
    const float* TS_RESTRICT pos = src + TS_CLAMP_SCREEN_POSITION * field;
    for (int i = 0; i < TS_CLAMP_LANES; ++i) {
        const float3 di = make_float3(pos[i], pos[field + i], pos[2 * field + i]) -
                          make_float3(L->p[0][i], L->p[1][i], L->p[2][i]);
        d[0][i] = di.x;
        d[1][i] = di.y;
        d[2][i] = di.z;
        d2[i] = ts_clamp_screen_dot(di, di);
        cos_x[i] = ts_clamp_screen_dot(make_float3(L->n[0][i], L->n[1][i], L->n[2][i]), di);
        ok[i] = use[i] & ts_clamp_screen_in_reach(d2[i], cos_x[i], inv_b);
    }
    for (int i = 0; i < TS_CLAMP_LANES; ++i) any |= ok[i];
    if (!any) return;
    const float* TS_RESTRICT area = src + TS_CLAMP_SCREEN_AREA * field;
    const float* TS_RESTRICT nq = src + (TS_CLAMP_SCREEN_COLD + TS_CLAMP_SCREEN_NORMAL) * field;
    const float* TS_RESTRICT sq = src + (TS_CLAMP_SCREEN_COLD + TS_CLAMP_SCREEN_SOURCE) * field;
    for (int i = 0; i < TS_CLAMP_LANES; ++i) {
        const float3 di = make_float3(d[0][i], d[1][i], d[2][i]);
        const float3 si = make_float3(sq[i], sq[field + i], sq[2 * field + i]);
        s[0][i] = si.x;
        s[1][i] = si.y;
        s[2][i] = si.z;
        const float ei = ts_clamp_screen_excess(
            d2[i], cos_x[i], -ts_clamp_screen_dot(make_float3(nq[i], nq[field + i], nq[2 * field + i]), di), area[i],
            si, b);
        ok[i] &= -(ei > 0.0f);
        e[i] = ei * w[i];
    }
    if (med) {
        /* Fog: the transmittance per lane that counts, in ts_clamp_screen_add's form. */
        for (int i = 0; i < TS_CLAMP_LANES; ++i) {
            if (!ok[i]) continue;
            const float3 tr = ts_medium_transmittance(med, make_float3(L->p[0][i], L->p[1][i], L->p[2][i]),
                                                      make_float3(d[0][i], d[1][i], d[2][i]), 0.0f, 1.0f);
            s[0][i] *= tr.x;
            s[1][i] *= tr.y;
            s[2][i] *= tr.z;
        }
    }
    /* s · 1 is s: without a medium the term is ts_clamp_screen_add's s · tr · (e · w). */
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < TS_CLAMP_LANES; ++i) L->sum[k][i] = ok[i] ? L->sum[k][i] + s[k][i] * e[i] : L->sum[k][i];
}

/* The lanes' sample at offset (ox, oy) from their pixels (x0 + 2i, y), weight w, for the
 * lanes in `use`: records side by side in one plane row. */
TS_LANES_INLINE void ts_clamp_lanes_offset(TsClampScreenLanes* L, const TsClampScreenPlanes* P, int x0, int y, int ox,
                                           int oy, const int* use, float w, float b, float inv_b, const TsMedium* med) {
    const int qy = y + oy;
    if (qy < 0 || qy >= P->height) return;
    int in[TS_CLAMP_LANES];
    float ws[TS_CLAMP_LANES];
    for (int i = 0; i < TS_CLAMP_LANES; ++i) {
        const int qx = x0 + ox + 2 * i;
        in[i] = use[i] & -((qx >= 0) & (qx < P->width));
        ws[i] = w;
    }
    ts_clamp_lanes_add(L, P->data + ts_clamp_planes_at(P, x0 + ox, qy), ts_clamp_planes_field(P), in, ws, b, inv_b,
                       med);
}

/* The lanes' samples at their own pixels (qx[i], qy[i]), weights w[i], for the lanes in
 * `use`: their records copied side by side. */
TS_LANES_INLINE void ts_clamp_lanes_at(TsClampScreenLanes* L, const TsClampScreenPlanes* P, const int* qx,
                                       const int* qy, const int* use, const float* w, float b, float inv_b,
                                       const TsMedium* med) {
    float rec[TS_CLAMP_SCREEN_FLOATS][TS_CLAMP_LANES];
    int in[TS_CLAMP_LANES];
    const size_t field = ts_clamp_planes_field(P);
    for (int i = 0; i < TS_CLAMP_LANES; ++i) {
        in[i] = use[i] & -((qx[i] >= 0) & (qx[i] < P->width) & (qy[i] >= 0) & (qy[i] < P->height));
        const size_t q = in[i] ? ts_clamp_planes_at(P, qx[i], qy[i]) : 0;
        for (int k = 0; k < TS_CLAMP_SCREEN_FLOATS; ++k) rec[k][i] = P->data[q + k * field];
    }
    ts_clamp_lanes_add(L, &rec[0][0], TS_CLAMP_LANES, in, w, b, inv_b, med);
}

/* E_res (irradiance / π, ts_clamp_screen_pixel's) of every lane that is on, into the
 * lanes' sums: the near square, then the rings. A ring's lanes whose window reaches past
 * it (r ≥ r0 · growth) share its radius and offsets; a lane whose window ends inside it
 * has its own (its last ring), taken per lane with its own offsets. */
TS_LANES_INLINE void ts_clamp_lanes_gather(TsClampScreenLanes* L, const TsClampScreenPlanes* P, int x0, int y, float b,
                                           const TsMedium* med) {
    const float inv_b = 1.0f / b;
    float rmax = 0.0f;
    for (int i = 0; i < TS_CLAMP_LANES; ++i) {
        L->sum[0][i] = L->sum[1][i] = L->sum[2][i] = 0.0f;
        rmax = L->on[i] ? fmax(rmax, L->r[i]) : rmax;
    }
    for (int dy = -TS_CLAMP_SCREEN_NEAR; dy <= TS_CLAMP_SCREEN_NEAR; ++dy)
        for (int dx = -TS_CLAMP_SCREEN_NEAR; dx <= TS_CLAMP_SCREEN_NEAR; ++dx)
            if (dx != 0 || dy != 0) ts_clamp_lanes_offset(L, P, x0, y, dx, dy, L->on, 1.0f, b, inv_b, med);
    float r0 = TS_CLAMP_SCREEN_FIRST_RING;
    float ring_c = 1.0f, ring_s = 0.0f;
    while (r0 < rmax) {
        const float r1 = r0 * TS_CLAMP_SCREEN_GROWTH;
        int full[TS_CLAMP_LANES], last[TS_CLAMP_LANES], any_full = 0, any_last = 0;
        float rm[TS_CLAMP_LANES], w[TS_CLAMP_LANES];
        for (int i = 0; i < TS_CLAMP_LANES; ++i) {
            /* ts_clamp_screen_pixel's r1 = fmin(r0 · growth, r): r1 itself where r ≥ r1. */
            const int in_ring = L->on[i] & -(r0 < L->r[i]);
            full[i] = in_ring & -(L->r[i] >= r1);
            last[i] = in_ring & ~full[i];
            const float ri = fmin(r1, L->r[i]);
            rm[i] = 0.5f * (r0 + ri);
            w[i] = ts_clamp_screen_ring_weight(r0, ri);
            any_full |= full[i];
            any_last |= last[i];
        }
        float c = ring_c, s = ring_s;
        ts_clamp_screen_turn(&ring_c, &ring_s, TS_CLAMP_SCREEN_GOLDEN_C, TS_CLAMP_SCREEN_GOLDEN_S);
        const float rm_full = 0.5f * (r0 + r1), w_full = ts_clamp_screen_ring_weight(r0, r1);
        for (int j = 0; j < TS_CLAMP_SCREEN_RING; ++j) {
            if (any_full)
                ts_clamp_lanes_offset(L, P, x0, y, ts_clamp_screen_offset(rm_full, c),
                                      ts_clamp_screen_offset(rm_full, s), full, w_full, b, inv_b, med);
            if (any_last) {
                int qx[TS_CLAMP_LANES], qy[TS_CLAMP_LANES];
                for (int i = 0; i < TS_CLAMP_LANES; ++i) {
                    qx[i] = x0 + 2 * i + ts_clamp_screen_offset(rm[i], c);
                    qy[i] = y + ts_clamp_screen_offset(rm[i], s);
                }
                ts_clamp_lanes_at(L, P, qx, qy, last, w, b, inv_b, med);
            }
            ts_clamp_screen_turn(&c, &s, TS_CLAMP_SCREEN_STEP_C, TS_CLAMP_SCREEN_STEP_S);
        }
        r0 = r1;
    }
}

TS_NAMESPACE_END
#endif /* TS_CLAMP_SCREEN16_H */
