// The 16-lane gather of the clamp compensation (kernels/shared/clamp_screen16.h) against the
// one-pixel gather of kernels/shared/clamp_screen.h, which a device resolving an igi frame
// runs: for every lane, E_res bit for bit, over records whose surfaces point every way (so
// about a quarter of the pairs face each other), with pixels not seen and sources of zero,
// windows of every radius (a lane's last ring cut short at its own radius), lanes off,
// lanes past the image's right side, pixels at the image's edges and at odd columns, with
// and without a medium, and records that break the arithmetic: Inf and NaN sources, NaN
// positions, a record at the lane's own position (d = 0). Images through the host and the device are compared by
// tests/kernels/igi_resolve_test.cpp.
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "kernels/shared/clamp_screen16.h"

namespace tessera {
namespace {

constexpr int kW = 150, kH = 90;  // kW even and not a multiple of 32: a row's last lanes fall off
constexpr float kB = 4.0f;        // clamp radius 0.5, in a field of points 1 apart at most

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Random records as a device keeps them (TS_CLAMP_SCREEN_FLOATS a pixel) and as planes.
struct Field {
    std::vector<float> records, planes;
    ts::TsClampScreenPlanes view{};

    explicit Field(uint32_t seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        std::normal_distribution<float> n(0.0f, 1.0f);
        records.assign(size_t(TS_CLAMP_SCREEN_FLOATS) * kW * kH, 0.0f);
        planes.assign(ts::ts_clamp_planes_floats(kW, kH), 0.0f);
        view = {planes.data(), kW, kH, ts::ts_clamp_planes_pitch(kW)};
        const size_t field = ts::ts_clamp_planes_field(&view);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                float* r = &records[size_t(TS_CLAMP_SCREEN_FLOATS) * (size_t(y) * kW + x)];
                if (u(rng) < 0.9f) {  // else a pixel not seen: all zero
                    const float s = u(rng) < 0.1f ? 0.0f : u(rng);
                    const ts::float3 nq = ts::normalize(ts::make_float3(n(rng), n(rng), n(rng)));
                    const float f[TS_CLAMP_SCREEN_FLOATS] = {
                        0.3f * x / kW + 0.2f * u(rng), 0.2f * y / kH + 0.2f * u(rng), 0.2f * u(rng),
                        0.002f * u(rng), nq.x, nq.y, nq.z, s, 0.5f * s, 2.0f * s};
                    std::memcpy(r, f, sizeof f);
                    const float odd = u(rng);  // 2% each: a masked lane's term must not leak
                    if (odd < 0.02f) r[TS_CLAMP_SCREEN_COLD + TS_CLAMP_SCREEN_SOURCE + 1] = INFINITY;
                    else if (odd < 0.04f) r[TS_CLAMP_SCREEN_COLD + TS_CLAMP_SCREEN_SOURCE] = NAN;
                    else if (odd < 0.06f) r[TS_CLAMP_SCREEN_POSITION + 2] = NAN;
                    else if (odd < 0.08f && x >= 2) std::memcpy(r, r - 2 * TS_CLAMP_SCREEN_FLOATS, 3 * sizeof(float));
                }
                const size_t at = ts::ts_clamp_planes_at(&view, x, y);
                for (int k = 0; k < TS_CLAMP_SCREEN_FLOATS; ++k) planes[at + k * field] = r[k];
            }
    }

