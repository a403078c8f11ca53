// The instant cache's record–VPL kernels (host/gi/ic_gather.h) on the OpenCL and Embree
// backends, given the same records, VPLs and visibility rows (one frame of the animated
// Cornell box, the cache built on Embree): the per-pair shadow-ray results and the record
// sums must agree.
#include <algorithm>
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "gi/ic_gather.h"
#include "opencl/device.h"
#include "support/ic_test_frame.h"

namespace tessera {
namespace {

struct KernelResults {
    std::vector<uint32_t> hits;  // per pair
    std::vector<float> sums;     // TS_IC_GATHER_FLOATS per record, from the Embree rows
};

KernelResults run_kernels(Backend& backend, const std::vector<IcRecord>& records, const std::vector<float>& vpls,
                          float b, const std::vector<uint32_t>& pairs, const std::vector<uint32_t>& rows) {
    KernelResults r;
    ic_set_record_inputs(backend, records, vpls);
    ic_trace_pairs(backend, b, pairs, r.hits);
    std::vector<uint32_t> items;
    for (uint32_t i = 0; i < records.size(); ++i) items.insert(items.end(), {i, i});
    ic_gather(backend, b, items, rows, r.sums);
    return r;
}

TEST(IcGatherKernels, OpenClAndEmbreeAgreeOnPairsAndSumsOfAnAnimatedFrame) {
    const test::IcTestFrame frame;
    auto opencl = make_backend({BackendKind::OpenCL, ""}, frame.buffers, frame.plan);
    const std::vector<IcRecord>& records = frame.records();
    const std::vector<float>& vpls = frame.vpls();
    const size_t nv = frame.vpl_count();
    ASSERT_GT(records.size(), 10u);
    ASSERT_GT(nv, 50u);
    const float b = 0.5f;  // bounds some geometry terms (G reaches ~10² near the walls' corners)

    // The rows the gathers sum over: the Embree pair results, packed as the cache packs
    // its rows (visible = TS_IC_PAIR_VISIBLE; facing and occluded pairs are not).
    std::vector<uint32_t> pairs, hits, rows;
    frame.trace_all_pairs(b, pairs, hits, rows);
    const KernelResults e = run_kernels(*frame.embree, records, vpls, b, pairs, rows);
    const KernelResults c = run_kernels(*opencl, records, vpls, b, pairs, rows);

    // The same shadow rays (the same shared code builds them) through two traversals,
    // Embree's and ours (kernels/bvh_traverse.h): both watertight, they could differ only
    // for a ray through a shared edge or vertex, where each picks one of the triangles;
    // none of this frame's pairs does, so the hit codes (triangle or visible/facing) are
    // the same.
    size_t visible = 0, facing = 0, occluded = 0, differ = 0;
    ASSERT_EQ(c.hits.size(), e.hits.size());
    for (size_t k = 0; k < e.hits.size(); ++k) {
        visible += e.hits[k] == TS_IC_PAIR_VISIBLE;
        facing += e.hits[k] == TS_IC_PAIR_FACING;
        occluded += e.hits[k] != TS_IC_PAIR_VISIBLE && e.hits[k] != TS_IC_PAIR_FACING;
        differ += c.hits[k] != e.hits[k];
    }
    EXPECT_GT(visible, e.hits.size() / 10);  // all three kinds occur in the frame
    EXPECT_GT(facing, e.hits.size() / 10);
    EXPECT_GT(occluded, e.hits.size() / 100);
    EXPECT_EQ(differ, 0u);

    // The same rows, VPLs and records: both backends sum the same terms in the same order
    // in double. On a CPU device (PoCL) the sums are the same floats. Elsewhere the terms'
    // OpenCL built-ins (normalize, ...) may round a few ulps apart from C++: on an H100
    // the sums differed in their last digits. Each term is positive, so a sum keeps its
    // terms' relative error: ~20 float operations of a few ulps each, ~1e-6; 1e-5 leaves
    // 10x. A lost or mis-weighted term moves a sum by ~1/(VPLs) ~ 1e-2.
    const double rel = select_cl_device("").type == "CPU" ? 0.0 : 1e-5;
    ASSERT_EQ(c.sums.size(), e.sums.size());
    size_t lit = 0;
    for (size_t k = 0; k < e.sums.size(); ++k) {
        lit += e.sums[k] > 0.0f && (k % TS_IC_GATHER_FLOATS) == TS_IC_GATHER_E;
        if (std::isinf(e.sums[k])) {
            EXPECT_EQ(c.sums[k], e.sums[k]) << "record " << k / TS_IC_GATHER_FLOATS << " output " << k % TS_IC_GATHER_FLOATS;
            continue;
        }
        EXPECT_NEAR(c.sums[k], e.sums[k], rel * std::fabs(e.sums[k]))
            << "record " << k / TS_IC_GATHER_FLOATS << " output " << k % TS_IC_GATHER_FLOATS;
    }
    EXPECT_GT(lit, records.size() / 2);
}

// Placement's pairs as a grid (TsFrame.ic_pair_grid: pair g = record g mod n, VPL g / n)
// must give what the same pairs give from an item list, on both backends and in launches
// that start mid-grid (ic_pair_first), with 16-pair packets that straddle two VPLs.
TEST(IcGatherKernels, PairGridEqualsTheItemList) {
    const test::IcTestFrame frame;
    auto opencl = make_backend({BackendKind::OpenCL, ""}, frame.buffers, frame.plan);
    const size_t nv = frame.vpl_count();
    std::vector<uint32_t> records;  // every third record, last first: not 0 .. n-1
    for (size_t i = frame.records().size(); i-- > 0;)
        if (i % 3 == 0) records.push_back(static_cast<uint32_t>(i));
    const size_t n = records.size();
    ASSERT_GT(n, 10u);
    ASSERT_NE(n % 16, 0u);
    std::vector<uint32_t> items;
    for (uint32_t j = 0; j < nv; ++j)
        for (const uint32_t r : records) items.insert(items.end(), {r, j});
    const float b = 0.5f;
    for (Backend* backend : {frame.embree.get(), opencl.get()}) {
        ic_set_record_inputs(*backend, frame.records(), frame.vpls());
        std::vector<uint32_t> listed, grid, part;
        ic_trace_pairs(*backend, b, items, listed);
        backend->set_input(KernelInput::IcPairRecords, records);
        const size_t split = n * nv / 3 + 5;  // mid-row, mid-packet
        ic_trace_pair_grid(*backend, b, static_cast<uint32_t>(n), 0u, split, grid);
        ic_trace_pair_grid(*backend, b, static_cast<uint32_t>(n), static_cast<uint32_t>(split), n * nv - split, part);
        grid.insert(grid.end(), part.begin(), part.end());
        ASSERT_EQ(grid.size(), listed.size());
        EXPECT_EQ(grid, listed) << backend->description();
        EXPECT_GT(std::count(listed.begin(), listed.end(), TS_IC_PAIR_VISIBLE), 0);
    }
}

TEST(IcGatherKernels, PackVisibleSetsOneBitPerUnoccludedPair) {
    // 40 VPLs: visible at 0, 31, 32 and 39; facing, occluded by objects 0 and 5 elsewhere.
    std::vector<int32_t> row(40, kIcFacing);
    row[3] = 0, row[17] = 5;
    for (int j : {0, 31, 32, 39}) row[j] = kIcVisible;
    uint32_t mask[2] = {0xdeadbeefu, 0xdeadbeefu};
    ic_pack_visible(row.data(), row.size(), mask);
    EXPECT_EQ(mask[0], 0x80000001u);
    EXPECT_EQ(mask[1], 0x81u);  // bits 32 and 39; the bits past the 40th stay 0
}

}  // namespace
}  // namespace tessera
