#include "gi/vpl_importance.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "device/ray_records.h"
#include "device/scene_view.h"
#include "kernels/shared/bsdf.h"
#include "kernels/shared/rng.h"
#include "kernels/shared/sampling.h"
#include "kernels/shared/vpl.h"
#include "kernels/shared/vpl_importance.h"

namespace tessera {
namespace {

using ts::float3;

// The cell offset of every view ray: irrational-looking, so no ray runs exactly along an
// edge of axis-aligned geometry in a symmetric view (ts_igi_camera_ray's concern).
constexpr float kCellOffset[2] = {0.3819660f, 0.6180340f};
// ε of the keep probability (Georgiev and Slusallek's floor). Cornell box frames measured
// alike for ε = 0.1-1 (one frame and 4 passes); ε = 1 bounds p below by 1/(2K), so that a
// kept VPL weighs at most twice a uniform choice's (keep_probabilities), which matters
// once the clamp has decayed over passes.
constexpr double kFloor = 1.0;
// Steps of the keep probability (keep_probabilities rounds up to them).
constexpr double kSteps = 64.0;
// Seed of the keep decisions ("vpli"), apart from every other stream.
constexpr uint32_t kKeepSeed = 0x76706c69u;
// Seed of the view points drawn for the visibility estimate ("visi").
constexpr uint32_t kVisibilitySeed = 0x76697369u;

uint32_t path_of(const float* v) {
    uint32_t p;
    std::memcpy(&p, v + TS_VPL_PATH, 4);
    return p;
}

// τ with Σ w_i · min(1, a_i / τ) = target (0 < target < Σ w_i): the sum falls as τ grows.
double keep_threshold(const std::vector<double>& a, const std::vector<double>& w, double target) {
    double lo = 0.0, hi = 0.0;
    for (size_t i = 0; i < a.size(); ++i) hi += w[i] * a[i];
    hi /= target;  // Σ w_i a_i / τ ≤ target here, and min(1, ·) only lowers the sum
    for (int it = 0; it < 100; ++it) {
        const double tau = 0.5 * (lo + hi);
        double s = 0.0;
        for (size_t i = 0; i < a.size(); ++i) s += w[i] * std::min(1.0, a[i] / tau);
        (s > target ? lo : hi) = tau;
    }
    return hi;
}

// How far (in steps) above a step p may lie and still take that step.
constexpr double kStepSlack = 1e-7;

// p rounded up to a multiple of 1/kSteps (at least one step): the backends trace the view
// points with their own rounding, and an importance that differs in its last bits must
// not change a weight 1/p (or the image would differ between backends in every pixel it
// lights). A p within kStepSlack of a step takes that step: in a set where no p reaches
// 1, τ = 2K·mean, so every VPL of importance 0 gets exactly 1/(2K), itself a step, and
// τ's last bit (the other VPLs' importance, traced with each backend's rounding) would
// otherwise decide between that step and the next. A p can still cross a step, but only
// when its own value lies within 1e-7 of one by chance.
double stepped(double p) {
    return std::min(1.0, std::max(1.0, std::ceil(p * kSteps - kStepSlack)) / kSteps);
}

}  // namespace

ViewPoints trace_view_points(Backend& backend, const SceneBuffers& scene, const TsFrame& frame, uint32_t grid) {
    std::vector<ts::TsRay> view_rays;
    std::vector<float> rays(size_t(TS_RAY_FLOATS) * grid * grid), hits;
    for (uint32_t gy = 0; gy < grid; ++gy)
        for (uint32_t gx = 0; gx < grid; ++gx) {
            // A point in cell (gx, gy) in pixel units: pixel px plus a fraction.
            const float x = (gx + kCellOffset[0]) * frame.width / grid, y = (gy + kCellOffset[1]) * frame.height / grid;
            const auto px = static_cast<uint32_t>(x), py = static_cast<uint32_t>(y);
            view_rays.push_back(ts::ts_camera_ray(&frame, px, py, x - px, y - py));
            store_ray(view_rays.back(), &rays[size_t(TS_RAY_FLOATS) * (gy * grid + gx)]);
        }
    backend.trace_closest(rays, hits);
    const ts::TsSceneView sv = make_scene_view(scene);
    ViewPoints out;
    auto push = [](std::vector<float>& dst, float3 f) { dst.insert(dst.end(), {f.x, f.y, f.z}); };
    for (size_t i = 0; i < view_rays.size(); ++i) {
        const ts::TsHit hit = load_hit(&hits[TS_HIT_FLOATS * i]);
        if (hit.prim == TS_NO_HIT) continue;
        uint32_t kind;
        std::memcpy(&kind, &scene.materials[TS_MATERIAL_FLOATS * scene.tri_mat[hit.prim] + TS_MAT_KIND], 4);
        if (ts::ts_is_specular(kind)) continue;
        const ts::TsRay& ray = view_rays[i];
        const ts::TsSurface s = ts::ts_surface_at(&sv, ray, hit);
        push(out.position, s.position);
        push(out.normal, s.shading_normal);
        push(out.geo_normal, s.geo_normal);
        push(out.origin, s.origin);
        out.pos_scale.push_back(s.pos_scale);
    }
    return out;
}

ViewPointHistory::CameraFloats ViewPointHistory::camera_of(const TsFrame& frame) {
    CameraFloats c;
    for (int a = 0; a < 3; ++a) {
        c[a] = frame.cam_pos[a];
        c[3 + a] = frame.cam_forward[a];
        c[6 + a] = frame.cam_right[a];
        c[9 + a] = frame.cam_up[a];
    }
    return c;
}

bool ViewPointHistory::near_traced(const CameraFloats& camera) const {
    auto vec = [](const CameraFloats& c, int at) { return float3{c[at], c[at + 1], c[at + 2]}; };
    const float moved = ts::length(vec(camera, 0) - vec(traced_camera_, 0));
    const float cos_turn = std::cos(kTurnDegrees * TS_PI / 180.0f);
    auto within = [&](int at) {
        return ts::dot(ts::normalize(vec(camera, at)), ts::normalize(vec(traced_camera_, at))) >= cos_turn;
    };
    return moved <= kMove * mean_distance_ && within(3) && within(9);
}

const ViewPoints& ViewPointHistory::points_for(Backend& backend, const SceneBuffers& scene, const TsFrame& frame,
                                               uint32_t grid) {
    const CameraFloats camera = camera_of(frame);
    const bool moving = have_last_ && camera != last_camera_;
    const bool keep = moving && have_points_ && grid == grid_ && near_traced(camera);
    last_camera_ = camera;
    have_last_ = true;
    if (keep) {
        kept_ = true;
        return points_;
    }
    points_ = trace_view_points(backend, scene, frame, grid);
    traced_camera_ = camera, grid_ = grid, have_points_ = true;
    double sum = 0.0;
    for (size_t j = 0; j < points_.count(); ++j) {
        const float3 d = ts::ts_f3_load(&points_.position[3 * j]) - ts::ts_f3_load(frame.cam_pos);
        sum += ts::length(d);
    }
    mean_distance_ = points_.count() ? static_cast<float>(sum / points_.count()) : 0.0f;
    return points_;
}

namespace {

// One VPL's c_ij over view points [j0, j1) (`pts`: the np points' coordinates as 9 arrays
// of np, the VplImportance input's layout), into row[0, j1 − j0). The arrays' own pointers
// and a size_t index (not ts_vpl_importance_term's uint offsets, which may wrap) let the
// loop run in SIMD.
void vpl_row(const float* pts, size_t np, size_t j0, size_t j1, const float* vpl, float lum, float g_clamp,
             float* row) {
    const float *x0 = pts, *x1 = pts + np, *x2 = pts + 2 * np, *n0 = pts + 3 * np, *n1 = pts + 4 * np;
    const float *n2 = pts + 5 * np, *g0 = pts + 6 * np, *g1 = pts + 7 * np, *g2 = pts + 8 * np;
    for (size_t j = j0; j < j1; ++j)
        row[j - j0] = ts::ts_vpl_importance_term_at(ts::make_float3(x0[j], x1[j], x2[j]),
                                                    ts::make_float3(n0[j], n1[j], n2[j]),
                                                    ts::make_float3(g0[j], g1[j], g2[j]), vpl, lum, g_clamp);
}

// The view points as the VplImportance input lays them out (layout_igi.h, TS_VI_*), with
// room for the weights (zeros).
std::vector<float> importance_input(const ViewPoints& points, float g_clamp) {
    const size_t np = points.count();
    std::vector<float> in(TS_VI_FLOATS(np), 0.0f);
    in[TS_VI_POINTS] = static_cast<float>(np);
    in[TS_VI_G_CLAMP] = g_clamp;
    for (int k = 0; k < TS_VI_POINT_FLOATS; ++k) {
        const std::vector<float>& src = k < 3 ? points.position : k < 6 ? points.normal : points.geo_normal;
        for (size_t j = 0; j < np; ++j) in[TS_VI_COORD(np, k) + j] = src[3 * j + k % 3];
    }
    return in;
}

// w_j = 1 / max(E_j, 10⁻³ · mean E) of the points' irradiance `e`, or nothing when the mean
// is not positive (no candidate lights any point).
std::vector<double> point_weights(const std::vector<double>& e) {
    const size_t np = e.size();
    double mean = 0.0;
    for (size_t j = 0; j < np; ++j) mean += e[j] / np;
    if (!(mean > 0.0)) return {};
    std::vector<double> w(np);
    for (size_t j = 0; j < np; ++j) w[j] = 1.0 / std::max(e[j], 1e-3 * mean);
    return w;
}

// Shadow ray k of S from a view point drawn by c_ij·w_j (stratified: the k-th of S equal
// steps of the VPL's cumulative sum `cdf`, jittered by `u`) to `vpl`, into ray (TS_RAY_FLOATS).
void visibility_ray(const ViewPoints& points, const std::vector<double>& cdf, uint32_t k, uint32_t S, float u,
                    const float* vpl, float* ray) {
    const double target = (k + double(u)) / S * cdf.back();
    const size_t j = std::min<size_t>(cdf.size() - 1, std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
    // From the point's ray origin, off its surface along the geometric normal (c_ij > 0
    // puts the VPL on that side), as a pixel's shadow ray to a VPL leaves (shared/vpl.h).
    const bool own = 3 * j + 2 < points.origin.size() && j < points.pos_scale.size();
    const float* x = own ? &points.origin[3 * j] : &points.position[3 * j];
    const float3 ng = ts::make_float3(points.geo_normal[3 * j], points.geo_normal[3 * j + 1], points.geo_normal[3 * j + 2]);
    const float scale = own ? points.pos_scale[j] : std::max({std::fabs(x[0]), std::fabs(x[1]), std::fabs(x[2])});
    store_ray(ts::ts_vpl_shadow_ray(ts::ts_offset_ray_origin(ts::make_float3(x[0], x[1], x[2]), ng, scale), vpl), ray);
}

// Scales Φ_i (`sum`) by the share of the S = vis.rays rays of VPL i (`rays`, S a VPL,
// drawn where drawn[i]; the others have no terms, Φ_i = 0, and trace none) that arrive:
// vpl_view_importance's visibility estimate. Packs the drawn VPLs' rays to the front of
// `rays` in place (a copy of them cost an allocation of the whole buffer a pass).
void scale_by_visibility(std::vector<float>& rays, const std::vector<uint8_t>& drawn, ViewVisibility& vis,
                         std::vector<double>& sum) {
    const size_t S = vis.rays, block = S * TS_RAY_FLOATS;
    size_t packed = 0;
    for (size_t i = 0; i < sum.size(); ++i) {
        if (!drawn[i]) continue;
        if (packed != i) std::copy_n(rays.begin() + i * block, block, rays.begin() + packed * block);
        ++packed;
    }
    rays.resize(packed * block);
    std::vector<uint32_t> occluded;
    vis.backend->trace_occluded(rays, occluded);
    vis.traced += rays.size() / TS_RAY_FLOATS;
    for (size_t i = 0, at = 0; i < sum.size(); ++i) {
        if (!drawn[i]) continue;
        size_t seen = 0;
        for (size_t k = 0; k < S; ++k) seen += occluded[at++] == 0u;
        sum[i] *= double(seen) / double(S);
    }
}

}  // namespace

std::vector<float> vpl_view_importance(const ViewPoints& points, const std::vector<float>& vpls, float g_clamp,
                                       size_t e_vpls, ViewVisibility* visibility, std::vector<float>* where) {
    const size_t nv = vpls.size() / TS_VPL_FLOATS, np = points.count();
    if (where) where->assign(3 * nv, std::numeric_limits<float>::quiet_NaN());
    std::vector<float> importance(nv, 0.0f);
    if (np == 0 || nv == 0) return importance;
    // The surface VPLs packed, with their flux's luminance (medium VPLs get 0, and the
    // medium's HG parameter is not needed): the loop over them then has no branch.
    std::vector<uint32_t> surface;
    std::vector<float> packed, lum;
    for (size_t i = 0; i < nv; ++i) {
        const float* v = &vpls[TS_VPL_FLOATS * i];
        if (ts::ts_vpl_in_medium(v)) continue;
        surface.push_back(static_cast<uint32_t>(i));
        packed.insert(packed.end(), v, v + TS_VPL_FLOATS);
        lum.push_back(ts::ts_vpl_importance_luminance(v));
    }
    const size_t ns = surface.size();
    if (ns == 0) return importance;
    // c_ij is computed twice, not stored (ns × np floats, 13 MB for the 12,700 candidates of
    // 2,048 paths at K = 4 and 256 points: written once and read twice, with a page fault
    // per 4 kB on a frame's first use, it cost more than the terms). The sums keep their
    // order (E_j over the VPLs in VPL order, Φ_i over the points in point order), so the
    // bits are those of the point-major loop this replaced and of the kernels.
    const std::vector<float> in = importance_input(points, g_clamp);
    const float* pts = in.data() + TS_VI_HEADER;
    constexpr size_t kPointBlock = 32;  // a block's terms stay in registers and L1
    // E_j over the surface VPLs among the first e_vpls.
    const size_t ne = static_cast<size_t>(std::lower_bound(surface.begin(), surface.end(), e_vpls) - surface.begin());
    std::vector<double> e(np, 0.0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, np, kPointBlock), [&](const tbb::blocked_range<size_t>& r) {
        float row[kPointBlock];
        for (size_t j0 = r.begin(); j0 < r.end(); j0 += kPointBlock) {
            const size_t j1 = std::min(r.end(), j0 + kPointBlock);
            for (size_t i = 0; i < ne; ++i) {
                vpl_row(pts, np, j0, j1, &packed[TS_VPL_FLOATS * i], lum[i], g_clamp, row);
                for (size_t j = j0; j < j1; ++j) e[j] += row[j - j0];
            }
        }
    });
    const std::vector<double> w = point_weights(e);
    if (w.empty()) return importance;
    // Φ_i = Σ_j c_ij w_j, each VPL's sum in point order; VPLs in parallel. With view rays
    // the running sums are the cumulative sum the rays' points are drawn from.
    const uint32_t S = visibility ? visibility->rays : 0u;
    std::vector<double> sum(ns, 0.0);
    std::vector<float> rays(size_t(ns) * S * TS_RAY_FLOATS, 0.0f);
    std::vector<uint8_t> drawn(S > 0 ? ns : 0, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, ns, 64), [&](const tbb::blocked_range<size_t>& r) {
        std::vector<float> row(np);
        std::vector<double> cdf(np);
        for (size_t i = r.begin(); i < r.end(); ++i) {
            const float* v = &packed[TS_VPL_FLOATS * i];
            vpl_row(pts, np, 0, np, v, lum[i], g_clamp, row.data());
            double s = 0.0;
            if (where) {
                // The centre's sums ride on the running sum's chain of dependent adds,
                // which bounds the loop's time: they cost next to nothing.
                double c[3] = {0.0, 0.0, 0.0};
                for (size_t j = 0; j < np; ++j) {
                    const double t = row[j] * w[j];
                    cdf[j] = (s += t);
                    for (size_t a = 0; a < 3; ++a) c[a] += t * pts[a * np + j];
                }
                if (s > 0.0)
                    for (size_t a = 0; a < 3; ++a) (*where)[3 * surface[i] + a] = static_cast<float>(c[a] / s);
            } else {
                for (size_t j = 0; j < np; ++j) cdf[j] = (s += row[j] * w[j]);
            }
            sum[i] = s;
            if (S == 0 || !(s > 0.0)) continue;
            drawn[i] = 1;
            ts::TsRng rng = ts::ts_rng_seed(kVisibilitySeed ^ visibility->seed_mix, surface[i], 0u);
            for (uint32_t k = 0; k < S; ++k)
                visibility_ray(points, cdf, k, S, ts::ts_rng_next(&rng), v, &rays[(i * S + k) * TS_RAY_FLOATS]);
        }
    });
    if (S > 0) scale_by_visibility(rays, drawn, *visibility, sum);
    for (size_t i = 0; i < ns; ++i) importance[surface[i]] = static_cast<float>(sum[i]);
    return importance;
}

