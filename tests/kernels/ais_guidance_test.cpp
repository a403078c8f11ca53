// The AIS schedule computed where the kernels run (KernelId::AisSchedule and EdgeSchedule,
// kernels/shared/ais_guidance.h, edge_guidance.h, ais_resolve.h) against the host's
// reference (compute_guidance, make_schedule, edge_guidance, make_edge_schedule): set masks,
// flags, item lists and edge-sample counts bit for bit, and a device frame's compact tables
// (AisTileSets, EdgeSegmentCounts, shared/ais_compact.h) decoded into the host's lists, on PoCL (OpenCL C) and on Embree
// (the shared code as C++ over the device's strided buffers). The inputs are synthetic
// G-buffers with every case the guidance branches on: planes meeting at creases and depth
// steps, escaped rays, penumbrae, VPL spikes, medium shafts and length steps, emitters.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "gi/ais_edges.h"
#include "gi/ais_items.h"
#include "gi/ais_schedule.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/layout_igi.h"
#include "kernels/shared/layout_pass.h"
#include "kernels/shared/sampling.h"
#include "support/ais_compact_checks.h"
#include "support/render_helpers.h"
#include "support/scoped_env.h"

namespace tessera {
namespace {

constexpr int kWidth = 37, kHeight = 29;  // not multiples of any tile: windows cross the borders

// A synthetic base pass: the surface and media kernels' outputs (TS_IGI_SURF_FLOATS and
// TS_IGI_MEDIA_FLOATS a pixel) and a resolved pass image (TS_PASS_FLOATS a pixel).
struct BasePass {
    std::vector<float> surf, media, pass;
};

// Three planes (a floor, a wall meeting it at a crease, a box face in front of the wall: a
// depth step) and a corner of sky; visibility in quarter steps with a penumbra band, E_id
// with spikes, a lit fraction in eighths with a shaft, ceiling lights as emitters.
BasePass synthetic_pass(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    BasePass b;
    b.surf.assign(size_t(kWidth) * kHeight * TS_IGI_SURF_FLOATS, 0.0f);
    b.media.assign(size_t(kWidth) * kHeight * TS_IGI_MEDIA_FLOATS, 0.0f);
    b.pass.assign(size_t(kWidth) * kHeight * TS_PASS_FLOATS, 0.0f);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const size_t p = size_t(y) * kWidth + x;
            float* s = &b.surf[p * TS_IGI_SURF_FLOATS];
            float* m = &b.media[p * TS_IGI_MEDIA_FLOATS];
            const bool sky = x > kWidth - 6 && y < 5;
            const bool box = x > 8 && x < 20 && y > 10 && y < 22;
            const bool floor = y >= 18 && !box;
            float n[3] = {0.0f, 0.0f, 1.0f}, depth = 4.0f + 0.01f * x;
            if (floor) n[0] = 0.0f, n[1] = 1.0f, n[2] = 0.0f, depth = 2.0f + 0.2f * (kHeight - y);
            if (box) depth = 2.5f + 0.02f * float(y % 3);
            if (sky) depth = INFINITY, n[2] = 0.0f;
            for (int j = 0; j < 3; ++j) s[TS_IGI_SURF_NORMAL + j] = n[j];
            s[TS_IGI_SURF_DISTANCE] = depth;
            const float pos[3] = {0.1f * x, 0.1f * y, sky ? 0.0f : -depth};
            for (int j = 0; j < 3; ++j) s[TS_IGI_SURF_POSITION + j] = pos[j];
            const bool penumbra = std::abs(x - y) < 4;
            s[TS_IGI_SURF_VISIBLE] = sky ? 0.0f : penumbra ? 0.25f * float(rng() % 5) : (x < y ? 0.0f : 1.0f);
            const float spike = u(rng) < 0.05f ? 40.0f : 1.0f;
            for (int j = 0; j < 3; ++j) s[TS_IGI_SURF_E_ID + j] = sky ? 0.0f : spike * (0.2f + 0.1f * u(rng)) * (j + 1);
            if (y < 2 && x > 10 && x < 16)
                for (int j = 0; j < 3; ++j) s[TS_IGI_SURF_EMISSION + j] = 50.0f;
            const bool shaft = x > 24 && x < 29;
            m[TS_IGI_MEDIA_LIT] = shaft ? 0.125f * float(rng() % 9) : 1.0f;
            m[TS_IGI_MEDIA_LENGTH] = sky ? 30.0f : depth * (box ? 0.5f : 1.0f);
            for (int j = 0; j < 3; ++j) m[TS_IGI_MEDIA_RADIANCE + j] = 0.05f * u(rng) * (shaft ? 4.0f : 1.0f);
            float* r = &b.pass[p * TS_PASS_FLOATS + TS_PASS_RADIANCE];
            for (int j = 0; j < 3; ++j) r[j] = (box ? 0.3f : 0.8f) * (0.9f + 0.2f * u(rng)) + 50.0f * s[TS_IGI_SURF_EMISSION];
        }
    return b;
}

// What the host's guidance reads of the pass, as AisFrame::base_of and IgiFrame::extract
// take it from the kernels' outputs.
AisBaseBuffers host_base(const BasePass& b, bool media, bool media_cov) {
    AisBaseBuffers base;
    GeometryBuffer& g = base.geometry;
    g.width = kWidth, g.height = kHeight;
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p) {
        const float* s = &b.surf[p * TS_IGI_SURF_FLOATS];
        const float* m = &b.media[p * TS_IGI_MEDIA_FLOATS];
        for (int j = 0; j < 3; ++j) g.normal.push_back(s[TS_IGI_SURF_NORMAL + j]);
        for (int j = 0; j < 3; ++j) g.position.push_back(s[TS_IGI_SURF_POSITION + j]);
        g.depth.push_back(s[TS_IGI_SURF_DISTANCE]);
        base.visibility.push_back(s[TS_IGI_SURF_VISIBLE]);
        base.indirect.push_back(ts::ts_luminance(ts::ts_f3_load(s + TS_IGI_SURF_E_ID)));
        if (!media) continue;
        base.lit_fraction.push_back(m[TS_IGI_MEDIA_LIT]);
        base.medium_length.push_back(m[TS_IGI_MEDIA_LENGTH]);
        if (media_cov) base.media.push_back(ts::ts_luminance(ts::ts_f3_load(m + TS_IGI_MEDIA_RADIANCE)));
    }
    return base;
}

