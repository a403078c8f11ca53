// The Embree backend's 16-record gather (host/backend/embree_ic_gather.cpp, through the
// shared ts_ic_gather16) against the one-record gather ts_ic_gather, on the records, VPLs
// and visibility rows of one frame of the animated Cornell box: every output must be
// equal bit for bit, for item lists whose length is not a multiple of 16, with records
// repeated and out of order, with rows that see no VPL, and in media.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "backend/embree_ic_gather.h"
#include "bvh/embree_device.h"
#include "kernels/shared/ic_gather.h"
#include "support/ic_test_frame.h"

namespace tessera {
namespace {

// The gathers of the frame's records with the given VPLs and medium (TS_MEDIUM_FLOATS),
// the 16-record gather against the one-record one. Items: every record with its own row,
// then 37 drawn at random (records repeated, rows not their own), so the last batch is
// part-full. Returns the 16-record outputs; `seen_none` counts items with an empty row.
class LanesAgainstOneRecord {
public:
    static constexpr float kBound = 0.5f;  // bounds some geometry terms: the clamp's select runs

    LanesAgainstOneRecord() {
        const std::vector<IcRecord>& records = frame_.records();
        nv_ = static_cast<uint32_t>(frame_.vpl_count());
        words_ = TS_IC_VISIBLE_WORDS(nv_);
        std::vector<uint32_t> pairs, hits;
        frame_.trace_all_pairs(kBound, pairs, hits, rows_);
        for (size_t i = 0; i < records.size(); i += 5) std::fill(&rows_[i * words_], &rows_[i * words_] + words_, 0u);
        for (uint32_t r = 0; r < records.size(); ++r) items_.insert(items_.end(), {r, r});
        std::mt19937 rng(7);
        for (int k = 0; k < 37; ++k)
            items_.insert(items_.end(), {static_cast<uint32_t>(rng() % records.size()),
                                         static_cast<uint32_t>(rng() % records.size())});
        for (const IcRecord& r : records) surfaces_.insert(surfaces_.end(), r.surface.begin(), r.surface.end());
    }

    size_t records() const { return frame_.records().size(); }
    const std::vector<float>& vpls() const { return frame_.vpls(); }
    size_t count() const { return items_.size() / TS_IC_GATHER_WORDS; }

    std::vector<float> run(const std::vector<float>& vpls, const std::vector<float>& medium, size_t& seen_none) const {
        const uint32_t set_start[2] = {0, nv_};
        ts::TsSceneView sv{};
        sv.medium = medium.data();
        sv.vpls = vpls.data();
        sv.vpl_set_start = set_start;
        sv.ic_record_surfaces = surfaces_.data();
        sv.ic_visibility = rows_.data();
        sv.items = items_.data();
        TsFrame f{};
        f.igi_g_clamp = kBound;
        std::vector<float> lanes(count() * TS_IC_GATHER_FLOATS);
        ic_gather_lanes(sv, f, count(), lanes);

        const ts::TsMedium med = ts::ts_medium_load(medium.data());
        seen_none = 0;
        for (size_t k = 0; k < count(); ++k) {
            const uint32_t* item = &items_[k * TS_IC_GATHER_WORDS];
            const ts::TsSurface surf =
                ts::ts_ic_record_surface(&surfaces_[size_t(item[TS_IC_GATHER_RECORD]) * TS_IC_GBUF_FLOATS]);
            float one[TS_IC_GATHER_FLOATS];
            {
                const FtzDazScope ftz;  // as the backend's dispatch runs both
                ts::ts_ic_gather(&surf, &rows_[item[TS_IC_GATHER_ROW] * words_], nv_, vpls.data(), &med, kBound, one);
                // ts_ic_gather's sums with the slab test on every link: both gathers skip
                // it where a link's ends lie in the medium, which must not change a bit.
                float slab[TS_IC_GATHER_FLOATS];
                slab_test_gather(surf, &rows_[item[TS_IC_GATHER_ROW] * words_], vpls, med, slab);
                EXPECT_EQ(std::memcmp(one, slab, sizeof one), 0) << "item " << k << ": E " << one[TS_IC_GATHER_E]
                                                                 << " vs the slab test's " << slab[TS_IC_GATHER_E];
            }
            seen_none += std::isinf(one[TS_IC_GATHER_HARMONIC]);
            EXPECT_EQ(std::memcmp(one, &lanes[k * TS_IC_GATHER_FLOATS], sizeof one), 0)
                << "item " << k << ": E " << one[TS_IC_GATHER_E] << " vs "
                << lanes[k * TS_IC_GATHER_FLOATS + TS_IC_GATHER_E] << ", harmonic " << one[TS_IC_GATHER_HARMONIC]
                << " vs " << lanes[k * TS_IC_GATHER_FLOATS + TS_IC_GATHER_HARMONIC];
        }
        return lanes;
    }

private:
    // ts_ic_gather written out, each link's transmittance from the slab test itself.
    void slab_test_gather(const ts::TsSurface& s, const uint32_t* row, const std::vector<float>& vpls,
                          const ts::TsMedium& med, float* out) const {
        ts::TsDouble3 sum = {0.0, 0.0, 0.0};
        double inv_dist = 0.0;
        uint32_t seen = 0;
        const ts::float3 org = ts::ts_offset_ray_origin(s.origin, s.geo_normal, s.pos_scale);
        for (uint32_t j = 0; j < nv_; ++j) {
            if (!(row[j >> 5] >> (j & 31u) & 1u)) continue;
            const float* v = &vpls[size_t(j) * TS_VPL_FLOATS];
            const float g = ts::ts_vpl_geometry_term(s.position, s.shading_normal, s.geo_normal, v, kBound, med.g);
            if (!(g > 0.0f)) continue;
            const ts::TsRay ray = ts::ts_vpl_shadow_ray(org, v);
            const ts::float3 tr = ts::ts_medium_transmittance(&med, ray.org, ray.dir, ray.tmin, ray.tmax);
            const ts::float3 d = ts::ts_f3_load(v + TS_VPL_POSITION) - s.position;
            ts::ts_vpl_gather_add_double(&sum, v, tr, g);
            inv_dist += 1.0 / std::sqrt(double(ts::dot(d, d)));
            ++seen;
        }
        ts::ts_ic_gather_store_double(out, sum, inv_dist, seen);
    }

