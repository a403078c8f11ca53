/* Instant Global Illumination and Adaptive Interleaved Sampling on OpenCL devices
 * (shared/igi.h, igi_media.h, ais_item.h): the surface kernel (G-buffer, direct light of the pixel's sample set,
 * indirect light from the set's VPLs), the AIS extra kernel (further sets for scheduled
 * pixels), the resolve kernel (filter and composite without a read-back) with the clamp
 * compensation's two kernels before it, and the media kernel (single-scattering ray march), dispatched only when the
 * scene has a medium and built with -DTS_HAS_MEDIUM only then. On CPU devices the host
 * launches the 16-ray packet variants of the surface and AIS kernels instead
 * (igi_packets.h: same images, faster traversal). */
#include "shared/layout_igi.h"
#include "shared/layout_pass.h"
#include "tracer.h"
#include "shared/ais_item.h"
#include "shared/igi_resolve.h"
#include "shared/pass_radiance.h"
#include "shared/edge_samples.h"
#include "shared/light_path_trace.h"
#include "shared/vpl_importance_items.h"
#include "igi_packets.h"

TS_PIXEL_KERNEL(igi_surface_pass, ts_igi_surface_pixel, TS_IGI_SURF_FLOATS)

/* AIS extra evaluations: item i (pixel, set | components << 8; items come grouped by
 * set) evaluates that set for those components at that pixel. */
TS_ITEM_KERNEL(ais_extra_pass, ts_ais_extra_item, TS_AIS_ITEM_FLOATS)

/* AIS edge samples: item i (pixel, sample j) traces the pixel's j-th extra camera sample
 * to its first diffuse surface (shared/edge_samples.h). */
TS_ITEM_KERNEL(edge_sample_pass, ts_edge_sample_item, TS_EDGE_SAMPLE_FLOATS)

/* A device frame's compact tables (shared/ais_compact.h): per (set, tile) the pixels that
 * evaluate the set beyond their own, per tile row its edge samples; then the extra sets and
 * edge samples over exactly their items, each finding its pixel from the tables. Launched
 * without an item list (Backend::launch_count_into). */
TS_ITEM_KERNEL(ais_tile_sets_pass, ts_ais_tile_sets_item, TS_AIS_TILE_SET_FLOATS)
TS_ITEM_KERNEL(ais_compact_pass, ts_ais_compact_item, TS_AIS_ITEM_FLOATS)
TS_ITEM_KERNEL(edge_segment_counts_pass, ts_edge_segment_counts_item, TS_EDGE_SEGMENT_FLOATS)
TS_ITEM_KERNEL(edge_compact_pass, ts_edge_compact_sample_item, TS_EDGE_SAMPLE_FLOATS)

/* Light paths: item i (Halton point, set, weight) traces one path through all its
 * segments and writes its VPLs, and with the media variant its ray lights
 * (shared/light_path_trace.h). */
TS_ITEM_KERNEL(light_paths_pass, ts_light_path_item, TS_LP_FLOATS)
TS_ITEM_KERNEL(light_paths_media_pass, ts_light_path_media_item, TS_LP_MEDIA_FLOATS)
TS_ITEM_KERNEL(light_path_gather_pass, ts_light_path_gather_item, TS_LP_GATHER_FLOATS)

/* The frame's filter and composite where the kernels ran (GPU variant; shared/igi_resolve.h):
 * reads the surface and media kernels' outputs in place, writes the pass image. */
TS_PIXEL_KERNEL(igi_resolve_pass, ts_igi_resolve_pixel, TS_PASS_FLOATS)

/* The VPLs' importance for the view: the candidates' irradiance at each view point, then
 * each VPL's share of it (shared/vpl_importance_items.h). Launched without a list. */
TS_ITEM_KERNEL(vpl_importance_points_pass, ts_vpl_importance_point_item, TS_VI_E_FLOATS)
TS_ITEM_KERNEL(vpl_importance_vpls_pass, ts_vpl_importance_vpl_item, 1)

/* Each pixel's AIS set masks from the base pass (shared/ais_guidance.h). */
TS_PIXEL_KERNEL(ais_schedule_pass, ts_ais_schedule_pixel, TS_AIS_MASK_FLOATS)
/* The resolved pass's luminance summed per row, for the edge contrast's ε (shared/ais_resolve.h). */
TS_ITEM_KERNEL(edge_row_sums_pass, ts_edge_row_sum_item, TS_EDGE_ROW_FLOATS)
/* Each pixel's edge-sample count from the resolved pass (shared/ais_resolve.h). */
TS_PIXEL_KERNEL(edge_schedule_pass, ts_edge_schedule_pixel, 1)

/* An AIS frame's edge samples merged into its resolved pass image (shared/igi_resolve.h). */
TS_PIXEL_KERNEL(ais_edge_merge_pass, ts_ais_edge_merge_pixel, TS_PASS_FLOATS)

/* Radiance-only passes (shared/pass_radiance.h): the two above keeping the radiance alone,
 * and the radiance of a resolved pass kept on the device. */
TS_PIXEL_KERNEL(igi_resolve_radiance_pass, ts_igi_resolve_radiance_pixel, TS_PASS_RADIANCE_FLOATS)
TS_PIXEL_KERNEL(ais_edge_merge_radiance_pass, ts_ais_edge_merge_radiance_pixel, TS_PASS_RADIANCE_FLOATS)
TS_PIXEL_KERNEL(pass_radiance_pass, ts_pass_radiance_pixel, TS_PASS_RADIANCE_FLOATS)

/* The clamp's screen-space compensation before the resolve (shared/igi_clamp_screen.h):
 * the pixels' records, then the gather at the even grid's pixels. */
TS_PIXEL_KERNEL(igi_clamp_records_pass, ts_igi_clamp_records_pixel, TS_CLAMP_SCREEN_FLOATS)
TS_PIXEL_KERNEL(igi_clamp_gather_pass, ts_igi_clamp_gather_pixel, TS_CLAMP_RESIDUAL_FLOATS)

#ifdef TS_HAS_MEDIUM
TS_PIXEL_KERNEL(igi_media_pass, ts_igi_media_pixel, TS_IGI_MEDIA_FLOATS)
#endif
