#include "gi/ais_edges.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/shared/composite.h"
#include "kernels/shared/discontinuity.h"
#include "kernels/shared/edge_guidance.h"
#include "kernels/shared/layout_igi.h"
#include "kernels/shared/layout_pass.h"
#include "kernels/shared/sampling.h"

namespace tessera {
namespace {

constexpr const auto& kWindow = ts::ts_edge_window;

ts::float3 f3(const std::vector<float>& v, size_t p) { return ts::ts_f3_load(&v[3 * p]); }

template <class F>
void parallel_rows(int height, F&& f) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& r) {
        for (int y = r.begin(); y < r.end(); ++y) f(y);
    });
}

// The steps (dx, dy) from a pair's first pixel to its second over ts_edge_pairs: the four
// ring steps and the two straight-through ones.
constexpr int kSteps[6][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {2, 0}, {0, 2}};

constexpr int step_of(int dx, int dy) {
    for (int k = 0; k < 6; ++k)
        if (kSteps[k][0] == dx && kSteps[k][1] == dy) return k;
    return -1;
}

// Pair i's step, an index into kSteps.
constexpr auto kPairStep = [] {
    std::array<int, 10> step{};
    for (int i = 0; i < 10; ++i)
        step[i] = step_of(ts::ts_edge_pairs[i][2] - ts::ts_edge_pairs[i][0], ts::ts_edge_pairs[i][3] - ts::ts_edge_pairs[i][1]);
    return step;
}();
static_assert(std::find(kPairStep.begin(), kPairStep.end(), -1) == kPairStep.end(), "a pair's step is not in kSteps");
// edge_guidance's quick test reads the 8 pixels around p: every pair's first pixel is one.
static_assert([] {
    for (const auto& pair : ts::ts_edge_pairs)
        if (pair[0] < -1 || pair[0] > 1 || pair[1] < -1 || pair[1] > 1 || (pair[0] == 0 && pair[1] == 0)) return false;
    return true;
}());

// Per pixel q, bit k set where the pair (q, q + kSteps[k]) lies in the image and is an
// edge: q's discontinuity test rejects its partner, or one of the two shows a light and
// the other does not. Each pair is tested once here, not once per pixel whose ring holds
// it (a ring pair lies in two pixels' rings).
std::vector<uint8_t> edge_pair_flags(const GeometryBuffer& g, const DiscontinuitySettings& s,
                                     const std::vector<uint8_t>& emitter) {
    const size_t pixels = size_t(g.width) * g.height;
    // The frame's precomputed masks (discontinuity_precompute) hold the test's answers for
    // a step that lies in the filter's window (the ring steps from tile 3 on, the
    // straight-through ones from tile 5; ts_discontinuity_position: a window moved in at
    // the border may not hold them). The test per pair took 6 ms of a 256² frame at tile 3
    // and 12 ms of a 512² frame at tile 8; the masks give the same bits.
    const bool masks = s.tile <= 8 && g.accepted.size() == pixels && g.accepted_for.tile == s.tile &&
                       g.accepted_for.normal_cos == s.normal_cos && g.accepted_for.depth_rel == s.depth_rel;
    // Each column's and row's window start, once: ts_discontinuity_position per pair
    // divided by the tile edge four times.
    const int n = static_cast<int>(s.tile);
    std::vector<int> lo_x(masks ? g.width : 0), lo_y(masks ? g.height : 0);
    for (size_t x = 0; x < lo_x.size(); ++x) lo_x[x] = ts::ts_discontinuity_lo_at(int(x), g.width, n);
    for (size_t v = 0; v < lo_y.size(); ++v) lo_y[v] = ts::ts_discontinuity_lo_at(int(v), g.height, n);
    std::vector<uint8_t> flags(pixels, 0);
    parallel_rows(g.height, [&](int qy) {
        for (int qx = 0; qx < g.width; ++qx) {
            const size_t qa = size_t(qy) * g.width + qx;
            uint8_t bits = 0;
            for (int k = 0; k < 6; ++k) {
                const int dx = kSteps[k][0], dy = kSteps[k][1], bx = qx + dx, by = qy + dy;
                if (bx < 0 || by < 0 || bx >= g.width || by >= g.height) continue;
                const size_t qb = size_t(by) * g.width + bx;
                const int bit = masks ? ts::ts_discontinuity_position_in(lo_x[qx], lo_y[qy], n, dx, dy) : -1;
                const bool accepted = bit >= 0 ? (g.accepted[qa] >> bit) & 1u : discontinuity_accepts(g, s, qa, qb);
                const bool light_edge = !emitter.empty() && (emitter[qa] != 0) != (emitter[qb] != 0);
                if (!accepted || light_edge) bits |= uint8_t(1u << k);
            }
            flags[qa] = bits;
        }
    });
    return flags;
}

}  // namespace

