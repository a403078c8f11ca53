#include "gi/ais_schedule.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ais_edges.h"
#include "kernels/shared/ais_guidance.h"
#include "kernels/shared/layout_igi.h"

namespace tessera {
namespace {

// The shared guidance's view of the host's base buffers (one float a pixel, luminances
// already taken; geometry as GeometryBuffer keeps it).
ts::TsAisGuideView guide_view(const AisBaseBuffers& b, const DiscontinuitySettings& s) {
    ts::TsAisGuideView v{};
    const GeometryBuffer& g = b.geometry;
    v.depth = g.depth.data();
    v.normal = g.normal.data();
    v.position = g.position.empty() ? nullptr : g.position.data();
    v.visibility = b.visibility.data();
    v.indirect = b.indirect.data();
    v.lit = b.lit_fraction.empty() ? nullptr : b.lit_fraction.data();
    v.length = b.medium_length.empty() ? nullptr : b.medium_length.data();
    v.media = b.media.empty() ? nullptr : b.media.data();
    v.depth_stride = v.surf_stride = v.media_stride = 1;
    v.vec_stride = 3;
    v.indirect_rgb = v.media_rgb = 0;
    v.width = g.width, v.height = g.height, v.tile = s.tile;
    v.cos_min = s.normal_cos, v.depth_rel = s.depth_rel;
    return v;
}

// Over one image row, each pixel's statistics of a one-float-a-pixel buffer over its
// accepted window positions (`masks`, the row's): SS's range (lo, hi) and ID's sums. Taken
// one window position at a time across the row, a branch-free loop the compiler runs in
// SIMD, instead of pixel by pixel over the mask's bits (at tile 8, 64 positions a pixel,
// that loop took 1.5 times as long). Each pixel's positions still come in window order,
// with the same operations as ts_ais_ss and ts_ais_window_cov: the same values.
struct WindowRow {
    std::vector<float> lo, hi;
    std::vector<double> sum, sum2;
    std::vector<int> count;  ///< accepted positions (moments)
    std::vector<float> cov;  ///< ts_ais_cov_of_sums of the above (window_row_cov)
};

void window_row(const float* v, const uint64_t* masks, int y, int w, int h, int n, const ptrdiff_t* offset,
                bool range, bool moments, WindowRow& r) {
    if (range) r.lo.assign(w, ts::TS_INF), r.hi.assign(w, -ts::TS_INF);
    if (moments) r.sum.assign(w, 0.0), r.sum2.assign(w, 0.0), r.count.assign(w, 0);
    int lo, hi;
    discontinuity_window(n, &lo, &hi);
    const float* row = v + size_t(y) * w;
    for (int i = 0; i < n * n; ++i) {
        const int dx = lo + i % n, dy = lo + i / n;
        if (y + dy < 0 || y + dy >= h) continue;  // no bit set: nothing to read
        const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
        const float* __restrict q = row + offset[i];
        const uint64_t* __restrict m = masks;
        if (range) {
            float *__restrict l = r.lo.data(), *__restrict u = r.hi.data();
            for (int x = x0; x < x1; ++x) {
                const uint32_t on = uint32_t(m[x] >> i) & 1u;
                const float s = q[x], l0 = l[x], u0 = u[x];
                l[x] = (on & uint32_t(s < l0)) ? s : l0;
                u[x] = (on & uint32_t(u0 < s)) ? s : u0;
            }
        }
        if (moments) {
            // A rejected position adds +0 (its value's bits masked off), which leaves a sum
            // that starts at +0 as it was; a conditional add would be a branch.
            double *__restrict a = r.sum.data(), *__restrict b = r.sum2.data();
            int* __restrict k = r.count.data();
            for (int x = x0; x < x1; ++x) {
                const uint64_t on = (m[x] >> i) & 1u;
                const double s = std::bit_cast<double>(std::bit_cast<uint64_t>(double(q[x])) & (0ull - on));
                a[x] += s;
                b[x] += s * s;
                k[x] += int(on);
            }
        }
    }
}

// Each pixel's ts_ais_cov_of_sums over the row's moments, in one loop the compiler runs in
// SIMD (with -fno-trapping-math, CMakeLists.txt): per pixel in the guidance loop, its
// four double divisions and square root were half of compute_guidance's time.
void window_row_cov(WindowRow& r, int w, float cov) {
    r.cov.resize(w);
    const double *__restrict a = r.sum.data(), *__restrict b = r.sum2.data();
    const int* __restrict k = r.count.data();
    float* __restrict c = r.cov.data();
    for (int x = 0; x < w; ++x) c[x] = ts::ts_ais_cov_of_sums(a[x], b[x], k[x], cov);
}

// For each own set (the pixel's position in its tile), the other sets ordered by the
// distance of the window position that holds them, farthest first (ties: lower set):
// n² rows of n² − 1 sets, as TS_AIS_TABLE_ORDER holds them.
std::vector<uint32_t> far_first_orders(int tile) {
    int lo, hi;
    discontinuity_window(tile, &lo, &hi);
    const int sets = tile * tile;
    std::vector<uint32_t> orders(size_t(sets) * (sets - 1));
    for (int py = 0; py < tile; ++py)
        for (int px = 0; px < tile; ++px) {
            std::vector<std::pair<int, int>> by_distance;  // (−distance², set)
            for (int dy = lo; dy <= hi; ++dy)
                for (int dx = lo; dx <= hi; ++dx)
                    if (dx || dy)
                        by_distance.push_back({-(dx * dx + dy * dy),
                                               interleave_set(px + dx + tile, py + dy + tile, tile)});
            std::sort(by_distance.begin(), by_distance.end());
            const size_t row = size_t(interleave_set(px, py, tile)) * (sets - 1);
            for (size_t r = 0; r < by_distance.size(); ++r) orders[row + r] = uint32_t(by_distance[r].second);
        }
    return orders;
}

// N_min: the accepted-neighbour count below which the filter cannot clean a pixel
// (docs/ais.md §3; default ⌈N/2⌉ of N = `sets`).
int min_accepted(const AisThresholds& t, int sets) { return t.min_accepted > 0 ? t.min_accepted : (sets + 1) / 2; }

ts::TsAisParams params_of(const AisThresholds& t, AisMode mode, int tile) {
    const int sets = tile * tile;
    ts::TsAisParams p{};
    p.trigger[kAisSS] = t.ss_trigger;
    p.trigger[kAisID] = t.id_trigger;
    p.trigger[kAisPM] = t.pm_trigger;
    p.id_cov = t.id_cov;
    p.pm_cov = t.pm_cov;
    p.min_accepted = min_accepted(t, sets);
    p.complete = t.complete_sets > 0 ? t.complete_sets : p.min_accepted;
    p.graded = t.graded_sets > 0 ? t.graded_sets : sets;  // ts_ais_set_mask takes min(G, N)
    p.amax = mode == AisMode::AMax;
    return p;
}

}  // namespace

AisGuidance compute_guidance(const AisBaseBuffers& base, const DiscontinuitySettings& filter,
                             const AisThresholds& t, const std::array<bool, kAisComponents>& enabled) {
    const int w = base.geometry.width, h = base.geometry.height;
    AisGuidance out;
    bool any = false;
    for (int c = 0; c < kAisComponents; ++c) {
        if (!enabled[c] || (c == kAisPM && base.lit_fraction.empty())) continue;
        out.g[c].assign(size_t(w) * h, 0.0f);
        out.grade[c].assign(size_t(w) * h, 0.0f);
        any = true;
    }
    if (!any) return out;
    out.missing.assign(size_t(w) * h, 0);
    out.held.assign(size_t(w) * h, 0);
    const ts::TsAisGuideView view = guide_view(base, filter);
    const ts::TsAisParams params = params_of(t, AisMode::A, filter.tile);
    const std::array<ptrdiff_t, 64> offset = discontinuity_window_offsets(filter.tile, w);
    const int n = filter.tile;
    int lo, hi;
    discontinuity_window(n, &lo, &hi);
    const bool ss = !out.g[kAisSS].empty(), id = !out.g[kAisID].empty();
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        std::vector<uint64_t> masks(w);
        WindowRow vis, ind;
        for (int y = rows.begin(); y < rows.end(); ++y) {
            for (int x = 0; x < w; ++x) masks[x] = discontinuity_window_mask(base.geometry, filter, x, y);
            // The rows' SIMD sums hold for the centred windows; a window moved in at the
            // border (ts_discontinuity_lo_at) takes the per-pixel functions, as the device.
            const bool row_moved = ts::ts_discontinuity_lo_at(y, h, n) != lo;
            if (ss && !row_moved) window_row(base.visibility.data(), masks.data(), y, w, h, n, offset.data(), true, false, vis);
            if (id && !row_moved) {
                window_row(base.indirect.data(), masks.data(), y, w, h, n, offset.data(), false, true, ind);
                window_row_cov(ind, w, params.id_cov);
            }
            const int sy = ts::ts_ais_window_origin(y, h, n);
            for (int x = 0; x < w; ++x) {
                const size_t p = size_t(y) * w + x;
                const bool moved = row_moved || ts::ts_discontinuity_lo_at(x, w, n) != lo;
                long moved_offset[64];
                if (moved) ts::ts_discontinuity_offsets_at(x, y, w, h, n, moved_offset);
                const long* off = moved ? moved_offset : offset.data();
                const uint64_t in_image = ts::ts_ais_in_image(x, y, w, h, n);
                const uint64_t accepted = masks[x];
                uint64_t missing, held;
                ts::ts_ais_window_sets(in_image, accepted, ts::ts_ais_window_origin(x, w, n), sy, n, &missing, &held);
                out.missing[p] = missing;
                out.held[p] = held;
                // SS and ID are 0 where the camera ray escaped (ts_ais_guidance).
                const bool surface = std::isfinite(base.geometry.depth[p]);
                if (ss && surface) {
                    const ts::TsAisValue v =
                        moved ? ts::ts_ais_ss(&view, &params, off, in_image, accepted, p)
                              : ts::ts_ais_ss_value(vis.lo[x], vis.hi[x], base.visibility[p], in_image, accepted,
                                                    params.min_accepted);
                    out.g[kAisSS][p] = v.g, out.grade[kAisSS][p] = v.grade;
                }
                if (id && surface) {
                    const ts::TsAisValue v =
                        moved ? ts::ts_ais_id(&view, &params, off, in_image, accepted, x, y)
                              : ts::ts_ais_id_value(&view, &params, ind.cov[x], in_image, accepted, x, y);
                    out.g[kAisID][p] = v.g, out.grade[kAisID][p] = v.grade;
                }
                if (!out.g[kAisPM].empty()) {
                    const ts::TsAisValue v = ts::ts_ais_guidance(&view, &params, off, kAisPM, in_image, accepted, x, y);
                    out.g[kAisPM][p] = v.g, out.grade[kAisPM][p] = v.grade;
                }
            }
        }
    });
    return out;
}