TsFrame frame_of(int tile, uint32_t components) {
    TsFrame f{};
    f.width = kWidth;
    f.height = kHeight;
    f.igi_tile = uint32_t(tile);
    const DiscontinuitySettings d;
    f.igi_filter_cos = d.normal_cos;
    f.igi_filter_depth = d.depth_rel;
    f.igi_components = components;
    return f;
}

std::unique_ptr<Backend> backend_of(BackendKind kind, SceneBuffers& buffers, const Scene& scene) {
    BackendOptions o{kind, ""};
    o.cl_packets = false;
    return make_backend(o, buffers, plan_effects(scene));
}

// A device frame's extra sets (shared/ais_compact.h): the tile sets counted where the kernels
// run, their prefix sums on the host, then every item decoded from them is the host list's
// item at the same place, and each pixel's item for each of its sets is found there.
void expect_compact_items(Backend& backend, const TsFrame& f, const std::vector<float>& masks,
                          const AisSchedule& host, const std::array<double, kAisComponents>& flagged) {
    backend.launch_into(KernelId::AisSchedule, f, KernelInput::AisMasks);
    const size_t tiles = ais_tile_count(f.width, f.height), pixels = size_t(f.width) * f.height;
    backend.launch_count_into(KernelId::AisTileSets, f, size_t(f.igi_tile) * f.igi_tile * tiles,
                              KernelInput::AisTileSets);
    std::vector<float> tile_sets;
    backend.read_input(KernelInput::AisTileSets, tile_sets);
    AisItemOffsets offsets;
    ais_item_offsets(tile_sets, size_t(f.igi_tile) * f.igi_tile, tiles, pixels, offsets);
    for (int c = 0; c < kAisComponents; ++c) EXPECT_EQ(offsets.flagged[c], flagged[c]) << "component " << c;
    test::expect_items_decode_as(f, masks, tile_sets, offsets, host);
}