float edge_epsilon(const std::vector<float>& radiance, int width, float dark) {
    const size_t pixels = radiance.size() / TS_PASS_FLOATS, height = width > 0 ? pixels / size_t(width) : 0;
    if (width <= 0 || height * size_t(width) != pixels || pixels * TS_PASS_FLOATS != radiance.size())
        throw std::invalid_argument("edge_epsilon: " + std::to_string(radiance.size()) + " floats are not rows of " +
                                    std::to_string(width) + " pixels");
    std::vector<double> rows(height);
    parallel_rows(static_cast<int>(height), [&](int y) {
        rows[y] = ts::ts_edge_row_luminance(radiance.data(), static_cast<uint32_t>(width), static_cast<uint32_t>(y));
    });
    double sum = 0.0;
    for (double r : rows) sum += r;
    return dark * static_cast<float>(sum / std::max<size_t>(1, pixels));
}

float edge_epsilon_of_rows(const std::vector<float>& rows, size_t pixels, float dark) {
    double sum = 0.0;
    for (size_t i = 0; i + TS_EDGE_ROW_FLOATS <= rows.size(); i += TS_EDGE_ROW_FLOATS) {
        const float* r = &rows[i];
        if (r[TS_EDGE_ROW_HAS_DOUBLE] > 0.0f)
            sum += std::bit_cast<double>(uint64_t(std::bit_cast<uint32_t>(r[TS_EDGE_ROW_DOUBLE + 1])) << 32 |
                                         std::bit_cast<uint32_t>(r[TS_EDGE_ROW_DOUBLE]));
        else
            sum += r[TS_EDGE_ROW_FLOAT];
    }
    return dark * static_cast<float>(sum / std::max<size_t>(1, pixels));
}

std::vector<float> edge_guidance(const GeometryBuffer& g, const DiscontinuitySettings& s,
                                 const std::vector<float>& radiance, float dark, const std::vector<uint8_t>& emitter) {
    const size_t pixels = size_t(g.width) * g.height;
    std::vector<float> y(pixels);
    parallel_rows(g.height, [&](int py) {
        for (size_t p = size_t(py) * g.width, end = p + g.width; p < end; ++p)
            y[p] = ts::ts_luminance(ts::ts_f3_load(&radiance[p * TS_PASS_FLOATS + TS_PASS_RADIANCE]));
    });
    const float eps = edge_epsilon(radiance, g.width, dark);
    const std::vector<uint8_t> edges = edge_pair_flags(g, s, emitter);
    std::vector<float> out(pixels, 0.0f);
    parallel_rows(g.height, [&](int py) {
        const bool inner_row = py > 0 && py + 1 < g.height;
        for (int px = 0; px < g.width; ++px) {
            const size_t p = size_t(py) * g.width + px;
            // Most pixels have no edge pair in their ring: every pair's first pixel is one
            // of the 8 around p, so none flagged there means 0 without the pairs' bounds.
            if (inner_row && px > 0 && px + 1 < g.width &&
                !(edges[p - g.width - 1] | edges[p - g.width] | edges[p - g.width + 1] | edges[p - 1] | edges[p + 1] |
                  edges[p + g.width - 1] | edges[p + g.width] | edges[p + g.width + 1]))
                continue;
            float best = 0.0f;
            // The neighbour pairs of ts_edge_pairs: a pair the first's discontinuity test
            // rejects, or on either side of a light's edge.
            for (int i = 0; i < 10; ++i) {
                size_t qa, qb;
                if (!ts::ts_edge_pair_pixels(px, py, g.width, g.height, i, &qa, &qb)) continue;
                if (!(edges[qa] >> kPairStep[i] & 1u)) continue;
                best = ts::ts_edge_max(best, ts::ts_edge_contrast(y[qa], y[qb], eps));
            }
            out[p] = best;
        }
    });
    return out;
}

EdgeSchedule make_edge_schedule(const std::vector<float>& guidance, const EdgeSettings& e, AisMode mode) {
    EdgeSchedule s;
    s.samples.assign(guidance.size(), 0);
    const uint32_t most = std::clamp<uint32_t>(e.samples, 1u, 15u);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, guidance.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t p = r.begin(); p < r.end(); ++p)
            s.samples[p] = static_cast<uint8_t>(
                ts::ts_edge_sample_count(guidance[p], e.trigger, e.full, most, mode == AisMode::AMax));
    });
    edge_schedule_items(s);
    return s;
}

