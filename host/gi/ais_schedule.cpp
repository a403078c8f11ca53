#include "gi/ais_schedule.h"

#include <algorithm>
#include <cmath>

namespace tessera {
namespace {

// Calls f(q) for every pixel q of p's filter window that lies in the image.
template <class F>
void for_window(const GeometryBuffer& g, int tile, int x, int y, F&& f) {
    int lo, hi;
    discontinuity_window(tile, &lo, &hi);
    for (int dy = lo; dy <= hi; ++dy)
        for (int dx = lo; dx <= hi; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx >= 0 && qy >= 0 && qx < g.width && qy < g.height) f(size_t(qy) * g.width + qx);
        }
}

// Calls f(q) for every pixel q of p's filter window that p accepts (p itself included).
template <class F>
void for_accepted(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y, F&& f) {
    const size_t p = size_t(y) * g.width + x;
    for_window(g, s.tile, x, y, [&](size_t q) {
        if (q == p || discontinuity_accepts(g, s, p, q)) f(q);
    });
}

// Whether the filter cannot clean p: it accepts fewer than `min_acc` neighbours because
// it rejects some inside the image (a window clipped by the image border is not an edge).
bool unfilterable(const GeometryBuffer& g, const DiscontinuitySettings& s, int min_acc, int x, int y) {
    int accepted = 0, in_image = 0;
    const size_t p = size_t(y) * g.width + x;
    for_window(g, s.tile, x, y, [&](size_t q) {
        ++in_image;
        accepted += q == p || discontinuity_accepts(g, s, p, q);
    });
    return accepted < min_acc && accepted < in_image;
}

bool on_geometric_edge(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y) {
    const size_t p = size_t(y) * g.width + x;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= g.width || qy >= g.height) continue;
            if (!discontinuity_accepts(g, s, p, size_t(qy) * g.width + qx)) return true;
        }
    return false;
}

float ss_guidance(const AisBaseBuffers& b, const DiscontinuitySettings& s, int min_acc, int x, int y) {
    const size_t p = size_t(y) * b.geometry.width + x;
    float lo = INFINITY, hi = -INFINITY;
    for_accepted(b.geometry, s, x, y, [&](size_t q) {
        lo = std::min(lo, b.visibility[q]);
        hi = std::max(hi, b.visibility[q]);
    });
    const float v = b.visibility[p];
    if (v > 0.0f && v < 1.0f && unfilterable(b.geometry, s, min_acc, x, y)) return 1.0f;
    return hi - lo;
}

float id_guidance(const AisBaseBuffers& b, const DiscontinuitySettings& s, const AisThresholds& t, int min_acc,
                  int x, int y) {
    double sum = 0.0, sum2 = 0.0;
    int count = 0;
    for_accepted(b.geometry, s, x, y, [&](size_t q) {
        sum += b.indirect[q];
        sum2 += double(b.indirect[q]) * b.indirect[q];
        ++count;
    });
    if (unfilterable(b.geometry, s, min_acc, x, y) || on_geometric_edge(b.geometry, s, x, y)) return 1.0f;
    const double mean = sum / count;
    if (!(mean > 0.0)) return 0.0f;
    const double cov = std::sqrt(std::max(0.0, sum2 / count - mean * mean)) / mean;
    return static_cast<float>(std::min(1.0, cov / t.id_cov));
}

float pm_guidance(const AisBaseBuffers& b, const DiscontinuitySettings& s, int x, int y) {
    const size_t p = size_t(y) * b.geometry.width + x;
    const float lp = b.medium_length[p];
    float lo = INFINITY, hi = -INFINITY;
    bool length_edge = false;
    for_window(b.geometry, s.tile, x, y, [&](size_t q) {
        lo = std::min(lo, b.lit_fraction[q]);
        hi = std::max(hi, b.lit_fraction[q]);
        length_edge |= std::abs(b.medium_length[q] - lp) > s.depth_rel * lp;
    });
    return length_edge ? 1.0f : hi - lo;
}

}  // namespace

AisGuidance compute_guidance(const AisBaseBuffers& base, const DiscontinuitySettings& filter,
                             const AisThresholds& t, const std::array<bool, kAisComponents>& enabled) {
    const int w = base.geometry.width, h = base.geometry.height;
    const int sets = filter.tile * filter.tile;
    const int min_acc = t.min_accepted > 0 ? t.min_accepted : (sets + 1) / 2;
    AisGuidance out;
    for (int c = 0; c < kAisComponents; ++c) {
        if (!enabled[c] || (c == kAisPM && base.lit_fraction.empty())) continue;
        out.g[c].assign(size_t(w) * h, 0.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t p = size_t(y) * w + x;
                if (c != kAisPM && !std::isfinite(base.geometry.depth[p])) continue;  // nothing to shade
                out.g[c][p] = c == kAisSS   ? ss_guidance(base, filter, min_acc, x, y)
                              : c == kAisID ? id_guidance(base, filter, t, min_acc, x, y)
                                            : pm_guidance(base, filter, x, y);
            }
    }
    return out;
}

AisSchedule make_schedule(const AisGuidance& guidance, const AisThresholds& t, AisMode mode, int width,
                          int height, int tile) {
    const int sets = tile * tile;
    const size_t pixels = size_t(width) * height;
    const float trigger[kAisComponents] = {t.ss_trigger, t.id_trigger, t.pm_trigger};
    AisSchedule s;
    std::vector<std::vector<std::pair<uint32_t, uint8_t>>> by_set(sets);
    std::vector<uint8_t> mask(size_t(sets), 0);
    for (int c = 0; c < kAisComponents; ++c) {
        if (guidance.g[c].empty()) continue;
        s.sets[c].assign(pixels, 1);
        size_t flagged = 0;
        for (size_t p = 0; p < pixels; ++p) {
            const float g = guidance.g[c][p];
            if (!(g > trigger[c])) continue;
            ++flagged;
            const int n = mode == AisMode::AMax ? sets : 1 + static_cast<int>(std::ceil(g * (sets - 1)));
            s.sets[c][p] = static_cast<uint8_t>(std::min(n, sets));
        }
        s.flagged[c] = pixels ? double(flagged) / pixels : 0.0;
    }
    for (size_t p = 0; p < pixels; ++p) {
        const int x = static_cast<int>(p % width), y = static_cast<int>(p / width);
        const int own = (x % tile) + tile * (y % tile);
        std::fill(mask.begin(), mask.end(), 0);
        for (int c = 0; c < kAisComponents; ++c) {
            if (s.sets[c].empty()) continue;
            for (int j = 1; j < s.sets[c][p]; ++j) mask[(own + j) % sets] |= uint8_t(1u << c);
        }
        for (int k = 0; k < sets; ++k)
            if (mask[k]) by_set[k].push_back({static_cast<uint32_t>(p), mask[k]});
    }
    for (int k = 0; k < sets; ++k)
        for (const auto& [p, m] : by_set[k]) {
            s.item_pixels.push_back(p);
            s.item_sets.push_back(static_cast<uint8_t>(k));
            s.item_components.push_back(m);
        }
    return s;
}

}  // namespace tessera
