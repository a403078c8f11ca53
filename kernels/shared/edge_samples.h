/* Edge samples, AIS's fourth component (docs/ais.md §9): extra camera samples inside a
 * pixel the host flagged as lying on a geometric edge. Each traces the camera ray at its
 * own position in the pixel, follows the specular bounces to the first diffuse surface as
 * the base pass does (ts_igi_view_from), and returns that surface's G-buffer entry and
 * material; the host shades it with the reconstructed irradiance of the neighbouring pixel
 * on the same surface (host/gi/ais_edges.h), so a sample costs its camera path only. */
#ifndef TS_EDGE_SAMPLES_H
#define TS_EDGE_SAMPLES_H
#include "shared/ais_compact.h"
#include "shared/igi.h"

TS_NAMESPACE_BEGIN

/* Position of edge sample j ≥ 1 of pixel (px, py) inside the pixel, in [0, 1)²: the base
 * sample's jitter u (the first two numbers of the pixel's stream, ts_igi_view_ray) moved
 * by the j-th Halton point (bases 2 and 3) modulo 1. The pixel's samples are then a
 * Cranley–Patterson-rotated Halton set whose point 0 is the base sample: stratified over
 * the pixel, each uniform in it, so their mean is the box-filtered radiance that `pt`'s
 * jittered samples average to. */
TS_INLINE void ts_edge_sample_jitter(const TsFrame* f, uint px, uint py, uint j, float* jx, float* jy) {
    TsRng rng = ts_rng_seed(f->seed, py * f->width + px, f->pass);
    float x = ts_rng_next(&rng) + ts_radical_inverse2(j);
    float y = ts_rng_next(&rng) + ts_radical_inverse3(j);
    /* u + h < 2, so one subtraction wraps it; a sum that rounds up to 1 wraps to 0. */
    *jx = x >= 1.0f ? x - 1.0f : x;
    *jy = y >= 1.0f ? y - 1.0f : y;
}

/* Edge sample `j` (≥ 1) of the `n` of pixel (px, py): its camera path to the first
 * diffuse surface. Writes TS_EDGE_SAMPLE_FLOATS values (layout_igi.h); a path that escapes
 * stores distance +inf, albedo and emission 0 and throughput 1, as ts_igi_surface_clear
 * does. Dielectric choices draw from the sample's own stream (seed hashed with j),
 * independent of the base sample's. The ray cone is the pixel's narrowed by √(n + 1): the
 * n + 1 samples split the pixel's footprint, so each filters textures over its share
 * (docs/texture-filtering.md; as passes narrow it by √(pass + 1)). */
TS_INLINE void ts_edge_sample(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint px, uint py,
                              uint j, uint n, float* out) {
    float jx, jy;
    ts_edge_sample_jitter(f, px, py, j, &jx, &jy);
    TsRng rng = ts_rng_seed(ts_pcg_hash(f->seed + j), py * f->width + px, f->pass);
    TsRay ray = ts_camera_ray(f, px, py, jx, jy);
    TsFrame narrow = *f;
    narrow.pixel_cone = f->pixel_cone / sqrt((float)n + 1.0f);
    TsIgiView v = ts_igi_view_from(sv, tracer, &narrow, ray, ts_trace_closest(tracer, ray), &rng);
    for (int i = 0; i < TS_EDGE_SAMPLE_FLOATS; ++i) out[i] = 0.0f;
    ts_f3_store(out + TS_EDGE_SAMPLE_THROUGHPUT, make_float3(1.0f, 1.0f, 1.0f));
    out[TS_EDGE_SAMPLE_DISTANCE] = TS_INF;
    if (v.hit.prim == TS_NO_HIT) return;
    ts_f3_store(out + TS_EDGE_SAMPLE_ALBEDO, ts_material_albedo(sv, &v.s));
    ts_f3_store(out + TS_EDGE_SAMPLE_EMISSION, ts_material_emission(sv, &v.s));
    ts_f3_store(out + TS_EDGE_SAMPLE_THROUGHPUT, v.throughput);
    ts_f3_store(out + TS_EDGE_SAMPLE_NORMAL, v.s.shading_normal);
    ts_f3_store(out + TS_EDGE_SAMPLE_POSITION, v.s.position);
    out[TS_EDGE_SAMPLE_DISTANCE] = v.distance;
}

/* The edge-sample kernel's work item i: item i of sv->items (TS_EDGE_ITEM_WORDS uints,
 * layout_igi.h: the pixel's row-major index, the sample's index j ≥ 1, the pixel's count). */
TS_INLINE void ts_edge_sample_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                   float* out) {
    uint p = sv->items[TS_EDGE_ITEM_WORDS * i + TS_EDGE_ITEM_PIXEL];
    uint j = sv->items[TS_EDGE_ITEM_WORDS * i + TS_EDGE_ITEM_SAMPLE];
    uint n = sv->items[TS_EDGE_ITEM_WORDS * i + TS_EDGE_ITEM_COUNT];
    ts_edge_sample(sv, tracer, f, p % f->width, p / f->width, j, n, out);
}

/* KernelId::EdgeCompactSample's work item i of a device frame: sample i of the tables kept
 * where the kernels run (ts_edge_compact_decode, shared/ais_compact.h). */
TS_INLINE void ts_edge_compact_sample_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                           float* out) {
    uint p, j, n;
    ts_edge_compact_decode(sv, f, i, &p, &j, &n);
    ts_edge_sample(sv, tracer, f, p % f->width, p / f->width, j, n, out);
}

TS_NAMESPACE_END
#endif /* TS_EDGE_SAMPLES_H */