AisSchedule make_schedule(const AisGuidance& guidance, const AisThresholds& t, AisMode mode, int width,
                          int height, int tile) {
    const int sets = tile * tile;
    const size_t pixels = size_t(width) * height;
    const ts::TsAisParams params = params_of(t, mode, tile);
    const std::vector<uint32_t> orders = far_first_orders(tile);
    AisSchedule s;
    for (int c = 0; c < kAisComponents; ++c) {
        if (guidance.g[c].empty()) continue;
        s.masks[c].resize(pixels);
        s.sets[c].resize(pixels);
        // Rows in parallel, each row's flagged count apart (summed in row order below).
        std::vector<uint32_t> flagged_in_row(size_t(height), 0);
        tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y < rows.end(); ++y)
                for (int x = 0; x < width; ++x) {
                    const size_t p = size_t(y) * width + x;
                    const int own = interleave_set(x, y, tile);
                    // A guidance without grades grades by g; without window sets, p holds
                    // only its own set and misses none.
                    const ts::TsAisValue v = {guidance.g[c][p], guidance.grade[c].empty() ? guidance.g[c][p]
                                                                                          : guidance.grade[c][p]};
                    flagged_in_row[y] += v.g > params.trigger[c];
                    const uint64_t held = guidance.held.empty() ? 0 : guidance.held[p];
                    const uint64_t missing = guidance.missing.empty() ? 0 : guidance.missing[p];
                    s.masks[c][p] = ts::ts_ais_set_mask(v, params.trigger[c], &params, own, sets, held, missing,
                                                        orders.data() + size_t(own) * (sets - 1));
                    s.sets[c][p] = static_cast<uint8_t>(std::popcount(s.masks[c][p]));
                }
        });
        size_t flagged = 0;
        for (uint32_t f : flagged_in_row) flagged += f;
        s.flagged[c] = pixels ? double(flagged) / pixels : 0.0;
    }
    schedule_items(s, width, height, tile);
    return s;
}

