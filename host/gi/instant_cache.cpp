#include "gi/instant_cache.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ic_gather.h"
#include "gi/ic_probe.h"
#include "gi/path_selection.h"
#include "kernels/shared/ic_lookup.h"
#include "kernels/shared/rng.h"
#include "kernels/shared/sampling.h"
#include "util/error.h"
#include "util/morton.h"

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Pairs per pair-kernel launch: bounds the item and output buffers (8 + 4 bytes a pair).
constexpr size_t kPairBatch = size_t(1) << 20;
// Visibility words per gather-kernel launch (64 MiB): at least one record's row.
constexpr size_t kGatherBatch = size_t(1) << 24;
// The smallest validity ball (a·R_i, in pixel footprints) the probe's bound may make:
// half a pixel, a leak no pixel centre one footprint away sees; below it records would
// crowd into concave corners without end (the reason for ic_record_radius's lower clamp).
constexpr float kProbeBallFloorPx = 0.5f;

bool has_surface(const float* g) { return ts::as_uint(g[TS_IC_GBUF_PRIM]) != TS_NO_HIT; }

}  // namespace

uint32_t ic_subsets_for(uint32_t spp, uint64_t pixels) {
    if (spp < 4) return 1u;
    if (spp < 16) return 2u;
    return pixels >= kIcManySubsetsPixels ? 16u : 4u;
}

// Each run of M blocks holds every subset once, where independent draws per block (before
// 2026-11-28) left the count of each subset in a region binomial: a region's mean now sees
// its M·N_p paths in nearer equal shares.
uint32_t ic_record_subset(uint32_t subsets, uint32_t level, uint32_t block, uint32_t pass, uint32_t seed) {
    if (subsets <= 1) return 0;
    uint32_t state = ts::ts_pcg_hash(block / subsets ^
                                     ts::ts_pcg_hash(level ^ ts::ts_pcg_hash(pass ^ ts::ts_pcg_hash(seed + 0x69637375u))));
    // Entry block mod M of a Fisher–Yates shuffle of 0 .. M − 1.
    std::vector<uint32_t> order(subsets);
    for (uint32_t k = 0; k < subsets; ++k) order[k] = k;
    for (uint32_t k = subsets - 1; k > 0; --k) {
        state = ts::ts_pcg_hash(state);
        std::swap(order[k], order[state % (k + 1)]);
    }
    return order[block % subsets];
}

void ic_gbuffer_from_surface(const std::vector<float>& surf, std::vector<float>& g) {
    const size_t pixels = surf.size() / TS_IGI_SURF_FLOATS;
    g.resize(pixels * TS_IC_GBUF_FLOATS);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t p = r.begin(); p < r.end(); ++p) {
            const float* s = &surf[p * TS_IGI_SURF_FLOATS];
            float* o = &g[p * TS_IC_GBUF_FLOATS];
            std::fill(o, o + TS_IC_GBUF_FLOATS, 0.0f);
            o[TS_IC_GBUF_PRIM] = ts::as_float(TS_NO_HIT);
            const bool seen = ts::as_uint(s[TS_IGI_SURF_PRIM]) != TS_NO_HIT;
            if (!seen || !(ts::ts_max3(ts::ts_f3_load(s + TS_IGI_SURF_ALBEDO)) > 0.0f)) continue;
            auto copy = [&](int to, int from, int n) { std::copy(s + from, s + from + n, o + to); };
            copy(TS_IC_GBUF_POSITION, TS_IGI_SURF_POSITION, 3);
            copy(TS_IC_GBUF_NORMAL, TS_IGI_SURF_NORMAL, 3);
            copy(TS_IC_GBUF_GEO_NORMAL, TS_IGI_SURF_GEO_NORMAL, 3);
            copy(TS_IC_GBUF_ORIGIN, TS_IGI_SURF_ORIGIN, 3);
            copy(TS_IC_GBUF_POS_SCALE, TS_IGI_SURF_POS_SCALE, 1);
            copy(TS_IC_GBUF_PRIM, TS_IGI_SURF_PRIM, 1);
            copy(TS_IC_GBUF_DISTANCE, TS_IGI_SURF_DISTANCE, 1);
        }
    });
}

InstantCache::InstantCache(const IcSettings& settings, const std::vector<SceneObject>& objects)
    : settings_(settings), cache_(settings.error_bound) {
    if (!(settings.min_radius_px > 0.0f && settings.min_radius_px <= settings.max_radius_px))
        throw InputError("ic: the record radius bounds must satisfy 0 < min <= max pixels");
    for (const SceneObject& o : objects) object_first_.push_back(o.first_triangle);
    if (object_first_.empty()) object_first_.push_back(0);
}