std::vector<float> vpl_view_importance_in_kernels(Backend& backend, const ViewPoints& points,
                                                 const std::vector<float>& vpls, float g_clamp, size_t e_chunk) {
    const size_t nv = vpls.size() / TS_VPL_FLOATS, np = points.count();
    std::vector<float> importance(nv, 0.0f);
    if (np == 0 || nv == 0) return importance;
    if (e_chunk > TS_VI_MAX_CHUNK)
        throw std::invalid_argument("vpl_view_importance_in_kernels: e_chunk " + std::to_string(e_chunk) +
                                    " is past " + std::to_string(TS_VI_MAX_CHUNK));
    if (e_chunk >= nv) e_chunk = 0;  // one chunk: the same sums as none
    std::vector<float> in = importance_input(points, g_clamp);
    in[TS_VI_CHUNK] = static_cast<float>(e_chunk);
    backend.set_input(KernelInput::Vpls, vpls);
    backend.set_input(KernelInput::VplSetStart, std::vector<uint32_t>{0u, static_cast<uint32_t>(nv)});
    backend.set_input(KernelInput::VplImportance, in);
    const TsFrame frame{};
    std::vector<float> out;
    const size_t chunks = e_chunk > 0 ? (nv + e_chunk - 1) / e_chunk : 1;
    backend.launch_count(KernelId::VplImportancePoints, frame, np * chunks, out);
    std::vector<double> e(np, 0.0);
    for (size_t c = 0; c < chunks; ++c)
        for (size_t j = 0; j < np; ++j) {
            const float* o = &out[TS_VI_E_FLOATS * (c * np + j)];
            e[j] += o[TS_VI_E_HAS_DOUBLE] != 0.0f
                        ? ts::ts_double_of_words(std::bit_cast<uint32_t>(o[TS_VI_E_DOUBLE]),
                                                 std::bit_cast<uint32_t>(o[TS_VI_E_DOUBLE + 1]))
                        : o[TS_VI_E_FLOAT];
        }
    const std::vector<double> w = point_weights(e);
    if (w.empty()) return importance;
    for (size_t j = 0; j < np; ++j) {
        uint32_t lo, hi;
        ts::ts_double_words(w[j], &lo, &hi);
        float* wj = &in[TS_VI_WEIGHT(np, j)];
        wj[0] = std::bit_cast<float>(lo), wj[1] = std::bit_cast<float>(hi), wj[2] = static_cast<float>(w[j]);
    }
    backend.set_input(KernelInput::VplImportance, in);
    backend.launch_count(KernelId::VplImportanceVpls, frame, nv, importance);
    return importance;
}

