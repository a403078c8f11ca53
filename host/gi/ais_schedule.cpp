#include "gi/ais_schedule.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace tessera {
namespace {

// p's filter window as bit sets over window positions i = (dy − lo)·n + (dx − lo).
struct WindowBits {
    uint64_t in_image = 0;  ///< the position lies in the image
    uint64_t accepted = 0;  ///< ... and p accepts it (p itself included)
};

// Constants of the window walks of one frame: the pixel offset of each window position,
// and the set each position holds for a pixel of each own set (an n×n window holds each
// set once, where depends only on the pixel's own set). Saves the walks a division and a
// modulo by n per position.
struct WindowWalk {
    int lo, hi;    // the window's offsets on each axis
    uint64_t all;  // every window position
    std::array<ptrdiff_t, 64> offset;
    std::vector<std::array<uint8_t, 64>> set_at;  // [own set][position]

    WindowWalk(int n, int width) : set_at(size_t(n) * n) {
        discontinuity_window(n, &lo, &hi);
        all = n * n == 64 ? ~0ull : (1ull << (n * n)) - 1;
        offset = discontinuity_window_offsets(n, width);
        for (int own = 0; own < n * n; ++own)  // a pixel of set `own` with its window in x, y >= 0
            for (int i = 0; i < n * n; ++i)
                set_at[own][i] =
                    static_cast<uint8_t>(interleave_set(own % n + n + lo + i % n, own / n + n + lo + i / n, n));
    }

    // Calls f(q) for each window position of `bits` around pixel p (pixel index q).
    template <class F>
    void for_positions(uint64_t bits, size_t p, F&& f) const {
        for (; bits; bits &= bits - 1) f(p + offset[std::countr_zero(bits)]);
    }

    // The sets held by the window positions in `bits` of a pixel of set `own`.
    uint64_t sets_of(uint64_t bits, int own) const {
        uint64_t sets = 0;
        for (; bits; bits &= bits - 1) sets |= 1ull << set_at[own][std::countr_zero(bits)];
        return sets;
    }
};

WindowBits window_bits(const GeometryBuffer& g, const DiscontinuitySettings& s, const WindowWalk& walk, int x,
                       int y) {
    WindowBits b;
    if (x + walk.lo >= 0 && y + walk.lo >= 0 && x + walk.hi < g.width && y + walk.hi < g.height) {
        b.in_image = walk.all;
    } else {
        int i = 0;
        for (int dy = walk.lo; dy <= walk.hi; ++dy)
            for (int dx = walk.lo; dx <= walk.hi; ++dx, ++i) {
                const int qx = x + dx, qy = y + dy;
                if (qx >= 0 && qy >= 0 && qx < g.width && qy < g.height) b.in_image |= 1ull << i;
            }
    }
    b.accepted = discontinuity_window_mask(g, s, x, y);
    return b;
}

// Whether the filter cannot clean p: it accepts fewer than `min_acc` neighbours because
// it rejects some inside the image (a window clipped by the image border is not an edge).
bool unfilterable(const WindowBits& b, int min_acc) {
    return std::popcount(b.accepted) < min_acc && b.accepted != b.in_image;
}

bool on_geometric_edge(const GeometryBuffer& g, const DiscontinuitySettings& s, const WindowBits& wb, int x,
                       int y) {
    int lo, hi;
    discontinuity_window(s.tile, &lo, &hi);
    if (lo <= -1 && hi >= 1) {  // the 3×3 neighbourhood lies in the window: read its bits
        const int n = s.tile;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const uint64_t bit = 1ull << ((dy - lo) * n + (dx - lo));
                if ((wb.in_image & bit) && !(wb.accepted & bit)) return true;
            }
        return false;
    }
    const size_t p = size_t(y) * g.width + x;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= g.width || qy >= g.height) continue;
            if (!discontinuity_accepts(g, s, p, size_t(qy) * g.width + qx)) return true;
        }
    return false;
}

struct Value {
    float g, grade;
};

Value ss_guidance(const AisBaseBuffers& b, const WindowWalk& walk, const WindowBits& wb, int min_acc, size_t p) {
    float lo = INFINITY, hi = -INFINITY;
    walk.for_positions(wb.accepted, p, [&](size_t q) {
        lo = std::min(lo, b.visibility[q]);
        hi = std::max(hi, b.visibility[q]);
    });
    const float v = b.visibility[p], range = hi - lo;
    const bool edge = v > 0.0f && v < 1.0f && unfilterable(wb, min_acc);
    return {edge ? 1.0f : range, range};
}

