// The irradiance cache's parts on analytic configurations: Ward's (shifted) weight, the
// record radius and gather, and the octree lookup against a brute-force sum.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "gi/instant_cache.h"
#include "gi/irradiance_cache.h"
#include "kernels/shared/ic_lookup.h"

namespace tessera {
namespace {

IcRecord record_at(glm::vec3 x, glm::vec3 n, float radius, glm::vec3 e = glm::vec3(1.0f)) {
    IcRecord r;
    r.surface = {x.x, x.y, x.z, n.x, n.y, n.z, n.x, n.y, n.z, x.x, x.y, x.z, 1.0f, 0.0f, 1.0f};
    r.radius = radius;
    r.e = {e.x, e.y, e.z};
    return r;
}

float weight(const IcRecord& r, glm::vec3 x, glm::vec3 n, float a) {
    float rec[TS_IC_RECORD_FLOATS];
    for (int c = 0; c < 3; ++c) {
        rec[TS_IC_RECORD_POSITION + c] = r.surface[TS_IC_GBUF_POSITION + c];
        rec[TS_IC_RECORD_NORMAL + c] = r.surface[TS_IC_GBUF_NORMAL + c];
        rec[TS_IC_RECORD_E + c] = r.e[c];
    }
    rec[TS_IC_RECORD_RADIUS] = r.radius;
    return ts::ts_ic_weight(rec, {x.x, x.y, x.z}, {n.x, n.y, n.z}, a);
}

TEST(WardWeight, MatchesTheFormulaAndTheValidityBounds) {
    const IcRecord r = record_at({0, 0, 0}, {0, 0, 1}, 1.0f);
    const float a = 0.5f;
    // ε = d/R: w = 1/ε − 1/a.
    EXPECT_FLOAT_EQ(weight(r, {0.25f, 0, 0}, {0, 0, 1}, a), 1.0f / 0.25f - 2.0f);
    EXPECT_FLOAT_EQ(weight(r, {0, 0.4f, 0}, {0, 0, 1}, a), 1.0f / 0.4f - 2.0f);
    // Fades to zero at the edge of validity, zero beyond it.
    EXPECT_NEAR(weight(r, {0.4999f, 0, 0}, {0, 0, 1}, a), 0.0f, 1e-3f);
    EXPECT_EQ(weight(r, {0.6f, 0, 0}, {0, 0, 1}, a), 0.0f);
    // Normal term: 30° tilt gives sqrt(1 − cos 30°) = 0.366 on top of d/R = 0.1.
    const float c30 = std::cos(0.5235988f), s30 = std::sin(0.5235988f);
    EXPECT_NEAR(weight(r, {0.1f, 0, 0}, {s30, 0, c30}, a), 1.0f / (0.1f + std::sqrt(1.0f - c30)) - 2.0f, 1e-4f);
    // 60° tilt: sqrt(0.5) = 0.707 > a, unusable even at the record.
    EXPECT_EQ(weight(r, {0, 0, 0}, {std::sin(1.0471976f), 0, std::cos(1.0471976f)}, a), 0.0f);
    // In front of the query point (the query lies behind the record's surface): rejected;
    // behind it: usable.
    EXPECT_EQ(weight(r, {0, 0, -0.1f}, {0, 0, 1}, a), 0.0f);
    EXPECT_FLOAT_EQ(weight(r, {0, 0, 0.1f}, {0, 0, 1}, a), 1.0f / 0.1f - 2.0f);
    // At the record itself the weight is bounded (ε floored at 1e-4·a).
    EXPECT_FLOAT_EQ(weight(r, {0, 0, 0}, {0, 0, 1}, a), 1.0f / (1e-4f * a) - 1.0f / a);
}

// ts_ic_weight's early distance test (dot(d, d) against (a·R)², with a 1e-3 margin) must
// not change any weight: on points within ±1e-6 of the validity limit |d| = a·R, where the
// two forms of the test round differently, the weight equals the formula's without it
// (with a margin of 0.9999 instead of 1.001 this fails).
TEST(WardWeight, DistancePreTestChangesNoWeight) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const float a = 0.3f;
    size_t usable = 0, unusable = 0;
    for (int i = 0; i < 200000; ++i) {
        const float radius = std::exp2(8.0f * u(rng));
        const glm::vec3 centre(100.0f * u(rng), 100.0f * u(rng), 100.0f * u(rng));
        const IcRecord r = record_at(centre, {0, 0, 1}, radius);
        const glm::vec3 dir = glm::normalize(glm::vec3(u(rng), u(rng), 0.0f));
        const glm::vec3 x = centre + dir * (a * radius * (1.0f + 1e-6f * u(rng)));
        const glm::vec3 n(0, 0, 1);
        // The formula of ts_ic_weight without the early test.
        const glm::vec3 d = x - centre;
        const float eps = glm::length(d) / radius + std::sqrt(std::fmax(0.0f, 1.0f - glm::dot(n, n)));
        const float expected = eps < a ? 1.0f / std::fmax(eps, 1e-4f * a) - 1.0f / a : 0.0f;
        const float w = weight(r, x, n, a);
        ASSERT_EQ(w, expected) << "point " << i;
        (w > 0.0f ? usable : unusable)++;
    }
    // Both sides of the limit are exercised.
    EXPECT_GT(usable, 1000u);
    EXPECT_GT(unusable, 1000u);
}

TEST(RecordRadius, ClampsToPixelFootprints) {
    // One pixel = 0.004 units at the record.
    EXPECT_FLOAT_EQ(ic_record_radius(0.05f, 0.004f, 1.5f, 20.0f), 0.05f);
    EXPECT_FLOAT_EQ(ic_record_radius(0.001f, 0.004f, 1.5f, 20.0f), 1.5f * 0.004f);
    EXPECT_FLOAT_EQ(ic_record_radius(INFINITY, 0.004f, 1.5f, 20.0f), 20.0f * 0.004f);
    // A camera on the surface (pixel size 0) still gives a positive radius.
    EXPECT_GT(ic_record_radius(0.05f, 0.0f, 1.5f, 20.0f), 0.0f);
}

TEST(IcOctree, LookupEqualsBruteForceOverAllRecords) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float a = 0.4f;
    IrradianceCache cache(a);
    std::vector<IcRecord> all;
    cache.rebuild({0, 0, 0}, {1, 1, 1});
    for (int i = 0; i < 400; ++i) {
        // Records on two planes with radii over two orders of magnitude, so they land on
        // many octree levels.
        const bool floor = i % 2 == 0;
        const glm::vec3 x = floor ? glm::vec3(u(rng), 0.0f, u(rng)) : glm::vec3(u(rng), u(rng), 1.0f);
        const glm::vec3 n = floor ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, -1);
        const IcRecord r = record_at(x, n, 0.005f * std::pow(40.0f, u(rng)), glm::vec3(u(rng), u(rng), u(rng)));
        all.push_back(r);
        cache.insert(r);
    }
    for (int rebuilt = 0; rebuilt < 2; ++rebuilt) {
        for (int q = 0; q < 2000; ++q) {
            const bool floor = q % 2 == 0;
            const glm::vec3 x = floor ? glm::vec3(u(rng), 0.0f, u(rng)) : glm::vec3(u(rng), u(rng), 1.0f);
            const glm::vec3 n = floor ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, -1);
            double wsum = 0.0, esum = 0.0;
            for (const IcRecord& r : all) {
                const float w = weight(r, x, n, a);
                wsum += w;
                esum += w * r.e[0];
            }
            glm::vec3 e;
            const float w = cache.lookup(x, n, &e);
            ASSERT_NEAR(w, wsum, 1e-4 * wsum + 1e-6) << "query " << q;
            // The placement's coverage test: Σ w > 0, decided at the first usable record.
            const IcCacheBuffers& b = cache.buffers();
            ASSERT_EQ(ts::ts_ic_covered(b.nodes.data(), b.refs.data(), b.records.data(), {x.x, x.y, x.z},
                                        {n.x, n.y, n.z}, a) != 0,
                      w > 0.0f)
                << "query " << q;
            if (wsum > 0) {
                ASSERT_NEAR(e.x, esum / wsum, 1e-4);
            }
        }
        cache.rebuild({0, 0, 0}, {1, 1, 1});  // the same answers after a rebuild
    }
}