std::vector<float> vpl_view_importance(Backend& backend, const ViewPoints& points, const std::vector<float>& vpls,
                                       float g_clamp) {
    return backend.traces_light_paths_in_kernel()
               ? vpl_view_importance_in_kernels(backend, points, vpls, g_clamp, backend.importance_chunk())
               : vpl_view_importance(points, vpls, g_clamp);
}

std::vector<double> keep_probabilities(const std::vector<float>& importance, const std::vector<bool>& medium,
                                       uint32_t oversampling) {
    // Each surface VPL a path of one VPL, each medium VPL one of none (1/K): the same
    // thresholds, floor and steps.
    std::vector<float> surface(importance.size(), 0.0f);
    std::vector<uint32_t> counts(importance.size(), 0u);
    for (size_t i = 0; i < importance.size(); ++i)
        if (!medium[i]) surface[i] = importance[i], counts[i] = 1u;
    return path_keep_probabilities(surface, counts, oversampling);
}

std::vector<double> path_keep_probabilities(const std::vector<float>& importance, const std::vector<uint32_t>& vpls,
                                            uint32_t oversampling) {
    const double k = std::max(1u, oversampling);
    std::vector<double> p(importance.size(), 1.0 / k), a, w;
    double total = 0.0, count = 0.0;
    for (size_t j = 0; j < importance.size(); ++j) {
        total += importance[j];
        count += vpls[j];
    }
    if (!(total > 0.0) || k == 1.0) return p;
    const double mean = total / count;  // per VPL
    for (size_t j = 0; j < importance.size(); ++j)
        if (vpls[j] > 0) {
            a.push_back(importance[j] + kFloor * mean * vpls[j]);
            w.push_back(vpls[j]);
        }
    const double tau = keep_threshold(a, w, count / k);
    for (size_t j = 0, aj = 0; j < importance.size(); ++j)
        if (vpls[j] > 0) p[j] = stepped(a[aj++] / tau);
    return p;
}

