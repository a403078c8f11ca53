// The Embree backend's 16-record gather (host/backend/embree_ic_gather.cpp, through the
// shared ts_ic_gather16) against the one-record gather ts_ic_gather, on the records, VPLs
// and visibility rows of one frame of the animated Cornell box: every output must be
// equal bit for bit, for item lists whose length is not a multiple of 16, with records
// repeated and out of order, and with rows that see no VPL.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "backend/embree_ic_gather.h"
#include "kernels/shared/ic_gather.h"
#include "support/ic_test_frame.h"

namespace tessera {
namespace {

TEST(EmbreeIcGather, SixteenRecordsAtOnceEqualOneAtATime) {
    const test::IcTestFrame frame;
    const std::vector<IcRecord>& records = frame.records();
    const std::vector<float>& vpls = frame.vpls();
    const uint32_t nv = static_cast<uint32_t>(frame.vpl_count());
    ASSERT_GT(records.size(), 40u);
    ASSERT_GT(nv, 50u);
    const float b = 0.5f;  // bounds some geometry terms, so the clamp's select is exercised

    // Rows from the traced pairs; every fifth row cleared (a record that sees no VPL).
    std::vector<uint32_t> pairs, hits, rows;
    frame.trace_all_pairs(b, pairs, hits, rows);
    const size_t words = TS_IC_VISIBLE_WORDS(nv);
    for (size_t i = 0; i < records.size(); i += 5) std::fill(&rows[i * words], &rows[i * words] + words, 0u);

    // 37 items: records drawn at random (repeats allowed), each with a random row.
    std::mt19937 rng(7);
    std::vector<uint32_t> items;
    for (int k = 0; k < 37; ++k)
        items.insert(items.end(), {static_cast<uint32_t>(rng() % records.size()),
                                   static_cast<uint32_t>(rng() % records.size())});
    std::vector<float> surfaces;
    for (const IcRecord& r : records) surfaces.insert(surfaces.end(), r.surface.begin(), r.surface.end());
    const std::vector<float> no_medium(TS_MEDIUM_FLOATS, 0.0f);
    const uint32_t set_start[2] = {0, nv};
    ts::TsSceneView sv{};
    sv.medium = no_medium.data();
    sv.vpls = vpls.data();
    sv.vpl_set_start = set_start;
    sv.ic_record_surfaces = surfaces.data();
    sv.ic_visibility = rows.data();
    sv.items = items.data();
    TsFrame f{};
    f.igi_g_clamp = b;
    const size_t count = items.size() / TS_IC_GATHER_WORDS;
    std::vector<float> lanes(count * TS_IC_GATHER_FLOATS);
    ic_gather_lanes(sv, f, count, lanes);

    const ts::TsMedium med = ts::ts_medium_load(no_medium.data());
    size_t seen_none = 0;
    for (size_t k = 0; k < count; ++k) {
        const uint32_t* item = &items[k * TS_IC_GATHER_WORDS];
        const ts::TsSurface surf = ts::ts_ic_record_surface(&surfaces[size_t(item[TS_IC_GATHER_RECORD]) * TS_IC_GBUF_FLOATS]);
        float one[TS_IC_GATHER_FLOATS];
        ts::ts_ic_gather(&surf, &rows[item[TS_IC_GATHER_ROW] * words], nv, vpls.data(), &med, b, one);
        seen_none += std::isinf(one[TS_IC_GATHER_HARMONIC]);
        EXPECT_EQ(std::memcmp(one, &lanes[k * TS_IC_GATHER_FLOATS], sizeof one), 0)
            << "item " << k << ": E " << one[TS_IC_GATHER_E] << " vs " << lanes[k * TS_IC_GATHER_FLOATS + TS_IC_GATHER_E]
            << ", harmonic " << one[TS_IC_GATHER_HARMONIC] << " vs "
            << lanes[k * TS_IC_GATHER_FLOATS + TS_IC_GATHER_HARMONIC];
    }
    EXPECT_GT(seen_none, 0u);          // some items sum over an empty row
    EXPECT_LT(seen_none, count / 2);   // most see VPLs
}

}  // namespace
}  // namespace tessera
