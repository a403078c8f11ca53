// The 16-lane link math of kernels/shared/igi_gather16.h, compiled as C++ with the Embree
// tracer's packet (an RTCRay16): for every lane, bit for bit what the shared one-pixel
// functions give (ts_light_contribution_from, ts_vpl_geometry, the gather terms), over lanes
// that face the link, face away, sit on the VPL itself (d = 0) or are hidden, with and
// without a medium, with the clamp on and off. No tracing (the functions only fill and
// read the packet), except ts_trace_occluded_ray_lanes, which traces a packet through the
// Cornell box. The whole gather is checked against the one-ray gather by the packet
// kernels' image tests (tests/backend/).
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "backend/embree_tracer.h"
#include "bvh/embree_scene.h"
#include "support/render_helpers.h"

// After the tracer.
#include "kernels/shared/igi.h"
#include "kernels/shared/igi_gather16.h"

namespace tessera {
namespace {

constexpr int kLanes = TS_PACKET_LANES;

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

ts::float3 unit(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    return ts::normalize(ts::make_float3(n(rng), n(rng), n(rng)));
}

// 16 surfaces in a unit box with random normals (so about half face a given point);
// lane 5 sits exactly at `at` (a VPL's position: d = 0).
std::vector<ts::TsSurface> surfaces(std::mt19937& rng, ts::float3 at) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<ts::TsSurface> s(kLanes);
    for (int i = 0; i < kLanes; ++i) {
        s[i] = ts::TsSurface{};
        s[i].position = i == 5 ? at : ts::make_float3(u(rng), u(rng), u(rng));
        s[i].geo_normal = unit(rng);
        s[i].shading_normal = ts::normalize(s[i].geo_normal + unit(rng) * 0.2f);
        s[i].pos_scale = 1.0f;
        s[i].origin = s[i].position;
    }
    return s;
}

ts::TsIgiLanes lanes_of(const std::vector<ts::TsSurface>& s) {
    ts::TsIgiLanes ls;
    for (int i = 0; i < kLanes; ++i) ts::ts_igi_lanes_set(&ls, i, &s[i]);
    return ls;
}

void expect_ray(const RTCRay16& r, int i, const ts::TsRay& want) {
    EXPECT_TRUE(same_bits(r.org_x[i], want.org.x) && same_bits(r.org_y[i], want.org.y) &&
                same_bits(r.org_z[i], want.org.z))
        << "lane " << i;
    EXPECT_TRUE(same_bits(r.dir_x[i], want.dir.x) && same_bits(r.dir_y[i], want.dir.y) &&
                same_bits(r.dir_z[i], want.dir.z))
        << "lane " << i;
    EXPECT_EQ(r.tnear[i], want.tmin);
    EXPECT_EQ(r.tfar[i], want.tmax);
}

// A VPL at (0.1, 0.2, 0.3) with normal +y, flux (2, 1, 0.5); in_medium: pos_scale < 0
// marks a medium VPL (layout_igi.h), its normal then being the light's propagation direction.
void make_vpl(float (&v)[TS_VPL_FLOATS], bool in_medium) {
    std::fill(std::begin(v), std::end(v), 0.0f);
    const float p[3] = {0.1f, 0.2f, 0.3f}, n[3] = {0.0f, 1.0f, 0.0f}, c[3] = {2.0f, 1.0f, 0.5f};
    std::copy(p, p + 3, v + TS_VPL_POSITION);
    std::copy(n, n + 3, v + TS_VPL_NORMAL);
    std::copy(c, c + 3, v + TS_VPL_FLUX);
    v[TS_VPL_POS_SCALE] = in_medium ? -1.0f : 1.0f;
}

TEST(IgiGather16, VplLinksEqualTheSharedGeometryTermPerLane) {
    std::mt19937 rng(3);
    for (bool in_medium : {false, true})
        for (float b : {0.5f, std::numeric_limits<float>::infinity()}) {
            float vpl[TS_VPL_FLOATS];
            make_vpl(vpl, in_medium);
            const auto s = surfaces(rng, ts::make_float3(vpl[0], vpl[1], vpl[2]));
            const ts::TsIgiLanes ls = lanes_of(s);
            ts::TsRayLanes r;
            ts::TsIgiLinkLanes L;
            for (int i = 0; i < kLanes; ++i) L.in_id[i] = i % 4 == 3 ? 0 : -1;  // lanes 3, 7, ... take no part
            ts::ts_igi_lanes_vpl_links(&ls, vpl, b, 0.7f, &L, &r);
            const float* g = L.g;
            const int* in = L.in_id;
            const int* traced = L.traced;
            int facing = 0;
            for (int i = 0; i < kLanes; ++i) {
                ts::TsRay want;
                const float gw = ts::ts_vpl_geometry(&s[i], vpl, b, 0.7f, &want);
                EXPECT_TRUE(same_bits(g[i], gw)) << "lane " << i << ": " << g[i] << " vs " << gw;
                EXPECT_EQ(traced[i], gw > 0.0f && in[i] ? -1 : 0) << "lane " << i;
                expect_ray(r, i, want);
                facing += gw > 0.0f;
            }
            EXPECT_EQ(g[5], 0.0f) << "a surface at the VPL itself gets nothing";
            EXPECT_GT(facing, 0);
            EXPECT_LT(facing, kLanes - 1);
        }
}

// A light triangle facing -y in the plane y = 0.9, centred over the origin, of edge
// `size`, with radiance (10, 8, 6); and a sample of it at (u, v) = (0.4, 0.6).
struct TestLight {
    std::array<float, TS_LIGHT_FLOATS> lights{};
    std::array<float, 1> cdf{1.0f};
    ts::TsLightSample q;