void schedule_items(AisSchedule& s, int width, int height, int tile) {
    s.item_pixels.clear();
    s.item_sets.clear();
    s.item_components.clear();
    const int sets = tile * tile;
    // Items grouped by set, then by tile and pixel, over the pixels that have extra sets at
    // all. Within a set, items run tile by tile (kItemTile² pixels, rows of tiles, scanline
    // inside a tile), so the 16 consecutive items a packet backend traces together lie
    // close on screen. Each pixel still adds its sets in increasing order: images do not
    // change.
    auto is_refined = [&](size_t p) {
        uint64_t extra = 0;
        for (int c = 0; c < kAisComponents; ++c)
            if (!s.masks[c].empty()) extra |= s.masks[c][p];
        return std::popcount(extra) > 1;
    };
    std::vector<uint32_t> refined;
    for (int ty = 0; ty < height; ty += int(kItemTile))
        for (int tx = 0; tx < width; tx += int(kItemTile))
            for (int y = ty; y < std::min(height, ty + int(kItemTile)); ++y)
                for (int x = tx; x < std::min(width, tx + int(kItemTile)); ++x)
                    if (is_refined(size_t(y) * width + x))
                        refined.push_back(static_cast<uint32_t>(size_t(y) * width + x));
    // A counting sort by set: each refined pixel's extra sets (its own set excluded) counted
    // per set, then the items placed, pixels in `refined` order within each set. The order
    // of the loop over every set and every refined pixel this replaced, in O(items).
    auto extra_sets = [&](uint32_t p) {
        uint64_t extra = 0;
        for (int c = 0; c < kAisComponents; ++c)
            if (!s.masks[c].empty()) extra |= s.masks[c][p];
        return extra & ~(1ull << interleave_set(static_cast<int>(p % width), static_cast<int>(p / width), tile));
    };
    std::vector<uint64_t> extra(refined.size());
    std::vector<size_t> next(size_t(sets) + 1, 0);
    for (size_t r = 0; r < refined.size(); ++r) {
        extra[r] = extra_sets(refined[r]);
        for (uint64_t b = extra[r]; b; b &= b - 1) ++next[std::countr_zero(b) + 1];
    }
    for (int k = 0; k < sets; ++k) next[k + 1] += next[k];  // next[k]: set k's first item
    s.item_pixels.resize(next[sets]);
    s.item_sets.resize(next[sets]);
    s.item_components.resize(next[sets]);
    for (size_t r = 0; r < refined.size(); ++r)
        for (uint64_t b = extra[r]; b; b &= b - 1) {
            const int k = std::countr_zero(b);
            const size_t at = next[k]++;
            uint8_t bits = 0;
            for (int c = 0; c < kAisComponents; ++c)
                if (!s.masks[c].empty() && (s.masks[c][refined[r]] >> k & 1)) bits |= uint8_t(1u << c);
            s.item_pixels[at] = refined[r];
            s.item_sets[at] = static_cast<uint8_t>(k);
            s.item_components[at] = bits;
        }
}

