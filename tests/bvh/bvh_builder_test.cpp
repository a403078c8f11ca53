// Structural checks of the flattened BVH: every triangle in exactly one leaf, every
// child box encloses everything below it, depth within the kernel's stack bound (and
// refused beyond it), and the OpenCL traversal of a tree at the depth limit.
#include "bvh/bvh_builder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "kernels/shared/layout_rays.h"
#include "kernels/shared/layout_scene.h"
#include "support/test_scenes.h"
#include "util/error.h"

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
    EXPECT_EQ(bvh.depth, 1);  // the wrapping inner node above the leaf
    EXPECT_EQ(bvh.max_leaf_size, 1);
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

// 4^levels small triangles at the leaves of a 4-ary spatial hierarchy: each cluster is
// four sub-clusters at the corners of a square, 10x smaller than the square's side, so
// the SAH separates them level by level and the triangles (1/100 of the finest spacing)
// are worth a node each.
void add_clusters(std::vector<glm::vec3>& pos, glm::vec3 centre, float side, int levels) {
    if (levels == 0) {
        const float e = 0.01f * side;
        pos.insert(pos.end(), {centre, centre + glm::vec3(e, 0, 0), centre + glm::vec3(0, e, e)});
        return;
    }
    for (int c = 0; c < 4; ++c) {
        const glm::vec3 corner(c & 1 ? 0.5f * side : -0.5f * side, c & 2 ? 0.5f * side : -0.5f * side, 0.0f);
        add_clusters(pos, centre + corner, 0.1f * side, levels - 1);
    }
}

TEST(BvhBuilder, DepthOfNestedClustersIsTheirLevelCount) {
    for (int levels = 1; levels <= 3; ++levels) {
        std::vector<glm::vec3> pos;
        add_clusters(pos, glm::vec3(0.0f), 100.0f, levels);
        FlatBvh bvh = build_bvh(pos);
        EXPECT_EQ(bvh.depth, levels) << levels << " levels of clusters";
        EXPECT_EQ(bvh.max_leaf_size, 1) << levels << " levels of clusters";
        EXPECT_EQ(bvh.node_count(), size_t((std::pow(4, levels) - 1) / 3)) << "a full 4-ary tree";
    }
}

TEST(BvhBuilder, CheckBvhLimitsRefusesTreesTheTraversalCannotHold) {
    FlatBvh bvh;
    bvh.depth = TS_BVH_MAX_DEPTH;
    bvh.max_leaf_size = TS_BVH_LEAF_MAX;
    EXPECT_NO_THROW(check_bvh_limits(bvh));
    bvh.depth = TS_BVH_MAX_DEPTH + 1;
    try {
        check_bvh_limits(bvh);
        ADD_FAILURE() << "a tree of depth " << bvh.depth << " was accepted";
    } catch (const RuntimeError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("depth " + std::to_string(TS_BVH_MAX_DEPTH + 1)), std::string::npos) << m;
        EXPECT_NE(m.find("TS_BVH_MAX_DEPTH = " + std::to_string(TS_BVH_MAX_DEPTH)), std::string::npos) << m;
    }
    bvh.depth = 1;
    bvh.max_leaf_size = TS_BVH_LEAF_MAX + 1;
    try {
        check_bvh_limits(bvh);
        ADD_FAILURE() << "a leaf of " << bvh.max_leaf_size << " triangles was accepted";
    } catch (const RuntimeError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("leaf of " + std::to_string(TS_BVH_LEAF_MAX + 1) + " triangles"), std::string::npos) << m;
        EXPECT_NE(m.find("TS_BVH_LEAF_MAX = " + std::to_string(TS_BVH_LEAF_MAX)), std::string::npos) << m;
    }
}

// Embree (kernels/builders/bvh_builder_sah.h, createLargeLeaf) stops SAH splitting 8
// levels above maxDepth and splits what is left by object median into leaves of at most
// maxLeafSize, or fails with "depth limit reached" when they do not fit below maxDepth.
// With maxDepth 2 (root = level 1) that is one inner node over at most 4 leaves of 4.
TEST(BvhBuilder, AtMaxDepthEmbreeSplitsLeavesOrFails) {
    std::vector<glm::vec3> pos;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 4 * TS_BVH_LEAF_MAX; ++i) {
        glm::vec3 c(u(rng), u(rng), u(rng));
        pos.insert(pos.end(), {c, c + glm::vec3(0.01f, 0, 0), c + glm::vec3(0, 0.01f, 0)});
    }
    BvhBuildSettings two;
    two.max_depth = 2;
    FlatBvh bvh = build_bvh(pos, two);
    EXPECT_EQ(bvh.depth, 1);
    EXPECT_EQ(bvh.max_leaf_size, TS_BVH_LEAF_MAX);
    std::vector<int> seen(pos.size() / 3, 0);
    Box all;
    all.lo = glm::vec3(-INFINITY);
    all.hi = glm::vec3(INFINITY);
    check_subtree(bvh, 0, all, seen);
    for (int c : seen) ASSERT_EQ(c, 1);

    pos.insert(pos.end(), {glm::vec3(2, 2, 2), glm::vec3(2.1f, 2, 2), glm::vec3(2, 2.1f, 2)});  // one too many
    try {
        build_bvh(pos, two);
        ADD_FAILURE() << pos.size() / 3 << " triangles built with maxDepth 2";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("depth limit reached"), std::string::npos) << e.what();
    }
    BvhBuildSettings deep;
    deep.max_depth = TS_BVH_MAX_DEPTH + 1;
    EXPECT_THROW(build_bvh(pos, deep), InputError);
}