void InstantCache::check_pairs(size_t records, size_t vpls) {
    if (double(records) * double(vpls) <= double(kMaxPairs)) return;
    throw RuntimeError("ic: the cache would keep " + std::to_string(records * vpls) + " record-VPL visibilities (" +
                       std::to_string(records) + " records x " + std::to_string(vpls) + " VPLs), more than " +
                       std::to_string(kMaxPairs) + "; lower --ic-paths, raise --ic-error or lower the resolution");
}

uint32_t InstantCache::object_of(uint32_t triangle) const {
    auto it = std::upper_bound(object_first_.begin(), object_first_.end(), triangle);
    return static_cast<uint32_t>(it - object_first_.begin()) - 1u;
}

LightPathSettings InstantCache::path_settings() const {
    LightPathSettings ls;
    ls.inv_paths = 1.0f / static_cast<float>(uint64_t(settings_.paths) * oversampling_);
    ls.medium_scattering = settings_.multiple_scattering;
    ls.max_bounces = settings_.light_path_depth;
    ls.seed = seed_;
    return ls;
}

// Path block `block` of K·paths candidates (K = 1: the paths themselves), kept for the
// view when K > 1 (select_paths).
void InstantCache::start_paths(Backend& backend, const SceneBuffers& scene, uint32_t block,
                               const IcPathSelection& selection) {
    oversampling_ = selection.view ? std::max(1u, selection.oversampling) : 1u;
    // M subsets of K·paths candidates each; a candidate weighs 1/(K·paths) (path_settings),
    // so each subset alone is the estimate of paths light paths.
    const uint64_t n = uint64_t(settings_.paths) * oversampling_ * subsets();
    paths_.assign(n, LightPath{});
    for (uint64_t j = 0; j < n; ++j) paths_[j].index = uint64_t(block) * n + j;
    stats_.light_path_rays += trace_light_paths(backend, scene, path_settings(), paths_);
    stats_.paths_retraced = paths_.size();
    if (oversampling_ > 1) {
        concat_vpls();
        // The points' irradiance E_j from the first subset's candidates (vpl_view_importance).
        // The view rays' draws are keyed by the pass's path block, as the paths are.
        ViewVisibility visibility{&backend, selection.view_rays, light_path_seed_mix(seed_) ^ block};
        std::vector<float> where;
        const std::vector<float> importance = vpl_view_importance(
            *selection.view, vpls_, selection.importance_clamp, subset_vpls_.at(1), &visibility, &where);
        stats_.view_rays += visibility.traced;
        // One systematic sample a subset: each subset's paths keep their share of every
        // part of the view.
        paths_ = select_paths(paths_, importance, where, size_t(settings_.paths) * oversampling_, oversampling_,
                              light_path_seed_mix(seed_));
    }
    concat_vpls();
}

void InstantCache::concat_vpls() {
    vpls_.clear();
    for (const LightPath& p : paths_) vpls_.insert(vpls_.end(), p.vpls.begin(), p.vpls.end());
    subset_vpls_ = subset_offsets(paths_);
    stats_.vpls = vpl_count(vpls_);
}

// Subset s is the candidates s·K·paths .. (s + 1)·K·paths − 1 of the pass's block: a run of
// consecutive Halton points, as well spread as the block (point i mod M would fix the
// leading base-2 digit of a subset's points). Kept paths stay in index order
// (select_paths), so each subset's VPLs are one run of columns.
std::vector<size_t> InstantCache::subset_offsets(const std::vector<LightPath>& paths) const {
    const uint32_t m = subsets();
    const uint64_t per_subset = uint64_t(settings_.paths) * oversampling_, first = uint64_t(pass_) * per_subset * m;
    std::vector<size_t> offsets(m + 1, 0);
    for (const LightPath& p : paths) {
        const uint64_t s = (p.index - first) / per_subset;
        if (p.index < first || s >= m) throw std::logic_error("ic: a light path outside its pass's block");
        offsets[s + 1] += p.vpls.size() / TS_VPL_FLOATS;
    }
    for (uint32_t s = 0; s < m; ++s) offsets[s + 1] += offsets[s];
    return offsets;
}

size_t InstantCache::widest_subset(const std::vector<size_t>& offsets) {
    size_t widest = 0;
    for (size_t s = 0; s + 1 < offsets.size(); ++s) widest = std::max(widest, offsets[s + 1] - offsets[s]);
    return widest;
}

size_t InstantCache::pairs_kept() const {
    size_t n = 0;
    for (const Row& row : rows_) n += row.size();
    return n;
}