    ts::float3 position(int x, int y) const {
        return ts::ts_f3_load(&records[size_t(TS_CLAMP_SCREEN_FLOATS) * (size_t(y) * kW + x)]);
    }
    ts::float3 normal(int x, int y) const {
        return ts::ts_f3_load(&records[size_t(TS_CLAMP_SCREEN_FLOATS) * (size_t(y) * kW + x) + TS_CLAMP_SCREEN_COLD]);
    }
};

ts::TsMedium fog() {
    ts::TsMedium m{};
    m.sigma_s = ts::make_float3(0.5f, 0.5f, 0.5f);
    m.sigma_t = ts::make_float3(0.7f, 0.8f, 0.9f);  // not grey: three exps
    m.present = 1;
    return m;
}

// Lanes x0 + 2i of row y, each on where the pixel is in the image and `on` says, with a
// window radius drawn from [0, 64] (a third at the largest, 64); returns the lanes whose
// E_res is not zero, after checking each lane's against ts_clamp_screen_pixel's.
int check_lanes(const Field& f, std::mt19937& rng, int x0, int y, const ts::TsMedium* med, float on_share) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    ts::TsClampScreenLanes L;
    for (int i = 0; i < TS_CLAMP_LANES; ++i) {
        const int x = x0 + 2 * i;
        const bool in = x < kW && u(rng) < on_share;
        const ts::float3 p = in ? f.position(x, y) : ts::make_float3(0.0f, 0.0f, 0.0f);
        const ts::float3 n = in ? f.normal(x, y) : ts::make_float3(0.0f, 0.0f, 0.0f);
        L.p[0][i] = p.x, L.p[1][i] = p.y, L.p[2][i] = p.z;
        L.n[0][i] = n.x, L.n[1][i] = n.y, L.n[2][i] = n.z;
        L.r[i] = !in ? 0.0f : u(rng) < 0.33f ? TS_CLAMP_SCREEN_MAX_RADIUS : TS_CLAMP_SCREEN_MAX_RADIUS * u(rng);
        L.on[i] = in ? -1 : 0;
    }
    ts::ts_clamp_lanes_gather(&L, &f.view, x0, y, kB, med);
    int lit = 0;
    for (int i = 0; i < TS_CLAMP_LANES; ++i) {
        if (!L.on[i]) continue;
        const int x = x0 + 2 * i;
        const ts::float3 want =
            ts::ts_clamp_screen_pixel(x, y, kW, kH, f.position(x, y), f.normal(x, y), L.r[i], kB, med,
                                      f.records.data());
        const ts::float3 got = ts::make_float3(L.sum[0][i], L.sum[1][i], L.sum[2][i]) * 0.31830989f;
        EXPECT_TRUE(same_bits(got.x, want.x) && same_bits(got.y, want.y) && same_bits(got.z, want.z))
            << "pixel (" << x << ", " << y << "), r " << L.r[i] << ": lanes " << got.x << " " << got.y << " "
            << got.z << ", one pixel " << want.x << " " << want.y << " " << want.z;
        lit += got.x > 0.0f;
    }
    return lit;
}

class ClampScreen16 : public ::testing::TestWithParam<bool> {};

TEST_P(ClampScreen16, LanesEqualTheOnePixelGather) {
    const Field f(7u);
    const ts::TsMedium m = fog();
    const ts::TsMedium* med = GetParam() ? &m : nullptr;
    std::mt19937 rng(11u);
    int lit = 0, lanes = 0;
    // Every row's even grid, as the host runs it, then rows from odd columns (a pixel that
    // gathers itself at an edge runs as lane 0 from any column).
    for (int y = 0; y < kH; ++y)
        for (int x0 = 0; x0 < kW; x0 += 2 * TS_CLAMP_LANES, lanes += TS_CLAMP_LANES)
            lit += check_lanes(f, rng, x0, y, med, 0.9f);
    for (int y : {0, 1, kH / 2, kH - 1})
        for (int x0 : {1, 3, kW / 2 + 1, kW - 1}) lit += check_lanes(f, rng, x0, y, med, 0.9f);
    // Lanes that gather get light in most pixels: the comparison is not of zeros.
    EXPECT_GT(lit, lanes / 2);
}

INSTANTIATE_TEST_SUITE_P(Medium, ClampScreen16, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? "Fog" : "Clear"; });

// The planes' pads hold the columns the lanes read past the image's sides: the lanes' reads
// from the first and the last pixel of a row at the largest offsets stay in the buffer.
TEST(ClampScreen16Planes, PadsHoldTheLargestOffsets) {
    ts::TsClampScreenPlanes P{nullptr, kW, kH, ts::ts_clamp_planes_pitch(kW)};
    const int reach = int(TS_CLAMP_SCREEN_MAX_RADIUS);
    const int last = kW - 1 + 2 * (TS_CLAMP_LANES - 1) + reach;  // the last lane's reach from the last pixel
    for (int x : {-reach, 1 - reach, last - 1, last}) {
        const size_t row = ts::ts_clamp_planes_at(&P, x & 1, 0) - TS_CLAMP_PLANE_PAD;
        EXPECT_GE(ts::ts_clamp_planes_at(&P, x, 0), row) << x;
        EXPECT_LT(ts::ts_clamp_planes_at(&P, x, 0), row + size_t(P.pitch)) << x;
    }
    // The last field's odd plane ends in the buffer; its pads too.
    const size_t end = ts::ts_clamp_planes_at(&P, 1, kH - 1) - TS_CLAMP_PLANE_PAD + size_t(P.pitch) +
                       (TS_CLAMP_SCREEN_FLOATS - 1) * ts::ts_clamp_planes_field(&P);
    EXPECT_LE(end, ts::ts_clamp_planes_floats(kW, kH));
}

}  // namespace
}  // namespace tessera