// A device frame's edge samples likewise: the host's (pixel, sample, count) items, tile by
// tile, each pixel's samples consecutive from ts_edge_compact_first.
void expect_compact_edges(Backend& backend, const TsFrame& f, const std::vector<float>& counts,
                          const EdgeSchedule& host) {
    backend.set_input(KernelInput::EdgeCounts, counts);
    std::vector<float> segment_counts;
    backend.launch_count(KernelId::EdgeSegmentCounts, f, ais_tile_count(f.width, f.height) * TS_AIS_TILE,
                         segment_counts);
    EdgeSegmentOffsets offsets;
    edge_segment_offsets(segment_counts, size_t(f.width) * f.height, offsets);
    test::expect_edges_decode_as(f, counts, offsets, host);
}

struct ScheduleCase {
    const char* name;
    BackendKind backend;
    int tile;
    AisMode mode;
    uint32_t components;  // TS_COMPONENT_* guided
    float pm_cov;
    int graded_sets = AisThresholds{}.graded_sets;
};

void PrintTo(const ScheduleCase& c, std::ostream* os) { *os << c.name; }

class AisScheduleKernel : public ::testing::TestWithParam<ScheduleCase> {};

TEST_P(AisScheduleKernel, EqualsTheHostSchedule) {
    const ScheduleCase& c = GetParam();
    const bool media = c.components & TS_COMPONENT_PM;
    const BasePass pass = synthetic_pass(11);
    AisBaseBuffers base = host_base(pass, media, c.pm_cov > 0.0f);
    DiscontinuitySettings filter;
    filter.tile = c.tile;
    discontinuity_precompute(base.geometry, filter);  // as the host frame does
    AisThresholds t;
    t.pm_cov = c.pm_cov;
    t.graded_sets = c.graded_sets;
    const std::array<bool, kAisComponents> enabled = {(c.components & TS_COMPONENT_SS) != 0,
                                                      (c.components & TS_COMPONENT_ID) != 0, media};
    const AisGuidance guidance = compute_guidance(base, filter, t, enabled);
    const AisSchedule host = make_schedule(guidance, t, c.mode, kWidth, kHeight, c.tile);

    const Scene scene = test::cornell_box();
    SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = backend_of(c.backend, buffers, scene);
    backend->set_input(KernelInput::IgiSurface, pass.surf);
    backend->set_input(KernelInput::IgiMedia, pass.media);
    backend->set_input(KernelInput::AisScheduleTable,
                       ais_schedule_table(t, c.mode, c.tile, c.components, EdgeSettings{}, 0.0f));
    std::vector<float> out;
    backend->launch(KernelId::AisSchedule, frame_of(c.tile, c.components), out);
    ASSERT_EQ(out.size(), size_t(kWidth) * kHeight * TS_AIS_MASK_FLOATS);

    const float trigger[kAisComponents] = {t.ss_trigger, t.id_trigger, t.pm_trigger};
    AisSchedule device;
    size_t flagged[kAisComponents] = {0, 0, 0};
    for (int k = 0; k < kAisComponents; ++k) {
        if (!enabled[k]) {
            // A component not guided keeps each pixel's own set and flags nothing (a pixel's
            // extra sets OR all three masks: ts_ais_extra_sets, shared/ais_compact.h).
            EXPECT_TRUE(host.masks[k].empty());
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x) {
                    const float* o = &out[(size_t(y) * kWidth + x) * TS_AIS_MASK_FLOATS];
                    const uint64_t own = 1ull << interleave_set(x, y, c.tile);
                    ASSERT_EQ(std::bit_cast<uint32_t>(o[TS_AIS_MASK_SETS(k)]), uint32_t(own));
                    ASSERT_EQ(std::bit_cast<uint32_t>(o[TS_AIS_MASK_SETS(k) + 1]), uint32_t(own >> 32));
                    ASSERT_EQ(std::bit_cast<uint32_t>(o[TS_AIS_MASK_FLAGS]) >> k & 1u, 0u);
                }
            continue;
        }
        device.masks[k].resize(size_t(kWidth) * kHeight);
        for (size_t p = 0; p < device.masks[k].size(); ++p) {
            const float* o = &out[p * TS_AIS_MASK_FLOATS];
            device.masks[k][p] = uint64_t(std::bit_cast<uint32_t>(o[TS_AIS_MASK_SETS(k) + 1])) << 32 |
                                 std::bit_cast<uint32_t>(o[TS_AIS_MASK_SETS(k)]);
            const bool flag = std::bit_cast<uint32_t>(o[TS_AIS_MASK_FLAGS]) >> k & 1u;
            ASSERT_EQ(device.masks[k][p], host.masks[k][p]) << "component " << k << " pixel " << p;
            ASSERT_EQ(flag, guidance.g[k][p] > trigger[k]) << "component " << k << " pixel " << p;
            flagged[k] += flag;
        }
        // The case flags some pixels and leaves others, or it tests little (tile 1: one set,
        // nothing to filter, nothing flagged).
        if (c.tile > 1) {
            EXPECT_GT(flagged[k], 0u) << "component " << k;
            EXPECT_LT(flagged[k], device.masks[k].size()) << "component " << k;
        }
    }
    schedule_items(device, kWidth, kHeight, c.tile);
    EXPECT_EQ(host.item_pixels.empty(), c.tile == 1);
    EXPECT_EQ(device.item_pixels, host.item_pixels);
    EXPECT_EQ(device.item_sets, host.item_sets);
    EXPECT_EQ(device.item_components, host.item_components);
    std::array<double, kAisComponents> fraction{};
    for (int k = 0; k < kAisComponents; ++k) fraction[k] = double(flagged[k]) / double(size_t(kWidth) * kHeight);
    expect_compact_items(*backend, frame_of(c.tile, c.components), out, host, fraction);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AisScheduleKernel,
    ::testing::Values(
        ScheduleCase{"OpenclA", BackendKind::OpenCL, 3, AisMode::A, 7u, 0.0f},
        ScheduleCase{"OpenclAMax", BackendKind::OpenCL, 3, AisMode::AMax, 7u, 0.0f},
        ScheduleCase{"OpenclTile2", BackendKind::OpenCL, 2, AisMode::A, 7u, 0.0f},
        ScheduleCase{"OpenclTile4PmCov", BackendKind::OpenCL, 4, AisMode::A, 7u, 1.0f},
        ScheduleCase{"OpenclTile8", BackendKind::OpenCL, 8, AisMode::A, TS_COMPONENT_SS | TS_COMPONENT_ID, 0.0f},
        ScheduleCase{"OpenclTile8AllGraded", BackendKind::OpenCL, 8, AisMode::A, TS_COMPONENT_SS | TS_COMPONENT_ID, 0.0f, 0},
        ScheduleCase{"OpenclTile4Graded3", BackendKind::OpenCL, 4, AisMode::A, 7u, 0.0f, 3},
        ScheduleCase{"OpenclIdOnly", BackendKind::OpenCL, 3, AisMode::A, TS_COMPONENT_ID, 0.0f},
        ScheduleCase{"OpenclTile1", BackendKind::OpenCL, 1, AisMode::A, 7u, 0.0f},
        ScheduleCase{"EmbreeA", BackendKind::Embree, 3, AisMode::A, 7u, 0.0f},
        ScheduleCase{"EmbreeTile4PmCov", BackendKind::Embree, 4, AisMode::A, 7u, 1.0f}),
    [](const auto& info) { return std::string(info.param.name); });

