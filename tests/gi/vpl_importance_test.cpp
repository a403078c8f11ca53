// VPLs for the view (gi/vpl_importance.h): the importance measure, the keep
// probabilities, the unbiased selection and the VPL lists generate_vpls makes with them.
#include <cmath>
#include <array>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gi/vpl_generator.h"
#include "gi/vpl_importance.h"
#include "device/frame.h"
#include "support/render_helpers.h"

namespace tessera {
namespace {

// A surface VPL at `pos` facing `normal` with grey flux `flux` from path `path`.
std::vector<float> vpl(std::array<float, 3> pos, std::array<float, 3> normal, float flux, uint32_t path,
                       bool medium = false) {
    std::vector<float> v(TS_VPL_FLOATS, 0.0f);
    for (int c = 0; c < 3; ++c) {
        v[TS_VPL_POSITION + c] = pos[c];
        v[TS_VPL_NORMAL + c] = normal[c];
        v[TS_VPL_FLUX + c] = flux;
    }
    std::memcpy(&v[TS_VPL_PATH], &path, 4);
    v[TS_VPL_POS_SCALE] = medium ? -1.0f : 2.0f;
    return v;
}

void add(std::vector<float>& list, const std::vector<float>& v) { list.insert(list.end(), v.begin(), v.end()); }

ViewPoints point_at_origin(std::array<float, 3> normal) {
    ViewPoints p;
    p.position = {0, 0, 0};
    p.normal = p.geo_normal = {normal[0], normal[1], normal[2]};
    return p;
}

TEST(VplImportance, WeighsThePointsByTheLeadingVplsWhenAsked) {
    // As above (G = 1 and 1/4 at the point), E_j from the first VPL only: E = 1, so the
    // importances are 1 and 1/4; from the first two, the shares 0.8 and 0.2 again.
    std::vector<float> vpls;
    add(vpls, vpl({0, 0, 1}, {0, 0, -1}, 1.0f, 0));
    add(vpls, vpl({0, 0, 2}, {0, 0, -1}, 1.0f, 1));
    const std::vector<float> first = vpl_view_importance(point_at_origin({0, 0, 1}), vpls, 1e30f, 1);
    ASSERT_EQ(first.size(), 2u);
    EXPECT_NEAR(first[0], 1.0f, 1e-6f);
    EXPECT_NEAR(first[1], 0.25f, 1e-6f);
    EXPECT_EQ(vpl_view_importance(point_at_origin({0, 0, 1}), vpls, 1e30f, 2),
              vpl_view_importance(point_at_origin({0, 0, 1}), vpls, 1e30f));
}

TEST(VplImportance, ViewRaysWeighOutTheVplsTheViewCannotSee) {
    // The Cornell box's view points (floor, walls, blocks). A VPL under the ceiling facing
    // down lights most of them; one above the ceiling facing down has the same kind of
    // terms (visibility is not in c_ij) but the ceiling hides it from every point. With
    // S view rays its importance is 0; the visible one keeps most of its share. A medium
    // VPL (0, no rays) comes first, so the surface VPLs' indices are not the list's; one
    // in front of the box's open side, facing the camera, lights no point and draws no rays. Each backend gives the same
    // floats for the same draws.
    Scene s = test::cornell_box();
    SceneBuffers b = make_scene_buffers(s);
    const TsFrame frame = make_frame(s.camera, 64, 64, 1, 1, b.light_count);
    std::vector<float> vpls;
    add(vpls, vpl({0.278f, 0.30f, 0.28f}, {0, 0, 0}, 1.0f, 2, true));
    add(vpls, vpl({0.278f, 0.50f, 0.28f}, {0, -1, 0}, 1.0f, 0));
    add(vpls, vpl({0.278f, 0.27f, -0.05f}, {0, 0, -1}, 1.0f, 3));
    add(vpls, vpl({0.278f, 0.60f, 0.28f}, {0, -1, 0}, 1.0f, 1));
    for (BackendKind kind : {BackendKind::Embree, BackendKind::OpenCL}) {
        auto backend = make_backend({kind, ""}, b, plan_effects(s));
        const ViewPoints view = trace_view_points(*backend, b, frame, 16);
        ASSERT_EQ(view.pos_scale.size(), view.count());
        ASSERT_EQ(view.origin.size(), 3 * view.count());
        const std::vector<float> blind = vpl_view_importance(view, vpls, 1e30f);
        ASSERT_EQ(blind[0], 0.0f) << "medium";
        ASSERT_GT(blind[1], 0.0f);
        ASSERT_EQ(blind[2], 0.0f) << "faces away from every point";
        ASSERT_GT(blind[3], 0.0f) << "c_ij alone does not see the ceiling";
        ViewVisibility vis{backend.get(), 8, 7};
        const std::vector<float> seen = vpl_view_importance(view, vpls, 1e30f, SIZE_MAX, &vis);
        EXPECT_EQ(vis.traced, 16u) << "8 rays for each of the 2 surface VPLs with terms";
        EXPECT_EQ(seen[0], 0.0f);
        EXPECT_EQ(seen[2], 0.0f);
        EXPECT_EQ(seen[3], 0.0f) << "behind the ceiling from every point";
        EXPECT_GT(seen[1], 0.5f * blind[1]) << "most points under the ceiling see it";
        EXPECT_LE(seen[1], blind[1]);
        ViewVisibility again{backend.get(), 8, 7};
        EXPECT_EQ(vpl_view_importance(view, vpls, 1e30f, SIZE_MAX, &again), seen);
        ViewVisibility none{backend.get(), 0, 7};
        EXPECT_EQ(vpl_view_importance(view, vpls, 1e30f, SIZE_MAX, &none), blind) << "S = 0: no rays";
        EXPECT_EQ(none.traced, 0u);
    }
}

TEST(VplImportance, IsEachVplsShareOfAPointsIrradiance) {
    // One point at the origin facing +z; VPLs straight above at heights 1 and 2 facing
    // down: G = 1 and 1/4, so the shares are 0.8 and 0.2. A medium VPL gets 0; a VPL
    // behind the point gets 0.
    std::vector<float> vpls;
    add(vpls, vpl({0, 0, 1}, {0, 0, -1}, 1.0f, 0));
    add(vpls, vpl({0, 0, 2}, {0, 0, -1}, 1.0f, 1));
    add(vpls, vpl({0, 0, 1}, {0, 0, -1}, 1.0f, 2, /*medium=*/true));
    add(vpls, vpl({0, 0, -1}, {0, 0, 1}, 1.0f, 3));
    const std::vector<float> phi = vpl_view_importance(point_at_origin({0, 0, 1}), vpls, 1e30f);
    ASSERT_EQ(phi.size(), 4u);
    EXPECT_NEAR(phi[0], 0.8f, 1e-6f);
    EXPECT_NEAR(phi[1], 0.2f, 1e-6f);
    EXPECT_EQ(phi[2], 0.0f);
    EXPECT_EQ(phi[3], 0.0f);
    // The clamp b = 0.5 caps the first VPL's G at 0.5: shares 0.5/0.75 and 0.25/0.75.
    const std::vector<float> clamped = vpl_view_importance(point_at_origin({0, 0, 1}), vpls, 0.5f);
    EXPECT_NEAR(clamped[0], 2.0f / 3.0f, 1e-6f);
    EXPECT_NEAR(clamped[1], 1.0f / 3.0f, 1e-6f);
    // Shares are relative: ten times the flux on every VPL changes nothing.
    std::vector<float> bright = vpls;
    for (size_t i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) bright[i * TS_VPL_FLOATS + TS_VPL_FLUX + c] *= 10.0f;
    EXPECT_NEAR(vpl_view_importance(point_at_origin({0, 0, 1}), bright, 1e30f)[0], 0.8f, 1e-6f);
    // No VPLs (a scene where every light path escapes): nothing to weigh.
    EXPECT_TRUE(vpl_view_importance(point_at_origin({0, 0, 1}), {}, 1e30f).empty());
    // A point facing away sees none of them: no importance at all.
    const std::vector<float> away =
        vpl_view_importance(point_at_origin({0, 0, -1}), {vpls.begin(), vpls.begin() + 2 * TS_VPL_FLOATS}, 1e30f);
    ASSERT_EQ(away.size(), 2u);
    for (float x : away) EXPECT_EQ(x, 0.0f);
}

TEST(VplImportance, PlacesEachVplWhereItsLightLandsInTheView) {
    // Points at x = 0 and x = 2 facing +z. A medium VPL first (NaN: the points do not see
    // the medium, and the surface VPLs' places must not shift onto its slot). VPLs over
    // x = 1 (heights 1 and 3, facing down) light both alike, so the points' irradiance is
    // equal and those VPLs land at x = 1; a VPL over x = 0.2 lights the first point more
    // (x within (0, 1)); a VPL facing up lights neither (NaN, importance 0).
    ViewPoints view;
    view.position = {0, 0, 0, 2, 0, 0};
    view.normal = view.geo_normal = {0, 0, 1, 0, 0, 1};
    std::vector<float> vpls;
    add(vpls, vpl({1, 0, 1}, {0, 0, -1}, 1.0f, 9, /*medium=*/true));
    add(vpls, vpl({1, 0, 1}, {0, 0, -1}, 1.0f, 0));
    add(vpls, vpl({1, 0, 3}, {0, 0, -1}, 1.0f, 1));
    add(vpls, vpl({1, 0, 1}, {0, 0, 1}, 1.0f, 2));
    std::vector<float> where;
    const std::vector<float> phi = vpl_view_importance(view, vpls, 1e30f, SIZE_MAX, nullptr, &where);
    ASSERT_EQ(where.size(), 12u);
    EXPECT_TRUE(std::isnan(where[0]));
    for (int v = 1; v < 3; ++v) {
        EXPECT_NEAR(where[3 * v], 1.0f, 1e-6f) << "VPL " << v;
        EXPECT_EQ(where[3 * v + 1], 0.0f);
        EXPECT_EQ(where[3 * v + 2], 0.0f);
    }
    EXPECT_EQ(phi[3], 0.0f);
    EXPECT_TRUE(std::isnan(where[9]));
    // The importance is the same with or without `where`.
    EXPECT_EQ(vpl_view_importance(view, vpls, 1e30f), phi);
    add(vpls, vpl({0.2f, 0, 1}, {0, 0, -1}, 1.0f, 3));
    vpl_view_importance(view, vpls, 1e30f, SIZE_MAX, nullptr, &where);
    EXPECT_GT(where[12], 0.0f);
    EXPECT_LT(where[12], 1.0f);
}

TEST(KeepProbabilities, MeetTheBudgetFavourImportanceAndBoundTheWeight) {
    // 200 surface VPLs of importance i² (a skewed measure) and 20 medium VPLs, K = 4.
    std::vector<float> importance;
    std::vector<bool> medium;
    for (int i = 0; i < 220; ++i) {
        importance.push_back(i < 200 ? float(i * i) : 0.0f);
        medium.push_back(i >= 200);
    }
    const uint32_t k = 4;
    const std::vector<double> p = keep_probabilities(importance, medium, k);
    double sum = 0.0;
    for (int i = 0; i < 200; ++i) {
        sum += p[i];
        EXPECT_LE(p[i], 1.0);
        // ε = 1 floors p at 1/(2K): a kept VPL weighs at most twice a uniform choice's.
        EXPECT_GE(p[i], 0.5 / k) << i;
        if (i > 0) {
            EXPECT_GE(p[i], p[i - 1]) << i;
        }
        EXPECT_EQ(std::ceil(p[i] * 64.0), p[i] * 64.0) << "a multiple of 1/64";
    }
    // The budget: 200/K before rounding each p up to 1/64, at most 200/64 above it.
    EXPECT_GE(sum, 200.0 / k - 1e-9);
    EXPECT_LE(sum, 200.0 / k + 200.0 / 64.0);
    // In proportion to Φ + ε Φ̄ (Φ̄ = 13233.5 here), each rounded up by less than 1/64: the
    // last VPL is about 4× as likely as the first (3.99 before rounding; the first, of
    // Φ = 0, sits on its step 1/(2K), and the last rounds up to 32/64).
    EXPECT_EQ(p[0], 0.5 / k);
    EXPECT_GT(p[199] / p[0], 3.0);
    EXPECT_LE(p[199] / p[0], 4.0);
    for (int i = 200; i < 220; ++i) EXPECT_EQ(p[i], 1.0 / k) << "medium VPLs: uniform";
    // Without any importance every VPL is kept with 1/K.
    const std::vector<double> flat = keep_probabilities(std::vector<float>(10, 0.0f), std::vector<bool>(10, false), k);
    ASSERT_EQ(flat.size(), 10u);
    for (double q : flat) EXPECT_EQ(q, 1.0 / k);
}

// In a set where no p reaches 1, τ = 2K·mean, so a VPL that lights no view point
// (Φ = 0) gets p = 1/(2K) = 8/64 at K = 4, a step of the rounding. Nudging another VPL's
// importance by one float ulp (a backend's rounding) moves τ in its last bits; p must
// stay 8/64 whichever way, or the VPL's weight (8 or 7.1) and its keep decision would
// differ between backends.
TEST(KeepProbabilities, ZeroImportanceStaysOnItsStepWhateverTheLastBits) {
    const uint32_t k = 4;
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(1.0f, 2.0f);
    for (int trial = 0; trial < 64; ++trial) {
        std::vector<float> importance(40, 0.0f);
        for (size_t i = 10; i < importance.size(); ++i) importance[i] = u(rng);  // all within 2× (none capped)
        const std::vector<bool> medium(importance.size(), false);
        for (int nudge = 0; nudge < 2; ++nudge) {
            if (nudge) importance[20] = std::nextafter(importance[20], 3.0f);
            const std::vector<double> p = keep_probabilities(importance, medium, k);
            for (size_t i = 0; i < 10; ++i) EXPECT_EQ(p[i], 8.0 / 64.0) << "trial " << trial << ", nudged " << nudge;
        }
    }
}

TEST(SelectVpls, KeepsTheFluxInExpectation) {
    // 20000 candidates of flux 1 from 5000 paths (4 each), importance skewed. Each kept
    // VPL carries 1/p, so the kept flux estimates the candidates' 20000 with variance
    // Σ (1 − p)/p, and the kept count estimates Σ p with variance Σ p(1 − p): 5σ bounds.
    std::vector<float> vpls, importance;
    std::vector<bool> medium;
    for (uint32_t i = 0; i < 20000; ++i) {
        add(vpls, vpl({0, 0, 0}, {0, 0, 1}, 1.0f, i / 4, /*medium=*/i % 50 == 0));
        importance.push_back(float((i * 7919u) % 100) * float((i * 104729u) % 13));
        medium.push_back(i % 50 == 0);
    }
    const uint32_t k = 4;
    const std::vector<double> p = keep_probabilities(importance, medium, k);
    double var_flux = 0.0, var_count = 0.0, mean_count = 0.0;
    for (double q : p) {
        var_flux += (1.0 - q) / q;
        var_count += q * (1.0 - q);
        mean_count += q;
    }
    std::vector<float> kept;
    const uint32_t n = select_vpls(vpls, importance, 0, 20000, k, 0u, kept);
    ASSERT_EQ(kept.size(), size_t(n) * TS_VPL_FLOATS);
    double flux = 0.0;
    for (uint32_t i = 0; i < n; ++i) flux += kept[i * TS_VPL_FLOATS + TS_VPL_FLUX];
    EXPECT_NEAR(flux, 20000.0, 5.0 * std::sqrt(var_flux));
    EXPECT_NEAR(double(n), mean_count, 5.0 * std::sqrt(var_count));
    // The same candidates keep the same VPLs.
    std::vector<float> again;
    select_vpls(vpls, importance, 0, 20000, k, 0u, again);
    EXPECT_EQ(kept, again);
}

TEST(PathKeepProbabilities, MeetTheVplBudgetAndFavourImportance) {
    // Paths of 1-4 VPLs, equal importance per VPL, every tenth path 50 times more.
    const uint32_t k = 4;
    std::vector<uint32_t> counts;
    std::vector<float> importance;
    double vpls = 0.0;
    for (uint32_t j = 0; j < 400; ++j) {
        counts.push_back(1 + j % 4);
        importance.push_back((j % 10 == 0 ? 50.0f : 1.0f) * counts.back());
        vpls += counts.back();
    }
    // The budget holds in VPLs (up to the 1/64 steps, which only round up); the important
    // paths are kept more, and of equally important VPLs the longer path more (it carries
    // more importance); no p is 0.
    const std::vector<double> p = path_keep_probabilities(importance, counts, k);
    double kept_vpls = 0.0;
    for (uint32_t j = 0; j < p.size(); ++j) {
        kept_vpls += p[j] * counts[j];
        EXPECT_GT(p[j], 0.0);
        if (j % 10 == 0) {
            EXPECT_GT(p[j], p[j + 1]) << j;
        }
        const bool plain_pair = j + 1 < p.size() && j % 10 != 0 && (j + 1) % 10 != 0;
        if (plain_pair && counts[j] < counts[j + 1]) {
            EXPECT_LT(p[j], p[j + 1]) << j;
        }
    }
    EXPECT_GE(kept_vpls, vpls / k - 1e-9);
    EXPECT_LE(kept_vpls, vpls / k + vpls / 64.0);
    // No importance anywhere, or paths without VPLs: the plain 1/K.
    for (double q : path_keep_probabilities(std::vector<float>(400, 0.0f), counts, k)) EXPECT_EQ(q, 1.0 / k);
    EXPECT_EQ(path_keep_probabilities({0.0f, 3.0f}, {0u, 2u}, k)[0], 1.0 / k);
}

TEST(SystematicSample, KeepsEachUnitWithItsProbabilityAndTheSumWithinOne) {
    // Over u on a grid of M points of [0, 1), unit j is kept for a fraction of the grid
    // within 1/M of p_j (its interval [C_{j-1}, C_j) holds p_j·M ± 1 grid points shifted by
    // an integer), and every u keeps floor(Σp) or ceil(Σp) units, every run of units
    // its share to within one.
    std::vector<double> p;
    for (uint32_t j = 0; j < 200; ++j) p.push_back(j % 7 == 0 ? 1.0 : double((j * 7919u) % 97) / 97.0);
    double sum = 0.0;
    for (double q : p) sum += q;
    const int grid = 4096;
    std::vector<int> kept_for(p.size(), 0);
    for (int g = 0; g < grid; ++g) {
        const std::vector<bool> keep = systematic_sample(p, (g + 0.5) / grid);
        int count = 0, run = 0;
        double run_share = 0.0;
        for (size_t j = 0; j < p.size(); ++j) {
            count += keep[j];
            kept_for[j] += keep[j];
            if (j < 50) run += keep[j], run_share += p[j];
        }
        ASSERT_GE(count, int(std::floor(sum))) << "u = " << (g + 0.5) / grid;
        ASSERT_LE(count, int(std::ceil(sum))) << "u = " << (g + 0.5) / grid;
        ASSERT_LE(std::abs(run - run_share), 1.0) << "units 0-49 keep their share to within one";
    }
    for (size_t j = 0; j < p.size(); ++j)
        EXPECT_NEAR(double(kept_for[j]) / grid, p[j], 1.0 / grid + 1e-12) << "unit " << j;
    // p = 0 is never kept, p = 1 always.
    const std::vector<bool> edge = systematic_sample({0.0, 1.0, 0.0, 1.0}, 0.999);
    EXPECT_EQ(edge, (std::vector<bool>{false, true, false, true}));
}

TEST(VplsForTheView, KeepASetsBudgetInItsSetAndRepeatExactly) {
    Scene s = test::cornell_box();
    SceneBuffers b = make_scene_buffers(s);
    auto em = make_backend({BackendKind::Embree, ""}, b, plan_effects(s));
    const TsFrame frame = make_frame(s.camera, 64, 64, 1, 1, b.light_count);
    const ViewPoints view = trace_view_points(*em, b, frame, 16);
    EXPECT_EQ(view.count(), 256u) << "every view ray of the closed box meets a diffuse wall";
    VplSettings vs;
    vs.sets = 9;
    vs.paths_per_set = 32;
    const VplList plain = generate_vpls(*em, b, vs);
    vs.importance_oversampling = 4;
    vs.view = &view;
    vs.importance_clamp = 100.0f;
    const VplList chosen = generate_vpls(*em, b, vs), again = generate_vpls(*em, b, vs);
    EXPECT_EQ(chosen.vpls, again.vpls);
    EXPECT_GT(chosen.rays, 3 * plain.rays) << "4× the candidate paths";
    // On average a set keeps 32 paths' worth: within 25% of the plain sets' total.
    EXPECT_NEAR(double(chosen.count()), double(plain.count()), 0.25 * plain.count());
    for (uint32_t k = 0; k < vs.sets; ++k) {
        ASSERT_LE(chosen.set_start[k], chosen.set_start[k + 1]);
        for (uint32_t i = chosen.set_start[k]; i < chosen.set_start[k + 1]; ++i)
            EXPECT_EQ(chosen.vpls[i * TS_VPL_FLOATS + TS_VPL_SET], float(k));
    }
}

TEST(ViewPointHistory, KeepsPointsWhileMovingALittleAndTracesThemAtRest) {
    Scene s = test::cornell_box();
    SceneBuffers b = make_scene_buffers(s);
    auto em = make_backend({BackendKind::Embree, ""}, b, plan_effects(s));
    auto frame_at = [&](glm::vec3 shift, glm::vec3 look_shift) {
        Camera c = s.camera;
        c.position += shift;
        c.look_at += shift + look_shift;
        return make_frame(c, 64, 64, 1, 1, b.light_count);
    };
    auto same = [](const ViewPoints& a, const ViewPoints& b) { return a.position == b.position && a.normal == b.normal; };
    const float d = glm::length(s.camera.look_at - s.camera.position);
    const TsFrame a = frame_at({0, 0, 0}, {0, 0, 0});
    const TsFrame a_moved = frame_at({0.01f * d, 0, 0}, {0, 0, 0});  // 1%: within kMove of the points' distance
    const TsFrame turned = frame_at({0, 0, 0}, {0.2f * d, 0, 0});     // ~11°: past kTurnDegrees
    ViewPointHistory h;
    auto points = [&](const TsFrame& f) {  // one frame: the viewer clears the flag before each pass
        h.clear_kept();
        return h.points_for(*em, b, f, 16);
    };
    const ViewPoints fresh_a = trace_view_points(*em, b, a, 16), fresh_moved = trace_view_points(*em, b, a_moved, 16);
    ASSERT_FALSE(same(fresh_a, fresh_moved)) << "the moved camera sees other points";
    EXPECT_TRUE(same(points(a), fresh_a));
    EXPECT_FALSE(h.kept()) << "the first frame traces";
    EXPECT_TRUE(same(points(a), fresh_a));
    EXPECT_FALSE(h.kept()) << "at rest every pass traces, as render does";
    EXPECT_TRUE(same(points(a_moved), fresh_a));
    EXPECT_TRUE(h.kept()) << "moving a little keeps the points";
    EXPECT_TRUE(same(points(a_moved), fresh_moved));
    EXPECT_FALSE(h.kept()) << "coming to rest traces the camera's own points";
    EXPECT_TRUE(same(points(turned), trace_view_points(*em, b, turned, 16)));
    EXPECT_FALSE(h.kept()) << "a turn past the hysteresis traces";
    EXPECT_TRUE(same(points(a), fresh_a));
    EXPECT_FALSE(h.kept()) << "and so does the way back";
}

}  // namespace
}  // namespace tessera
