// Builds the BVH that the OpenCL kernels traverse, with Embree's BVH builder
// (rtcNewBVH / rtcBuildBVH and our own node callbacks), flattened into the node and
// triangle arrays declared in kernels/shared/layout_scene.h.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "kernels/shared/layout_scene.h"

namespace tessera {

/// Build settings: binned SAH (RTC_BUILD_QUALITY_MEDIUM; spatial splits measured no
/// gain on comparable scenes, docs/ray-tracing.md §1), branching factor 4 to match the
/// float4 node test, at most TS_BVH_LEAF_MAX (4) triangles per leaf, Embree maxDepth
/// `max_depth` (bounds the traversal stack). Costs: traversal 1, intersection 1.5 (a
/// watertight triangle test costs about one and a half float4 node tests in the kernel).
struct BvhBuildSettings {
    float traversal_cost = 1.0f;
    float intersection_cost = 1.5f;
    /// Embree's maxDepth, 1..TS_BVH_MAX_DEPTH; lower only to test the limit.
    /// Embree counts the root as level 1, so the tree gets at most max_depth - 1 inner
    /// levels (FlatBvh::depth). Embree's SAH stops splitting 8 levels above it and
    /// splits the rest by object median into leaves of at most TS_BVH_LEAF_MAX; if
    /// they do not fit, rtcBuildBVH fails ("depth limit reached") and build_bvh throws.
    int max_depth = TS_BVH_MAX_DEPTH;
};

/// The flattened BVH. `nodes` has TS_NODE_FLOATS floats per node and `tris`
/// TS_BVH_TRI_FLOATS floats per triangle, both in the layout of shared/layout_scene.h.
struct FlatBvh {
    std::vector<float> nodes;
    std::vector<float> tris;
    size_t node_count() const;
    int depth = 0;          ///< levels of inner nodes on the longest root-to-leaf path
    int max_leaf_size = 0;  ///< most triangles in one leaf
};

/// Builds over triangles given as 3 vertices each (`positions.size()` = 3 × count).
/// Triangle i keeps index i in the output (bvh_tris word 3). Zero triangles gives a
/// root with no children, which every ray misses. Throws InputError for a max_depth
/// outside 1..TS_BVH_MAX_DEPTH, RuntimeError on an Embree failure (with Embree's
/// message, e.g. "depth limit reached") and, through check_bvh_limits, for a tree
/// the OpenCL traversal cannot hold; never returns a truncated tree.
FlatBvh build_bvh(const std::vector<glm::vec3>& positions, const BvhBuildSettings& settings = {});

/// Throws RuntimeError naming the value found and the limit if `bvh.depth` exceeds
/// TS_BVH_MAX_DEPTH (the traversal stack of TS_BVH_STACK_SIZE entries holds
/// 3 · depth + 1, kernels/shared/layout_scene.h) or `bvh.max_leaf_size` exceeds
/// TS_BVH_LEAF_MAX (a leaf's count is packed in 3 bits). build_bvh calls it on every tree.
void check_bvh_limits(const FlatBvh& bvh);

}  // namespace tessera
