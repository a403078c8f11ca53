// The instant cache's record–VPL kernels (host/gi/ic_gather.h) on the OpenCL and Embree
// backends, given the same records, VPLs and visibility rows (one frame of the animated
// Cornell box, the cache built on Embree): the per-pair shadow-ray results and the record
// sums must agree.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "gi/ic_gather.h"
#include "opencl/device.h"
#include "support/ic_test_frame.h"
#include "support/scoped_env.h"

namespace tessera {
namespace {

struct KernelResults {
    std::vector<uint32_t> hits;  // per pair
    std::vector<float> sums;     // TS_IC_GATHER_FLOATS per record, from the Embree rows
};

// 0 visible, 1 facing (no ray), 2 occluded (the code is then a triangle on the ray).
int pair_class(uint32_t hit) { return hit == TS_IC_PAIR_VISIBLE ? 0 : hit == TS_IC_PAIR_FACING ? 1 : 2; }

// Pairs that two backends class apart: all of them, and those not on a knife edge
// (IcTestFrame::pair_faces_on_edge, pair_ray_only_grazes), which no correct traversal
// classes apart. A CPU device (PoCL) builds the rays from the same floats as C++ and
// must class every pair alike; a GPU's built-ins may tip a knife-edge pair.
struct ClassesApart {
    size_t all = 0, inside = 0;
    void add(const test::IcTestFrame& f, float b, uint32_t record, uint32_t vpl, uint32_t h1, uint32_t h2) {
        const int c1 = pair_class(h1), c2 = pair_class(h2);
        if (c1 == c2) return;
        ++all;
        const bool edge = c1 == 1 || c2 == 1 ? f.pair_faces_on_edge(record, vpl) : f.pair_ray_only_grazes(b, record, vpl);
        inside += !edge;
    }
    void expect(const char* what) const {
        EXPECT_EQ(inside, 0u) << what << ": pairs classed apart off a knife edge";
        if (select_cl_device("").type == "CPU") {
            EXPECT_EQ(all, 0u) << what;
        }
        std::printf("  %s: %zu pairs classed apart, %zu of them off a knife edge\n", what, all, inside);
    }
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

    // The GPU variant's one-ray pair kernel (the short-stack traversal) classes the pairs
    // as the packets do, with occluders on the rays too.
    {
        BackendOptions o{BackendKind::OpenCL, ""};
        o.cl_gpu_variant = true;
        auto gpu = make_backend(o, frame.buffers, frame.plan);
        std::vector<uint32_t> g;
        ic_set_record_inputs(*gpu, records, vpls);
        ic_trace_pairs(*gpu, b, pairs, g);
        ASSERT_EQ(g.size(), e.hits.size());
        ClassesApart apart;
        size_t off_ray = 0;
        for (size_t k = 0; k < g.size(); ++k) {
            apart.add(frame, b, pairs[2 * k], pairs[2 * k + 1], g[k], e.hits[k]);
            off_ray += pair_class(g[k]) == 2 && !frame.pair_ray_meets(b, pairs[2 * k], pairs[2 * k + 1], g[k]);
        }
        apart.expect("GPU variant against Embree");
        EXPECT_EQ(off_ray, 0u);
    }