// Triangle i of `n` lies in the band a_{i+1} <= x + y <= a_i (a_i = top r^i) of the
// plane z = -c a_i: vertices (a_i, 0), (0, a_i) and ((a_i + a_{i+1}) / 4)(1, 1). The
// set of triangles i..n-1 is the whole set scaled by r^i, so the SAH cuts off the
// largest few at each level and the depth grows with n (about 1.4 levels per factor 10
// at r = 0.8) until Embree's limit. No two overlap in x and y, so a ray along z hits at
// most one.
struct BandScene {
    int n;
    double r, top, c;
};

std::vector<glm::vec3> band_triangles(const BandScene& b) {
    std::vector<glm::vec3> pos;
    for (int i = 0; i < b.n; ++i) {
        const double a = b.top * std::pow(b.r, i);
        const float af = static_cast<float>(a), m = static_cast<float>(a * (1.0 + b.r) / 4.0),
                    z = static_cast<float>(-b.c * a);
        pos.insert(pos.end(), {{af, 0.0f, z}, {0.0f, af, z}, {m, m, z}});
    }
    return pos;
}

// Depth (inner nodes above) of each triangle's leaf.
void leaf_depths(const FlatBvh& bvh, int ref, int depth, std::vector<int>& out) {
    if (ref < 0) {
        const uint32_t v = ~static_cast<uint32_t>(ref);
        for (uint32_t i = v >> 3; i < (v >> 3) + (v & 7u); ++i) {
            uint32_t prim;
            std::memcpy(&prim, &bvh.tris[i * TS_BVH_TRI_FLOATS + TS_BVH_TRI_PRIM], 4);
            out.at(prim) = depth;
        }
        return;
    }
    for (int c = 0; c < 4; ++c) {
        int child;
        std::memcpy(&child, &bvh.nodes[size_t(ref) * TS_NODE_FLOATS + TS_NODE_REFS + c], 4);
        leaf_depths(bvh, child, depth + 1, out);
    }
}

struct BruteHit {
    uint32_t prim = TS_NO_HIT;
    double t = INFINITY;
    double edge_margin = INFINITY;  ///< smallest |barycentric| over the triangles the ray's line meets
};

// Closest hit over all triangles in double precision (Möller–Trumbore), and how near
// (in barycentrics) the ray's line passes to any triangle's edge, so that a ray whose
// answer could flip with rounding can be left out of the comparison.
BruteHit brute_force_closest(const std::vector<glm::vec3>& pos, glm::dvec3 o, glm::dvec3 d) {
    BruteHit best;
    for (size_t i = 0; i < pos.size() / 3; ++i) {
        const glm::dvec3 p0(pos[3 * i]), e1 = glm::dvec3(pos[3 * i + 1]) - p0, e2 = glm::dvec3(pos[3 * i + 2]) - p0;
        const glm::dvec3 pv = glm::cross(d, e2);
        const double det = glm::dot(e1, pv);
        if (det == 0.0) continue;
        const glm::dvec3 tv = o - p0, qv = glm::cross(tv, e1);
        const double u = glm::dot(tv, pv) / det, v = glm::dot(d, qv) / det, t = glm::dot(e2, qv) / det;
        if (t <= 0.0) continue;
        best.edge_margin = std::min({best.edge_margin, std::abs(u), std::abs(v), std::abs(1.0 - u - v)});
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t < best.t) {
            best.t = t;
            best.prim = static_cast<uint32_t>(i);
        }
    }
    return best;
}