// The coefficient of variation of v over p's accepted window positions, over `cov`,
// clamped to 1 (0 where the mean is 0): g_var of ID and PM.
float window_cov(const std::vector<float>& v, const WindowWalk& walk, const WindowBits& wb, size_t p, float cov) {
    double sum = 0.0, sum2 = 0.0;
    int count = 0;
    walk.for_positions(wb.accepted, p, [&](size_t q) {
        sum += v[q];
        sum2 += double(v[q]) * v[q];
        ++count;
    });
    const double mean = sum / count;
    return mean > 0.0 ? static_cast<float>(std::min(1.0, std::sqrt(std::max(0.0, sum2 / count - mean * mean)) / mean / cov))
                      : 0.0f;
}

Value id_guidance(const AisBaseBuffers& b, const DiscontinuitySettings& s, const AisThresholds& t,
                  const WindowWalk& walk, const WindowBits& wb, int min_acc, int x, int y) {
    const size_t p = size_t(y) * b.geometry.width + x;
    const float var = window_cov(b.indirect, walk, wb, p, t.id_cov);
    const bool edge = unfilterable(wb, min_acc) || on_geometric_edge(b.geometry, s, wb, x, y);
    return {edge ? 1.0f : var, var};
}

// g_len looks only at the neighbours the filter rejects: a smooth change of the medium
// length (a slanted wall) is no failure, as the box filter's mean of a linear ramp is its
// centre value (docs/ais.md §3).
Value pm_guidance(const AisBaseBuffers& b, const DiscontinuitySettings& s, const AisThresholds& t,
                  const WindowWalk& walk, const WindowBits& wb, size_t p) {
    const float lp = b.medium_length[p];
    float lo = INFINITY, hi = -INFINITY;
    walk.for_positions(wb.in_image, p, [&](size_t q) {
        lo = std::min(lo, b.lit_fraction[q]);
        hi = std::max(hi, b.lit_fraction[q]);
    });
    bool length_edge = false;
    walk.for_positions(wb.in_image & ~wb.accepted, p, [&](size_t q) {
        length_edge |= std::abs(b.medium_length[q] - lp) > s.depth_rel * lp;
    });
    const bool var = t.pm_cov > 0.0f && !b.media.empty();
    const float grade = std::max(hi - lo, var ? window_cov(b.media, walk, wb, p, t.pm_cov) : 0.0f);
    return {length_edge ? 1.0f : grade, grade};
}

// For each own set (the pixel's position in its tile), the other sets ordered by the
// distance of the window position that holds them, farthest first (ties: lower set).
std::vector<std::vector<int>> far_first_orders(int tile) {
    int lo, hi;
    discontinuity_window(tile, &lo, &hi);
    std::vector<std::vector<int>> orders(size_t(tile) * tile);
    for (int py = 0; py < tile; ++py)
        for (int px = 0; px < tile; ++px) {
            std::vector<std::pair<int, int>> by_distance;  // (−distance², set)
            for (int dy = lo; dy <= hi; ++dy)
                for (int dx = lo; dx <= hi; ++dx)
                    if (dx || dy)
                        by_distance.push_back({-(dx * dx + dy * dy),
                                               interleave_set(px + dx + tile, py + dy + tile, tile)});
            std::sort(by_distance.begin(), by_distance.end());
            for (const auto& [d, set] : by_distance) orders[interleave_set(px, py, tile)].push_back(set);
        }
    return orders;
}

// N_min: the accepted-neighbour count below which the filter cannot clean a pixel
// (docs/ais.md §3; default ⌈N/2⌉ of N = `sets`).
int min_accepted(const AisThresholds& t, int sets) { return t.min_accepted > 0 ? t.min_accepted : (sets + 1) / 2; }

// A's grade: the signal's strength above its trigger, in [0, 1].
float grade_of(const AisGuidance& g, int c, size_t p, float trigger) {
    const auto& signal = g.grade[c].empty() ? g.g[c] : g.grade[c];
    return std::clamp((signal[p] - trigger) / (1.0f - trigger), 0.0f, 1.0f);
}