std::vector<uint32_t> ais_schedule_table(const AisThresholds& t, AisMode mode, int tile, uint32_t components,
                                         const EdgeSettings& e, float edge_epsilon) {
    const ts::TsAisParams p = params_of(t, mode, tile);
    std::vector<uint32_t> table(TS_AIS_TABLE_ORDER, 0u);
    for (int c = 0; c < kAisComponents; ++c) table[TS_AIS_TABLE_TRIGGER + c] = std::bit_cast<uint32_t>(p.trigger[c]);
    table[TS_AIS_TABLE_ID_COV] = std::bit_cast<uint32_t>(p.id_cov);
    table[TS_AIS_TABLE_PM_COV] = std::bit_cast<uint32_t>(p.pm_cov);
    table[TS_AIS_TABLE_MIN_ACCEPTED] = uint32_t(p.min_accepted);
    table[TS_AIS_TABLE_COMPLETE] = uint32_t(p.complete);
    table[TS_AIS_TABLE_GRADED] = uint32_t(p.graded);
    table[TS_AIS_TABLE_MODE] = uint32_t(p.amax);
    table[TS_AIS_TABLE_COMPONENTS] = components;
    table[TS_AIS_TABLE_EDGE_TRIGGER] = std::bit_cast<uint32_t>(e.trigger);
    table[TS_AIS_TABLE_EDGE_FULL] = std::bit_cast<uint32_t>(e.full);
    table[TS_AIS_TABLE_EDGE_SAMPLES] = std::clamp<uint32_t>(e.samples, 1u, 15u);
    table[TS_AIS_TABLE_EDGE_EPSILON] = std::bit_cast<uint32_t>(edge_epsilon);
    const std::vector<uint32_t> orders = far_first_orders(tile);
    table.insert(table.end(), orders.begin(), orders.end());
    return table;
}

}  // namespace tessera