    const test::IcTestFrame frame_;
    uint32_t nv_ = 0;
    size_t words_ = 0;
    std::vector<uint32_t> rows_, items_;
    std::vector<float> surfaces_;
};

// A medium buffer (layout_scene.h): box min/max in scene units; an empty box for none
// bounding it (the medium fills space).
std::vector<float> medium(std::array<float, 3> sigma_t, float g, std::array<float, 3> lo = {},
                          std::array<float, 3> hi = {}) {
    std::vector<float> m(TS_MEDIUM_FLOATS, 0.0f);
    for (int a = 0; a < 3; ++a) {
        m[TS_MEDIUM_SIGMA_A + a] = 0.25f * sigma_t[a];
        m[TS_MEDIUM_SIGMA_S + a] = 0.75f * sigma_t[a];
        m[TS_MEDIUM_BOX_MIN + a] = lo[a];
        m[TS_MEDIUM_BOX_MAX + a] = hi[a];
    }
    m[TS_MEDIUM_G] = g;
    m[TS_MEDIUM_BOUNDED] = lo != hi ? 1.0f : 0.0f;
    m[TS_MEDIUM_PRESENT] = 1.0f;
    return m;
}

// How many of the two gathers' outputs differ in E.
size_t differing(const std::vector<float>& a, const std::vector<float>& b) {
    size_t n = 0;
    for (size_t k = 0; k < a.size(); k += TS_IC_GATHER_FLOATS)
        n += std::memcmp(&a[k + TS_IC_GATHER_E], &b[k + TS_IC_GATHER_E], 3 * sizeof(float)) != 0;
    return n;
}

TEST(EmbreeIcGather, SixteenRecordsAtOnceEqualOneAtATime) {
    const LanesAgainstOneRecord check;
    ASSERT_GT(check.records(), 40u);
    ASSERT_GT(check.vpls().size() / TS_VPL_FLOATS, 50u);
    size_t seen_none = 0;
    check.run(check.vpls(), std::vector<float>(TS_MEDIUM_FLOATS, 0.0f), seen_none);
    EXPECT_GT(seen_none, 0u);                // some items sum over an empty row
    EXPECT_LT(seen_none, check.count() / 2);  // most see VPLs
}

// With a medium: its transmittance on every link and its phase function at medium VPLs,
// bit for bit as the one-record gather takes them. The boxes: the Cornell box's room
// (both ends of nearly every link inside: the exponential without the slab test), its
// left third (links in, out and across), one far from every record (no link meets it:
// the sums of the clear room) and none (fog filling space).
TEST(EmbreeIcGather, SixteenRecordsAtOnceEqualOneAtATimeInAMedium) {
    const LanesAgainstOneRecord check;
    std::vector<float> vpls = check.vpls();
    // Every seventh VPL a medium VPL (negative pos_scale; its normal stands in for the
    // light's propagation direction): the Henyey–Greenstein phase instead of a cosine.
    for (size_t j = 0; j < vpls.size() / TS_VPL_FLOATS; j += 7)
        vpls[j * TS_VPL_FLOATS + TS_VPL_POS_SCALE] = -std::fabs(vpls[j * TS_VPL_FLOATS + TS_VPL_POS_SCALE]);
    size_t seen_none = 0;
    const std::vector<float> clear = check.run(vpls, std::vector<float>(TS_MEDIUM_FLOATS, 0.0f), seen_none);

    const std::vector<float> room = check.run(vpls, medium({1.5f, 1.5f, 1.5f}, 0.3f, {0, 0, 0}, {0.556f, 0.5488f, 0.5592f}), seen_none);
    const std::vector<float> third = check.run(vpls, medium({1.0f, 2.0f, 4.0f}, -0.4f, {0, 0, 0}, {0.185f, 0.5488f, 0.5592f}), seen_none);
    const std::vector<float> far = check.run(vpls, medium({1.0f, 2.0f, 4.0f}, 0.0f, {10, 10, 10}, {11, 11, 11}), seen_none);
    const std::vector<float> space = check.run(vpls, medium({0.5f, 1.0f, 2.0f}, 0.6f), seen_none);
    const size_t n = check.count();
    EXPECT_GT(differing(room, clear), n / 2);   // fog on nearly every link dims the sums
    EXPECT_GT(differing(third, clear), n / 4);  // some links cross the third
    EXPECT_LT(differing(third, clear), differing(room, clear));
    EXPECT_EQ(differing(far, clear), 0u);       // a far box changes nothing, not even a bit
    EXPECT_GT(differing(space, clear), n / 2);
}

}  // namespace
}  // namespace tessera