void edge_schedule_items(EdgeSchedule& s) {
    s.items.clear();
    size_t flagged = 0;
    size_t words = 0;
    for (uint8_t n : s.samples) {
        flagged += n > 0;
        words += size_t(n) * TS_EDGE_ITEM_WORDS;
    }
    s.items.resize(words);
    uint32_t* item = s.items.data();
    for (size_t p = 0; p < s.samples.size(); ++p)
        for (uint32_t j = 1, n = s.samples[p]; j <= n; ++j, item += TS_EDGE_ITEM_WORDS) {
            item[TS_EDGE_ITEM_PIXEL] = static_cast<uint32_t>(p);
            item[TS_EDGE_ITEM_SAMPLE] = j;
            item[TS_EDGE_ITEM_COUNT] = n;
        }
    s.flagged = s.samples.empty() ? 0.0 : double(flagged) / double(s.samples.size());
}

size_t edge_sample_match(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y, const float* sample) {
    const float zs = sample[TS_EDGE_SAMPLE_DISTANCE];
    const ts::float3 ns = ts::ts_f3_load(sample + TS_EDGE_SAMPLE_NORMAL);
    const ts::float3 xs = ts::ts_f3_load(sample + TS_EDGE_SAMPLE_POSITION);
    const bool plane = !g.position.empty();
    const ts::float3 none = ts::make_float3(0.0f, 0.0f, 0.0f);
    const size_t p = size_t(y) * g.width + x;
    size_t accepted = p, nearest = p;
    float accepted_d = std::numeric_limits<float>::infinity(), depth_d = accepted_d;
    bool any = false;
    for (const auto& o : kWindow) {
        const int qx = x + o[0], qy = y + o[1];
        if (qx < 0 || qy < 0 || qx >= g.width || qy >= g.height) continue;
        const size_t q = size_t(qy) * g.width + qx;
        const float zq = g.depth[q];
        const ts::float3 xq = plane ? f3(g.position, q) : none;
        if (ts::ts_discontinuity_accepts(zs, ns, plane ? xs : none, zq, f3(g.normal, q), xq, plane, s.normal_cos,
                                         s.depth_rel)) {
            // Escaped samples match the first escaped pixel; surfaces the nearest point.
            const ts::float3 d = xq - xs;
            const float d2 = !std::isfinite(zs) ? 0.0f : plane ? ts::dot(d, d) : std::fabs(zq - zs);
            if (!any || d2 < accepted_d) accepted = q, accepted_d = d2;
            any = true;
        } else if (std::isfinite(zs) && std::isfinite(zq)) {
            const float dz = std::fabs(zq - zs);
            if (dz < depth_d) nearest = q, depth_d = dz;
        }
    }
    if (!std::isfinite(zs) && !any) return p;
    return any ? accepted : nearest;
}

void merge_edge_samples(const GeometryBuffer& g, const DiscontinuitySettings& s, const EdgeSchedule& schedule,
                        const std::vector<float>& samples, const EdgeShading& shading, std::vector<float>& out) {
    // Each flagged pixel's first item: its samples are consecutive items.
    std::vector<size_t> first(schedule.samples.size(), 0);
    for (size_t i = 0, n = schedule.items.size() / TS_EDGE_ITEM_WORDS; i < n; ++i) {
        const size_t p = schedule.items[TS_EDGE_ITEM_WORDS * i + TS_EDGE_ITEM_PIXEL];
        if (schedule.items[TS_EDGE_ITEM_WORDS * i + TS_EDGE_ITEM_SAMPLE] == 1) first[p] = i;
    }
    parallel_rows(g.height, [&](int y) {
        for (int x = 0; x < g.width; ++x) {
            const size_t p = size_t(y) * g.width + x;
            const uint32_t n = schedule.samples[p];
            if (n == 0) continue;
            float* o = &out[p * TS_PASS_FLOATS + TS_PASS_RADIANCE];
            double sum[3] = {o[0], o[1], o[2]};
            for (uint32_t j = 0; j < n; ++j) {
                const float* e = &samples[(first[p] + j) * TS_EDGE_SAMPLE_FLOATS];
                const size_t q = edge_sample_match(g, s, x, y, e);
                const ts::float3 l = ts::ts_igi_composite(
                    f3(*shading.transmittance, q), ts::ts_f3_load(e + TS_EDGE_SAMPLE_THROUGHPUT),
                    ts::ts_f3_load(e + TS_EDGE_SAMPLE_EMISSION), ts::ts_f3_load(e + TS_EDGE_SAMPLE_ALBEDO),
                    f3(*shading.e_ss, q), f3(*shading.e_id, q), f3(*shading.l_pm, q));
                sum[0] += l.x, sum[1] += l.y, sum[2] += l.z;
            }
            for (int c = 0; c < 3; ++c) o[c] = static_cast<float>(sum[c] / (n + 1));
        }
    });
}

}  // namespace tessera