std::vector<bool> systematic_sample(const std::vector<double>& p, double u) {
    std::vector<bool> keep(p.size(), false);
    // Unit j owns [C_{j-1}, C_j) of the cumulative sum; it is kept when one of the points
    // u, u + 1, u + 2, ... falls there: ceil(C_j - u) > ceil(C_{j-1} - u).
    double c = 0.0, before = std::ceil(-u);
    for (size_t j = 0; j < p.size(); ++j) {
        c += p[j];
        const double after = std::ceil(c - u);
        keep[j] = after > before;
        before = after;
    }
    return keep;
}

uint32_t select_vpls(const std::vector<float>& vpls, const std::vector<float>& importance, size_t begin, size_t end,
                     uint32_t oversampling, uint32_t seed_mix, std::vector<float>& out) {
    std::vector<bool> medium;
    for (size_t i = begin; i < end; ++i) medium.push_back(ts::ts_vpl_in_medium(&vpls[TS_VPL_FLOATS * i]));
    const std::vector<double> p =
        keep_probabilities(std::vector<float>(importance.begin() + begin, importance.begin() + end), medium,
                           oversampling);
    uint32_t kept = 0, place = 0, last_path = ~0u;
    for (size_t i = begin; i < end; ++i) {
        const float* v = &vpls[TS_VPL_FLOATS * i];
        const uint32_t path = path_of(v);
        place = path == last_path ? place + 1 : 0;
        last_path = path;
        ts::TsRng rng = ts::ts_rng_seed(kKeepSeed ^ seed_mix, path, place);
        const double pi = p[i - begin];
        if (!(ts::ts_rng_next(&rng) < pi)) continue;
        const size_t at = out.size();
        out.insert(out.end(), v, v + TS_VPL_FLOATS);
        for (int c = 0; c < 3; ++c) out[at + TS_VPL_FLUX + c] = static_cast<float>(v[TS_VPL_FLUX + c] / pi);
        ++kept;
    }
    return kept;
}

}  // namespace tessera