uint64_t InstantCache::probe(Backend& backend, std::vector<IcRecord>& records,
                             const std::vector<uint32_t>& which) const {
    // Only a hit nearer than 2a·R_max can lower R_i below its upper clamp R_max.
    std::vector<float> reach(which.size());
    for (size_t k = 0; k < which.size(); ++k)
        reach[k] = 2.0f * settings_.error_bound * settings_.max_radius_px * records[which[k]].pixel_size;
    uint64_t rays = 0;
    const auto t0 = Clock::now();
    const std::vector<float> d = ic_probe_distances(backend, records, which, reach, &rays);
    for (size_t k = 0; k < which.size(); ++k) records[which[k]].probe = d[k];
    times_.probe += since(t0);
    return rays;
}

float InstantCache::radius_of(const IcRecord& r, float harmonic_mean) const {
    // The validity ball a·R_i stays within half the probe's nearest hit: the probe's 32
    // rays see the nearest surface only to within ~1.3× its distance (a ray seldom grazes
    // toward it), and half leaves that margin.
    const float a = settings_.error_bound;
    const float bound = r.probe / (2.0f * a);
    // The lower clamp gives way to that bound down to a ball of half a pixel: at a = 2 the
    // clamp's 1.5 footprints made a ball of 3 pixels, which reached across a 2 mm wall
    // (10% of the lit floor's radiance on the dark side's first pixel). For a <= 1/3 the
    // floor is the clamp itself, so the default's radii are as before (docs/instant-caching.md §4).
    const float ball_floor = std::min(settings_.min_radius_px, kProbeBallFloorPx / a) * r.pixel_size;
    const float ward = ic_record_radius(harmonic_mean, r.pixel_size, settings_.min_radius_px, settings_.max_radius_px);
    // Never 0 (a probe hit at the record): ic_record_radius's own floor.
    return std::max({std::min(ward, std::max(bound, ball_floor)), 1e-6f * r.pixel_size, std::numeric_limits<float>::min()});
}

// Launches the pair kernel over pairs 0 .. total-1, at most kPairBatch at a time
// (`launch(begin, count, hits)`), and hands each pair's hit to `write(pair, hit)` in
// parallel (pairs are distinct, so each writes its own row entry). Returns rays traced.
template <class Launch, class Write>
uint64_t InstantCache::trace_in_batches(size_t total, Launch&& launch, Write&& write) const {
    uint64_t traced = 0;
    std::vector<uint32_t> hits;
    for (size_t begin = 0; begin < total; begin += kPairBatch) {
        const size_t count = std::min(kPairBatch, total - begin);
        launch(begin, count, hits);
        traced += count - static_cast<size_t>(std::count(hits.begin(), hits.end(), TS_IC_PAIR_FACING));
        tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) write(begin + i, hits[i]);
        });
    }
    return traced;
}

// A row entry from the pair kernel's hit: the codes as they are, a triangle as its object.
int32_t InstantCache::row_code(uint32_t hit) const {
    static_assert(kIcVisible == int32_t(TS_IC_PAIR_VISIBLE) && kIcFacing == int32_t(TS_IC_PAIR_FACING),
                  "row entries are the pair kernel's codes");
    return hit == TS_IC_PAIR_FACING || hit == TS_IC_PAIR_VISIBLE ? static_cast<int32_t>(hit)
                                                                 : static_cast<int32_t>(object_of(hit));
}

// Traces the shadow ray of every pair whose geometry term is positive (the pair kernel)
// and writes each pair's visibility into the record's row (kIcFacing for the others).
// A pair's VPL is a column of vpls, which are the current ones (subset_vpls_). Returns
// rays traced.
uint64_t InstantCache::trace_pairs(Backend& backend, const std::vector<float>& vpls, const std::vector<Pair>& pairs,
                                   float g_clamp, std::vector<Row>& rows) const {
    if (pairs.empty()) return 0;
    const auto t0 = Clock::now();
    ic_set_record_inputs(backend, cache_.records(), vpls);
    std::vector<uint32_t> items;
    const uint64_t traced = trace_in_batches(
        pairs.size(),
        [&](size_t begin, size_t n, std::vector<uint32_t>& hits) {
            items.resize(TS_IC_PAIR_WORDS * n);
            tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
                for (size_t i = r.begin(); i < r.end(); ++i) {
                    items[TS_IC_PAIR_WORDS * i + TS_IC_PAIR_RECORD] = pairs[begin + i].record;
                    items[TS_IC_PAIR_WORDS * i + TS_IC_PAIR_VPL] = pairs[begin + i].vpl;
                }
            });
            const auto tk = Clock::now();
            ic_trace_pairs(backend, g_clamp, items, hits);
            times_.pair_kernel += since(tk);
        },
        [&](size_t g, uint32_t hit) {
            const Pair& p = pairs[g];
            rows[p.record][p.vpl - row_first(cache_.records()[p.record], subset_vpls_)] = row_code(hit);
        });
    times_.pairs += since(t0);
    return traced;
}

