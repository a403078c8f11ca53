/* The buffers every kernel of the kernel table (host/device/kernel_table.h) reads after
 * the frame and the BVH, declared once. From these two lists, in this order, come the
 * kernels' argument list (TS_KERNEL_ARGS, kernels/tracer.h), the shading code's view of
 * the buffers (TsSceneView, shared/geometry.h), the host's KernelInput enum, its count and
 * input_info (host/device/kernel_table.h), the C++ scene view (host/device/scene_view.h,
 * the Embree backend's scene_view) and the OpenCL backend's uploads and bindings.
 *
 * Adding a buffer: one line in a list; its data in SceneBuffers (a scene buffer, a
 * member of the same name) or set with Backend::set_input (a named input); and its use in
 * the shared code through TsSceneView::field.
 */
#ifndef TS_KERNEL_INPUTS_H
#define TS_KERNEL_INPUTS_H

/* X(field, element type, what): the scene's shading buffers, the SceneBuffers members of
 * the same names (host/device/scene_buffers.h: the layouts are there), uploaded with the
 * scene. */
#define TS_SCENE_BUFFERS(X)                       \
    X(tri_pos, float, "triangle positions")       \
    X(tri_nrm, float, "triangle normals")         \
    X(tri_uv, float, "triangle uvs")              \
    X(tri_mat, uint, "triangle materials")        \
    X(materials, float, "materials")              \
    X(tex_info, uint, "texture table")            \
    X(tex_texels, uint, "textures")               \
    X(lights, float, "lights")                    \
    X(light_cdf, float, "light CDF")              \
    X(medium, float, "medium")

/* X(KernelInput name, field, element type, what): the named inputs a backend keeps between
 * launches (Backend::set_input), null or a placeholder where a launch does not use them:
 *   Vpls             TS_VPL_FLOATS per VPL, sorted by sample set (layout_igi.h)
 *   VplSetStart      sample set k's VPLs are [start[k], start[k+1])
 *   Vrls             TS_VRL_FLOATS per ray light, sorted by sample set (layout_igi.h);
 *                    read only when TsFrame.igi_media_vpls is TS_MEDIA_VPLS_RAYS
 *   VrlSetStart      sample set k's ray lights are [start[k], start[k+1]), likewise
 *   IcGbuffer        TS_IC_GBUF_FLOATS per pixel (ic_gbuffer_from_surface, gi/instant_cache.h)
 *   IcNodes          TS_IC_NODE_FLOATS per octree node, root first
 *   IcRefs           the octree nodes' record lists, concatenated
 *   IcRecords        TS_IC_RECORD_FLOATS per record
 *   IcRecordSurfaces TS_IC_GBUF_FLOATS per cache record, the G-buffer entry it was made at
 *                    (KernelId::IcPair and IcGather; their VPLs are the Vpls input, one set)
 *   IcVisibility     record–VPL visibility rows, bit masks of TS_IC_VISIBLE_WORDS(VPLs of
 *                    the Vpls input) uints each (layout_ic.h; KernelId::IcGather)
 *   IcPairRecords    the records (IcRecordSurfaces indices) of a pair grid, in the order
 *                    its pairs take them (KernelId::IcPair with TsFrame.ic_pair_grid > 0)
 *   IgiSurface       TS_IGI_SURF_FLOATS per pixel, KernelId::IgiSurface's output kept where
 *                    the kernels run (Backend::launch_into; KernelId::IgiResolve, AisSchedule
 *                    and EdgeSchedule read it)
 *   IgiMedia         TS_IGI_MEDIA_FLOATS per pixel, KernelId::IgiMedia's output kept
 *                    likewise; read only when the frame's components include TS_COMPONENT_PM
 *                    (KernelId::IgiResolve, AisSchedule)
 *   ClampRecords     TS_CLAMP_SCREEN_FLOATS per pixel, KernelId::IgiClampRecords's output
 *                    kept likewise (layout_igi.h; KernelId::IgiClampGather reads it)
 *   ClampResidual    TS_CLAMP_RESIDUAL_FLOATS per pixel, KernelId::IgiClampGather's output
 *                    kept likewise; read only when TsFrame.igi_clamp_screen is 1
 *   LightPathTable   the light-path kernel's parameters and Halton digits
 *                    (layout_light_path.h; KernelId::LightPaths)
 *   LightPathOut     KernelId::LightPaths' or LightPathsMedia's output kept where the
 *                    kernels run (KernelId::LightPathGather copies from it)
 *   AisItems         TS_AIS_ITEM_FLOATS per item of the frame's AIS list, a device frame's
 *                    KernelId::AisCompactItem output kept where the kernels run
 *                    (Backend::launch_count_into)
 *   AisMasks         TS_AIS_MASK_FLOATS per pixel, KernelId::AisSchedule's output kept
 *                    (KernelId::AisTileSets, AisCompactItem and IgiResolve read it)
 *   AisTileSets      TS_AIS_TILE_SET_FLOATS per (set, tile), KernelId::AisTileSets's output
 *                    kept (layout_igi.h; shared/ais_compact.h)
 *   AisItemOffsets   their counts' exclusive prefix sums, n²·T + 1 (layout_igi.h); with
 *                    AisMasks and AisTileSets read when TsFrame.igi_ais is 1
 *   IgiPass          TS_PASS_FLOATS per pixel, KernelId::IgiResolve's output kept
 *                    (KernelId::EdgeRowSums, EdgeSchedule and AisEdgeMerge read it)
 *   EdgeSamples      TS_EDGE_SAMPLE_FLOATS per edge sample of the frame,
 *                    KernelId::EdgeCompactSample's output kept
 *   EdgeCounts       one float a pixel, KernelId::EdgeSchedule's output kept (its edge
 *                    samples)
 *   EdgeSegmentOffsets  the tiles' edge samples' exclusive prefix sums, T + 1 (layout_igi.h;
 *                    KernelId::EdgeCompactSample and AisEdgeMerge read them with EdgeCounts)
 *   AisScheduleTable the AIS schedule's parameters and set orders (layout_igi.h,
 *                    TS_AIS_TABLE_*; KernelId::AisSchedule and EdgeSchedule read it)
 *   VplImportance    the view points and weights of the VPLs' importance (layout_igi.h,
 *                    TS_VI_*; KernelId::VplImportancePoints and VplImportanceVpls, whose
 *                    VPLs are the Vpls input, one set) */
