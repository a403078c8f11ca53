// The kernel table: every kernel a backend can launch, declared once. Both backends
// dispatch from it: the OpenCL backend builds `program` and runs kernel `name` from it;
// the Embree backend calls the shared C++ function of the same entry over TBB.
//
// Adding a kernel: one TS_KERNEL_TABLE entry below, the shared function in
// kernels/shared/ (a per-pixel function `fn(sv, tracer, frame, x, y, out)` or a per-item
// function `fn(sv, tracer, frame, i, out)`), its one-line OpenCL wrapper in `program`
// (TS_PIXEL_KERNEL / TS_ITEM_KERNEL, kernels/tracer.h), and its output size in the kernels/shared/layout_*.h of its concern.
#pragma once
#include <cstdint>

#include "kernels/shared/kernel_inputs.h"
#include "kernels/shared/layout_ic.h"
#include "kernels/shared/layout_igi.h"
#include "kernels/shared/layout_light_path.h"
#include "kernels/shared/layout_pass.h"

/* X(id, OpenCL kernel name, program file under kernels/, output floats per work item,
 *   item words (0: one work item per pixel of the frame, written at the pixel's place;
 *   n > 0: one per item of a list with n uints per item, written in list order),
 *   shared C++ function the Embree backend calls,
 *   OpenCL packet kernel in the same program (nullptr: none): on CPU devices it replaces
 *   the per-ray kernel with 16 rays per work item, over 4x4 pixel blocks for a pixel
 *   kernel (ts_packet_block_count) and over groups of 16 items for an item kernel,
 *   Embree packet function (no_packets: none), host/backend/embree_packets.h and its
 *   neighbours; it may decline a launch (the per-ray function then runs)). */
#define TS_KERNEL_TABLE(X)                                                                                        \
    X(Direct, "direct_pass", "direct.cl", TS_PASS_FLOATS, 0, ts_direct_pixel, nullptr, no_packets)                \
    X(PathTrace, "pt_pass", "pt.cl", TS_PASS_FLOATS, 0, ts_pt_pixel, nullptr, no_packets)                         \
    X(IgiSurface, "igi_surface_pass", "igi.cl", TS_IGI_SURF_FLOATS, 0, ts_igi_surface_pixel, "igi_surface_packets", \
      igi_surface_packets)                                                                                        \
    X(IgiMedia, "igi_media_pass", "igi.cl", TS_IGI_MEDIA_FLOATS, 0, ts_igi_media_pixel, "igi_media_packets",       \
      igi_media_packets)                                                                                          \
    X(IgiResolve, "igi_resolve_pass", "igi.cl", TS_PASS_FLOATS, 0, ts_igi_resolve_pixel, nullptr, no_packets)     \
    X(IgiResolveRadiance, "igi_resolve_radiance_pass", "igi.cl", TS_PASS_RADIANCE_FLOATS, 0,                      \
      ts_igi_resolve_radiance_pixel, nullptr, no_packets)                                                         \
    X(AisSchedule, "ais_schedule_pass", "igi.cl", TS_AIS_MASK_FLOATS, 0, ts_ais_schedule_pixel, nullptr,         \
      no_packets)                                                                                                 \
    X(EdgeRowSums, "edge_row_sums_pass", "igi.cl", TS_EDGE_ROW_FLOATS, 1, ts_edge_row_sum_item, nullptr,          \
      no_packets)                                                                                                 \
    X(EdgeSchedule, "edge_schedule_pass", "igi.cl", 1, 0, ts_edge_schedule_pixel, nullptr, no_packets)            \
    X(AisEdgeMerge, "ais_edge_merge_pass", "igi.cl", TS_PASS_FLOATS, 0, ts_ais_edge_merge_pixel, nullptr,         \
      no_packets)                                                                                                 \
    X(AisEdgeMergeRadiance, "ais_edge_merge_radiance_pass", "igi.cl", TS_PASS_RADIANCE_FLOATS, 0,                \
      ts_ais_edge_merge_radiance_pixel, nullptr, no_packets)                                                      \
    X(PassRadiance, "pass_radiance_pass", "igi.cl", TS_PASS_RADIANCE_FLOATS, 0, ts_pass_radiance_pixel, nullptr,  \
      no_packets)                                                                                                 \
    X(IgiClampRecords, "igi_clamp_records_pass", "igi.cl", TS_CLAMP_SCREEN_FLOATS, 0, ts_igi_clamp_records_pixel,  \
      nullptr, no_packets)                                                                                        \
    X(IgiClampGather, "igi_clamp_gather_pass", "igi.cl", TS_CLAMP_RESIDUAL_FLOATS, 0, ts_igi_clamp_gather_pixel,   \
      nullptr, no_packets)                                                                                        \
    X(AisItem, "ais_extra_pass", "igi.cl", TS_AIS_ITEM_FLOATS, TS_AIS_ITEM_WORDS, ts_ais_extra_item,               \
      "ais_extra_packets", ais_item_packets)                                                                      \
    X(AisTileSets, "ais_tile_sets_pass", "igi.cl", TS_AIS_TILE_SET_FLOATS, 1, ts_ais_tile_sets_item, nullptr,     \
      no_packets)                                                                                                 \
    X(AisCompactItem, "ais_compact_pass", "igi.cl", TS_AIS_ITEM_FLOATS, 1, ts_ais_compact_item, nullptr,           \
      no_packets)                                                                                                 \
    X(EdgeSegmentCounts, "edge_segment_counts_pass", "igi.cl", TS_EDGE_SEGMENT_FLOATS, 1, ts_edge_segment_counts_item,         \
      nullptr, no_packets)                                                                                        \
    X(EdgeCompactSample, "edge_compact_pass", "igi.cl", TS_EDGE_SAMPLE_FLOATS, 1, ts_edge_compact_sample_item,     \
      nullptr, no_packets)                                                                                        \
    X(EdgeSample, "edge_sample_pass", "igi.cl", TS_EDGE_SAMPLE_FLOATS, TS_EDGE_ITEM_WORDS, ts_edge_sample_item,    \
      nullptr, no_packets)                                                                                        \
    X(VplImportancePoints, "vpl_importance_points_pass", "igi.cl", TS_VI_E_FLOATS, 1, ts_vpl_importance_point_item, \
      nullptr, no_packets)                                                                                        \
    X(VplImportanceVpls, "vpl_importance_vpls_pass", "igi.cl", 1, 1, ts_vpl_importance_vpl_item, nullptr,          \
      no_packets)                                                                                                 \
    X(LightPaths, "light_paths_pass", "igi.cl", TS_LP_FLOATS, TS_LP_ITEM_WORDS, ts_light_path_item, nullptr,       \
      no_packets)                                                                                                 \
    X(LightPathsMedia, "light_paths_media_pass", "igi.cl", TS_LP_MEDIA_FLOATS, TS_LP_ITEM_WORDS,                   \
      ts_light_path_media_item, nullptr, no_packets)                                                              \
    X(LightPathGather, "light_path_gather_pass", "igi.cl", TS_LP_GATHER_FLOATS, 1, ts_light_path_gather_item,      \
      nullptr, no_packets)                                                                                        \
    X(IcInterpolate, "ic_interpolate", "ic.cl", TS_IC_INTERP_FLOATS, 0, ts_ic_interpolate_kernel_pixel, nullptr,   \
      no_packets)                                                                                                 \
    X(IcPair, "ic_pair_pass", "ic.cl", TS_IC_PAIR_FLOATS, TS_IC_PAIR_WORDS, ts_ic_pair_item, "ic_pair_packets",    \
      ic_pair_packets)                                                                                            \
    X(IcGather, "ic_gather_pass", "ic.cl", TS_IC_GATHER_FLOATS, TS_IC_GATHER_WORDS, ts_ic_gather_item, nullptr,    \
      ic_gather_packets)

