/* Material evaluation: Lambertian albedo (Kd, optionally × map_Kd) and emission. */
#ifndef TS_MATERIAL_H
#define TS_MATERIAL_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/layout_scene.h"
#include "shared/srgb_table.h"

TS_NAMESPACE_BEGIN

/* sRGB transfer curve inverse (IEC 61966-2-1), one 8-bit channel (0..255) to linear. */
TS_INLINE float ts_srgb_to_linear(uint c8) { return ts_srgb_table[c8 & 0xffu]; }

TS_INLINE float3 ts_texel(TS_GLOBAL const uint* texels, uint offset, uint w, int x, int y) {
    uint t = texels[offset + (uint)y * w + (uint)x];
    return make_float3(ts_srgb_to_linear(t & 0xffu), ts_srgb_to_linear((t >> 8) & 0xffu),
                       ts_srgb_to_linear((t >> 16) & 0xffu));
}

/* Bilinear lookup in one mip level (w×h texels from texel offset off) with wrap-around
 * addressing; v = 0 is the bottom row (OBJ). */
TS_INLINE float3 ts_texture_bilinear(TS_GLOBAL const uint* texels, uint off, uint w, uint h, float2 uv) {
    float fx = (uv.x - floor(uv.x)) * (float)w - 0.5f;
    float fy = (1.0f - (uv.y - floor(uv.y))) * (float)h - 0.5f;
    float x0f = floor(fx), y0f = floor(fy);
    float ax = fx - x0f, ay = fy - y0f;
    int iw = (int)w, ih = (int)h;
    int x0 = ((int)x0f % iw + iw) % iw, y0 = ((int)y0f % ih + ih) % ih;
    int x1 = (x0 + 1) % iw, y1 = (y0 + 1) % ih;
    float3 a = ts_texel(texels, off, w, x0, y0) * (1.0f - ax) + ts_texel(texels, off, w, x1, y0) * ax;
    float3 b = ts_texel(texels, off, w, x0, y1) * (1.0f - ax) + ts_texel(texels, off, w, x1, y1) * ax;
    return a * (1.0f - ay) + b * ay;
}

/* Texel offset and size of mip level `level` of a texture whose level 0 is w×h at `off`
 * (levels stored one after another; layout_scene.h textures). */
TS_INLINE uint ts_mip_level(uint off, uint* w, uint* h, uint level) {
    for (uint l = 0u; l < level; ++l) {
        off += *w * *h;
        *w = *w > 1u ? *w >> 1 : 1u;
        *h = *h > 1u ? *h >> 1 : 1u;
    }
    return off;
}

/* Texture lookup filtered to a footprint `uv_footprint` wide in texture coordinates
 * (TsSurface::uv_footprint): trilinear between the two mip levels around
 * λ = log2(footprint in level-0 texels) (Williams 1983, "Pyramidal parametrics"); at
 * λ <= 0 (footprint 0: rays that are not a camera's) the bilinear lookup of level 0. */
TS_INLINE float3 ts_texture_lookup(const TsSceneView* sv, int tex, float2 uv, float uv_footprint) {
    TS_GLOBAL const uint* info = sv->tex_info + TS_TEX_INFO_UINTS * (uint)tex;
    uint off = info[TS_TEX_OFFSET], w = info[TS_TEX_WIDTH], h = info[TS_TEX_HEIGHT];
    float lambda = uv_footprint > 0.0f ? log2(uv_footprint * sqrt((float)w * (float)h)) : 0.0f;
    if (!(lambda > 0.0f)) return ts_texture_bilinear(sv->tex_texels, off, w, h, uv);
    uint last = info[TS_TEX_LEVELS] - 1u;
    float lf = fmin(lambda, (float)last);
    uint l0 = (uint)lf;
    float a = lf - (float)l0;
    off = ts_mip_level(off, &w, &h, l0);
    float3 c0 = ts_texture_bilinear(sv->tex_texels, off, w, h, uv);
    if (!(a > 0.0f) || l0 >= last) return c0;
    off = ts_mip_level(off, &w, &h, 1u);
    return c0 * (1.0f - a) + ts_texture_bilinear(sv->tex_texels, off, w, h, uv) * a;
}

/* Diffuse reflectance at a surface point, each channel in [0, 1]. */
TS_INLINE float3 ts_material_albedo(const TsSceneView* sv, const TsSurface* s) {
    TS_GLOBAL const float* M = sv->materials + TS_MATERIAL_FLOATS * s->material;
    float3 kd = ts_f3_load(M + TS_MAT_ALBEDO);
#ifdef TS_HAS_TEXTURES
    int tex = as_int(M[TS_MAT_TEXTURE]);
    if (tex >= 0) kd = kd * ts_texture_lookup(sv, tex, s->uv, s->uv_footprint);
#endif
    return kd;
}

/* Radiance emitted toward the viewer: area lights emit from their front face only. */
TS_INLINE float3 ts_material_emission(const TsSceneView* sv, const TsSurface* s) {
    TS_GLOBAL const float* M = sv->materials + TS_MATERIAL_FLOATS * s->material;
    return s->front_face ? ts_f3_load(M + TS_MAT_EMISSION) : make_float3(0.0f, 0.0f, 0.0f);
}

TS_NAMESPACE_END
#endif /* TS_MATERIAL_H */
