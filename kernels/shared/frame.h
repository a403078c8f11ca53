/* What every kernel receives by value: TsFrame, the per-frame parameters (C++ and
 * OpenCL C alike), and the fixed work-group size. One struct for every method (a kernel
 * argument's layout must not depend on the method); its fields say which method reads
 * them. */
#ifndef TS_FRAME_H
#define TS_FRAME_H

/* Fixed OpenCL work-group size for every kernel: PoCL runs a work-group as a loop over
 * work-items, so one size keeps one compiled variant; 64 divides all our launch sizes
 * after rounding up. */
#define TS_WORKGROUP_SIZE 64

/* Per-frame parameters, passed by value to the kernels and to the Embree path.
 * Only 4-byte scalars, so the layout is the same in OpenCL C and C++.
 * The camera ray through pixel (x, y) with sub-pixel offset (jx, jy) in [0,1)^2 is
 *   dir = forward + (2 (x + jx) / width - 1) right + (1 - 2 (y + jy) / height) up,
 * where |right| = tan(vfov/2) · width/height and |up| = tan(vfov/2). */
typedef struct TsFrame {
    float cam_pos[3];
    float cam_forward[3];
    float cam_right[3];
    float cam_up[3];
    unsigned int width;
    unsigned int height;
    unsigned int pass;           /* sample pass index, 0-based; one pass = 1 spp */
    unsigned int shadow_samples; /* area-light samples per camera hit */
    unsigned int seed;
    unsigned int light_count;
    unsigned int max_depth;      /* pt: scattering vertices (surface or medium) per path; 1 = direct lighting */
    unsigned int max_scatter;    /* pt: medium scattering vertices per path; 0 = unlimited */
    float light_power;           /* sum over lights of selection luminance × area (for pdfs) */
    unsigned int igi_tile;       /* igi: interleave tile edge n (n² sample sets) */
    unsigned int igi_steps;      /* igi: ray-march steps per pixel along the camera ray */
    float igi_g_clamp;           /* igi: bound b on the VPL geometry term (scene units^-2) */
    float igi_rotation[3];       /* igi: per-frame Cranley–Patterson shift of the set samples */
    float igi_march_far;         /* igi: march limit for rays that escape a medium filling space:
                                    past it (twice the scene diagonal beyond the camera's
                                    distance to the origin) no geometry can light them */
    unsigned int igi_components; /* igi/ais: TS_COMPONENT_* bits of what to compute */
    float ic_error_bound;        /* ic: Ward's a of the interpolation kernel (shared/ic_lookup.h) */
    unsigned int igi_media_vpls; /* igi: 1 = the ray march gathers VPLs too (multiple
                                    scattering; light paths then scatter in the medium) */
    float pixel_cone;            /* texture filtering: spread angle of a pixel's ray cone
                                    (radians, 2·tan(vfov/2)/height); 0 = finest mip level
                                    only (pt, the reference, supersamples instead) */
    unsigned int igi_filter;     /* igi resolve: 1 = the discontinuity filter (window edge
                                    igi_tile), 0 = components unfiltered (shared/igi_resolve.h) */
    float igi_filter_cos;        /* igi resolve: the filter's normal threshold (cos) */
    float igi_filter_depth;      /* igi resolve: the filter's plane distance, relative to depth */
    unsigned int igi_equiangular; /* igi: 1 = the ray march's light samples at equiangular
                                     distances, MIS with the march's (shared/igi_march.h); 0 = at
                                     the march's own points */
    float igi_march_rotation;     /* igi: per-frame Cranley–Patterson shift of the ray march's
                                     points, apart from igi_rotation: one shared shift would tie
                                     each step's distance to its light sample's position
                                     (shared/igi_march.h, ts_igi_march_t) */
    unsigned int igi_clamp_screen; /* igi resolve: 1 = E_id gains the clamp's screen-space
                                      compensation, TsSceneView.clamp_residual
                                      (shared/igi_clamp_screen.h); 0 = none */
    unsigned int igi_ais;          /* igi resolve: 1 = an AIS frame: a pixel's components with
                                      extra sets combine them (TsSceneView.ais_items,
                                      ais_masks and the compact tables; shared/ais_resolve.h); 0 = igi */
    unsigned int ic_pair_grid;     /* ic pair kernel: 0 = its pairs from the item list; n > 0 =
                                      the grid of the IcPairRecords input's n records and every
                                      VPL, pair g = (record g mod n, VPL g / n) (shared/ic.h) */
    unsigned int ic_pair_first;    /* ic pair grid: the launch's first pair g */
    float far_lo[3];               /* pt: the far roulette's region (shared/medium.h,
                                      ts_far_importance): the box of the scene's surfaces and
                                      the camera (scene units), */
    float far_hi[3];
    float far_margin;              /* grown by this margin (its diagonal); 0: no far roulette */
} TsFrame;

#ifdef __cplusplus
/* Compile-time checks of the layouts above (shared/layout_check.h). */
#include "shared/layout_check.h"

/* TsFrame crosses to OpenCL by value (clSetKernelArg with sizeof(TsFrame)): 48 4-byte
 * scalars with no padding, so its layout is the same in both languages. */
static_assert(std::is_standard_layout_v<TsFrame> && std::is_trivially_copyable_v<TsFrame>,
              "frame.h: TsFrame must stay a plain struct");
static_assert(sizeof(TsFrame) == 48 * 4 && offsetof(TsFrame, width) == 12 * 4 &&
                  offsetof(TsFrame, light_power) == 20 * 4 && offsetof(TsFrame, igi_components) == 28 * 4 &&
                  offsetof(TsFrame, ic_error_bound) == 29 * 4 && offsetof(TsFrame, pixel_cone) == 31 * 4 &&
                  offsetof(TsFrame, igi_filter_depth) == 34 * 4 && offsetof(TsFrame, igi_equiangular) == 35 * 4 &&
                  offsetof(TsFrame, igi_march_rotation) == 36 * 4 && offsetof(TsFrame, igi_clamp_screen) == 37 * 4 &&
                  offsetof(TsFrame, igi_ais) == 38 * 4 && offsetof(TsFrame, ic_pair_first) == 40 * 4 &&
                  offsetof(TsFrame, far_lo) == 41 * 4 && offsetof(TsFrame, far_margin) == 47 * 4,
              "frame.h: TsFrame is not 48 packed 4-byte scalars; update the kernels' copy (same struct) and this check");
#endif /* __cplusplus */

#endif /* TS_FRAME_H */
