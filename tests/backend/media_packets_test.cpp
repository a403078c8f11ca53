// The ray march in packets (host/backend/embree_media_packets.cpp; kernels/igi_packets.h,
// igi_media_packets and the PM part of ais_extra_packets): in one packet, PM items of
// different sample sets, items without PM and idle lanes must each get exactly what the
// one-ray-at-a-time march (ts_igi_media_set) gives, on both backends, with the medium VPLs
// gathered and without (single scattering, no VPL share). Whole images are covered by the
// fog cases of embree_packets_test.cpp and opencl_packets_test.cpp; this test builds the
// item lists those images rarely produce (sets interleaved within one packet).
#include <cstring>
#include <filesystem>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/frame.h"
#include "integrators/ais_frame.h"
#include "opencl/device.h"
#include "scene/loader.h"

namespace tessera {
namespace {

constexpr uint32_t kSize = 20;  // image edge: 400 pixels

// 37 items (two full packets and one of 5 lanes): pixel 7i mod 400, set (i / 3) mod 9, so
// a packet holds six sets in runs of three; every fourth item has no PM, every fourth
// PM alone, the rest SS, ID and PM.
std::vector<uint32_t> mixed_items() {
    std::vector<uint32_t> list;
    for (uint32_t i = 0; i < 37; ++i) {
        const uint32_t mask = i % 4 == 3   ? TS_COMPONENT_SS | TS_COMPONENT_ID
                              : i % 4 == 1 ? TS_COMPONENT_PM
                                           : TS_COMPONENT_SS | TS_COMPONENT_ID | TS_COMPONENT_PM;
        list.push_back((7 * i) % (kSize * kSize));
        list.push_back((i / 3) % 9 | mask << 8);
    }
    return list;
}

// What the march gathers besides the lights (TsFrame.igi_media_vpls).
enum class Media { Single, PointVpls, RayLights };

std::vector<float> items_of(BackendKind kind, bool packets, Media media) {
    const Scene s =
        load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / "cornell-box-fog.json", make_data_path(std::nullopt));
    const SceneBuffers b = make_scene_buffers(s);
    BackendOptions o{kind, ""};
    o.embree_packets = o.cl_packets = packets;
    auto be = make_backend(o, b, plan_effects(s));
    // Packets must really be on where asked (Embree always, OpenCL on CPU devices), or the
    // comparison is one mode against itself.
    if (kind == BackendKind::Embree || cl_device_prefers_packets(select_cl_device(""))) {
        EXPECT_EQ(be->description().find("16-ray packets") != std::string::npos, packets) << be->description();
    }
    IgiSettings is;
    is.paths_per_set = 8;
    is.multiple_scattering = media != Media::Single;
    is.ray_lights = media == Media::RayLights;
    AisFrame igi(*be, b, plan_effects(s), is);
    TsFrame f = make_frame(s.camera, kSize, kSize, is.set_shadow_samples, 1, b.light_count);
    f.light_power = b.light_power;
    std::vector<float> out;
    igi.render_pass(f, out);  // generates and uploads the pass's VPLs
    std::vector<float> items;
    be->launch_items(KernelId::AisItem, igi.prepare(f), mixed_items(), items);
    return items;
}

class MediaPackets : public ::testing::TestWithParam<std::tuple<BackendKind, Media>> {};

TEST_P(MediaPackets, MixedSetItemsEqualOneRayAtATimeBitForBit) {
    const auto [kind, media] = GetParam();
    const std::vector<float> single = items_of(kind, false, media), packets = items_of(kind, true, media);
    ASSERT_EQ(single.size(), 37u * TS_AIS_ITEM_FLOATS);
    ASSERT_EQ(packets.size(), single.size());
    EXPECT_EQ(std::memcmp(single.data(), packets.data(), single.size() * sizeof(float)), 0);
    // The march ran: the PM items in the fog-filled box see in-scattered light, the
    // others none.
    int lit = 0, pm_items = 0;
    for (uint32_t i = 0; i < 37; ++i) {
        const float* pm = &packets[i * TS_AIS_ITEM_FLOATS + TS_AIS_ITEM_PM];
        if (i % 4 == 3) {
            EXPECT_EQ(pm[0] + pm[1] + pm[2], 0.0f) << "item " << i;
            continue;
        }
        ++pm_items;
        lit += pm[0] > 0.0f;
    }
    EXPECT_EQ(lit, pm_items);
}

INSTANTIATE_TEST_SUITE_P(Backends, MediaPackets,
                         ::testing::Combine(::testing::Values(BackendKind::Embree, BackendKind::OpenCL),
                                            ::testing::Values(Media::Single, Media::PointVpls, Media::RayLights)),
                         [](const auto& info) {
                             const Media m = std::get<1>(info.param);
                             return std::string(std::get<0>(info.param) == BackendKind::Embree ? "Embree" : "OpenCL") +
                                    (m == Media::Single ? "_Single" : m == Media::PointVpls ? "_Multiple" : "_RayLights");
                         });

}  // namespace
}  // namespace tessera
