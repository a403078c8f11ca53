// kernels/shared/igi_march16.h ts_igi_march_vpl_links16 and ts_igi_march_vrl_links16: the
// VPL and ray-light links of 16 marches at once must be ts_igi_march_vpl_link's and
// ts_igi_march_vrl_link's, lane by lane, bit for bit: which lanes link, and each linked
// lane's weight, tint and shadow ray. Whole foggy images are compared with the
// one-ray march in tests/backend/media_packets_test.cpp; this test reaches the cases those
// images rarely hold: a VPL on a lane's camera ray (d = 0 at the link's point), VPLs
// facing away, medium VPLs with and without ray lights, equiangular points near the VPL
// and the step's own point far from it, NaN and infinite VPLs, lanes left out (holding NaNs); ray lights
// crossing a lane's camera ray, passing near it or far, with NaN ends or no length.
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

// The tracer first (embree_tracer.h): the shared code calls it.
#include "backend/embree_tracer.h"
#include "kernels/shared/igi_march16.h"

namespace tessera {
namespace {

using ts::float3;
using ts::make_float3;

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(float3 a, float3 b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z); }

ts::TsMedium fog() {
    const float buf[TS_MEDIUM_FLOATS] = {0.1f, 0.1f, 0.1f, 0.5f, 0.5f, 0.5f, 0.3f, 0.0f,
                                         0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f};
    return ts::ts_medium_load(buf);
}

float3 unit(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    return ts::normalize(make_float3(n(rng), n(rng), n(rng)));
}

// A VPL at y: a surface VPL facing n, or (medium) a medium VPL whose light travelled along n.
std::vector<float> vpl_at(float3 y, float3 n, bool medium) {
    std::vector<float> v(TS_VPL_FLOATS, 0.0f);
    ts::ts_f3_store(v.data() + TS_VPL_POSITION, y);
    ts::ts_f3_store(v.data() + TS_VPL_NORMAL, n);
    ts::ts_f3_store(v.data() + TS_VPL_FLUX, make_float3(1.0f, 1.0f, 1.0f));
    v[TS_VPL_POS_SCALE] = medium ? -1.0f : 4.0f;
    return v;
}

// The lanes' answer (`lanes`, and s's weights, tints and shadow rays) against the one-lane
// link one_lane(l, &shadow, &w, &tint) of every lane of `in`, bit for bit. Returns the
// lanes that link; adds to the counts.
template <class OneLane>
uint32_t expect_lanes_are(const ts::TsMarchStep& s, uint32_t in, uint32_t lanes, OneLane one_lane, int round,
                          int* linked, int* unlinked) {
    EXPECT_EQ(lanes & ~in, 0u);
    uint32_t ones = 0;
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        if (!(in >> l & 1u)) continue;
        ts::TsRay shadow{};
        float w = 0.0f;
        float3 tint = make_float3(0.0f, 0.0f, 0.0f);
        const bool one = one_lane(l, &shadow, &w, &tint);
        EXPECT_EQ((lanes >> l & 1u) != 0, one) << "round " << round << " lane " << l;
        if (!one || !(lanes >> l & 1u)) {
            *unlinked += !one;
            continue;
        }
        ++*linked;
        ones |= 1u << l;
        EXPECT_TRUE(same_bits(s.w[l], w)) << "round " << round << " lane " << l << ": " << s.w[l] << " " << w;
        EXPECT_TRUE(same_bits(s.tint[l], tint)) << "round " << round << " lane " << l;
        EXPECT_TRUE(same_bits(s.shadow[l].org, shadow.org) && same_bits(s.shadow[l].dir, shadow.dir) &&
                    same_bits(s.shadow[l].tmin, shadow.tmin) && same_bits(s.shadow[l].tmax, shadow.tmax))
            << "round " << round << " lane " << l;
    }
    return ones;
}

// 16 marches with random cameras and steps, as the march has them at a step; the lanes
// outside `in` hold NaNs and no step, which the lanes' functions must not read.
void random_marches(std::mt19937& rng, const ts::TsMedium& med, bool equiangular, uint32_t in, ts::TsIgiMarch* m,
                    ts::TsMarchStep* s) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float nan = std::nanf("");
    for (int l = 0; l < TS_PACKET_LANES; ++l) {
        ts::TsIgiMarch& ml = m[l];
        std::memset(&ml, 0, sizeof ml);
        ml.ray.org = make_float3(4.0f * u(rng) - 2.0f, 4.0f * u(rng) - 2.0f, 4.0f * u(rng) - 2.0f);
        ml.ray.dir = unit(rng);
        ml.ray.tmax = ts::TS_INF;
        ml.t0 = u(rng);
        ml.t1 = ml.t0 + 0.5f + 4.0f * u(rng);
        ml.step = (ml.t1 - ml.t0) / 8.0f;
        ml.active = 1;
        ml.equiangular = equiangular;
        ml.key = uint32_t(rng());
        s->t[l] = ml.t0 + (ml.t1 - ml.t0) * u(rng);
        if (in >> l & 1u) {
            ts::ts_igi_march_step_begin(&ml, &med, s->t[l]);
        } else {
            ml.ray.org = ml.ray.dir = make_float3(nan, nan, nan);
            ml.t0 = ml.t1 = ml.step = s->t[l] = nan;
        }
    }
}