// A's sets for a flagged pixel p with own set `own`: missing sets until p holds `complete`
// distinct sets, then ⌈grade·(N−1)⌉ more, both in `order` (farthest window position first).
uint64_t a_mask(const AisGuidance& g, size_t p, int own, int complete, float grade,
                const std::vector<int>& order, int sets) {
    uint64_t mask = 1ull << own;
    const uint64_t held = g.held.empty() ? mask : g.held[p] | mask;
    if (!g.missing.empty()) {
        int need = complete - std::popcount(held);
        for (int k : order) {
            if (need <= 0) break;
            if (!(g.missing[p] >> k & 1)) continue;
            mask |= 1ull << k;
            --need;
        }
    }
    int more = static_cast<int>(std::ceil(grade * (sets - 1)));
    for (int k : order) {
        if (more <= 0) break;
        if (mask >> k & 1) continue;
        mask |= 1ull << k;
        --more;
    }
    return mask;
}

}  // namespace

AisGuidance compute_guidance(const AisBaseBuffers& base, const DiscontinuitySettings& filter,
                             const AisThresholds& t, const std::array<bool, kAisComponents>& enabled) {
    const int w = base.geometry.width, h = base.geometry.height;
    const int sets = filter.tile * filter.tile;
    const int min_acc = min_accepted(t, sets);
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
    const WindowWalk walk(filter.tile, w);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                const size_t p = size_t(y) * w + x;
                const WindowBits wb = window_bits(base.geometry, filter, walk, x, y);
                const int own = interleave_set(x, y, filter.tile);
                out.missing[p] = walk.sets_of(wb.in_image & ~wb.accepted, own);
                out.held[p] = walk.sets_of(wb.accepted, own);
                for (int c = 0; c < kAisComponents; ++c) {
                    if (out.g[c].empty()) continue;
                    if (c != kAisPM && !std::isfinite(base.geometry.depth[p])) continue;  // nothing to shade
                    const Value v = c == kAisSS   ? ss_guidance(base, walk, wb, min_acc, p)
                                    : c == kAisID ? id_guidance(base, filter, t, walk, wb, min_acc, x, y)
                                                  : pm_guidance(base, filter, t, walk, wb, p);
                    out.g[c][p] = v.g;
                    out.grade[c][p] = v.grade;
                }
            }
    });
    return out;
}

AisSchedule make_schedule(const AisGuidance& guidance, const AisThresholds& t, AisMode mode, int width,
                          int height, int tile) {
    const int sets = tile * tile;
    const int complete = t.complete_sets > 0 ? t.complete_sets : min_accepted(t, sets);
    const size_t pixels = size_t(width) * height;
    const uint64_t all = sets == 64 ? ~0ull : (1ull << sets) - 1;
    const float trigger[kAisComponents] = {t.ss_trigger, t.id_trigger, t.pm_trigger};
    const std::vector<std::vector<int>> orders = far_first_orders(tile);
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
                    uint64_t mask = 1ull << own;
                    if (guidance.g[c][p] > trigger[c]) {
                        ++flagged_in_row[y];
                        if (mode == AisMode::AMax) {
                            mask = all;
                        } else {
                            mask = a_mask(guidance, p, own, complete, grade_of(guidance, c, p, trigger[c]),
                                          orders[own], sets);
                        }
                    }
                    s.masks[c][p] = mask;
                    s.sets[c][p] = static_cast<uint8_t>(std::popcount(mask));
                }
        });
        size_t flagged = 0;
        for (uint32_t f : flagged_in_row) flagged += f;
        s.flagged[c] = pixels ? double(flagged) / pixels : 0.0;
    }
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
    for (int k = 0; k < sets; ++k)
        for (uint32_t p : refined) {
            if (k == interleave_set(static_cast<int>(p % width), static_cast<int>(p / width), tile)) continue;
            uint8_t bits = 0;
            for (int c = 0; c < kAisComponents; ++c)
                if (!s.masks[c].empty() && (s.masks[c][p] >> k & 1)) bits |= uint8_t(1u << c);
            if (!bits) continue;
            s.item_pixels.push_back(p);
            s.item_sets.push_back(static_cast<uint8_t>(k));
            s.item_components.push_back(bits);
        }
    return s;
}

}  // namespace tessera