// The rebuild builds the octree's top levels serially and the subtrees below them in
// parallel (irradiance_cache.cpp); the incremental inserts build it serially. With the
// same root, every node holds the same records in the same order, so every lookup must
// give the same bits: a different order of summation would differ in the last bits.
TEST(IcOctree, ParallelRebuildGivesTheInsertionsLookupsBitForBit) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float a = 0.3f;
    IrradianceCache inserted(a), rebuilt(a);
    // Spheres inside [0, 1]³ (positions in [0.1, 0.9], a·R ≤ 0.03), so the rebuild's root,
    // which grows around the spheres, is the inserted cache's root.
    inserted.rebuild({0, 0, 0}, {1, 1, 1});
    std::vector<IcRecord> all;
    for (int i = 0; i < 6000; ++i) {
        const int plane = i % 3;  // a floor, a wall and scattered points: uneven subtrees
        glm::vec3 x(0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng));
        if (plane == 0) x.y = 0.1f;
        if (plane == 1) x.z = 0.9f;
        const glm::vec3 n = plane == 1 ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
        const IcRecord r = record_at(x, n, 0.002f * std::pow(50.0f, u(rng)), glm::vec3(u(rng), u(rng), u(rng)));
        inserted.insert(r);
        rebuilt.records().push_back(r);
    }
    rebuilt.rebuild({0, 0, 0}, {1, 1, 1});
    EXPECT_EQ(rebuilt.buffers().refs.size(), inserted.buffers().refs.size());
    EXPECT_EQ(rebuilt.buffers().nodes.size(), inserted.buffers().nodes.size());
    int served = 0;
    for (int q = 0; q < 20000; ++q) {
        const int plane = q % 3;
        glm::vec3 x(0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng));
        if (plane == 0) x.y = 0.1f;
        if (plane == 1) x.z = 0.9f;
        const glm::vec3 n = plane == 1 ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
        glm::vec3 e_inserted, e_rebuilt;
        const float w_inserted = inserted.lookup(x, n, &e_inserted);
        const float w_rebuilt = rebuilt.lookup(x, n, &e_rebuilt);
        ASSERT_EQ(w_rebuilt, w_inserted) << "query " << q;
        ASSERT_EQ(e_rebuilt, e_inserted) << "query " << q;
        served += w_inserted > 0.0f;
    }
    EXPECT_GT(served, 8000);  // the floor's and the wall's queries sum several records each
}

}  // namespace
}  // namespace tessera
