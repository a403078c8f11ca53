// The AIS frame reconstructed where the kernels ran (kernels/shared/ais_resolve.h,
// AisFrame::resolve_on_device: the set masks and edge-sample counts computed there, the
// extra sets' merge, the reconstruction, the clamp's compensation, the composite and the edge samples' merge on the device) against the
// host's (AisFrame's refine, reconstruct_component, compensate_clamp, composite, finish).
// The OpenCL GPU variant runs the device path, its full-stack per-ray variant the host's,
// over the same hits (tests/backend/opencl_gpu_variant_test.cpp); both trace their light
// paths on the host, so the VPLs are the same bits. The device sums in double in the host's
// order, so the images must be the same bits, through a medium too (the compensation's
// transmittance takes the shared exponential on both sides, ts_exp3).
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
    return make_backend(test::opencl_per_ray(gpu_variant, false), buffers, plan_effects(scene));
}

struct DeviceCase {
    const char* name;
    const char* scene;
    Method method;
    uint32_t tile;
    bool filter;
    uint32_t components;
    uint32_t width = 41, height = 33;  // not a multiple of any tile: windows cross the borders
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
    rs.width = c.width;
    rs.height = c.height;
    rs.spp = 2;
    rs.igi.tile = c.tile;
    rs.igi.paths_per_set = 8;
    rs.igi.filter = c.filter;
    rs.igi.components = c.components;
    auto host = opencl(buffers, scene, false), device = opencl(buffers, scene, true);
    ASSERT_TRUE(device->resolves_on_device());
    const Image a = render_frame(*host, scene, buffers, rs), b = render_frame(*device, scene, buffers, rs);
    // The device path ran (the extra sets kept there and, with edges, merged there), and
    // the host's did not. render_frame without AOVs, checkpoint or cluster reads back the
    // radiance alone (IgiSettings::pass_aovs): with edges the whole pass stays on the
    // device for their schedule, and the merge (or, without samples, a copy) keeps the
    // radiance; without, the resolve itself does.
    const bool edges = c.components & TS_COMPONENT_EDGE;
    EXPECT_EQ(device->dispatch_count(edges ? KernelId::IgiResolve : KernelId::IgiResolveRadiance), 2u);
    EXPECT_EQ(device->dispatch_count(edges ? KernelId::IgiResolveRadiance : KernelId::IgiResolve), 0u);
    EXPECT_EQ(device->dispatch_count(KernelId::AisEdgeMerge), 0u);
    EXPECT_GT(device->dispatch_count(KernelId::AisSchedule), 0u);  // the set masks, not the G-buffer
    EXPECT_EQ(host->dispatch_count(KernelId::AisSchedule), 0u);
    EXPECT_EQ(device->dispatch_count(KernelId::EdgeSchedule), edges ? 2u : 0u);
    EXPECT_EQ(host->dispatch_count(KernelId::IgiResolve), 0u);
    EXPECT_EQ(host->dispatch_count(KernelId::AisEdgeMergeRadiance), 0u);
    if (edges) {
        EXPECT_GT(device->dispatch_count(KernelId::AisEdgeMergeRadiance), 0u);
        EXPECT_EQ(device->dispatch_count(KernelId::AisEdgeMergeRadiance) + device->dispatch_count(KernelId::PassRadiance),
                  2u);
    }
    // The device listed nothing: its extra sets and edge samples ran from its compact
    // tables (shared/ais_compact.h) as often as the host's lists ran theirs.
    EXPECT_EQ(device->dispatch_count(KernelId::AisItem), 0u);
    EXPECT_EQ(device->dispatch_count(KernelId::EdgeSample), 0u);
    EXPECT_EQ(device->dispatch_count(KernelId::AisTileSets), 2u);
    EXPECT_EQ(device->dispatch_count(KernelId::AisCompactItem), host->dispatch_count(KernelId::AisItem));
    EXPECT_EQ(device->dispatch_count(KernelId::EdgeCompactSample), host->dispatch_count(KernelId::EdgeSample));
    test::expect_images_identical(a, b);
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
                      DeviceCase{"FogAMax", "cornell-box-fog.json", Method::AisMax, 3, true, kAll},
                      // 64 sets (masks past bit 31), one set (no extra items), edges alone
                      // (no component guided), and a frame smaller than one 16×16 tile.
                      DeviceCase{"Tile8AMax", "cornell-box.json", Method::AisMax, 8, true, kAll},
                      DeviceCase{"Tile1", "cornell-box.json", Method::Ais, 1, true, kAll},
                      DeviceCase{"EdgesOnly", "cornell-box.json", Method::Ais, 3, true, TS_COMPONENT_EDGE},
                      DeviceCase{"SmallTile8", "cornell-box.json", Method::AisMax, 8, true, kAll, 7, 9}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace tessera