struct EdgeCase {
    const char* name;
    BackendKind backend;
    AisMode mode;
    int tile;
};

void PrintTo(const EdgeCase& c, std::ostream* os) { *os << c.name; }

class EdgeScheduleKernel : public ::testing::TestWithParam<EdgeCase> {};

TEST_P(EdgeScheduleKernel, EqualsTheHostSchedule) {
    const EdgeCase& c = GetParam();
    const BasePass pass = synthetic_pass(5);
    AisBaseBuffers base = host_base(pass, false, false);
    DiscontinuitySettings filter;
    filter.tile = c.tile;
    discontinuity_precompute(base.geometry, filter);  // tile 3: the host reads the masks
    std::vector<uint8_t> emitter;
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p) {
        const float* le = &pass.surf[p * TS_IGI_SURF_FLOATS + TS_IGI_SURF_EMISSION];
        emitter.push_back(le[0] + le[1] + le[2] > 0.0f);
    }
    EdgeSettings e;
    e.samples = 6;
    const EdgeSchedule host =
        make_edge_schedule(edge_guidance(base.geometry, filter, pass.pass, e.dark, emitter), e, c.mode);

    const Scene scene = test::cornell_box();
    SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = backend_of(c.backend, buffers, scene);
    backend->set_input(KernelInput::IgiSurface, pass.surf);
    backend->set_input(KernelInput::IgiPass, pass.pass);
    backend->set_input(KernelInput::AisScheduleTable,
                       ais_schedule_table(AisThresholds{}, c.mode, c.tile, 0u, e, edge_epsilon(pass.pass, kWidth, e.dark)));
    std::vector<float> counts;
    backend->launch(KernelId::EdgeSchedule, frame_of(c.tile, 0u), counts);
    ASSERT_EQ(counts.size(), host.samples.size());
    EdgeSchedule device;
    for (float n : counts) device.samples.push_back(static_cast<uint8_t>(n));
    edge_schedule_items(device);
    EXPECT_EQ(device.samples, host.samples);
    EXPECT_EQ(device.items, host.items);
    EXPECT_EQ(device.flagged, host.flagged);
    expect_compact_edges(*backend, frame_of(c.tile, 0u), counts, host);
    // Flagged and unflagged pixels, and graded counts between 1 and the most under A.
    EXPECT_GT(host.flagged, 0.0);
    EXPECT_LT(host.flagged, 1.0);
    if (c.mode == AisMode::A) {
        bool graded = false;
        for (uint8_t n : host.samples) graded |= n > 0 && n < e.samples;
        EXPECT_TRUE(graded);
    }
}

