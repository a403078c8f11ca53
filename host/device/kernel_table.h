// The kernel table: every kernel a backend can launch, declared once. Both backends
// dispatch from it: the OpenCL backend builds `program` and runs kernel `name` from it;
// the Embree backend calls the shared C++ function of the same entry over TBB.
//
// Adding a kernel: one TS_KERNEL_TABLE entry below, the shared function in
// kernels/shared/ (a per-pixel function `fn(sv, tracer, frame, x, y, out)` or a per-item
// function `fn(sv, tracer, frame, i, out)`), its one-line OpenCL wrapper in `program`
// (TS_PIXEL_KERNEL / TS_ITEM_KERNEL, kernels/tracer.h), and its output size in layout.h.
#pragma once
#include <cstdint>

#include "kernels/shared/layout.h"

/* X(id, OpenCL kernel name, program file under kernels/, output floats per work item,
 *   item words (0: one work item per pixel of the frame, written at the pixel's place;
 *   n > 0: one per item of a list with n uints per item, written in list order),
 *   shared C++ function the Embree backend calls). */
#define TS_KERNEL_TABLE(X)                                                                               \
    X(Direct, "direct_pass", "direct.cl", TS_PASS_FLOATS, 0, ts_direct_pixel)                            \
    X(PathTrace, "pt_pass", "pt.cl", TS_PASS_FLOATS, 0, ts_pt_pixel)                                     \
    X(IgiSurface, "igi_surface_pass", "igi.cl", TS_IGI_SURF_FLOATS, 0, ts_igi_surface_pixel)             \
    X(IgiMedia, "igi_media_pass", "igi.cl", TS_IGI_MEDIA_FLOATS, 0, ts_igi_media_pixel)                  \
    X(IgiResolve, "igi_resolve_pass", "igi.cl", TS_PASS_FLOATS, 0, ts_igi_resolve_pixel)                 \
    X(AisItem, "ais_extra_pass", "igi.cl", TS_AIS_ITEM_FLOATS, TS_AIS_ITEM_WORDS, ts_ais_extra_item)     \
    X(EdgeSample, "edge_sample_pass", "igi.cl", TS_EDGE_SAMPLE_FLOATS, TS_EDGE_ITEM_WORDS, ts_edge_sample_item) \
    X(IcInterpolate, "ic_interpolate", "ic.cl", TS_IC_INTERP_FLOATS, 0, ts_ic_interpolate_kernel_pixel)     \
    X(IcPair, "ic_pair_pass", "ic.cl", TS_IC_PAIR_FLOATS, TS_IC_PAIR_WORDS, ts_ic_pair_item)             \
    X(IcGather, "ic_gather_pass", "ic.cl", TS_IC_GATHER_FLOATS, TS_IC_GATHER_WORDS, ts_ic_gather_item)

namespace tessera {

enum class KernelId {
#define TS_KERNEL_ID(id, name, program, floats, words, fn) id,
    TS_KERNEL_TABLE(TS_KERNEL_ID)
#undef TS_KERNEL_ID
};

#define TS_KERNEL_COUNT(id, name, program, floats, words, fn) +1
constexpr int kKernelCount = 0 TS_KERNEL_TABLE(TS_KERNEL_COUNT);
#undef TS_KERNEL_COUNT

/// One table entry, as the host reads it.
struct KernelInfo {
    const char* name;     ///< OpenCL kernel name
    const char* program;  ///< program file under kernels/
    int out_floats;       ///< output floats per work item (layout.h)
    int item_words;       ///< 0: launched over pixels; n: over items of n uints each
};

const KernelInfo& kernel_info(KernelId k);

/// The named inputs a backend keeps between launches (set with Backend::set_input):
/// per-frame buffers the kernels read through TsSceneView (kernels/shared/geometry.h).
/// Adding one: an entry here and in input_info, a TsSceneView field, a TS_KERNEL_ARGS
/// argument (kernels/tracer.h) and its line in the Embree backend's scene_view().
enum class KernelInput {
    Vpls,         ///< floats: TS_VPL_FLOATS per VPL, sorted by sample set (layout.h)
    VplSetStart,  ///< uints: sample set k's VPLs are [start[k], start[k+1])
    IcGbuffer,    ///< floats: TS_IC_GBUF_FLOATS per pixel (ic_gbuffer_from_surface, gi/instant_cache.h)
    IcNodes,      ///< floats: TS_IC_NODE_FLOATS per octree node, root first
    IcRefs,       ///< uints: the octree nodes' record lists, concatenated
    IcRecords,    ///< floats: TS_IC_RECORD_FLOATS per record
    /// floats: TS_IC_GBUF_FLOATS per cache record, the G-buffer entry it was made at
    /// (KernelId::IcPair and IcGather; their VPLs are the Vpls input, one set)
    IcRecordSurfaces,
    /// uints: record–VPL visibility rows, bit masks of TS_IC_VISIBLE_WORDS(VPLs of the
    /// Vpls input) uints each (layout.h; KernelId::IcGather)
    IcVisibility,
    /// floats: TS_IGI_SURF_FLOATS per pixel, KernelId::IgiSurface's output kept where the
    /// kernels run (Backend::launch_into; KernelId::IgiResolve reads it)
    IgiSurface,
    /// floats: TS_IGI_MEDIA_FLOATS per pixel, KernelId::IgiMedia's output kept likewise;
    /// read only when the frame's components include TS_COMPONENT_PM
    IgiMedia,
};
constexpr int kKernelInputCount = 10;

struct KernelInputInfo {
    const char* name;  ///< for error messages ("VPL set table")
    bool is_uint;      ///< uint data (else float)
};

const KernelInputInfo& input_info(KernelInput in);

}  // namespace tessera