// Builds the band scene, traces rays along z on OpenCL and compares with the brute
// force: per triangle k, four rays through points inside triangle k and four through
// points of the square [0, a_k]^2 (which may fall on a smaller triangle or a gap).
// A ray starts `origin_above` · a_k above the plane z = 0 and points down, or
// (origin_above < 0) alternately 1 unit below pointing up and 1 above pointing down. Axis-parallel rays keep the kernel's shear exact. Returns the tree's depth.
int expect_band_scene_traces_like_brute_force(const BandScene& band, double origin_above) {
    const std::vector<glm::vec3> pos = band_triangles(band);
    const FlatBvh bvh = build_bvh(pos);
    std::vector<int> depth_of(band.n, -1);
    leaf_depths(bvh, 0, 0, depth_of);

    Scene scene;
    scene.name = "band-triangles";
    const uint32_t m = test::add_material(scene, glm::vec3(0.5f));
    scene.positions = pos;
    scene.normals.assign(pos.size(), glm::vec3(0, 0, 1));
    scene.uvs.assign(pos.size(), glm::vec2(0.0f));
    scene.material.assign(pos.size() / 3, m);
    SceneBuffers buffers = make_scene_buffers(scene);
    auto cl = make_backend({BackendKind::OpenCL, ""}, buffers, plan_effects(scene));

    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<float> rays;
    std::vector<BruteHit> expected;
    for (int k = 0; k < band.n; ++k)
        for (int j = 0; j < 8; ++j) {
            const glm::dvec3 p0(pos[3 * k]), p1(pos[3 * k + 1]), p2(pos[3 * k + 2]);
            glm::dvec3 p;
            if (j < 4) {
                double b1 = 0.02 + 0.96 * u(rng), b2 = 0.02 + 0.96 * u(rng);
                if (b1 + b2 > 0.98) b1 = 0.98 - b1 + 0.02, b2 = 0.98 - b2 + 0.02;
                p = p0 + b1 * (p1 - p0) + b2 * (p2 - p0);
            } else {
                p = p0.x * glm::dvec3(u(rng), u(rng), 0.0);
            }
            const float dz = origin_above >= 0.0 || j % 2 ? -1.0f : 1.0f;
            const float oz = origin_above >= 0.0 ? static_cast<float>(origin_above * p0.x) : -dz;
            const glm::vec3 o(static_cast<float>(p.x), static_cast<float>(p.y), oz);
            const BruteHit b = brute_force_closest(pos, glm::dvec3(o), glm::dvec3(0.0, 0.0, dz));
            if (b.edge_margin < 1e-4) continue;  // within rounding of some triangle's edge
            rays.insert(rays.end(), {o.x, o.y, o.z, 0.0f, 0.0f, 0.0f, dz, INFINITY});
            expected.push_back(b);
        }
    std::vector<float> hits;
    cl->trace_closest(rays, hits);
    size_t hit_count = 0, deepest = 0, wrong = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        uint32_t prim;
        std::memcpy(&prim, &hits[TS_HIT_FLOATS * i + TS_HIT_PRIM], 4);
        if (prim != expected[i].prim && wrong++ == 0)
            ADD_FAILURE() << "ray " << i << " hit " << prim << ", brute force " << expected[i].prim;
        if (prim != expected[i].prim || prim == TS_NO_HIT) continue;
        ++hit_count;
        deepest += depth_of[prim] == bvh.depth;
        EXPECT_NEAR(hits[TS_HIT_FLOATS * i + TS_HIT_T], expected[i].t, 1e-5 * expected[i].t) << "ray " << i;
    }
    std::printf("  %d band triangles: BVH depth %d, %zu nodes; %zu rays compared: %zu hits, %zu in leaves at "
                "depth %d\n",
                band.n, bvh.depth, bvh.node_count(), expected.size(), hit_count, deepest, bvh.depth);
    EXPECT_EQ(wrong, 0u) << "rays whose closest hit differs from the brute force";
    EXPECT_LE(bvh.depth, TS_BVH_MAX_DEPTH);
    EXPECT_GT(expected.size(), size_t(band.n) * 8 * 9 / 10) << "few rays should pass near an edge";
    EXPECT_GT(hit_count, expected.size() / 2);
    EXPECT_GT(deepest, 10u) << "rays should reach the deepest leaves";
    return bvh.depth;
}

// Scales 1e16..1e-16 in one plane: the deepest band scene whose edge functions (products
// of two coordinates) stay normal floats. Embree stops SAH splitting 8 levels above
// maxDepth (root = level 1), so a depth of TS_BVH_MAX_DEPTH - 8 or more means its limit
// shaped this tree.
TEST(BvhBuilder, TreeAtEmbreesDepthLimitTracesLikeBruteForceOnOpenCL) {
    const int depth = expect_band_scene_traces_like_brute_force({330, 0.8, 1e16, 0.0}, -1.0);
    EXPECT_GE(depth, TS_BVH_MAX_DEPTH - 8) << "the scene should reach Embree's depth limit";
}

// Triangle i at z = -a_i and each ray starting a_k above z = 0: every larger triangle's
// leaf box is hit but lies farther than the subtree of the smaller ones, so the traversal
// visits that subtree first and keeps up to three leaves per level on its stack, about
// 3 · depth of them (a stack of 100 entries fails this test). Scales 1e12..1e-12 keep the
// distance computation (products of three coordinates) within normal floats.
TEST(BvhBuilder, TreeThatFillsTheTraversalStackTracesLikeBruteForceOnOpenCL) {
    const int depth = expect_band_scene_traces_like_brute_force({248, 0.8, 1e12, 1.0}, 1.0);
    EXPECT_GE(depth, 34) << "3 · depth + 1 stack entries should exceed 100";
}

}  // namespace
}  // namespace tessera