TEST(IgiMarch16, VplLinksEqualTheOneLaneLinkBitForBit) {
    const ts::TsMedium med = fog();
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int linked = 0, unlinked = 0, near_points = 0;
    for (int round = 0; round < 3000; ++round) {
        TsFrame f{};
        f.igi_g_clamp = round % 7 == 0 ? 1e30f : 0.5f + 4.0f * u(rng);
        f.igi_media_vpls = round % 3 == 0 ? TS_MEDIA_VPLS_RAYS : 1u;
        const bool equiangular = round % 4 != 3;
        ts::TsIgiMarch m[TS_PACKET_LANES];
        ts::TsMarchStep s;
        const uint32_t in = round % 5 == 4 ? uint32_t(rng()) & 0xfffeu : 0xffffu;  // lane 0 in: the VPL is by it
        random_marches(rng, med, equiangular, in, m, &s);
        // The VPL: near lane 0's camera ray (an equiangular point drawn toward it) or far
        // from every ray, sometimes exactly at lane 0's step point, or not a number.
        const int kind = int(rng() % 8);
        float3 y = make_float3(6.0f * u(rng) - 3.0f, 6.0f * u(rng) - 3.0f, 6.0f * u(rng) - 3.0f);
        if (kind <= 2) y = m[0].ray.org + m[0].ray.dir * s.t[0] + unit(rng) * (0.05f * u(rng));
        if (kind == 3) y = m[0].ray.org + m[0].ray.dir * s.t[0];
        if (kind == 4) y.y = rng() % 2 ? std::nanf("") : INFINITY;
        const std::vector<float> vpl = vpl_at(y, unit(rng), rng() % 3 == 0);
        const uint32_t lanes = ts::ts_igi_march_vpl_links16(&f, &med, m, in, vpl.data(), &s);
        const auto one_lane = [&](int l, ts::TsRay* shadow, float* w, float3* tint) {
            return ts::ts_igi_march_vpl_link(&f, &med, &m[l], s.t[l], vpl.data(), shadow, w, tint) != 0;
        };
        const uint32_t ones = expect_lanes_are(s, in, lanes, one_lane, round, &linked, &unlinked);
        float b = 0.0f, eq;
        ts::ts_igi_march_vpl_clamp(&f, vpl.data(), &b);
        for (int l = 0; l < TS_PACKET_LANES; ++l)
            if (ones >> l & 1u)
                near_points += ts::ts_igi_march_toward(&m[l], y, 1.0f / std::sqrt(b), s.t[l], &eq) != s.t[l];
    }
    EXPECT_GT(linked, 10000);  // both answers, and equiangular points, were seen many times
    EXPECT_GT(unlinked, 10000);
    EXPECT_GT(near_points, 300);
}

TEST(IgiMarch16, RayLightLinksEqualTheOneLaneLinkBitForBit) {
    const ts::TsMedium med = fog();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int linked = 0, unlinked = 0;
    for (int round = 0; round < 3000; ++round) {
        TsFrame f{};
        f.seed = uint32_t(rng());
        f.pass = round;
        ts::TsIgiMarch m[TS_PACKET_LANES];
        ts::TsMarchStep s;
        const uint32_t in = round % 5 == 4 ? uint32_t(rng()) & 0xfffeu : 0xffffu;  // lane 0 in: the ray light is by it
        random_marches(rng, med, round % 4 != 3, in, m, &s);
        // The ray light: through lane 0's step point, near lane 0's camera ray or anywhere;
        // sometimes with a NaN start or no length.
        const int kind = int(rng() % 8);
        float3 start = make_float3(6.0f * u(rng) - 3.0f, 6.0f * u(rng) - 3.0f, 6.0f * u(rng) - 3.0f);
        const float3 omega = unit(rng);
        float length = 0.1f + 5.0f * u(rng);
        const float3 p0 = m[0].ray.org + m[0].ray.dir * s.t[0];
        if (kind == 0) start = p0 - omega * (length * u(rng));
        if (kind <= 2 && kind > 0) start = p0 + unit(rng) * (0.1f * u(rng)) - omega * (length * u(rng));
        if (kind == 3) start.z = std::nanf("");
        if (kind == 4) length = rng() % 2 ? 0.0f : std::nanf("");
        std::vector<float> vrl(TS_VRL_FLOATS, 0.0f);
        ts::ts_f3_store(vrl.data() + TS_VRL_START, start);
        ts::ts_f3_store(vrl.data() + TS_VRL_DIR, omega);
        ts::ts_f3_store(vrl.data() + TS_VRL_FLUX, make_float3(1.0f, 1.0f, 1.0f));
        vrl[TS_VRL_LENGTH] = length;
        const uint32_t j = uint32_t(rng() % 1000);
        const float stride = float(1 + rng() % 64);
        const uint32_t lanes = ts::ts_igi_march_vrl_links16(&f, &med, m, in, j, stride, vrl.data(), &s);
        const auto one_lane = [&](int l, ts::TsRay* shadow, float* w, float3* tint) {
            return ts::ts_igi_march_vrl_link(&med, &m[l], s.t[l], ts::ts_igi_vrl_u(&f, &m[l], j), stride, vrl.data(),
                                             shadow, w, tint) != 0;
        };
        expect_lanes_are(s, in, lanes, one_lane, round, &linked, &unlinked);
    }
    EXPECT_GT(linked, 20000);
    EXPECT_GT(unlinked, 3000);
}

}  // namespace
}  // namespace tessera