// trace_pairs for every pair of `records` and the VPLs of its subset (`offsets`): subset by
// subset, the records of one in the given order (trace_subset_grid). With one subset, one
// grid of every record and VPL.
uint64_t InstantCache::trace_pair_grid(Backend& backend, const std::vector<float>& vpls,
                                       const std::vector<size_t>& offsets, const std::vector<uint32_t>& records,
                                       float g_clamp, std::vector<Row>& rows) const {
    if (records.empty() || vpls.empty()) return 0;
    const auto t0 = Clock::now();
    ic_set_record_inputs(backend, cache_.records(), vpls);
    times_.pairs += since(t0);
    const size_t m = offsets.size() - 1;
    if (m == 1) return trace_subset_grid(backend, vpls, 0, vpl_count(vpls), records, g_clamp, rows);
    const std::vector<IcRecord>& all = cache_.records();
    uint64_t traced = 0;
    for (size_t s = 0; s < m; ++s) {
        std::vector<uint32_t> mine;
        for (const uint32_t r : records)
            if (all[r].subset == s) mine.push_back(r);
        traced += trace_subset_grid(backend, vpls, offsets[s], offsets[s + 1], mine, g_clamp, rows);
    }
    return traced;
}

// The grid of `records` and VPL columns first .. end-1, VPL by VPL and the records in the
// given order, which the kernel reads without a list (ic_trace_pair_grid); the record
// inputs are set (trace_pair_grid), with all of `vpls`. The rows of `records` are those
// of subset [first, end): pair (record, first + k) writes entry k. Placement gives its records in
// Morton order of their grid cells, so 16 consecutive pairs are a 4×4 block of records
// and one VPL, rays that end at one point and trace as a coherent packet
// (docs/instant-caching.md §7). Pairs are independent, so the order changes no result.
uint64_t InstantCache::trace_subset_grid(Backend& backend, const std::vector<float>& vpls, size_t first, size_t end,
                                         const std::vector<uint32_t>& records, float g_clamp,
                                         std::vector<Row>& rows) const {
    const size_t n = records.size(), total = n * (end - first);
    if (total == 0) return 0;
    const auto t0 = Clock::now();
    if (first != 0 || end != vpl_count(vpls))
        ic_set_vpl_inputs(backend, std::vector<float>(vpls.begin() + first * TS_VPL_FLOATS,
                                                      vpls.begin() + end * TS_VPL_FLOATS));
    backend.set_input(KernelInput::IcPairRecords, records);
    const uint64_t traced = trace_in_batches(
        total,
        [&](size_t begin, size_t count, std::vector<uint32_t>& hits) {
            const auto tk = Clock::now();
            ic_trace_pair_grid(backend, g_clamp, static_cast<uint32_t>(n), static_cast<uint32_t>(begin), count, hits);
            times_.pair_kernel += since(tk);
        },
        [&](size_t g, uint32_t hit) { rows[records[g % n]][g / n] = row_code(hit); });
    times_.pairs += since(t0);
    return traced;
}

// In launches of at most kGatherBatch mask words; the masks start zeroed, so a fill may
// set only the bits it means.
std::vector<float> InstantCache::gather_outputs(Backend& backend, const std::vector<float>& vpls,
                                                const std::vector<IcRecord>& records,
                                                const std::vector<uint32_t>& which, float g_clamp,
                                                const MaskFill& fill) const {
    std::vector<float> outputs(TS_IC_GATHER_FLOATS * which.size());
    if (which.empty()) return outputs;
    const auto t0 = Clock::now();
    ic_set_record_inputs(backend, records, vpls);
    const size_t nv = vpl_count(vpls), words = TS_IC_VISIBLE_WORDS(nv);
    const size_t per_launch = std::max<size_t>(1, kGatherBatch / std::max<size_t>(words, 1));
    std::vector<uint32_t> items, visibility;
    std::vector<float> out;
    for (size_t begin = 0; begin < which.size(); begin += per_launch) {
        const size_t n = std::min(per_launch, which.size() - begin);
        items.resize(TS_IC_GATHER_WORDS * n);
        visibility.assign(n * words, 0u);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t k = r.begin(); k < r.end(); ++k) {
                items[TS_IC_GATHER_WORDS * k + TS_IC_GATHER_RECORD] = which[begin + k];
                items[TS_IC_GATHER_WORDS * k + TS_IC_GATHER_ROW] = static_cast<uint32_t>(k);
                fill(begin + k, visibility.data() + k * words);
            }
        });
        const auto tk = Clock::now();
        ic_gather(backend, g_clamp, items, visibility, out);
        times_.gather_kernel += since(tk);
        std::copy(out.begin(), out.begin() + TS_IC_GATHER_FLOATS * n, outputs.begin() + TS_IC_GATHER_FLOATS * begin);
    }
    times_.gather += since(t0);
    return outputs;
}

