/* Instant Global Illumination on OpenCL devices (shared/igi.h): the surface kernel
 * (G-buffer, direct light of the pixel's sample set, indirect light from the set's
 * VPLs) and the media kernel (single-scattering ray march), dispatched only when the
 * scene has a medium and built with -DTS_HAS_MEDIUM only then. */
#include "shared/layout.h"
#include "tracer.h"
#include "shared/igi.h"

__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void igi_surface_pass(TS_PIXEL_KERNEL_ARGS) {
    TS_PIXEL_KERNEL_BODY(ts_igi_surface_pixel, TS_IGI_SURF_FLOATS)
}

#ifdef TS_HAS_MEDIUM
__kernel __attribute__((reqd_work_group_size(TS_WORKGROUP_SIZE, 1, 1)))
void igi_media_pass(TS_PIXEL_KERNEL_ARGS) {
    TS_PIXEL_KERNEL_BODY(ts_igi_media_pixel, TS_IGI_MEDIA_FLOATS)
}
#endif
