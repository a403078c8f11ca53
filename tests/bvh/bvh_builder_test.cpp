// Structural checks of the flattened BVH: every triangle in exactly one leaf, every
// child box encloses everything below it, depth within the kernel's stack bound.
#include "bvh/bvh_builder.h"

#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "kernels/shared/layout.h"

namespace tessera {
namespace {

struct Box {
    glm::vec3 lo{INFINITY}, hi{-INFINITY};
};

// Walks the subtree of child reference `ref`, checking containment in `box`.
void check_subtree(const FlatBvh& bvh, int ref, const Box& box, std::vector<int>& seen) {
    if (ref < 0) {
        uint32_t v = ~static_cast<uint32_t>(ref);
        for (uint32_t i = v >> 3; i < (v >> 3) + (v & 7u); ++i) {
            const float* t = &bvh.tris[i * TS_BVH_TRI_FLOATS];
            uint32_t prim;
            std::memcpy(&prim, &t[TS_BVH_TRI_PRIM], 4);
            ++seen.at(prim);
            for (int k = 0; k < 3; ++k)
                for (int a = 0; a < 3; ++a) {
                    EXPECT_GE(t[TS_BVH_TRI_VERTEX(k) + a], box.lo[a]);
                    EXPECT_LE(t[TS_BVH_TRI_VERTEX(k) + a], box.hi[a]);
                }
        }
        return;
    }
    const float* n = &bvh.nodes[size_t(ref) * TS_NODE_FLOATS];
    for (int c = 0; c < 4; ++c) {
        int child;
        std::memcpy(&child, &n[TS_NODE_REFS + c], 4);
        Box b;
        for (int a = 0; a < 3; ++a) {
            b.lo[a] = n[TS_NODE_MIN(a) + c];
            b.hi[a] = n[TS_NODE_MAX(a) + c];
        }
        if (child == -1) {  // unused slot: an empty box
            EXPECT_GT(b.lo.x, b.hi.x);
            continue;
        }
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(b.lo[a], box.lo[a]);
            EXPECT_LE(b.hi[a], box.hi[a]);
        }
        check_subtree(bvh, child, b, seen);
    }
}

TEST(BvhBuilder, EveryTriangleOnceAndBoxesNest) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-10.0f, 10.0f), s(-0.5f, 0.5f);
    std::vector<glm::vec3> pos;
    for (int i = 0; i < 5000; ++i) {
        glm::vec3 c(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k) pos.push_back(c + glm::vec3(s(rng), s(rng), s(rng)));
    }
    FlatBvh bvh = build_bvh(pos);
    ASSERT_GT(bvh.node_count(), 1u);
    EXPECT_EQ(bvh.tris.size(), 5000u * TS_BVH_TRI_FLOATS);
    EXPECT_LE(bvh.depth, TS_BVH_MAX_DEPTH);
    std::vector<int> seen(5000, 0);
    Box all;
    all.lo = glm::vec3(-INFINITY);
    all.hi = glm::vec3(INFINITY);
    check_subtree(bvh, 0, all, seen);
    for (int c : seen) ASSERT_EQ(c, 1);
}

TEST(BvhBuilder, SingleTriangleRootIsWrapped) {
    std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    FlatBvh bvh = build_bvh(pos);
    ASSERT_EQ(bvh.node_count(), 1u);
    int ref;
    std::memcpy(&ref, &bvh.nodes[TS_NODE_REFS], 4);
    EXPECT_LT(ref, -1);  // a leaf with one triangle
    EXPECT_EQ((~static_cast<uint32_t>(ref)) & 7u, 1u);
}

TEST(BvhBuilder, EmptySceneHasEmptyRoot) {
    FlatBvh bvh = build_bvh({});
    ASSERT_EQ(bvh.node_count(), 1u);
    EXPECT_TRUE(bvh.tris.empty());
}

}  // namespace
}  // namespace tessera