    explicit TestLight(float size) {
        const float p0[3] = {-size / 3, 0.9f, -size / 3}, e1[3] = {size, 0.0f, 0.0f}, e2[3] = {0.0f, 0.0f, size};
        const float le[3] = {10.0f, 8.0f, 6.0f};
        std::copy(p0, p0 + 3, lights.begin() + TS_LIGHT_P0);
        std::copy(e1, e1 + 3, lights.begin() + TS_LIGHT_E1);
        std::copy(e2, e2 + 3, lights.begin() + TS_LIGHT_E2);
        std::copy(le, le + 3, lights.begin() + TS_LIGHT_RADIANCE);
        lights[TS_LIGHT_AREA] = 0.5f * size * size;
        q = ts::ts_sample_light(lights.data(), cdf.data(), 1u, 0.3f, 0.4f, 0.6f);
    }
};

// Lanes far from the light (a 0.02 triangle) share q's point; near it (a 3-unit triangle
// over the whole box) each lane draws its own in solid angle. Either way every lane gets
// ts_light_contribution_from's contribution and ray, bit for bit.
TEST(IgiGather16, LightLinksEqualTheSharedContributionPerLane) {
    for (float size : {0.02f, 3.0f}) {
        std::mt19937 rng(5);
        const TestLight light(size);
        const auto s = surfaces(rng, ts::make_float3(0.0f, 0.0f, 0.0f));
        const ts::TsIgiLanes ls = lanes_of(s);
        ts::TsRayLanes r;
        ts::TsIgiLinkLanes L;
        for (int i = 0; i < kLanes; ++i) L.in_ss[i] = i == 6 ? 0 : -1;  // lane 6 takes no part
        ts::ts_igi_lanes_light_links(light.lights.data(), &ls, light.q, &L, &r);
        const auto& c = L.c;
        const int* in = L.in_ss;
        const int* traced = L.traced;
        int lit = 0, drawn_in_solid_angle = 0;
        for (int i = 0; i < kLanes; ++i) {
            ts::TsRay want;
            const ts::float3 cw = ts::ts_light_contribution_from(light.lights.data(), &s[i], light.q, &want);
            EXPECT_TRUE(same_bits(c[0][i], cw.x) && same_bits(c[1][i], cw.y) && same_bits(c[2][i], cw.z))
                << "lane " << i;
            EXPECT_EQ(traced[i], ts::ts_igi_light_link_traced(cw) && in[i] ? -1 : 0) << "lane " << i;
            expect_ray(r, i, want);
            lit += traced[i] != 0;
            drawn_in_solid_angle +=
                ts::ts_light_sample_from(light.lights.data(), light.q, s[i].position).inv_pdf_solid_angle > 0.0f;
        }
        EXPECT_GT(lit, 0);
        EXPECT_LT(lit, kLanes);
        if (size > 1.0f)
            EXPECT_GT(drawn_in_solid_angle, kLanes / 2);
        else
            EXPECT_EQ(drawn_in_solid_angle, 0);
    }
}

// Sums after two VPLs and two light samples with a fixed visibility pattern equal the
// one-pixel gather (ts_igi_gather_add) of the visible links, bit for bit; hidden lanes'
// sums do not move, and the light samples traced (faced) and seen are counted.
void expect_gather_equals_one_pixel_gather(const ts::TsMedium& med) {
    std::mt19937 rng(7);
    float vpl[TS_VPL_FLOATS];
    make_vpl(vpl, false);
    const auto s = surfaces(rng, ts::make_float3(vpl[0], vpl[1], vpl[2]));
    ts::TsIgiLanes ls = lanes_of(s);
    ts::TsSceneView sv{};
    sv.vpls = vpl;
    std::vector<ts::TsIgiGather> want(kLanes, ts::ts_igi_gather_begin());
    const TestLight light(0.02f);
    const ts::TsLightSample q = light.q;
    for (int round = 0; round < 2; ++round) {
        ts::TsRayLanes r;
        ts::TsIgiLinkLanes L;
        std::fill(std::begin(L.in_id), std::end(L.in_id), -1);
        std::fill(std::begin(L.in_ss), std::end(L.in_ss), -1);
        ts::ts_igi_lanes_vpl_links(&ls, vpl, 0.5f, 0.0f, &L, &r);
        for (int i = 0; i < kLanes; ++i) L.visible[i] = L.g[i] > 0.0f && (i + round) % 3 != 0 ? -1 : 0;
        ts::ts_igi_lanes_vpl_gather(&ls, vpl, &L, &med, &r);
        const int* visible = L.visible;
        for (int i = 0; i < kLanes; ++i) {
            if (!visible[i]) continue;
            ts::TsIgiLink l;
            l.vpl = 0;
            l.g = ts::ts_vpl_geometry(&s[i], vpl, 0.5f, 0.0f, &l.shadow);
            ts::ts_igi_gather_add(&want[i], &sv, &med, &l);
        }
        ts::ts_igi_lanes_light_links(light.lights.data(), &ls, q, &L, &r);
        for (int i = 0; i < kLanes; ++i) L.visible[i] = L.traced[i] && (i + round) % 4 != 1 ? -1 : 0;
        if (round == 1) L.traced[5] = L.visible[5] = 0;  // a lane that does not face the sample
        ts::ts_igi_lanes_light_gather(&ls, &L, &med, &r);
        for (int i = 0; i < kLanes; ++i) {
            want[i].facing += L.traced[i] ? 1u : 0u;  // as ts_igi_surface_set counts them
            if (!visible[i]) continue;
            ts::TsIgiLink l;
            l.vpl = TS_NO_HIT;
            l.c = ts::ts_light_contribution_from(light.lights.data(), &s[i], q, &l.shadow);
            ts::ts_igi_gather_add(&want[i], &sv, &med, &l);
        }
    }
    int any = 0, blocked = 0;
    for (int i = 0; i < kLanes; ++i) {
        EXPECT_TRUE(same_bits(ls.id[0][i], want[i].id.x) && same_bits(ls.id[1][i], want[i].id.y) &&
                    same_bits(ls.id[2][i], want[i].id.z))
            << "lane " << i << " E_id " << ls.id[0][i] << " vs " << want[i].id.x;
        EXPECT_TRUE(same_bits(ls.ss[0][i], want[i].ss.x) && same_bits(ls.ss[1][i], want[i].ss.y) &&
                    same_bits(ls.ss[2][i], want[i].ss.z))
            << "lane " << i << " E_ss " << ls.ss[0][i] << " vs " << want[i].ss.x;
        EXPECT_EQ(ls.seen[i], want[i].seen) << "lane " << i;
        EXPECT_EQ(ls.facing[i], want[i].facing) << "lane " << i;
        any += want[i].id.x > 0.0f && want[i].ss.x > 0.0f;
        blocked += want[i].facing > want[i].seen;
    }
    EXPECT_GT(any, 0) << "the pattern must leave some lanes with both sums";
    EXPECT_GT(blocked, 0) << "... and some with samples faced but blocked";
    EXPECT_EQ(want[5].facing, 1u) << "lane 5 faces one of the two samples";
}

// The visibility AIS's SS guidance reads: the fraction of the m light samples not blocked,
// a sample behind the surface's plane counting as not blocked (it is no shadow).
TEST(IgiGather, VisibilityIsTheFractionOfSamplesNotBlocked) {
    TsFrame f{};
    f.shadow_samples = 4;
    ts::float3 e_ss, e_id;
    float visible = -1.0f;
    ts::TsIgiGather g = ts::ts_igi_gather_begin();
    ts::ts_igi_gather_end(&g, &f, &e_ss, &e_id, &visible);
    EXPECT_EQ(visible, 1.0f) << "facing no sample: no shadow";
    g.facing = 2, g.seen = 2;
    ts::ts_igi_gather_end(&g, &f, &e_ss, &e_id, &visible);
    EXPECT_EQ(visible, 1.0f) << "both faced samples visible, two behind the plane";
    g.facing = 1, g.seen = 0;
    ts::ts_igi_gather_end(&g, &f, &e_ss, &e_id, &visible);
    EXPECT_EQ(visible, 0.75f) << "the one faced sample blocked";
    g.facing = 4, g.seen = 1;
    ts::ts_igi_gather_end(&g, &f, &e_ss, &e_id, &visible);
    EXPECT_EQ(visible, 0.25f);
    g.facing = 4, g.seen = 0;
    ts::ts_igi_gather_end(&g, &f, &e_ss, &e_id, &visible);
    EXPECT_EQ(visible, 0.0f) << "umbra";
}

// The packet's answers are the single rays' (ts_trace_occluded) for the traced lanes, in
// both packet modes; untraced lanes come back not visible.
TEST(IgiGather16, OcclusionEqualsSingleRays) {
    const Scene scene = test::cornell_box();
    const SceneBuffers buffers = make_scene_buffers(scene);
    ts::TsTracer tracer{};
    tracer.scene = build_embree_scene(buffers);
    const SceneBounds& box = buffers.bounds;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.02f, 0.98f);
    auto inside = [&] {
        return ts::make_float3(box.lo.x + u(rng) * (box.hi.x - box.lo.x), box.lo.y + u(rng) * (box.hi.y - box.lo.y),
                               box.lo.z + u(rng) * (box.hi.z - box.lo.z));
    };
    int blocked = 0, open = 0;
    for (int round = 0; round < 8; ++round) {
        ts::TsRayLanes r;
        ts::ts_ray_lanes_init(&r);
        ts::TsIgiLinkLanes L;
        int* traced = L.traced;
        int* visible = L.visible;
        std::array<ts::TsRay, kLanes> rays;
        for (int i = 0; i < kLanes; ++i) {
            rays[i].org = inside();
            rays[i].dir = inside() - rays[i].org;
            rays[i].tmin = 0.0f;
            rays[i].tmax = 1.0f;
            ts::ts_ray_lanes_put(&r, i, rays[i]);
            traced[i] = (i + round) % 5 == 0 ? 0 : -1;
        }
        tracer.coherent = round % 2 == 0;
        ts::ts_trace_occluded_ray_lanes(&tracer, &r, traced, visible);
        for (int i = 0; i < kLanes; ++i) {
            const bool hidden = ts::ts_trace_occluded(&tracer, rays[i]);
            EXPECT_EQ(visible[i], traced[i] && !hidden ? -1 : 0) << "round " << round << ", lane " << i;
            blocked += traced[i] && hidden;
            open += traced[i] && !hidden;
        }
    }
    rtcReleaseScene(tracer.scene);
    EXPECT_GT(blocked, 5) << "the short and tall blocks should stop some rays";
    EXPECT_GT(open, 5);
}

TEST(IgiGather16, GatherWithoutMediumEqualsOnePixelGather) {
    ts::TsMedium none{};
    expect_gather_equals_one_pixel_gather(none);
}

TEST(IgiGather16, GatherInFogEqualsOnePixelGather) {
    ts::TsMedium fog{};
    fog.present = 1;
    fog.sigma_s = ts::make_float3(0.5f, 0.6f, 0.7f);
    fog.sigma_t = ts::make_float3(0.8f, 0.9f, 1.0f);
    expect_gather_equals_one_pixel_gather(fog);
}

}  // namespace
}  // namespace tessera