namespace tessera {

enum class KernelId {
#define TS_KERNEL_ID(id, name, program, floats, words, fn, cl_packets, packets) id,
    TS_KERNEL_TABLE(TS_KERNEL_ID)
#undef TS_KERNEL_ID
};

#define TS_KERNEL_COUNT(id, name, program, floats, words, fn, cl_packets, packets) +1
constexpr int kKernelCount = 0 TS_KERNEL_TABLE(TS_KERNEL_COUNT);
#undef TS_KERNEL_COUNT

/// One table entry, as the host reads it.
struct KernelInfo {
    const char* name;     ///< OpenCL kernel name
    const char* program;  ///< program file under kernels/
    int out_floats;       ///< output floats per work item (kernels/shared/layout_*.h)
    int item_words;       ///< 0: launched over pixels; n: over items of n uints each
    const char* packet_name;  ///< OpenCL packet kernel (nullptr: none), see TS_KERNEL_TABLE
};

const KernelInfo& kernel_info(KernelId k);

/// The named inputs a backend keeps between launches (set with Backend::set_input):
/// per-frame buffers the kernels read through TsSceneView, one per line of
/// TS_KERNEL_INPUTS (kernels/shared/kernel_inputs.h, which gives each one's layout), in
/// that order (the kernels' argument order).
enum class KernelInput {
#define TS_INPUT_ENUM(name, field, type, what) name,
    TS_KERNEL_INPUTS(TS_INPUT_ENUM)
#undef TS_INPUT_ENUM
};
#define TS_INPUT_COUNT(name, field, type, what) +1
constexpr int kKernelInputCount = 0 TS_KERNEL_INPUTS(TS_INPUT_COUNT);
#undef TS_INPUT_COUNT
#define TS_SCENE_COUNT(field, type, what) +1
/// The scene's shading buffers each kernel receives (TS_SCENE_BUFFERS).
constexpr int kSceneBufferCount = 0 TS_SCENE_BUFFERS(TS_SCENE_COUNT);
#undef TS_SCENE_COUNT

/// The C++ element type of a list's `type` token: TS_ELEMENT_TYPE(uint) is uint32_t.
#define TS_ELEMENT_TYPE(type) TS_ELEMENT_TYPE_##type
#define TS_ELEMENT_TYPE_float float
#define TS_ELEMENT_TYPE_uint uint32_t

struct KernelInputInfo {
    const char* name;  ///< for error messages ("VPL set table")
    bool is_uint;      ///< uint data (else float)
};

const KernelInputInfo& input_info(KernelInput in);

}  // namespace tessera
