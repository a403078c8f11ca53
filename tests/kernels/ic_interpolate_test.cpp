// The interpolation kernel (KernelId::IcInterpolate, ts_ic_interpolate_kernel_pixel in
// kernels/shared/ic.h) on both backends: a pixel's E, Σ w and clamp residual do not depend
// on the order the work items take the pixels. InstantCache::indirect launches it in row
// order (igi_tile = 1), which keeps neighbouring pixels' octree walks in cache, while igi's
// pixel kernels de-interleave the items by sample set; the images must not change with it.
#include <cstring>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "gi/irradiance_cache.h"
#include "support/ic_test_frame.h"

namespace tessera {
namespace {

std::vector<float> interpolate(Backend& backend, const IcCacheBuffers& flat, const std::vector<float>& gbuffer,
                               TsFrame frame, uint32_t order_tile) {
    backend.set_input(KernelInput::IcGbuffer, gbuffer);
    backend.set_input(KernelInput::IcNodes, flat.nodes);
    backend.set_input(KernelInput::IcRefs, flat.refs);
    backend.set_input(KernelInput::IcRecords, flat.records);
    frame.igi_tile = order_tile;
    std::vector<float> out;
    backend.launch(KernelId::IcInterpolate, frame, out);
    return out;
}

TEST(IcInterpolateKernel, APixelsOutputDoesNotDependOnTheWorkItemOrder) {
    test::IcTestFrame f;  // frame 12 of the animated Cornell box, 40², its cache built on Embree
    IrradianceCache cache = f.settings.ic_state->pass(0).cache();
    const IcCacheBuffers& flat = cache.buffers();
    const std::vector<float>& gbuffer = f.settings.ic_state->gbuffer();
    const size_t pixels = size_t(f.settings.width) * f.settings.height;
    ASSERT_EQ(gbuffer.size(), pixels * TS_IC_GBUF_FLOATS);
    TsFrame frame = make_render_frame(f.scene.camera, f.settings.width, f.settings.height, f.buffers, f.settings);
    frame.pass = 0;
    frame.ic_error_bound = cache.error_bound();
    frame.igi_g_clamp = 0.5f;  // finite: the residual's rays run (G reaches ~10² in the box's corners)
    auto opencl = make_backend({BackendKind::OpenCL, ""}, f.buffers, f.plan);
    for (Backend* backend : {f.embree.get(), opencl.get()}) {
        const std::vector<float> rows = interpolate(*backend, flat, gbuffer, frame, 1);
        size_t covered = 0, with_residual = 0;
        for (uint32_t tile : {2u, 3u, 4u}) {
            const std::vector<float> sets = interpolate(*backend, flat, gbuffer, frame, tile);
            ASSERT_EQ(sets.size(), rows.size());
            EXPECT_EQ(std::memcmp(sets.data(), rows.data(), rows.size() * sizeof(float)), 0)
                << backend->description() << ", tile " << tile;
        }
        for (size_t p = 0; p < pixels; ++p) {
            const float* o = &rows[p * TS_IC_INTERP_FLOATS];
            covered += o[TS_IC_INTERP_WEIGHT] > 0.0f;
            with_residual += o[TS_IC_INTERP_RESIDUAL] + o[TS_IC_INTERP_RESIDUAL + 1] + o[TS_IC_INTERP_RESIDUAL + 2] > 0.0f;
        }
        // The comparison has something to compare: most pixels lie under records, and the
        // clamp's residual is nonzero at many (the box's corners and the cube's edges).
        EXPECT_GT(covered, pixels / 2) << backend->description();
        EXPECT_GT(with_residual, pixels / 20) << backend->description();
    }
}

}  // namespace
}  // namespace tessera
