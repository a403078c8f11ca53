/* Adaptive Interleaved Sampling's extra evaluations (docs/ais.md): one item is a pixel,
 * a sample set and the components the schedule asks of it, evaluated with the same camera
 * ray, surface and set samples as the base pass (shared/igi.h, shared/igi_media.h), from
 * the host's item list or from the tables the device compacted (shared/ais_compact.h). */
#ifndef TS_AIS_ITEM_H
#define TS_AIS_ITEM_H
#include "shared/ais_compact.h"
#include "shared/igi_media.h"

TS_NAMESPACE_BEGIN

/* Decodes item i of sv->items (TS_AIS_ITEM_WORDS,
 * layout_igi.h): pixel (px, py), sample set k, components `mask` (TS_COMPONENT_*). */
TS_INLINE void ts_ais_item_decode(const TsSceneView* sv, const TsFrame* f, uint i, uint* px, uint* py, uint* k,
                                  uint* mask) {
    uint p = sv->items[TS_AIS_ITEM_WORDS * i + TS_AIS_ITEM_PIXEL], code = sv->items[TS_AIS_ITEM_WORDS * i + TS_AIS_ITEM_CODE];
    *px = p % f->width;
    *py = p / f->width;
    *k = code & 0xffu;
    *mask = code >> 8;
}

/* Whether an AIS item needs the surface terms (and so the view's camera path). */
TS_INLINE int ts_ais_item_has_surface(uint mask) { return (mask & (TS_COMPONENT_SS | TS_COMPONENT_ID)) != 0u; }

TS_INLINE void ts_ais_item_store_surface(float3 e_ss, float3 e_id, float* out) {
    ts_f3_store(out + TS_AIS_ITEM_E_SS, e_ss);
    ts_f3_store(out + TS_AIS_ITEM_E_ID, e_id);
}

/* The media part of an AIS item: set k's single-scattering estimate at pixel (px, py). */
TS_INLINE void ts_ais_item_media(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint px, uint py,
                                 uint k, uint mask, float* out) {
#ifdef TS_HAS_MEDIUM
    if (mask & TS_COMPONENT_PM) {
        float m[TS_IGI_MEDIA_FLOATS];
        m[TS_IGI_MEDIA_LIT] = m[TS_IGI_MEDIA_LENGTH] = 0.0f;
        ts_igi_media_set(sv, tracer, f, px, py, k, m);
        for (int c = 0; c < 3; ++c) out[TS_AIS_ITEM_PM + c] = m[TS_IGI_MEDIA_RADIANCE + c];
    }
#else
    (void)sv, (void)tracer, (void)f, (void)px, (void)py, (void)k, (void)mask, (void)out;
#endif
}

/* One AIS extra evaluation: sample set k for pixel (px, py), for the components in mask
 * (TS_COMPONENT_*). Writes TS_AIS_ITEM_FLOATS values; the same camera ray, surface and
 * set samples as the base pass would use for set k, so a pixel evaluated for every set
 * gets exactly the full-rate (non-interleaved) estimate. */
TS_INLINE void ts_ais_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint px, uint py,
                           uint k, uint mask, float* out) {
    for (int i = 0; i < TS_AIS_ITEM_FLOATS; ++i) out[i] = 0.0f;
    if (ts_ais_item_has_surface(mask)) {
        TsIgiView v = ts_igi_view(sv, tracer, f, px, py);
        if (v.hit.prim != TS_NO_HIT) {
            float3 e_ss, e_id;
            float visible;
            ts_igi_surface_set(sv, tracer, f, &v, k, mask, &e_ss, &e_id, &visible);
            ts_ais_item_store_surface(e_ss, e_id, out);
        }
    }
    ts_ais_item_media(sv, tracer, f, px, py, k, mask, out);
}

/* The ais extra kernel's work item i: item i of sv->items through ts_ais_item. */
TS_INLINE void ts_ais_extra_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                 float* out) {
    uint px, py, k, mask;
    ts_ais_item_decode(sv, f, i, &px, &py, &k, &mask);
    ts_ais_item(sv, tracer, f, px, py, k, mask, out);
}

/* KernelId::AisCompactItem's work item i of a device frame: item i of the tables kept where
 * the kernels run (ts_ais_compact_decode, shared/ais_compact.h) through ts_ais_item. */
TS_INLINE void ts_ais_compact_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint i,
                                   float* out) {
    uint px, py, k, mask;
    ts_ais_compact_decode(sv, f, i, &px, &py, &k, &mask);
    ts_ais_item(sv, tracer, f, px, py, k, mask, out);
}

TS_NAMESPACE_END
#endif /* TS_AIS_ITEM_H */
