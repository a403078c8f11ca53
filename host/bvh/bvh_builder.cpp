#include "bvh/bvh_builder.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>

#include <embree3/rtcore.h>

#include "bvh/embree_device.h"
#include "kernels/shared/layout_scene.h"
#include "util/error.h"

namespace tessera {
namespace {

// Build-time nodes live in Embree's thread-local allocator until flattening.
struct BuildNode {
    bool leaf;
    unsigned count;
};
struct InnerNode : BuildNode {
    RTCBounds bounds[4];
    const BuildNode* child[4];
};
struct LeafNode : BuildNode {
    unsigned prim[TS_BVH_LEAF_MAX];
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int count, void*) {
    auto* n = static_cast<InnerNode*>(rtcThreadLocalAlloc(alloc, sizeof(InnerNode), 16));
    n->leaf = false;
    n->count = count;
    return n;
}

void set_children(void* node, void** children, unsigned int count, void*) {
    auto* n = static_cast<InnerNode*>(node);
    for (unsigned i = 0; i < count; ++i) n->child[i] = static_cast<const BuildNode*>(children[i]);
}

void set_bounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
    auto* n = static_cast<InnerNode*>(node);
    for (unsigned i = 0; i < count; ++i) n->bounds[i] = *bounds[i];
}

// Embree never passes more than maxLeafSize primitives (its bvh_builder_sah.h splits
// larger sets by object median, or fails at maxDepth); should it, the true count is kept
// so check_bvh_limits refuses the tree, and only the first TS_BVH_LEAF_MAX are stored.
void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count,
                  void*) {
    auto* l = static_cast<LeafNode*>(rtcThreadLocalAlloc(alloc, sizeof(LeafNode), 16));
    l->leaf = true;
    l->count = static_cast<unsigned>(count);
    for (size_t i = 0; i < std::min<size_t>(count, TS_BVH_LEAF_MAX); ++i) l->prim[i] = prims[i].primID;
    return l;
}

class Flattener {
public:
    Flattener(const std::vector<glm::vec3>& positions, FlatBvh& out) : pos_(positions), out_(out) {}

    // Returns the child reference for `n` (see layout_scene.h).
    int flatten(const BuildNode* n, int depth) {
        out_.depth = std::max(out_.depth, depth);
        if (n->leaf) return emit_leaf(static_cast<const LeafNode*>(n));
        const auto* in = static_cast<const InnerNode*>(n);
        size_t index = new_node();
        for (unsigned i = 0; i < in->count; ++i) {
            int ref = flatten(in->child[i], depth + 1);
            set_slot(index, i, in->bounds[i], ref);
        }
        return static_cast<int>(index);
    }

    // A root that is itself a leaf gets an inner node above it: kernels start at node 0.
    void wrap_leaf_root(const BuildNode* leaf, const RTCBounds& bounds) {
        size_t index = new_node();
        set_slot(index, 0, bounds, flatten(leaf, 1));
    }

    size_t new_node() {
        size_t index = out_.nodes.size() / TS_NODE_FLOATS;
        out_.nodes.resize(out_.nodes.size() + TS_NODE_FLOATS, 0.0f);
        float* f = &out_.nodes[index * TS_NODE_FLOATS];
        const float inf = std::numeric_limits<float>::infinity();
        for (int axis = 0; axis < 3; ++axis)
            for (int c = 0; c < 4; ++c) {
                f[TS_NODE_MIN(axis) + c] = inf;   // empty box: min = +inf ...
                f[TS_NODE_MAX(axis) + c] = -inf;  // ... max = -inf
            }
        int empty = -1;
        for (int c = 0; c < 4; ++c) std::memcpy(&f[TS_NODE_REFS + c], &empty, 4);
        return index;
    }

private:
    void set_slot(size_t index, unsigned slot, const RTCBounds& b, int ref) {
        float* f = &out_.nodes[index * TS_NODE_FLOATS];
        const float lo[3] = {b.lower_x, b.lower_y, b.lower_z};
        const float hi[3] = {b.upper_x, b.upper_y, b.upper_z};
        for (int axis = 0; axis < 3; ++axis) {
            f[TS_NODE_MIN(axis) + slot] = lo[axis];
            f[TS_NODE_MAX(axis) + slot] = hi[axis];
        }
        std::memcpy(&f[TS_NODE_REFS + slot], &ref, 4);
    }

    int emit_leaf(const LeafNode* l) {
        out_.max_leaf_size = std::max(out_.max_leaf_size, static_cast<int>(l->count));
        const unsigned count = std::min<unsigned>(l->count, TS_BVH_LEAF_MAX);  // see create_leaf
        uint32_t first = static_cast<uint32_t>(out_.tris.size() / TS_BVH_TRI_FLOATS);
        for (unsigned i = 0; i < count; ++i) {
            uint32_t prim = l->prim[i];
            float t[TS_BVH_TRI_FLOATS] = {};
            for (int k = 0; k < 3; ++k) {
                const glm::vec3& p = pos_[3 * prim + k];
                t[TS_BVH_TRI_VERTEX(k) + 0] = p.x;
                t[TS_BVH_TRI_VERTEX(k) + 1] = p.y;
                t[TS_BVH_TRI_VERTEX(k) + 2] = p.z;
            }
            std::memcpy(&t[TS_BVH_TRI_PRIM], &prim, 4);
            out_.tris.insert(out_.tris.end(), t, t + TS_BVH_TRI_FLOATS);
        }
        return static_cast<int>(~((first << 3) | count));
    }