// E of records[k] for every k of `which` from rows[k] (over the subsets `offsets`) and
// `vpls` (the gather kernel); returns their harmonic mean distances to the visible VPLs,
// in the order of `which`. The records go to the kernel grouped by subset: a batch of
// records that share their VPLs walks one subset's columns, where a batch of M subsets
// walks M (the Embree gather adds every VPL one lane sees to all 16; a lane that does not
// see it adds +0, so the sums are the same in any grouping).
std::vector<float> InstantCache::gather(Backend& backend, const std::vector<float>& vpls,
                                        const std::vector<size_t>& offsets, const std::vector<Row>& rows,
                                        std::vector<IcRecord>& records, const std::vector<uint32_t>& which,
                                        float g_clamp, std::vector<IcGatherSums>* sums) const {
    std::vector<uint32_t> order(which.size());
    for (uint32_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return records[which[a]].subset < records[which[b]].subset; });
    std::vector<uint32_t> grouped(which.size());
    for (size_t k = 0; k < order.size(); ++k) grouped[k] = which[order[k]];
    const std::vector<float> out = gather_outputs(backend, vpls, records, grouped, g_clamp, [&](size_t k, uint32_t* mask) {
        const IcRecord& r = records[grouped[k]];
        ic_pack_visible(rows[grouped[k]].data(), rows[grouped[k]].size(), mask, row_first(r, offsets));
    });
    std::vector<float> harmonic(which.size());
    for (size_t k = 0; k < order.size(); ++k) {
        const float* o = &out[TS_IC_GATHER_FLOATS * k];
        IcRecord& r = records[grouped[k]];
        r.e = {o[TS_IC_GATHER_E], o[TS_IC_GATHER_E + 1], o[TS_IC_GATHER_E + 2]};
        harmonic[order[k]] = o[TS_IC_GATHER_HARMONIC];
        if (sums) (*sums)[grouped[k]] = IcGatherSums::from_output(o);
    }
    return harmonic;
}

// Whether a record of `cache` is usable at each of `pixels` (G-buffer indices of pixels
// with a surface; ts_ic_covered), one byte each.
std::vector<uint8_t> InstantCache::covered(IrradianceCache& cache, const std::vector<float>& gbuffer,
                                           const std::vector<uint32_t>& pixels) const {
    std::vector<uint8_t> out(pixels.size(), 0);
    if (cache.records().empty()) return out;
    const IcCacheBuffers& b = cache.buffers();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
            const float* g = &gbuffer[size_t(pixels[i]) * TS_IC_GBUF_FLOATS];
            out[i] = ts::ts_ic_covered(b.nodes.data(), b.refs.data(), b.records.data(),
                                       ts::ts_f3_load(g + TS_IC_GBUF_POSITION), ts::ts_f3_load(g + TS_IC_GBUF_NORMAL),
                                       settings_.error_bound);
        }
    });
    return out;
}