#define TS_KERNEL_INPUTS(X)                                                  \
    X(Vpls, vpls, float, "VPL")                                              \
    X(VplSetStart, vpl_set_start, uint, "VPL set table")                     \
    X(Vrls, vrls, float, "ray light")                                        \
    X(VrlSetStart, vrl_set_start, uint, "ray light set table")               \
    X(IcGbuffer, ic_gbuffer, float, "ic G-buffer")                           \
    X(IcNodes, ic_nodes, float, "ic octree")                                 \
    X(IcRefs, ic_refs, uint, "ic record lists")                              \
    X(IcRecords, ic_records, float, "ic records")                            \
    X(IcRecordSurfaces, ic_record_surfaces, float, "ic record surfaces")     \
    X(IcVisibility, ic_visibility, uint, "ic visibility")                    \
    X(IcPairRecords, ic_pair_records, uint, "ic pair records")               \
    X(IgiSurface, igi_surface, float, "igi surface")                         \
    X(IgiMedia, igi_media, float, "igi media")                               \
    X(ClampRecords, clamp_records, float, "clamp records")                   \
    X(ClampResidual, clamp_residual, float, "clamp residual")               \
    X(LightPathTable, light_path_table, uint, "light path table")            \
    X(LightPathOut, light_path_out, float, "light path output")              \
    X(AisItems, ais_items, float, "AIS items")                               \
    X(AisMasks, ais_masks, float, "AIS set masks")                           \
    X(AisTileSets, ais_tile_sets, float, "AIS tile sets")                    \
    X(AisItemOffsets, ais_item_offsets, uint, "AIS item offsets")            \
    X(IgiPass, igi_pass, float, "igi pass")                                  \
    X(EdgeSamples, edge_samples, float, "edge samples")                      \
    X(EdgeCounts, edge_counts, float, "edge counts")                         \
    X(EdgeSegmentOffsets, edge_segment_offsets, uint, "edge tile offsets")         \
    X(AisScheduleTable, ais_schedule_table, uint, "AIS schedule table")      \
    X(VplImportance, vpl_importance, float, "VPL importance")

/* TsSceneView's pointer to one buffer (shared/geometry.h). */
#define TS_VIEW_SCENE_FIELD(field, type, what) TS_GLOBAL const type* field;
#define TS_VIEW_INPUT_FIELD(name, field, type, what) TS_GLOBAL const type* field;

#endif /* TS_KERNEL_INPUTS_H */