// The edge contrast's ε from the device's row sums (KernelId::EdgeRowSums) is the host's
// edge_epsilon bit for bit where the device sums in double; the float form (TS_NO_DOUBLE)
// within its rounding.
TEST(EdgeRowSumsKernel, GiveTheHostsEpsilon) {
    const BasePass pass = synthetic_pass(5);
    const float eps = edge_epsilon(pass.pass, kWidth, 0.01f);
    EXPECT_GT(eps, 0.0f);
    const Scene scene = test::cornell_box();
    SceneBuffers buffers = make_scene_buffers(scene);
    for (BackendKind kind : {BackendKind::OpenCL, BackendKind::Embree}) {
        auto backend = backend_of(kind, buffers, scene);
        backend->set_input(KernelInput::IgiPass, pass.pass);
        std::vector<float> sums;
        backend->launch_count(KernelId::EdgeRowSums, frame_of(3, 0u), kHeight, sums);
        EXPECT_EQ(edge_epsilon_of_rows(sums, size_t(kWidth) * kHeight, 0.01f), eps);
    }
    test::ScopedEnv options("TESSERA_CL_OPTIONS", "-DTS_NO_DOUBLE");
    auto backend = backend_of(BackendKind::OpenCL, buffers, scene);
    backend->set_input(KernelInput::IgiPass, pass.pass);
    std::vector<float> sums;
    backend->launch_count(KernelId::EdgeRowSums, frame_of(3, 0u), kHeight, sums);
    EXPECT_EQ(sums[TS_EDGE_ROW_HAS_DOUBLE], 0.0f);  // the float form ran
    EXPECT_NEAR(edge_epsilon_of_rows(sums, size_t(kWidth) * kHeight, 0.01f), eps, 1e-6f * eps);
}

INSTANTIATE_TEST_SUITE_P(Cases, EdgeScheduleKernel,
                         ::testing::Values(EdgeCase{"OpenclA", BackendKind::OpenCL, AisMode::A, 3},
                                           EdgeCase{"OpenclAMaxTile4", BackendKind::OpenCL, AisMode::AMax, 4},
                                           EdgeCase{"EmbreeA", BackendKind::Embree, AisMode::A, 3}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace tessera