    const std::vector<glm::vec3>& pos_;
    FlatBvh& out_;
};

}  // namespace

size_t FlatBvh::node_count() const { return nodes.size() / TS_NODE_FLOATS; }

void check_bvh_limits(const FlatBvh& bvh) {
    if (bvh.depth > TS_BVH_MAX_DEPTH)
        throw RuntimeError("BVH depth " + std::to_string(bvh.depth) + " exceeds the limit TS_BVH_MAX_DEPTH = " +
                           std::to_string(TS_BVH_MAX_DEPTH) + " (the OpenCL traversal stack of TS_BVH_STACK_SIZE = " +
                           std::to_string(TS_BVH_STACK_SIZE) + " entries needs 3 * depth + 1)");
    if (bvh.max_leaf_size > TS_BVH_LEAF_MAX)
        throw RuntimeError("BVH leaf of " + std::to_string(bvh.max_leaf_size) +
                           " triangles exceeds the limit TS_BVH_LEAF_MAX = " + std::to_string(TS_BVH_LEAF_MAX) +
                           " (leaf references pack the count in 3 bits)");
}

FlatBvh build_bvh(const std::vector<glm::vec3>& positions, const BvhBuildSettings& settings) {
    if (settings.max_depth < 1 || settings.max_depth > TS_BVH_MAX_DEPTH)
        throw InputError("BVH build setting max_depth = " + std::to_string(settings.max_depth) +
                         ": expected 1.." + std::to_string(TS_BVH_MAX_DEPTH) + " (TS_BVH_MAX_DEPTH)");
    const size_t count = positions.size() / 3;
    // A leaf reference packs the first triangle's index above 3 count bits in 31 bits.
    if (count >= (size_t(1) << 28))
        throw InputError("scene has " + std::to_string(count) + " triangles: the BVH layout holds at most " +
                         std::to_string((size_t(1) << 28) - 1) + " (28-bit triangle indices, kernels/shared/layout_scene.h)");
    FlatBvh out;
    Flattener flat(positions, out);
    if (count == 0) {
        flat.new_node();
        return out;
    }
    std::vector<RTCBuildPrimitive> prims(count);
    RTCBounds scene{};
    for (size_t i = 0; i < count; ++i) {
        glm::vec3 lo = glm::min(glm::min(positions[3 * i], positions[3 * i + 1]), positions[3 * i + 2]);
        glm::vec3 hi = glm::max(glm::max(positions[3 * i], positions[3 * i + 1]), positions[3 * i + 2]);
        prims[i] = RTCBuildPrimitive{lo.x, lo.y, lo.z, 0u, hi.x, hi.y, hi.z, static_cast<unsigned>(i)};
        if (i == 0) scene = RTCBounds{lo.x, lo.y, lo.z, 0, hi.x, hi.y, hi.z, 0};
        scene.lower_x = std::min(scene.lower_x, lo.x);
        scene.lower_y = std::min(scene.lower_y, lo.y);
        scene.lower_z = std::min(scene.lower_z, lo.z);
        scene.upper_x = std::max(scene.upper_x, hi.x);
        scene.upper_y = std::max(scene.upper_y, hi.y);
        scene.upper_z = std::max(scene.upper_z, hi.z);
    }
    RTCBVH bvh = rtcNewBVH(embree_device());
    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.byteSize = sizeof(args);
    args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    args.maxBranchingFactor = 4;
    args.maxDepth = static_cast<unsigned>(settings.max_depth);
    args.minLeafSize = 1;
    args.maxLeafSize = TS_BVH_LEAF_MAX;
    args.traversalCost = settings.traversal_cost;
    args.intersectionCost = settings.intersection_cost;
    args.bvh = bvh;
    args.primitives = prims.data();
    args.primitiveCount = prims.size();
    args.primitiveArrayCapacity = prims.size();
    args.createNode = create_node;
    args.setNodeChildren = set_children;
    args.setNodeBounds = set_bounds;
    args.createLeaf = create_leaf;
    auto* root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
    if (!root) {
        rtcReleaseBVH(bvh);
        const std::string what = "rtcBuildBVH over " + std::to_string(count) + " triangles with maxDepth " +
                                 std::to_string(settings.max_depth);
        check_embree(what.c_str());
        throw RuntimeError("Embree: " + what + " returned no root");
    }
    out.nodes.reserve(count / 2 * TS_NODE_FLOATS);
    out.tris.reserve(count * TS_BVH_TRI_FLOATS);
    if (root->leaf)
        flat.wrap_leaf_root(root, scene);
    else
        flat.flatten(root, 0);
    rtcReleaseBVH(bvh);  // frees every build node; the flat arrays are all we keep
    check_bvh_limits(out);
    return out;
}

}  // namespace tessera
