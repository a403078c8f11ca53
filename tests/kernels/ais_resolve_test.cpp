// The AIS frame reconstructed where the kernels ran (kernels/shared/ais_resolve.h,
// AisFrame::resolve_on_device: the set masks and edge-sample counts computed there, the
// extra sets' merge, the reconstruction, the clamp's compensation, the composite and the edge samples' merge on the device) against the
// host's (AisFrame's refine, reconstruct_component, compensate_clamp, composite, finish).
// The OpenCL GPU variant runs the device path, its full-stack per-ray variant the host's,
// over the same hits (tests/backend/opencl_gpu_variant_test.cpp); both trace their light
// paths on the host, so the VPLs are the same bits. The device sums in double in the host's
// order, so the images must be the same bits; through a medium the compensation's exp may
// round an ulp apart (as in tests/kernels/igi_resolve_test.cpp).
#include <cmath>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "integrators/ais_frame.h"
#include "kernels/shared/layout_igi.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "support/render_helpers.h"

namespace tessera {
namespace {

std::unique_ptr<Backend> opencl(const SceneBuffers& buffers, const Scene& scene, bool gpu_variant) {
    BackendOptions o{BackendKind::OpenCL, ""};
    o.cl_packets = false;
    o.cl_gpu_variant = gpu_variant;
    o.cl_light_path_kernel = false;
    return make_backend(o, buffers, plan_effects(scene));
}

struct DeviceCase {
    const char* name;
    const char* scene;
    Method method;
    uint32_t tile;
    bool filter;
    uint32_t components;
};

void PrintTo(const DeviceCase& c, std::ostream* os) { *os << c.name; }

const uint32_t kAll = TS_COMPONENT_SS | TS_COMPONENT_ID | TS_COMPONENT_PM | TS_COMPONENT_EDGE;

class AisDeviceFrame : public ::testing::TestWithParam<DeviceCase> {};

TEST_P(AisDeviceFrame, EqualsTheHostFrame) {
    const DeviceCase& c = GetParam();
    const Scene scene = load_scene(std::filesystem::path(TESSERA_SCENES_DIR) / c.scene, make_data_path(std::nullopt));
    SceneBuffers buffers = make_scene_buffers(scene);
    RenderSettings rs;
    rs.method = c.method;
    rs.width = 41;  // not a multiple of any tile: windows cross the borders
    rs.height = 33;
    rs.spp = 2;
    rs.igi.tile = c.tile;
    rs.igi.paths_per_set = 8;
    rs.igi.filter = c.filter;
    rs.igi.components = c.components;
    auto host = opencl(buffers, scene, false), device = opencl(buffers, scene, true);
    ASSERT_TRUE(device->resolves_on_device());
    const Image a = render_frame(*host, scene, buffers, rs), b = render_frame(*device, scene, buffers, rs);
    // The device path ran (the extra sets kept there and, with edges, merged there), and
    // the host's did not.
    EXPECT_GT(device->dispatch_count(KernelId::IgiResolve), 0u);
    EXPECT_GT(device->dispatch_count(KernelId::AisSchedule), 0u);  // the set masks, not the G-buffer
    EXPECT_EQ(host->dispatch_count(KernelId::AisSchedule), 0u);
    EXPECT_EQ(device->dispatch_count(KernelId::EdgeSchedule), c.components & TS_COMPONENT_EDGE ? 2u : 0u);
    EXPECT_EQ(host->dispatch_count(KernelId::IgiResolve), 0u);
    EXPECT_EQ(host->dispatch_count(KernelId::AisEdgeMerge), 0u);
    if (c.components & TS_COMPONENT_EDGE) {
        EXPECT_GT(device->dispatch_count(KernelId::AisEdgeMerge), 0u);
    }
    EXPECT_EQ(device->dispatch_count(KernelId::AisItem), host->dispatch_count(KernelId::AisItem));
    if (!plan_effects(scene).medium) {
        test::expect_images_identical(a, b);
        return;
    }
    // An ulp of a transmittance moves one positive term of a pixel's E_res by ~1e-7 of
    // itself: 1e-5 of each channel leaves a margin; a different reconstruction is ~1e-2.
    for (const char* ch : {"R", "G", "B"}) {
        const auto &x = a.find(ch)->data, &y = b.find(ch)->data;
        for (size_t i = 0; i < x.size(); ++i) ASSERT_NEAR(y[i], x[i], 1e-5f * std::fabs(x[i]) + 1e-12f) << ch << " " << i;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AisDeviceFrame,
    ::testing::Values(DeviceCase{"A", "cornell-box.json", Method::Ais, 3, true, kAll},
                      DeviceCase{"AMax", "cornell-box.json", Method::AisMax, 3, true, kAll},
                      DeviceCase{"Tile4", "cornell-box.json", Method::Ais, 4, true, kAll},
                      DeviceCase{"Tile2AMax", "cornell-box.json", Method::AisMax, 2, true, kAll},
                      DeviceCase{"NoFilter", "cornell-box.json", Method::Ais, 3, false, kAll},
                      DeviceCase{"NoEdges", "cornell-box.json", Method::Ais, 3, true,
                                 TS_COMPONENT_SS | TS_COMPONENT_ID},
                      DeviceCase{"IdOnly", "cornell-box.json", Method::AisMax, 3, true, TS_COMPONENT_ID | TS_COMPONENT_EDGE},
                      DeviceCase{"Fog", "cornell-box-fog.json", Method::Ais, 3, true, kAll},
                      DeviceCase{"FogAMax", "cornell-box-fog.json", Method::AisMax, 3, true, kAll}),
    [](const auto& info) { return std::string(info.param.name); });

// The items of each pixel, as the device reads them: offsets over the pixels, then each
// pixel's entries in increasing set order (the list's order), with the item's index and code.
TEST(AisPixelItems, ListEachPixelsItemsInSetOrder) {
    // Pixels 0..3; items grouped by set as make_schedule lists them: set 1 (pixels 2, 0),
    // set 4 (pixel 2), set 7 (pixels 0, 2).
    const std::vector<uint32_t> list = {2, 1 | 2u << 8, 0, 1 | 1u << 8, 2, 4 | 7u << 8, 0, 7 | 2u << 8, 2, 7 | 4u << 8};
    const std::vector<uint32_t> t = ais_pixel_items(list, 4);
    ASSERT_EQ(t.size(), 5u + TS_AIS_ENTRY_WORDS * 5u);
    EXPECT_EQ(std::vector<uint32_t>(t.begin(), t.begin() + 5), (std::vector<uint32_t>{0, 2, 2, 5, 5}));
    auto entry = [&](uint32_t k, int w) { return t[5 + TS_AIS_ENTRY_WORDS * k + w]; };
    // Pixel 0: items 1 (set 1) and 3 (set 7); pixel 2: items 0, 2, 4 (sets 1, 4, 7).
    const uint32_t items[5] = {1, 3, 0, 2, 4};
    for (uint32_t k = 0; k < 5; ++k) {
        EXPECT_EQ(entry(k, TS_AIS_ENTRY_ITEM), items[k]) << k;
        EXPECT_EQ(entry(k, TS_AIS_ENTRY_CODE), list[2 * items[k] + 1]) << k;
    }
}

TEST(AisPixelItems, EdgeSamplesCodeFirstAndCount) {
    EdgeSchedule s;
    s.samples = {0, 2, 0, 1};
    s.items = {1, 1, 2, 1, 2, 2, 3, 1, 1};
    const std::vector<uint32_t> code = edge_pixel_samples(s);
    EXPECT_EQ(code, (std::vector<uint32_t>{0u, 0u << TS_EDGE_PIXEL_FIRST_SHIFT | 2u, 0u,
                                           2u << TS_EDGE_PIXEL_FIRST_SHIFT | 1u}));
}

}  // namespace
}  // namespace tessera
