// The OpenCL backend's 16-ray packet kernels on CPU devices (host/backend/opencl_backend.cpp,
// kernels/bvh_packet.h, kernels/igi_packets.h, kernels/ic.cl): each lane of a packet must get the
// occlusion (ts_bvh_occluded) and the closest hit (ts_bvh_closest) its own per-ray
// traversal gives, so images with packets on
// equal those with packets off, bit for bit. Both run the same shared transport in the
// same link order per pixel; only the traversal differs.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "opencl/device.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "support/data_files.h"
#include "support/render_helpers.h"

namespace tessera {
namespace {

std::unique_ptr<Backend> opencl(const SceneBuffers& buffers, const Scene& scene, bool packets) {
    BackendOptions o{BackendKind::OpenCL, ""};
    o.cl_packets = packets;
    return make_backend(o, buffers, plan_effects(scene));
}

// Packets are the OpenCL backend's choice on CPU devices (cl_device_prefers_packets): on
// a GPU both backends would trace per ray and the comparison would be vacuous, so the
// tests skip there. On a CPU device the packet backend must trace packets, or they fail.
bool cpu_device() { return cl_device_prefers_packets(select_cl_device("")); }
bool runs_packets(const Backend& b) { return b.description().find("16-ray packets") != std::string::npos; }

// Shadow-ray-like queries, 16 per packet, in five kinds of packets (n rays in all):
//  - coherent: 16 origins on one triangle towards one point elsewhere (a link of 16
//    pixels of one interleave set), lanes sharing most nodes;
//  - incoherent: 16 unrelated surface-to-surface rays, lanes parting at the root;
//  - axis-aligned: as coherent, with the direction's x, y or z component exactly zero
//    for some lanes (the slab test's zero-direction guard);
//  - one origin to the vertices of 16 consecutive triangles (near one another in the
//    mesh), exactly: rays through box corners and shared edges; where the lanes agree on
//    the direction signs, the frustum traversal (kernels/bvh_frustum.h) runs;
//  - one origin towards one point, each lane's direction component scaled by 1 ± 0.2%:
//    a camera-like tile (frustum traversal); in every other such packet one component
//    is +0 in all lanes (the zero-direction guard's 1/d = 1e30 in the frustum's bounds).
std::vector<float> packet_rays(const Scene& s, size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const size_t tris = s.positions.size() / 3;
    auto on = [&](size_t t) {
        float a = u(rng), b = u(rng);
        if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
        return s.positions[3 * t] + a * (s.positions[3 * t + 1] - s.positions[3 * t]) +
               b * (s.positions[3 * t + 2] - s.positions[3 * t]);
    };
    auto tri = [&] { return std::min(tris - 1, size_t(u(rng) * tris)); };
    std::vector<float> rays;
    auto add = [&](glm::vec3 o, glm::vec3 d) { rays.insert(rays.end(), {o.x, o.y, o.z, 1e-4f, d.x, d.y, d.z, 0.999f}); };
    for (size_t p = 0; rays.size() < n * TS_RAY_FLOATS; ++p) {
        const size_t from = tri();
        const glm::vec3 target = on(tri());
        const glm::vec3 shared_origin = on(from);
        const size_t first_target = tri();
        for (int i = 0; i < 16; ++i) {
            if (p % 5 == 1) {
                const glm::vec3 o = on(tri());
                add(o, on(tri()) - o);
            } else if (p % 5 == 3) {
                const size_t t = std::min(tris - 1, first_target + i);
                add(shared_origin, s.positions[3 * t + i % 3] - shared_origin);
            } else if (p % 5 == 4) {
                glm::vec3 d = target - shared_origin;
                d *= glm::vec3(1.0f) + 0.004f * glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
                if (p / 5 % 2 == 1) d[p % 3] = 0.0f;
                add(shared_origin, d);
            } else {
                const glm::vec3 o = on(from);
                glm::vec3 d = target - o;
                if (p % 5 == 2 && i % 2 == 0) d[i / 2 % 3] = 0.0f;
                add(o, d);
            }
        }
    }
    rays.resize(n * TS_RAY_FLOATS);
    return rays;
}

void expect_packets_equal_single_rays(const Scene& scene) {
    SceneBuffers buffers = make_scene_buffers(scene);
    auto single = opencl(buffers, scene, false), packets = opencl(buffers, scene, true);
    if (!cpu_device()) GTEST_SKIP() << "not a CPU device: " << packets->description();
    ASSERT_TRUE(runs_packets(*packets)) << packets->description();
    ASSERT_FALSE(runs_packets(*single));
    // 60007 rays: the last packet has 7 lanes, the rest of its lanes idle.
    const std::vector<float> rays = packet_rays(scene, 60007, 11);
    std::vector<uint32_t> os, op;
    single->trace_occluded(rays, os);
    packets->trace_occluded(rays, op);
    ASSERT_EQ(os.size(), op.size());
    size_t blocked = 0, differ = 0;
    for (size_t i = 0; i < os.size(); ++i) {
        if (os[i] != op[i] && differ++ < 5) ADD_FAILURE() << "ray " << i << ": per ray " << os[i] << ", packet " << op[i];
        blocked += os[i];
    }
    EXPECT_EQ(differ, 0u);
    // Not vacuous: a fair share of the rays is blocked and a fair share is not.
    EXPECT_GT(blocked, os.size() / 10);
    EXPECT_LT(blocked, os.size() * 9 / 10);

    // Closest hits (ts_bvh_closest16) of the same rays made unbounded, so nearly all hit:
    // t bit for bit, and the same triangle, u and v, except where two triangles are hit
    // at exactly the same t (coincident faces; the two traversals visit them in another
    // order), which may happen only on a few rays; and on the rays aimed at a vertex
    // (packets p % 5 == 3), where every triangle sharing the vertex is hit at that t. Their
    // t may differ by a few ulps: each triangle's plane rounds the vertex's distance its
    // own way (the hit distance comes from the plane, kernels/bvh_traverse.h; Sibenik:
    // up to 1.6e-6 relative), and which
    // of them a traversal tests before the box test culls the rest depends on its order.
    auto at_vertex = [](size_t i) { return i / 16 % 5 == 3; };
    auto same_t = [&](size_t i, const float* a, const float* b) {
        if (std::memcmp(a + TS_HIT_T, b + TS_HIT_T, 4) == 0) return true;
        return at_vertex(i) && std::abs(a[TS_HIT_T] - b[TS_HIT_T]) <= 1e-5f * std::abs(a[TS_HIT_T]);
    };
    std::vector<float> open = rays;
    for (size_t i = 0; i < os.size(); ++i) open[TS_RAY_FLOATS * i + TS_RAY_TMAX] = INFINITY;
    std::vector<float> hs, hp;
    single->trace_closest(open, hs, Backend::RayOrder::Coherent16);
    packets->trace_closest(open, hp, Backend::RayOrder::Coherent16);  // packets only for coherent batches
    ASSERT_EQ(hs.size(), hp.size());
    size_t hit = 0, ties = 0, wrong = 0;
    for (size_t i = 0; i < os.size(); ++i) {
        const float* a = &hs[TS_HIT_FLOATS * i];
        const float* b = &hp[TS_HIT_FLOATS * i];
        const bool t_same = same_t(i, a, b);
        const bool rest_same = std::memcmp(a, b, TS_HIT_FLOATS * 4) == 0;
        uint32_t prim;
        std::memcpy(&prim, a + TS_HIT_PRIM, 4);
        hit += prim != TS_NO_HIT;
        ties += t_same && !rest_same && !at_vertex(i);
        if (!t_same && wrong++ < 5)
            ADD_FAILURE() << "ray " << i << ": per-ray t " << a[TS_HIT_T] << ", packet t " << b[TS_HIT_T];
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_LE(ties, os.size() / 10000);
    EXPECT_GT(hit, os.size() * 9 / 10);

    // The same rays as an incoherent batch: 60007 rays, more than the backend's
    // kMinSortedRays, so the packets trace them in coherent_ray_order
    // (host/backend/ray_order.h) and must put each result back at its ray's index. With
    // the order reversed first, a result left where its packet traced it would land on
    // another ray.
    std::vector<float> reversed(open.size());
    for (size_t i = 0; i < os.size(); ++i)
        std::memcpy(&reversed[TS_RAY_FLOATS * i], &open[TS_RAY_FLOATS * (os.size() - 1 - i)], TS_RAY_FLOATS * 4);
    std::vector<float> hr;
    packets->trace_closest(reversed, hr, Backend::RayOrder::Incoherent);
    ASSERT_EQ(hr.size(), hs.size());
    wrong = 0;
    for (size_t i = 0; i < os.size(); ++i) {
        const float* a = &hs[TS_HIT_FLOATS * (os.size() - 1 - i)];
        const float* b = &hr[TS_HIT_FLOATS * i];
        if (!same_t(os.size() - 1 - i, a, b) && wrong++ < 5)
            ADD_FAILURE() << "sorted batch, ray " << i << ": per-ray t " << a[TS_HIT_T] << ", packet t " << b[TS_HIT_T];
    }
    EXPECT_EQ(wrong, 0u);
}

TEST(OpenCLPackets, OcclusionEqualsPerRayOnTheCornellBox) {
    expect_packets_equal_single_rays(load_scene(default_scene_path(), make_data_path(std::nullopt)));
}

TEST(OpenCLPackets, OcclusionEqualsPerRayOnSibenik) {
    DataPath data = make_data_path(std::nullopt);
    if (!test::on_data_path(data, "sibenik/sibenik.obj")) GTEST_SKIP() << "sibenik/sibenik.obj is not on the data path";
    expect_packets_equal_single_rays(load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "sibenik.json", data));
}

// Sorting an incoherent batch changes the order packets trace it in, never a result: the
// occlusion and closest hits of the 60007 rays are the same, bit for bit, with the sort
// off (BackendOptions::cl_sort_incoherent). Both trace packets; only their lanes differ.
TEST(OpenCLPackets, SortedIncoherentBatchesGiveTheUnsortedResults) {
    const Scene scene = load_scene(default_scene_path(), make_data_path(std::nullopt));
    SceneBuffers buffers = make_scene_buffers(scene);
    auto sorted = opencl(buffers, scene, true);
    BackendOptions o{BackendKind::OpenCL, ""};
    o.cl_sort_incoherent = false;
    auto unsorted = make_backend(o, buffers, plan_effects(scene));
    if (!cpu_device()) GTEST_SKIP() << "not a CPU device: " << sorted->description();
    ASSERT_TRUE(runs_packets(*sorted)) << sorted->description();
    std::vector<float> rays = packet_rays(scene, 60007, 5);
    std::vector<uint32_t> oa, ob;
    sorted->trace_occluded(rays, oa);
    unsorted->trace_occluded(rays, ob);
    EXPECT_EQ(oa, ob);
    EXPECT_GT(std::count(oa.begin(), oa.end(), 1u), 6000);
    for (size_t i = 0; i < oa.size(); ++i) rays[TS_RAY_FLOATS * i + TS_RAY_TMAX] = INFINITY;
    std::vector<float> ha, hb;
    sorted->trace_closest(rays, ha);
    unsorted->trace_closest(rays, hb);
    ASSERT_EQ(ha.size(), hb.size());
    size_t differ = 0;
    for (size_t i = 0; i < oa.size(); ++i)
        differ += std::memcmp(&ha[TS_HIT_FLOATS * i + TS_HIT_T], &hb[TS_HIT_FLOATS * i + TS_HIT_T], 4) != 0;
    EXPECT_EQ(differ, 0u);
    // Not vacuous: both batches went through the sort on one backend and neither on the
    // other.
    EXPECT_EQ(sorted->sorted_batch_count(), 2u);
    EXPECT_EQ(unsorted->sorted_batch_count(), 0u);
}

TEST(OpenCLPackets, DescriptionNamesTheTraversal) {
    const Scene scene = load_scene(default_scene_path(), make_data_path(std::nullopt));
    SceneBuffers buffers = make_scene_buffers(scene);
    auto packets = opencl(buffers, scene, true);
    if (!cpu_device()) GTEST_SKIP() << "not a CPU device: " << packets->description();
    ASSERT_TRUE(runs_packets(*packets)) << packets->description();
    EXPECT_NE(opencl(buffers, scene, false)->description().find("per-ray BVH4"), std::string::npos);
}

// Images: igi, ais and ais-max (surface pass and AIS items go through packets) and ic
// (the record-VPL pair rays, ic_pair_packets), at a size that is not a multiple of the
// tile nor of the 4×4 packet block, so packets with idle lanes and sets of unequal size
// are covered. Fog adds the media part of AIS items; a light crossing a wall the packets
// whose lanes draw their own light points (igi_gather16.h, ts_igi_lanes_light_links_near).
class OpenCLPacketImages : public ::testing::TestWithParam<Method> {};

void expect_packet_image_equals_per_ray(const std::filesystem::path& scene_file, Method method) {
    const Scene scene = load_scene(scene_file, make_data_path(std::nullopt));
    SceneBuffers buffers = make_scene_buffers(scene);
    const RenderSettings rs = test::packet_test_settings(method);
    auto single = opencl(buffers, scene, false), packets = opencl(buffers, scene, true);
    if (!cpu_device()) GTEST_SKIP() << "not a CPU device: " << packets->description();
    ASSERT_TRUE(runs_packets(*packets)) << packets->description();
    test::expect_images_identical(render_frame(*single, scene, buffers, rs), render_frame(*packets, scene, buffers, rs));
}

TEST_P(OpenCLPacketImages, EqualPerRayImagesBitForBit) {
    expect_packet_image_equals_per_ray(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box-fog.json", GetParam());
}

TEST_P(OpenCLPacketImages, EqualPerRayImagesBitForBitNearALight) {
    expect_packet_image_equals_per_ray(std::filesystem::path(TESSERA_TEST_DATA) / "near_light.json", GetParam());
}

// Fog over the floor only: links clear of its box gather without the medium
// (ts_igi_vpl_medium, ts_igi_light_medium), the others with it.
TEST_P(OpenCLPacketImages, EqualPerRayImagesBitForBitWithFogOverTheFloor) {
    expect_packet_image_equals_per_ray(std::filesystem::path(TESSERA_TEST_DATA) / "fog_floor.json", GetParam());
}

INSTANTIATE_TEST_SUITE_P(Methods, OpenCLPacketImages,
                         ::testing::Values(Method::Igi, Method::Ais, Method::AisMax, Method::Ic),
                         [](const auto& info) { return test::method_param_name(info.param); });

}  // namespace
}  // namespace tessera
