// kernels/shared/ic_gather.h and the gather sums of shared/vpl.h compiled as C++: a record's
// E and harmonic mean distance over the VPLs its row marks visible, and the compensated
// float sum that devices without doubles use in their place.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "kernels/shared/ic_gather.h"

namespace tessera {
namespace {

TEST(IcGather, SumsVisibleVplsAndTakesTheirHarmonicMeanDistance) {
    // A record at the origin facing +z; VPLs straight above at heights 1, 3 and 2 facing
    // down, weights C = 1, 2, 4; the third is occluded (its bit clear). G = 1/d² (both
    // cosines 1).
    const float g[TS_IC_GBUF_FLOATS] = {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1.0f, 0.0f, 1.0f};
    const ts::TsSurface s = ts::ts_ic_record_surface(g);
    std::vector<float> vpls;
    for (float h : {1.0f, 3.0f, 2.0f}) {
        const float c = h == 1.0f ? 1.0f : h == 3.0f ? 2.0f : 4.0f;
        vpls.insert(vpls.end(), {0, 0, h, 0, 0, -1, c, c, c, 0, 0, 1.0f});
    }
    const std::vector<uint32_t> row = {0b011u};  // bit j: VPL j visible
    const std::vector<float> no_medium(TS_MEDIUM_FLOATS, 0.0f);
    const ts::TsMedium med = ts::ts_medium_load(no_medium.data());
    float out[TS_IC_GATHER_FLOATS];
    ts::ts_ic_gather(&s, row.data(), 3, vpls.data(), &med, INFINITY, out);
    // The shadow ray ends just short of the VPL (t < 0.99999), the sum uses the true G.
    EXPECT_NEAR(out[TS_IC_GATHER_E], (1.0f + 2.0f / 9.0f) / M_PI, 1e-6);
    EXPECT_NEAR(out[TS_IC_GATHER_HARMONIC], 2.0f / (1.0f + 1.0f / 3.0f), 1e-5);
    // The clamp b bounds G: with b = 0.5 the first VPL contributes 0.5, not 1.
    ts::ts_ic_gather(&s, row.data(), 3, vpls.data(), &med, 0.5f, out);
    EXPECT_NEAR(out[TS_IC_GATHER_E], (0.5f + 2.0f / 9.0f) / M_PI, 1e-6);
    // No visible VPL: E = 0, distance +inf.
    const std::vector<uint32_t> none = {0u};
    ts::ts_ic_gather(&s, none.data(), 3, vpls.data(), &med, INFINITY, out);
    EXPECT_EQ(out[TS_IC_GATHER_E], 0.0f);
    EXPECT_EQ(out[TS_IC_GATHER_HARMONIC], INFINITY);
}

TEST(IcGather, CompensatedFloatSumKeepsWhatAPlainFloatSumLoses) {
    // 1 followed by 10^5 terms of 1e-8: each term is below half an ulp of the running
    // sum, so a plain float sum stays at 1 (error 1e-3). Neumaier's sum keeps every lost
    // part in its compensation c, itself summed in float: its error is 2ε|S| plus that of
    // a plain float sum of the lost parts, at most n·ε·|c| = 1e5 · 6e-8 · 1e-3 = 6e-6
    // (8.8e-7 measured), 170 times under the plain sum's.
    float plain = 1.0f, s = 1.0f, c = 0.0f;
    long double exact = 1.0L;
    for (int i = 0; i < 100000; ++i) {
        plain += 1e-8f;
        ts::ts_sum_compensated_add(&s, &c, 1e-8f);
        exact += static_cast<long double>(1e-8f);
    }
    EXPECT_EQ(plain, 1.0f);
    EXPECT_NEAR(s + c, static_cast<double>(exact), 6e-6);
    EXPECT_GT(std::fabs(plain - static_cast<double>(exact)), 5e-4);
}

TEST(IcGather, CompensatedAndDoubleGatherAgree) {
    // The two accumulators of shared/vpl.h over 5000 VPL terms spanning six orders of
    // magnitude: the float form (devices without doubles) must match the double form
    // (the C++ and fp64 devices) to a few float ulps.
    std::vector<float> vpl(TS_VPL_FLOATS, 0.0f);
    const ts::float3 tr = ts::make_float3(1.0f, 1.0f, 1.0f);  // no medium
    ts::TsSum3 f{};
    ts::TsDouble3 d{0, 0, 0};
    for (int i = 0; i < 5000; ++i) {
        const float w = std::pow(10.0f, -3.0f + 6.0f * float((i * 7919) % 5000) / 5000.0f);
        vpl[TS_VPL_FLUX] = w, vpl[TS_VPL_FLUX + 1] = 0.5f * w, vpl[TS_VPL_FLUX + 2] = 0.25f * w;
        ts::ts_vpl_gather_add_compensated(&f, vpl.data(), tr, 0.3f);
        ts::ts_vpl_gather_add_double(&d, vpl.data(), tr, 0.3f);
    }
    const ts::float3 a = ts::ts_vpl_gather_result_compensated(f), b = ts::ts_vpl_gather_result_double(d);
    EXPECT_NEAR(a.x, b.x, 4e-7 * b.x);
    EXPECT_NEAR(a.y, b.y, 4e-7 * b.y);
    EXPECT_NEAR(a.z, b.z, 4e-7 * b.z);
}

}  // namespace
}  // namespace tessera
