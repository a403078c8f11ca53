// Builds the BVH that the OpenCL kernels traverse, with Embree's BVH builder
// (rtcNewBVH / rtcBuildBVH and our own node callbacks), flattened into the node and
// triangle arrays declared in kernels/shared/layout.h.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

/// Build settings: binned SAH (RTC_BUILD_QUALITY_MEDIUM; spatial splits measured no
/// gain on comparable scenes, docs/ray-tracing.md §1), branching factor 4 to match the
/// float4 node test, at most 4 triangles per leaf, maxDepth TS_BVH_MAX_DEPTH (bounds
/// the traversal stack). Costs: traversal 1, intersection 1.5 (a watertight triangle
/// test costs about one and a half float4 node tests in the kernel).
struct BvhBuildSettings {
    float traversal_cost = 1.0f;
    float intersection_cost = 1.5f;
};

/// The flattened BVH. `nodes` has TS_NODE_FLOATS floats per node and `tris`
/// TS_BVH_TRI_FLOATS floats per triangle, both in the layout of shared/layout.h.
struct FlatBvh {
    std::vector<float> nodes;
    std::vector<float> tris;
    size_t node_count() const;
    int depth = 0;  ///< levels of inner nodes on the longest root-to-leaf path
};

/// Builds over triangles given as 3 vertices each (`positions.size()` = 3 × count).
/// Triangle i keeps index i in the output (bvh_tris word 3). Zero triangles gives a
/// root with no children, which every ray misses. Throws RuntimeError on an Embree
/// failure.
FlatBvh build_bvh(const std::vector<glm::vec3>& positions, const BvhBuildSettings& settings = {});

}  // namespace tessera