    // The same shadow rays (the same shared code builds them) through two traversals,
    // Embree's and ours (kernels/bvh_traverse.h): both watertight, they could differ only
    // for a ray through a shared edge or vertex, where each picks one of the triangles;
    // none of this frame's pairs does, so on a CPU device they are visible, facing or
    // occluded alike (on a GPU, ClassesApart above). The knife-edge tests are selective:
    // few occluded or visible pairs are knife edges, so a traversal that lost or added
    // triangles would be caught. (Facing pairs are often coplanar, each on a wall: those
    // are knife edges, and their G is ~0 either way.) An
    // occluded pair's code is the triangle its any-hit query found first, which depends on
    // the traversal: each backend's must lie on the pair's shadow ray.
    size_t visible = 0, facing = 0, occluded = 0, off_ray = 0;
    ClassesApart apart;
    ASSERT_EQ(c.hits.size(), e.hits.size());
    for (size_t k = 0; k < e.hits.size(); ++k) {
        visible += e.hits[k] == TS_IC_PAIR_VISIBLE;
        facing += e.hits[k] == TS_IC_PAIR_FACING;
        const bool blocked = pair_class(e.hits[k]) == 2;
        occluded += blocked;
        apart.add(frame, b, pairs[2 * k], pairs[2 * k + 1], c.hits[k], e.hits[k]);
        if (blocked)
            for (const uint32_t hit : {e.hits[k], c.hits[k]})
                off_ray += !frame.pair_ray_meets(b, pairs[2 * k], pairs[2 * k + 1], hit);
    }
    EXPECT_GT(visible, e.hits.size() / 10);  // all three kinds occur in the frame
    EXPECT_GT(facing, e.hits.size() / 10);
    EXPECT_GT(occluded, e.hits.size() / 100);
    size_t grazing = 0, facing_edge = 0;
    for (size_t k = 0; k < e.hits.size(); ++k) {
        const int cls = pair_class(e.hits[k]);
        grazing += cls == 2 && frame.pair_ray_only_grazes(b, pairs[2 * k], pairs[2 * k + 1]);
        facing_edge += cls == 0 && frame.pair_faces_on_edge(pairs[2 * k], pairs[2 * k + 1]);
    }
    EXPECT_LT(grazing, occluded / 100) << "occluded pairs that only graze a triangle";
    EXPECT_LT(facing_edge, visible / 100) << "visible pairs with a cosine near 0";
    std::printf("  knife edges: %zu of %zu occluded pairs, %zu of %zu visible (%zu pairs)\n", grazing, occluded,
                facing_edge, visible, e.hits.size());
    apart.expect("OpenCL against Embree");
    EXPECT_EQ(off_ray, 0u);

