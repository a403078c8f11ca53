// The light-path kernel (kernels/shared/light_path_trace.h, trace_light_paths_in_kernel):
// one work item per path through all its segments leaves the VPLs and ray lights of the
// host's batched tracer (trace_light_paths), which runs the same per-segment code. On
// Embree both are the same C++ code over the same hits: bit for bit (the kernel runs under
// Embree's flush-to-zero, the host's loop does not: a subnormal intermediate would differ,
// none occurs in these scenes). On OpenCL (PoCL) the
// kernel is OpenCL C, whose libm (sin, cos, log) may round otherwise in the last place:
// equal counts and records within float rounding. Paths past the kernel's slots are traced
// again on the host. The Halton table reproduces the digits of the project's figures.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "gi/halton.h"
#include "gi/light_paths.h"
#include "kernels/shared/halton.h"
#include "kernels/shared/layout_light_path.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace tessera {
namespace {

// Paths 0..count−1 of 3 sets, path j weighted 1 + (j mod 3)/2 (the weights of paths kept
// for the view reach the records).
std::vector<LightPath> fresh_paths(uint32_t count) {
    std::vector<LightPath> paths(count);
    for (uint32_t j = 0; j < count; ++j) {
        paths[j].index = 1000u + j;
        paths[j].set = j % 3;
        paths[j].weight = 1.0f + 0.5f * float(j % 3);
    }
    return paths;
}

LightPathSettings media_settings(bool medium) {
    LightPathSettings ls;
    ls.medium_scattering = medium;
    ls.ray_lights = medium;
    ls.inv_paths = 1.0f / 64.0f;
    ls.segments = false;
    return ls;
}

// Records equal field by field: bits for the set and path fields, within `rel` of the
// value's magnitude (and 1e-6 absolutely) for the floats.
void expect_records_near(const std::vector<float>& a, const std::vector<float>& b, float rel, const char* what,
                         size_t path) {
    ASSERT_EQ(a.size(), b.size()) << what << " of path " << path;
    for (size_t i = 0; i < a.size(); ++i) {
        const int field = int(i % TS_VPL_FLOATS);
        if (field == TS_VPL_PATH || field == TS_VPL_SET) {
            EXPECT_EQ(std::memcmp(&a[i], &b[i], 4), 0) << what << " of path " << path << ", field " << field;
            continue;
        }
        EXPECT_NEAR(a[i], b[i], rel * std::fabs(b[i]) + 1e-6f) << what << " of path " << path << ", field " << field;
    }
}

struct Traced {
    std::vector<LightPath> paths;
    uint64_t rays = 0;
};

Traced trace(Backend& backend, const SceneBuffers& buffers, const LightPathSettings& ls, bool in_kernel,
             uint32_t count) {
    Traced t{fresh_paths(count), 0};
    t.rays = in_kernel ? trace_light_paths_in_kernel(backend, buffers, ls, t.paths)
                       : trace_light_paths(backend, buffers, ls, t.paths);
    return t;
}

// What `want`'s paths left: VPLs, ray lights, and paths with more VPLs than the kernel's slots.
struct Left {
    size_t vpls = 0, vrls = 0, overflows = 0;
};

// `got`'s paths equal `want`'s bit for bit (VPLs, ray lights, lights and rays); returns
// what want's paths left.
Left expect_same_paths(const Traced& got, const Traced& want) {
    Left left;
    EXPECT_EQ(got.paths.size(), want.paths.size());
    for (size_t j = 0; j < want.paths.size() && j < got.paths.size(); ++j) {
        EXPECT_EQ(got.paths[j].vpls, want.paths[j].vpls) << "path " << j;
        EXPECT_EQ(got.paths[j].vrls, want.paths[j].vrls) << "path " << j;
        EXPECT_EQ(got.paths[j].light, want.paths[j].light) << "path " << j;
        left.vpls += want.paths[j].vpls.size() / TS_VPL_FLOATS;
        left.vrls += want.paths[j].vrls.size() / TS_VRL_FLOATS;
        left.overflows += want.paths[j].vpls.size() > size_t(TS_LP_MAX_VPLS) * TS_VPL_FLOATS;
    }
    EXPECT_EQ(got.rays, want.rays);
    return left;
}

// The kernel's paths against the host's on Embree (bits) and on OpenCL (rounding).
void expect_kernel_matches_host(const Scene& scene, bool medium) {
    const SceneBuffers buffers = make_scene_buffers(scene);
    const EffectPlan plan = plan_effects(scene);
    auto embree = make_backend({BackendKind::Embree, ""}, buffers, plan);
    ASSERT_FALSE(embree->traces_light_paths_in_kernel()) << "the CPU backends keep the host's VPLs";
    const LightPathSettings ls = media_settings(medium);
    const Traced host = trace(*embree, buffers, ls, false, 256);
    const Traced kernel = trace(*embree, buffers, ls, true, 256);
    const Left left = expect_same_paths(kernel, host);
    // Ray-light slots only where paths leave ray lights.
    EXPECT_EQ(embree->dispatch_count(KernelId::LightPathsMedia), medium ? 1u : 0u);
    EXPECT_EQ(embree->dispatch_count(KernelId::LightPaths), medium ? 0u : 1u);
    EXPECT_GT(left.vpls, 256u) << "paths bounce";
    if (medium) {
        EXPECT_GT(left.vrls, 256u) << "paths cross the fog";
    }

    BackendOptions o{BackendKind::OpenCL, ""};
    o.cl_gpu_variant = true;  // the variant a GPU runs, which traces its light paths in the kernel
    auto cl = make_backend(o, buffers, plan);
    ASSERT_TRUE(cl->traces_light_paths_in_kernel());
    const Traced device = trace(*cl, buffers, ls, false, 256);
    EXPECT_EQ(device.rays, host.rays);
    for (size_t j = 0; j < host.paths.size(); ++j) {
        expect_records_near(device.paths[j].vpls, host.paths[j].vpls, 1e-4f, "VPLs", j);
        expect_records_near(device.paths[j].vrls, host.paths[j].vrls, 1e-4f, "ray lights", j);
    }
}

TEST(LightPathKernel, LeavesTheHostsVplsInTheCornellBox) { expect_kernel_matches_host(test::cornell_box(), false); }

TEST(LightPathKernel, LeavesTheHostsVplsAndRayLightsInFog) {
    expect_kernel_matches_host(test::shipped_scene("cornell-box-fog.json"), true);
}

TEST(LightPathKernel, MirrorsAndGlassScatterAsOnTheHost) {
    // A grey box with a mirror over half its floor and a glass slab's two faces: specular
    // bounces leave no VPL but use the vertex's Halton numbers (the Fresnel choice) as on
    // the host.
    Scene s = test::closed_box({0, 0, 0}, {1, 1, 1}, glm::vec3(0.7f), glm::vec3(5.0f), 0.2f);
    const uint32_t mirror = test::add_material(s, glm::vec3(0.0f)), glass = test::add_material(s, glm::vec3(0.0f));
    s.materials[mirror].illum = 3;
    s.materials[mirror].specular = glm::vec3(0.9f);
    s.materials[glass].illum = 7;
    s.materials[glass].ior = 1.5f;
    test::add_quad(s, {0.0f, 0.01f, 0.0f}, {0, 0, 1.0f}, {0.5f, 0, 0}, mirror);  // faces +y
    test::add_quad(s, {0.3f, 0.4f, 0.3f}, {0.4f, 0, 0}, {0, 0, 0.4f}, glass);    // faces -y
    test::add_quad(s, {0.3f, 0.2f, 0.3f}, {0, 0, 0.4f}, {0.4f, 0, 0}, glass);    // faces +y
    expect_kernel_matches_host(s, false);
}

TEST(LightPathKernel, PathsPastItsSlotsAreTracedAgainOnTheHost) {
    // A white furnace (albedo 1: roulette never ends a path) runs the paths that miss the
    // light's back to max_bounces, past TS_LP_MAX_VPLS and past the bounces that take
    // Halton dimensions (kHaltonLightPathBounces; the counter-based generator after): the
    // host traces those again, so the VPLs are still the host's.
    const Scene s = test::closed_box({0, 0, 0}, {1, 1, 1}, glm::vec3(1.0f), glm::vec3(1.0f), 0.2f);
    const SceneBuffers buffers = make_scene_buffers(s);
    auto embree = make_backend({BackendKind::Embree, ""}, buffers, plan_effects(s));
    LightPathSettings ls = media_settings(false);
    ls.max_bounces = kHaltonLightPathBounces + 16;
    // 128 paths: of 32, two lived 80 bounces (the light's front, of albedo 0, ends the others).
    const Traced host = trace(*embree, buffers, ls, false, 128), kernel = trace(*embree, buffers, ls, true, 128);
    size_t long_paths = 0;
    for (size_t j = 0; j < host.paths.size(); ++j) {
        long_paths += host.paths[j].vpls.size() == size_t(ls.max_bounces) * TS_VPL_FLOATS;
        EXPECT_EQ(kernel.paths[j].vpls, host.paths[j].vpls) << "path " << j;
    }
    EXPECT_GT(long_paths, 4u) << "paths outlive the kernel's slots";
    EXPECT_EQ(kernel.rays, host.rays);
}

// The paths' output read back whole and by KernelId::LightPathGather (headers, then the
// records left): the same paths bit for bit, as the gather only copies; paths that overflow
// the slots are traced again on the host either way.
void expect_gather_matches_whole(const Scene& scene, const LightPathSettings& ls, uint32_t count,
                                 size_t min_overflows) {
    const SceneBuffers buffers = make_scene_buffers(scene);
    const EffectPlan plan = plan_effects(scene);
    BackendOptions o{BackendKind::OpenCL, ""};
    o.cl_gpu_variant = true;
    auto whole = make_backend(o, buffers, plan);
    o.cl_light_path_gather = true;
    auto gathered = make_backend(o, buffers, plan);
    ASSERT_TRUE(gathered->gathers_light_paths());
    ASSERT_FALSE(whole->gathers_light_paths());
    const Traced a = trace(*whole, buffers, ls, true, count), b = trace(*gathered, buffers, ls, true, count);
    EXPECT_EQ(gathered->dispatch_count(KernelId::LightPathGather), 2u) << "the headers, then the records";
    EXPECT_EQ(whole->dispatch_count(KernelId::LightPathGather), 0u);
    const Left left = expect_same_paths(b, a);
    EXPECT_GT(left.vpls, size_t(count)) << "paths bounce";
    if (ls.ray_lights) {
        EXPECT_GT(left.vrls, size_t(count)) << "paths cross the fog";
    }
    EXPECT_GE(left.overflows, min_overflows);
}

TEST(LightPathKernel, GatheredReadBackLeavesTheSamePaths) {
    expect_gather_matches_whole(test::cornell_box(), media_settings(false), 256, 0);
    expect_gather_matches_whole(test::shipped_scene("cornell-box-fog.json"), media_settings(true), 256, 0);
    // A white furnace: paths past the slots (traced again on the host) among gathered ones.
    const Scene furnace = test::closed_box({0, 0, 0}, {1, 1, 1}, glm::vec3(1.0f), glm::vec3(1.0f), 0.2f);
    LightPathSettings ls = media_settings(false);
    ls.max_bounces = TS_LP_MAX_VPLS + 8;
    expect_gather_matches_whole(furnace, ls, 32, 4);
}

TEST(LightPathKernel, TheTableCrossesOnceWhileItsSettingsHold) {
    // The Halton table is the same frame after frame: it is stored once, and again only
    // when a setting it holds changes (the seed's scramble), and the paths traced with the
    // kept table are those of a fresh backend's first trace.
    const Scene s = test::cornell_box();
    const SceneBuffers buffers = make_scene_buffers(s);
    auto embree = make_backend({BackendKind::Embree, ""}, buffers, plan_effects(s));
    LightPathSettings ls = media_settings(false);
    const Traced first = trace(*embree, buffers, ls, true, 64);
    const Traced again = trace(*embree, buffers, ls, true, 64);
    EXPECT_EQ(embree->changed_input_stores(), 1u);
    ls.seed = 7;
    const Traced seeded = trace(*embree, buffers, ls, true, 64);
    EXPECT_EQ(embree->changed_input_stores(), 2u);
    auto fresh = make_backend({BackendKind::Embree, ""}, buffers, plan_effects(s));
    const Traced reference = trace(*fresh, buffers, ls, true, 64);
    size_t differ = 0;
    for (size_t j = 0; j < first.paths.size(); ++j) {
        EXPECT_EQ(again.paths[j].vpls, first.paths[j].vpls) << "path " << j;
        EXPECT_EQ(seeded.paths[j].vpls, reference.paths[j].vpls) << "path " << j;
        differ += seeded.paths[j].vpls != first.paths[j].vpls;
    }
    EXPECT_GT(differ, 32u) << "another seed's table draws other paths";
    // A plain set_input in between stores the table again on the next trace.
    embree->set_input(KernelInput::LightPathTable, std::vector<uint32_t>(1, 0u));
    const Traced after = trace(*embree, buffers, ls, true, 64);
    EXPECT_EQ(embree->changed_input_stores(), 3u);
    for (size_t j = 0; j < after.paths.size(); ++j) EXPECT_EQ(after.paths[j].vpls, reference.paths[j].vpls);
}

// The scrambled radical inverse as the project computed it before the table (the digits
// of every figure in bench/results): a reference for ts_halton_sample.
double reference_halton(uint64_t index, uint32_t base, const uint32_t* perm) {
    const double inv = 1.0 / base;
    double f = inv, r = 0.0;
    while (f > 1e-17) {
        r += perm[index % base] * f;
        index /= base;
        f *= inv;
    }
    return std::min(r, 0.99999999999999989);
}

TEST(LightPathKernel, HaltonTableKeepsTheDigits) {
    const ScrambledHalton h(40, 0x7e55e7au);
    const std::vector<uint32_t>& t = h.table();
    ASSERT_EQ(t[TS_HALTON_DIMS], 40u);
    EXPECT_EQ(t[TS_HALTON_BASES + 0], 2u);
    EXPECT_EQ(t[TS_HALTON_BASES + 39], 173u);  // the 40th prime
    for (int d = 0; d < 40; ++d) {
        const uint32_t b = t[TS_HALTON_BASES + d];
        const uint32_t* perm = &t[t[TS_HALTON_BASES + 40 + d]];
        std::vector<bool> seen(b, false);
        for (uint32_t j = 0; j < b; ++j) seen[perm[j]] = true;
        EXPECT_EQ(std::count(seen.begin(), seen.end(), true), int(b)) << "a permutation of the digits, dim " << d;
        for (uint64_t i : {0ull, 1ull, 7ull, 1234ull, 987654321ull, (1ull << 40) + 3})
            EXPECT_EQ(h.sample(i, d), static_cast<float>(reference_halton(i, b, perm))) << "dim " << d << " point " << i;
    }
    EXPECT_THROW((void)h.sample(0, 40), std::out_of_range);
}

}  // namespace
}  // namespace tessera
