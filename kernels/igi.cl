/* Instant Global Illumination and Adaptive Interleaved Sampling on OpenCL devices
 * (shared/igi.h): the surface kernel (G-buffer, direct light of the pixel's sample set,
 * indirect light from the set's VPLs), the AIS extra kernel (further sets for scheduled
 * pixels), and the media kernel (single-scattering ray march), dispatched only when the
 * scene has a medium and built with -DTS_HAS_MEDIUM only then. */
#include "shared/layout.h"
#include "tracer.h"
#include "shared/igi.h"

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void igi_surface_pass(TS_PIXEL_KERNEL_ARGS) {
    TS_PIXEL_KERNEL_BODY(ts_igi_surface_pixel, TS_IGI_SURF_FLOATS)
}

/* AIS extra evaluations: work-item i evaluates sample set item_codes[i] & 0xff for the
 * components item_codes[i] >> 8 at pixel item_pixels[i]; items come grouped by set. */
__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void ais_extra_pass(TS_PIXEL_KERNEL_ARGS, __global const uint* item_pixels, __global const uint* item_codes,
                    uint item_count) {
    uint i = get_global_id(0);
    if (i >= item_count) return;
    TS_KERNEL_VIEWS
    uint p = item_pixels[i], code = item_codes[i];
    float v[TS_AIS_ITEM_FLOATS];
    ts_ais_item(&sv, &tracer, &frame, p % frame.width, p / frame.width, code & 0xffu, code >> 8, v);
    for (int k = 0; k < TS_AIS_ITEM_FLOATS; ++k) out[(size_t)i * TS_AIS_ITEM_FLOATS + k] = v[k];
}

#ifdef TS_HAS_MEDIUM
__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void igi_media_pass(TS_PIXEL_KERNEL_ARGS) {
    TS_PIXEL_KERNEL_BODY(ts_igi_media_pixel, TS_IGI_MEDIA_FLOATS)
}
#endif