    // The same rows, VPLs and records: both backends sum the same terms in the same order
    // in double. On a CPU device (PoCL) the sums are the same floats. Elsewhere the terms'
    // OpenCL built-ins (normalize, ...) may round a few ulps apart from C++: on an H100
    // the sums differed in their last digits. Each term is positive, so a sum keeps its
    // terms' relative error: ~20 float operations of a few ulps each, ~1e-6; 1e-5 leaves
    // 10x. A lost or mis-weighted term moves a sum by ~1/(VPLs) ~ 1e-2.
    // The sums' (hi, lo) pairs are compared as their sums: a lo is the rounding residue of
    // its hi, so where the his differ in an ulp the los differ wholly.
    const double rel = select_cl_device("").type == "CPU" ? 0.0 : 1e-5;
    ASSERT_EQ(c.sums.size(), e.sums.size());
    if (rel == 0.0) {
        EXPECT_EQ(c.sums, e.sums);
    }
    size_t lit = 0;
    for (size_t i = 0; i < records.size(); ++i) {
        const float *ce = &c.sums[i * TS_IC_GATHER_FLOATS], *ee = &e.sums[i * TS_IC_GATHER_FLOATS];
        lit += ee[TS_IC_GATHER_E] > 0.0f;
        for (int k : {TS_IC_GATHER_E, TS_IC_GATHER_E + 1, TS_IC_GATHER_E + 2, TS_IC_GATHER_HARMONIC}) {
            if (std::isinf(ee[k])) {
                EXPECT_EQ(ce[k], ee[k]) << "record " << i << " output " << k;
            } else {
                EXPECT_NEAR(ce[k], ee[k], rel * std::fabs(ee[k])) << "record " << i << " output " << k;
            }
        }
        const IcGatherSums cs = IcGatherSums::from_output(ce), es = IcGatherSums::from_output(ee);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(cs.e[ch], es.e[ch], rel * std::fabs(es.e[ch])) << "record " << i;
        EXPECT_NEAR(cs.inv_dist, es.inv_dist, rel * std::fabs(es.inv_dist)) << "record " << i;
        EXPECT_EQ(cs.seen, es.seen) << "record " << i;
    }
    EXPECT_GT(lit, records.size() / 2);
}

// A gather's sums (IcGatherSums) form its E and harmonic mean distance as the kernel
// does, and sums over disjoint VPL subsets add up to the sum over their union: what the
// temporal update's re-sum by change relies on (temporal_update.cpp). Both backends.
TEST(IcGatherKernels, SumsOfDisjointVplSubsetsAddUp) {
    const test::IcTestFrame frame;
    auto opencl = make_backend({BackendKind::OpenCL, ""}, frame.buffers, frame.plan);
    const std::vector<IcRecord>& records = frame.records();
    const float b = 0.5f;
    std::vector<uint32_t> pairs, hits, rows;
    frame.trace_all_pairs(b, pairs, hits, rows);
    // Split each row's visible VPLs in two: the even and the odd ones.
    std::vector<uint32_t> even(rows.size()), odd(rows.size());
    for (size_t w = 0; w < rows.size(); ++w) even[w] = rows[w] & 0x55555555u, odd[w] = rows[w] & 0xaaaaaaaau;
    std::vector<uint32_t> items;
    for (uint32_t i = 0; i < records.size(); ++i) items.insert(items.end(), {i, i});
    for (Backend* backend : {frame.embree.get(), opencl.get()}) {
        ic_set_record_inputs(*backend, records, frame.vpls());
        std::vector<float> whole, a, z;
        ic_gather(*backend, b, items, rows, whole);
        ic_gather(*backend, b, items, even, a);
        ic_gather(*backend, b, items, odd, z);
        size_t split = 0;
        for (size_t i = 0; i < records.size(); ++i) {
            const float* w = &whole[i * TS_IC_GATHER_FLOATS];
            const IcGatherSums all = IcGatherSums::from_output(w);
            // E and the harmonic mean from the sums are the kernel's, bit for bit (the
            // (hi, lo) pair holds the double sum to 2^-48, far inside a float's rounding).
            const std::array<float, 3> e = all.irradiance();
            for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(e[ch], w[TS_IC_GATHER_E + ch]) << "record " << i;
            EXPECT_EQ(all.harmonic_mean(), w[TS_IC_GATHER_HARMONIC]) << "record " << i;
            IcGatherSums parts = IcGatherSums::from_output(&a[i * TS_IC_GATHER_FLOATS]);
            split += parts.seen > 0 && parts.seen < all.seen;
            parts += IcGatherSums::from_output(&z[i * TS_IC_GATHER_FLOATS]);
            EXPECT_EQ(parts.seen, all.seen) << "record " << i;
            // Two orders of the same double sum of ≤ nv positive terms: within nv ulps.
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(parts.e[ch], all.e[ch], 1e-14 * all.e[ch]) << "record " << i;
            EXPECT_NEAR(parts.inv_dist, all.inv_dist, 1e-14 * all.inv_dist) << "record " << i;
            // Subtracting the odd part leaves the even one; subtracting both leaves exactly 0.
            IcGatherSums rest = all;
            rest -= IcGatherSums::from_output(&z[i * TS_IC_GATHER_FLOATS]);
            const IcGatherSums even_sum = IcGatherSums::from_output(&a[i * TS_IC_GATHER_FLOATS]);
            EXPECT_NEAR(rest.e[0], even_sum.e[0], 1e-14 * all.e[0]) << "record " << i;
            rest -= even_sum;
            EXPECT_EQ(rest.seen, 0) << "record " << i;
            EXPECT_EQ(rest.irradiance()[0], 0.0f) << "record " << i;
            EXPECT_TRUE(std::isinf(rest.harmonic_mean())) << "record " << i;
        }
        EXPECT_GT(split, records.size() / 2) << "most records see VPLs of both halves";
    }
    // The float form (devices without doubles: a compensated sum and its compensation as
    // the pair): the same counts, sums within float rounding of the double ones (each term
    // rounded in float, ~1e-7; 1e-5 leaves room).
    std::vector<float> in_double, in_float;
    ic_set_record_inputs(*frame.embree, records, frame.vpls());
    ic_gather(*frame.embree, b, items, rows, in_double);
    test::ScopedEnv options("TESSERA_CL_OPTIONS", "-DTS_NO_DOUBLE");
    auto single = make_backend({BackendKind::OpenCL, ""}, frame.buffers, frame.plan);
    ic_set_record_inputs(*single, records, frame.vpls());
    ic_gather(*single, b, items, rows, in_float);
    bool differs = false;
    for (size_t i = 0; i < records.size(); ++i) {
        const IcGatherSums d = IcGatherSums::from_output(&in_double[i * TS_IC_GATHER_FLOATS]);
        const IcGatherSums f = IcGatherSums::from_output(&in_float[i * TS_IC_GATHER_FLOATS]);
        EXPECT_EQ(f.seen, d.seen) << "record " << i;
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(f.e[ch], d.e[ch], 1e-5 * d.e[ch]) << "record " << i;
        EXPECT_NEAR(f.inv_dist, d.inv_dist, 1e-5 * d.inv_dist) << "record " << i;
        differs |= f.e[0] != d.e[0];
    }
    EXPECT_TRUE(differs) << "-DTS_NO_DOUBLE no longer reaches the kernels";
}

// Placement's pairs as a grid (TsFrame.ic_pair_grid: pair g = record g mod n, VPL g / n)
// must give what the same pairs give from an item list (the same visibility, an occluder
// on the ray), on both backends and in launches that start mid-grid (ic_pair_first), with
// 16-pair packets that straddle two VPLs.
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
        // The same classes; an occluder may differ (a packet's walk depends on its other
        // lanes, and the split regroups them), but each lies on its pair's ray.
        size_t differ = 0, off_ray = 0, occluded = 0;
        for (size_t k = 0; k < listed.size(); ++k) {
            differ += pair_class(grid[k]) != pair_class(listed[k]);
            if (pair_class(listed[k]) != 2) continue;
            ++occluded;
            for (const uint32_t hit : {grid[k], listed[k]})
                off_ray += !frame.pair_ray_meets(b, items[2 * k], items[2 * k + 1], hit);
        }
        EXPECT_EQ(differ, 0u) << backend->description();
        EXPECT_EQ(off_ray, 0u) << backend->description();
        EXPECT_GT(occluded, 0u);
        EXPECT_GT(std::count(listed.begin(), listed.end(), TS_IC_PAIR_VISIBLE), 0);
    }
}

