// host/bvh/embree_device.h: FtzDazScope sets flush-to-zero and denormals-are-zero for its
// lifetime only, so an Embree render leaves the calling thread's float mode as it was (it
// once stayed set, and host code after the kernels then read denormals as zero).
#include "bvh/embree_device.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include "support/render_helpers.h"

namespace tessera {
namespace {

constexpr unsigned kFtzDaz = _MM_FLUSH_ZERO_ON | _MM_DENORMALS_ZERO_ON;

// A denormal read under denormals-are-zero compares equal to 0.
bool denormals_read_as_zero() {
    volatile float tiny = std::numeric_limits<float>::denorm_min();
    return tiny == 0.0f;
}

TEST(FtzDazScope, SetsTheModeForItsLifetimeAndRestoresIt) {
    const unsigned before = _mm_getcsr();
    ASSERT_EQ(before & kFtzDaz, 0u) << "the test thread starts in IEEE mode";
    {
        const FtzDazScope scope;
        EXPECT_EQ(_mm_getcsr() & kFtzDaz, kFtzDaz);
        EXPECT_TRUE(denormals_read_as_zero());
    }
    EXPECT_EQ(_mm_getcsr(), before);
    EXPECT_FALSE(denormals_read_as_zero());
}

TEST(FtzDazScope, AnEmbreeRenderLeavesTheCallingThreadInIeeeMode) {
    RenderSettings rs;
    rs.method = Method::Ais;
    rs.width = rs.height = 16;
    rs.spp = 1;
    const Image img = test::render_with(BackendKind::Embree, test::cornell_box(), rs);
    ASSERT_GT(img.width, 0);
    EXPECT_EQ(_mm_getcsr() & kFtzDaz, 0u);
    EXPECT_FALSE(denormals_read_as_zero());
}

}  // namespace
}  // namespace tessera