// Coarse-to-fine placement (docs/instant-caching.md §7): on pixel grids of stride 8, 4, 2, 1,
// every grid pixel no record covers gets one; each level's records are gathered and
// inserted before the next level's coverage test, so a level never duplicates a coarser
// one's work and the result does not depend on thread timing.
//
// A pixel is covered when one record is usable there (ts_ic_covered), so coverage by the
// records kept from earlier frames (tic) is tested once, on the finest grid (the coarser
// grids' pixels are among its pixels), and each level then tests only the pixels they
// leave against this frame's new records, in a tree of their own. The same pixels get
// records as with every level tested against the whole cache; the whole cache's flat
// buffers are then made once a frame, not once a level (Sibenik's TIC: 720k nodes).
void InstantCache::place(Backend& backend, const std::vector<float>& gbuffer, const TsFrame& frame,
                         float g_clamp, const SceneBounds& bounds) {
    const float footprint = 2.0f * std::sqrt(frame.cam_up[0] * frame.cam_up[0] + frame.cam_up[1] * frame.cam_up[1] +
                                             frame.cam_up[2] * frame.cam_up[2]) / static_cast<float>(frame.height);
    auto t_cover = Clock::now();
    std::vector<uint32_t> seen;  // the pixels with a surface
    for (uint32_t p = 0; p < frame.width * frame.height; ++p)
        if (has_surface(&gbuffer[size_t(p) * TS_IC_GBUF_FLOATS])) seen.push_back(p);
    std::vector<uint8_t> covered_before(size_t(frame.width) * frame.height, 0);
    {
        const std::vector<uint8_t> c = covered(cache_, gbuffer, seen);
        for (size_t i = 0; i < seen.size(); ++i) covered_before[seen[i]] = c[i];
    }
    // This frame's records, where the cache held some before (else the cache itself).
    const bool kept = !cache_.records().empty();
    IrradianceCache fresh_tree(settings_.error_bound);
    if (kept) fresh_tree.rebuild(bounds.lo, bounds.hi);
    IrradianceCache& fresh_cover = kept ? fresh_tree : cache_;
    stats_.coverage_seconds += since(t_cover);
    for (const uint32_t stride : {8u, 4u, 2u, 1u}) {
        std::vector<uint32_t> candidates;
        for (uint32_t y = 0; y < frame.height; y += stride)
            for (uint32_t x = 0; x < frame.width; x += stride) {
                const uint32_t p = y * frame.width + x;
                if (has_surface(&gbuffer[size_t(p) * TS_IC_GBUF_FLOATS]) && !covered_before[p]) candidates.push_back(p);
            }
        t_cover = Clock::now();
        const std::vector<uint8_t> covered_now = covered(fresh_cover, gbuffer, candidates);
        stats_.coverage_seconds += since(t_cover);
        const size_t first = cache_.records().size();
        const size_t fresh_count = std::count(covered_now.begin(), covered_now.end(), uint8_t(0));
        check_pairs(first + fresh_count, widest_subset(subset_vpls_));
        std::vector<std::pair<uint32_t, uint32_t>> blocked;  // (Morton code of the grid cell, record)
        for (size_t i = 0; i < candidates.size(); ++i) {
            if (covered_now[i]) continue;
            IcRecord rec;
            std::memcpy(rec.surface.data(), &gbuffer[size_t(candidates[i]) * TS_IC_GBUF_FLOATS],
                        sizeof(float) * TS_IC_GBUF_FLOATS);
            rec.pixel_size = rec.surface[TS_IC_GBUF_DISTANCE] * footprint;
            rec.last_in_view = frame_count_;
            // The probe's key: the pixel, pass and seed, which every backend has alike (not
            // the position, whose last bit the backends' camera rays round differently).
            // One placement makes at most one record a pixel (a record covers its own point).
            rec.probe_key = ts::ts_pcg_hash(candidates[i] ^ ts::ts_pcg_hash(frame.pass ^ ts::ts_pcg_hash(frame.seed)));
            const uint32_t x = candidates[i] % frame.width / stride, y = candidates[i] / frame.width / stride;
            // The records of a level in one 16×16-pixel block of the image share a subset:
            // they are neighbours in Morton order, so the pair kernel's packets of 16 rays
            // stay groups of nearby records, and a 4×3 region of a 384×256 image still
            // holds ~30 blocks of each level, so its mean sees every subset. A record's
            // subset depends on its pixel alone, not on which other records were made.
            rec.subset = record_subset(stride, morton2(x * stride >> 4, y * stride >> 4));
            blocked.push_back({morton2(x, y), static_cast<uint32_t>(cache_.records().size())});
            cache_.records().push_back(rec);  // inserted in the octree once its radius is known
            rows_.emplace_back(row_size(rec, subset_vpls_), kIcFacing);
            sums_.emplace_back();
        }
        std::sort(blocked.begin(), blocked.end());
        std::vector<uint32_t> order(blocked.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = blocked[i].second;
        stats_.shadow_rays += trace_pair_grid(backend, vpls_, subset_vpls_, order, g_clamp, rows_);
        std::vector<uint32_t> which(cache_.records().size() - first);
        for (size_t i = 0; i < which.size(); ++i) which[i] = static_cast<uint32_t>(first + i);
        stats_.probe_rays += probe(backend, cache_.records(), which);
        const std::vector<float> harmonic =
            gather(backend, vpls_, subset_vpls_, rows_, cache_.records(), which, g_clamp, &sums_);
        std::vector<IcRecord> fresh(cache_.records().begin() + first, cache_.records().end());
        cache_.records().resize(first);
        for (size_t i = 0; i < fresh.size(); ++i) {
            fresh[i].radius = radius_of(fresh[i], harmonic[i]);
            cache_.insert(fresh[i]);
            if (kept) fresh_tree.insert(fresh[i]);
        }
        stats_.created += fresh.size();
    }
}

void InstantCache::indirect(Backend& backend, const SceneBuffers& scene, const TsFrame& frame,
                            const std::vector<float>& surf, float g_clamp, const IcPathSelection& selection,
                            std::vector<float>& gbuffer, std::vector<float>& e_id, std::vector<float>& residual) {
    stats_ = IcFrameStats{};
    times_ = StageTimes{};
    auto t0 = Clock::now();
    if (!settings_.temporal || !have_previous_) {
        cache_ = IrradianceCache(settings_.error_bound);
        rows_.clear();
        sums_.clear();
        pass_ = frame.pass, seed_ = frame.seed;
        start_paths(backend, scene, frame.pass, selection);
    } else {
        if (frame.pass != pass_ || frame.seed != seed_)
            throw std::logic_error("tic: a temporal cache serves one pass and seed (pass " + std::to_string(pass_) +
                                   ", seed " + std::to_string(seed_) + "), asked for pass " +
                                   std::to_string(frame.pass) + ", seed " + std::to_string(frame.seed));
        update(backend, scene, g_clamp);
    }
    stats_.update_seconds = since(t0);

    t0 = Clock::now();
    ic_gbuffer_from_surface(surf, gbuffer);
    const SceneBounds& bounds = scene.bounds;
    const auto t_octree = Clock::now();
    cache_.rebuild(bounds.lo, bounds.hi);
    stats_.octree_seconds = since(t_octree);
    place(backend, gbuffer, frame, g_clamp, bounds);
    stats_.place_seconds = since(t0);

    t0 = Clock::now();
    const IcCacheBuffers& flat = cache_.buffers();
    backend.set_input(KernelInput::IcGbuffer, gbuffer);
    backend.set_input(KernelInput::IcNodes, flat.nodes);
    backend.set_input(KernelInput::IcRefs, flat.refs);
    backend.set_input(KernelInput::IcRecords, flat.records);
    TsFrame interp_frame = frame;
    interp_frame.ic_error_bound = settings_.error_bound;
    // Work items in row order, not de-interleaved by igi's sample sets (ts_pixel_of_work_item):
    // the interpolation has no sets, and neighbouring pixels walk the same octree nodes and
    // records, so row order finds them in cache. Each pixel's output is at its place and its
    // residual's random stream is keyed by the pixel, so the image is the same bits.
    // Sibenik, 512²: 0.77x (Embree) and 0.84x (PoCL) the stage's time (bench/results/tic_host_work.md).
    interp_frame.igi_tile = 1;
    interp_frame.igi_g_clamp = settings_.clamp_compensation ? g_clamp : std::numeric_limits<float>::infinity();
    std::vector<float> interp;
    backend.launch(KernelId::IcInterpolate, interp_frame, interp);
    const size_t pixels = gbuffer.size() / TS_IC_GBUF_FLOATS;
    e_id.assign(3 * pixels, 0.0f);
    residual.assign(3 * pixels, 0.0f);
    for (size_t p = 0; p < pixels; ++p) {
        const float* g = &gbuffer[p * TS_IC_GBUF_FLOATS];
        if (!has_surface(g)) continue;
        const float* in = &interp[TS_IC_INTERP_FLOATS * p];
        glm::vec3 e(in[TS_IC_INTERP_E], in[TS_IC_INTERP_E + 1], in[TS_IC_INTERP_E + 2]);
        // Placement covered this pixel on the host; a kernel rounding a weight at the edge
        // of a record's validity differently can still miss it.
        if (!(in[TS_IC_INTERP_WEIGHT] > 0.0f)) {
            const float *x = g + TS_IC_GBUF_POSITION, *n = g + TS_IC_GBUF_NORMAL;
            cache_.lookup({x[0], x[1], x[2]}, {n[0], n[1], n[2]}, &e);
            ++stats_.fallback_pixels;
        }
        for (int c = 0; c < 3; ++c) {
            e_id[3 * p + c] = e[c];
            residual[3 * p + c] = in[TS_IC_INTERP_RESIDUAL + c];
        }
    }
    stats_.records = cache_.records().size();
    stats_.interpolate_seconds = since(t0);
    stats_.pair_seconds = times_.pairs, stats_.pair_kernel_seconds = times_.pair_kernel;
    stats_.probe_seconds = times_.probe;
    stats_.gather_seconds = times_.gather, stats_.gather_kernel_seconds = times_.gather_kernel;
    if (settings_.temporal) {
        mark_in_view(frame);
        snapshot(scene, g_clamp);
    }
    ++frame_count_;
}

// A record is in view when its position projects into the image (10% margin) in front of
// the camera; occlusion is not tested (an occluded record may reappear soon).
void InstantCache::mark_in_view(const TsFrame& f) {
    const glm::vec3 cam(f.cam_pos[0], f.cam_pos[1], f.cam_pos[2]), fwd(f.cam_forward[0], f.cam_forward[1], f.cam_forward[2]),
        right(f.cam_right[0], f.cam_right[1], f.cam_right[2]), up(f.cam_up[0], f.cam_up[1], f.cam_up[2]);
    const float r2 = glm::dot(right, right), u2 = glm::dot(up, up);
    for (IcRecord& r : cache_.records()) {
        const glm::vec3 d = r.position() - cam;
        const float t = glm::dot(d, fwd);
        if (!(t > 0.0f)) continue;
        const float sx = glm::dot(d, right) / (r2 * t), sy = glm::dot(d, up) / (u2 * t);
        if (std::fabs(sx) <= 1.1f && std::fabs(sy) <= 1.1f) r.last_in_view = frame_count_;
    }
}

std::vector<IcRecord> InstantCache::rebuilt_records(Backend& backend, const SceneBuffers& scene,
                                                   float g_clamp) const {
    std::vector<LightPath> paths;
    for (const LightPath& p : paths_) paths.push_back(untraced(p));
    trace_light_paths(backend, scene, path_settings(), paths);
    std::vector<float> vpls;
    for (const LightPath& p : paths) vpls.insert(vpls.end(), p.vpls.begin(), p.vpls.end());
    const std::vector<size_t> offsets = subset_offsets(paths);
    const std::vector<IcRecord>& records = cache_.records();
    std::vector<Row> rows;
    for (const IcRecord& r : records) rows.emplace_back(row_size(r, offsets), kIcFacing);
    std::vector<uint32_t> order(records.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    trace_pair_grid(backend, vpls, offsets, order, g_clamp, rows);
    std::vector<IcRecord> out(records);
    std::vector<uint32_t> all(out.size());
    for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    probe(backend, out, all);
    const std::vector<float> harmonic = gather(backend, vpls, offsets, rows, out, all, g_clamp);
    for (size_t i = 0; i < out.size(); ++i) out[i].radius = radius_of(out[i], harmonic[i]);
    return out;
}

IcFrameStats& IcFrameStats::operator+=(const IcFrameStats& o) {
    records += o.records, created += o.created, removed += o.removed, resummed += o.resummed;
    resummed_by_change += o.resummed_by_change;
    evicted += o.evicted, rows_remade += o.rows_remade;
    vpls += o.vpls, paths_retraced += o.paths_retraced, vpls_changed += o.vpls_changed;
    light_path_rays += o.light_path_rays, view_rays += o.view_rays, shadow_rays += o.shadow_rays;
    probe_rays += o.probe_rays;
    fallback_pixels += o.fallback_pixels;
    update_seconds += o.update_seconds, place_seconds += o.place_seconds;
    interpolate_seconds += o.interpolate_seconds;
    pair_seconds += o.pair_seconds, pair_kernel_seconds += o.pair_kernel_seconds, probe_seconds += o.probe_seconds;
    gather_seconds += o.gather_seconds, gather_kernel_seconds += o.gather_kernel_seconds;
    octree_seconds += o.octree_seconds, coverage_seconds += o.coverage_seconds;
    return *this;
}

std::string describe_ic(const IcSettings& settings, const IcFrameStats& s, uint32_t passes) {
    char buf[768], over[48] = "", subsets[40] = "", kept[64] = ", as drawn";
    if (passes > 1) std::snprintf(over, sizeof over, " summed over %u passes", passes);
    if (settings.path_importance > 1)
        std::snprintf(kept, sizeof kept, ", kept for the view from %ux (%u view rays a VPL)", settings.path_importance,
                      settings.view_rays);
    if (settings.subsets > 1) std::snprintf(subsets, sizeof subsets, " in each of %u subsets", settings.subsets);
    std::snprintf(buf, sizeof buf,
                  "%s: a %.2f, %u paths%s%s%s: %zu VPLs, %zu records (+%zu, -%zu, %zu re-summed, %zu by the changed VPLs), "
                  "%zu paths re-traced, "
                  "rays: %llu light-path + %llu view + %llu shadow + %llu probe, update %.1f ms, place+gather %.1f ms, interpolate %.1f ms; of update and placement: shadow rays %.1f ms "
                  "(kernel %.1f), probes %.1f, gathers %.1f (kernel %.1f), octree %.1f, coverage %.1f",
                  settings.temporal ? "tic" : "ic", settings.error_bound, settings.paths, subsets, over, kept,
                  s.vpls, s.records,
                  s.created, s.removed, s.resummed, s.resummed_by_change, s.paths_retraced,
                  static_cast<unsigned long long>(s.light_path_rays), static_cast<unsigned long long>(s.view_rays),
                  static_cast<unsigned long long>(s.shadow_rays), static_cast<unsigned long long>(s.probe_rays),
                  1e3 * s.update_seconds, 1e3 * s.place_seconds, 1e3 * s.interpolate_seconds, 1e3 * s.pair_seconds,
                  1e3 * s.pair_kernel_seconds, 1e3 * s.probe_seconds, 1e3 * s.gather_seconds,
                  1e3 * s.gather_kernel_seconds, 1e3 * s.octree_seconds, 1e3 * s.coverage_seconds);
    return buf;
}

}  // namespace tessera