TEST(IcGatherKernels, PackVisibleSetsOneBitPerUnoccludedPair) {
    // 40 VPLs: visible at 0, 31, 32 and 39; facing, occluded by objects 0 and 5 elsewhere.
    std::vector<int32_t> row(40, kIcFacing);
    row[3] = 0, row[17] = 5;
    for (int j : {0, 31, 32, 39}) row[j] = kIcVisible;
    uint32_t mask[2] = {0u, 0u};
    ic_pack_visible(row.data(), row.size(), mask);
    EXPECT_EQ(mask[0], 0x80000001u);
    EXPECT_EQ(mask[1], 0x81u);  // bits 32 and 39; the bits past the 40th stay 0
}

TEST(IcGatherKernels, PackVisibleAtAColumnOffsetKeepsTheOtherColumnsBits) {
    // A subset's row of 8 VPLs, columns 28..35, into a mask that already holds column 2:
    // the row straddles a word, and column 2 stays set.
    std::vector<int32_t> row(8, kIcFacing);
    row[0] = row[4] = row[7] = kIcVisible;  // columns 28, 32, 35
    row[5] = 3;                             // occluded by object 3
    uint32_t mask[2] = {1u << 2, 0u};
    ic_pack_visible(row.data(), row.size(), mask, 28);
    EXPECT_EQ(mask[0], (1u << 2) | (1u << 28));
    EXPECT_EQ(mask[1], (1u << 0) | (1u << 3));
}

}  // namespace
}  // namespace tessera
