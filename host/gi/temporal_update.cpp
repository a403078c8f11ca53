// Temporal instant caching: the per-frame update of InstantCache (docs/instant-caching.md §8).
// Everything a change cannot affect is kept; what it can affect is recomputed exactly as a
// rebuild would compute it, so the updated cache equals a rebuilt one (same records, same
// VPLs) up to the order of float sums.
//
// The tests, for the objects O that moved since the previous frame (any vertex differs):
//   light path  re-traced (with its fixed Halton point) if its light changed (radiance or
//               geometry; all paths if the light-selection CDF changed), a segment hit an
//               object of O or a triangle whose material changed, or a segment meets
//               the new bounding box of an object of O (a moved object may now block it;
//               it cannot have blocked it before, or the segment would have hit it).
//               A re-traced path's VPLs that land where they were keep their visibility
//               (only their weight changes); the others are new.
//   record      removed if it lies on an object of O or its sphere (x_i, max(R_i, probe_i))
//               meets the old or new box of an object of O (its radius, probe and
//               neighbourhood may be stale); placement recreates records where coverage
//               is missing.
//   pair        (record, VPL) re-traced if the VPL is new, its stored occluder is in O
//               (the blocker moved), or it was unoccluded and its shadow segment meets the
//               new box of an object of O. A pair blocked by a static object stays
//               blocked; a pair whose geometry term was 0 stays 0 (neither end moved).
//   eviction    a record out of the view frustum for evict_after_frames frames in a row
//               is dropped first (it would only cost update work).
//   E           re-summed (no rays) for records with a re-traced pair, and for all records
//               when a VPL weight or the geometry-term bound changed. Where fewer VPLs
//               were added and removed than there are VPLs, a record's sums
//               are updated instead of re-made: minus its old sum over the VPLs that
//               changed or whose pair was re-traced, plus its new sum over them (the
//               gather's double sums, IcGatherSums; equal to a full re-sum up to rounding).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "gi/instant_cache.h"
#include "kernels/shared/vpl.h"
#include "util/error.h"

namespace tessera {
namespace {

constexpr int32_t kNeedsTrace = -3;  // a row entry of a new VPL column

struct Box {
    glm::vec3 lo{INFINITY}, hi{-INFINITY};
    void grow(const float* p) {
        for (int a = 0; a < 3; ++a) lo[a] = std::fmin(lo[a], p[a]), hi[a] = std::fmax(hi[a], p[a]);
    }
    void grow(const Box& b) {
        for (int a = 0; a < 3; ++a) lo[a] = std::fmin(lo[a], b.lo[a]), hi[a] = std::fmax(hi[a], b.hi[a]);
    }
    // Widens the box by a few ulps of its coordinates: the float slab test must not miss a
    // ray the (watertight) tracer finds grazing an edge of the object, least of all for a
    // flat object whose box has zero thickness. Conservative: it costs a few extra rays.
    void pad() {
        for (int a = 0; a < 3; ++a) {
            const float e = 1e-5f * std::max({1.0f, std::fabs(lo[a]), std::fabs(hi[a])});
            lo[a] -= e, hi[a] += e;
        }
    }
    // One axis of the slab test on the running interval [t0, t1]: l and h are the slab's
    // planes relative to the ray's origin, d the direction component, `out` whether the
    // origin lies outside the slab. Branch-free, so that loops over rays vectorise. A zero d
    // with the origin on a plane gives NaN: the interval is left alone and the origin's
    // side decides (a zero d otherwise gives the infinities of 1/0). fmax / fmin are
    // written as comparisons (the libm calls do not vectorise): no NaN reaches them, and
    // the sign of a zero cannot change the final t0 > t1.
    static void slab(float d, float l, float h, bool out, float& t0, float& t1, int32_t& ok) {
        const float inv = 1.0f / d;
        const float n = l * inv, f = h * inv;
        const int32_t nan = (n != n) | (f != f);
        const float mn = n > f ? f : n, mx = n > f ? n : f;
        t0 = nan ? t0 : (mn > t0 ? mn : t0);
        t1 = nan ? t1 : (mx < t1 ? mx : t1);
        ok &= ~(nan & int32_t(out)) & 1;
    }
    // Whether org + t·dir for t in [t0, t1] meets the box. A slab test's early exits become
    // one final test: t0 only grows and t1 only shrinks over the axes.
    bool meets(const float* org, const float* dir, float t0, float t1) const {
        int32_t ok = 1;
        for (int a = 0; a < 3; ++a)
            slab(dir[a], lo[a] - org[a], hi[a] - org[a], (org[a] < lo[a]) | (org[a] > hi[a]), t0, t1, ok);
        return ok && !(t0 > t1);
    }
    // meets() for n rays from org to the points (ex[j], ey[j], ez[j]): ray j has direction
    // end_j - org (as ts_shadow_ray forms it) over [t0, t1]; hit[j] |= the answer. The
    // per-ray set-up is hoisted, and GCC vectorises the loop over j.
    void meets_many(const float* org, const float* __restrict ex, const float* __restrict ey,
                    const float* __restrict ez, size_t n, float t0, float t1, int32_t* __restrict hit) const {
        const float ox = org[0], oy = org[1], oz = org[2];
        const float lx = lo[0] - ox, ly = lo[1] - oy, lz = lo[2] - oz;  // the slab planes from org
        const float hx = hi[0] - ox, hy = hi[1] - oy, hz = hi[2] - oz;
        const bool out_x = (ox < lo[0]) | (ox > hi[0]), out_y = (oy < lo[1]) | (oy > hi[1]),
                   out_z = (oz < lo[2]) | (oz > hi[2]);
        for (size_t j = 0; j < n; ++j) {
            float a0 = t0, a1 = t1;
            int32_t ok = 1;
            slab(ex[j] - ox, lx, hx, out_x, a0, a1, ok);
            slab(ey[j] - oy, ly, hy, out_y, a0, a1, ok);
            slab(ez[j] - oz, lz, hz, out_z, a0, a1, ok);
            hit[j] |= ok & int32_t(!(a0 > a1));
        }
    }
    bool meets_sphere(glm::vec3 c, float r) const {
        const glm::vec3 d = glm::max(glm::vec3(0.0f), glm::max(lo - c, c - hi));
        return glm::dot(d, d) <= r * r;
    }
};

// A run of VPL columns that keep their order: new columns [to, to + n) are old columns
// [from, from + n), or new ones (from = kNewColumns) whose pairs need tracing.
struct ColumnRun {
    uint32_t to, from, n;
};
constexpr uint32_t kNewColumns = UINT32_MAX;

// old_column (per new column, its old column or -1) as runs: a re-traced path's VPLs
// shift the columns after it by a few, so a row is a handful of copies, not a gather.
std::vector<ColumnRun> column_runs(const std::vector<int64_t>& old_column) {
    std::vector<ColumnRun> runs;
    for (size_t j = 0; j < old_column.size(); ++j) {
        const uint32_t from = old_column[j] >= 0 ? static_cast<uint32_t>(old_column[j]) : kNewColumns;
        ColumnRun* last = runs.empty() ? nullptr : &runs.back();
        const bool extends = last && (from == kNewColumns ? last->from == kNewColumns
                                                          : last->from != kNewColumns && last->from + last->n == from);
        if (extends)
            ++last->n;
        else
            runs.push_back({static_cast<uint32_t>(j), from, 1u});
    }
    return runs;
}

// The new row from the old one: copies of the kept columns, kNeedsTrace in the new ones.
void remap_row(const std::vector<ColumnRun>& runs, const int32_t* old_row, size_t old_first, int32_t* row,
               size_t first, size_t end) {
    // A row spans its subset's columns: new [first, end), old from old_first. A path keeps
    // its subset, so a kept column of the new range comes from the old row's range.
    for (const ColumnRun& run : runs) {
        const size_t lo = std::max<size_t>(run.to, first), hi = std::min<size_t>(run.to + run.n, end);
        if (lo >= hi) continue;
        if (run.from == kNewColumns)
            std::fill(row + (lo - first), row + (hi - first), kNeedsTrace);
        else
            std::copy(old_row + (run.from + (lo - run.to) - old_first), old_row + (run.from + (hi - run.to) - old_first),
                      row + (lo - first));
    }
}

// Pair j of a record's row must be re-traced: it never was (kNeedsTrace), its occluder is
// one of the `moved` objects, or it was unoccluded and its segment meets a moved box
// (trace[j] = 1 on entry). trace[j] becomes 1 for those, 0 for the rest. Compares only,
// so GCC vectorises both loops (the moved objects are few; a table lookup would not).
void mark_retrace(const int32_t* __restrict row, size_t n, const std::vector<uint32_t>& moved,
                  int32_t* __restrict trace) {
    for (size_t j = 0; j < n; ++j) trace[j] = (row[j] == kNeedsTrace) | ((row[j] == kIcVisible) & trace[j]);
    for (const uint32_t m : moved)
        for (size_t j = 0; j < n; ++j) trace[j] |= row[j] == static_cast<int32_t>(m);
}

bool differ(const std::vector<float>& a, const std::vector<float>& b, size_t at, size_t n) {
    return std::memcmp(&a[at], &b[at], n * sizeof(float)) != 0;
}

void set_bit(uint32_t* mask, uint32_t j) { mask[j >> 5] |= 1u << (j & 31u); }

// Sets in `mask` the bits of the columns in `which` that `row` (columns first ..
// first + n − 1) marks visible.
void mark_visible(const int32_t* row, size_t first, size_t n, const std::vector<uint32_t>& which, uint32_t* mask) {
    for (const uint32_t j : which)
        if (j >= first && j - first < n && row[j - first] == kIcVisible) set_bit(mask, j);
}

}  // namespace

struct InstantCache::ChangedVpls {
    std::vector<uint32_t> added;    // new columns whose VPL is new or differs in any float
    std::vector<uint32_t> removed;  // old columns no new column keeps as it was
};

// What changed between the VPLs the rows were traced with and the new ones, given
// old_column (per new column, its old column with the same position, normal and offset
// scale, or -1).
InstantCache::ChangedVpls InstantCache::changed_vpls(const std::vector<float>& old_vpls,
                                                     const std::vector<float>& vpls,
                                                     const std::vector<int64_t>& old_column) {
    ChangedVpls c;
    std::vector<uint8_t> kept(vpl_count(old_vpls), 0);
    for (size_t j = 0; j < old_column.size(); ++j) {
        const int64_t k = old_column[j];
        if (k >= 0 && std::memcmp(&vpls[j * TS_VPL_FLOATS], &old_vpls[size_t(k) * TS_VPL_FLOATS],
                                  TS_VPL_FLOATS * sizeof(float)) == 0)
            kept[size_t(k)] = 1;
        else
            c.added.push_back(static_cast<uint32_t>(j));
    }
    for (size_t k = 0; k < kept.size(); ++k)
        if (!kept[k]) c.removed.push_back(static_cast<uint32_t>(k));
    return c;
}

struct InstantCache::Change {
    std::vector<uint32_t> moved;            // objects of O
    std::vector<Box> old_box, new_box;      // per object
    std::vector<uint8_t> is_moved;          // per object
    std::vector<uint8_t> material_changed;  // per material
    std::vector<uint8_t> light_changed;     // per light
    bool all_paths = false;
};

void InstantCache::snapshot(const SceneBuffers& scene, float g_clamp) {
    prev_tri_pos_ = scene.tri_pos;
    prev_materials_ = scene.materials;
    prev_lights_ = scene.lights;
    prev_light_cdf_ = scene.light_cdf;
    prev_g_clamp_ = g_clamp;
    have_previous_ = true;
}

void InstantCache::evict_out_of_view() {
    std::vector<IcRecord>& records = cache_.records();
    size_t kept = 0;
    for (size_t i = 0; i < records.size(); ++i) {
        if (frame_count_ - records[i].last_in_view > settings_.evict_after_frames) continue;
        if (kept != i) {  // a self-move would empty the row
            records[kept] = records[i];
            rows_[kept] = std::move(rows_[i]);
            sums_[kept] = sums_[i];
        }
        ++kept;
    }
    stats_.evicted = records.size() - kept;
    records.resize(kept);
    rows_.resize(kept);
    sums_.resize(kept);
}

void InstantCache::update(Backend& backend, const SceneBuffers& scene, float g_clamp) {
    evict_out_of_view();
    if (scene.tri_pos.size() != prev_tri_pos_.size() || scene.materials.size() != prev_materials_.size())
        throw RuntimeError("tic: the scene's triangles or materials changed in number between frames");
    Change ch;
    const size_t objects = object_first_.size();
    ch.old_box.resize(objects), ch.new_box.resize(objects), ch.is_moved.assign(objects, 0);
    // Per object, over its triangles in parallel: min and max are exact, so the boxes do
    // not depend on how the range is split (Sibenik's 75k triangles: 3.5 ms serially).
    struct ObjectChange {
        bool moved = false;
        Box old_box, new_box;
    };
    for (uint32_t o = 0; o < objects; ++o) {
        const uint32_t begin = std::min(object_first_[o], scene.triangle_count);
        const uint32_t end = o + 1 < objects ? std::min(object_first_[o + 1], scene.triangle_count) : scene.triangle_count;
        const ObjectChange c = tbb::parallel_reduce(
            tbb::blocked_range<uint32_t>(begin, std::max(begin, end), 4096), ObjectChange{},
            [&](const tbb::blocked_range<uint32_t>& r, ObjectChange c) {
                for (uint32_t t = r.begin(); t < r.end(); ++t) {
                    c.moved = c.moved || differ(scene.tri_pos, prev_tri_pos_, 9 * size_t(t), 9);
                    for (int v = 0; v < 3; ++v) {
                        c.old_box.grow(&prev_tri_pos_[9 * size_t(t) + 3 * v]);
                        c.new_box.grow(&scene.tri_pos[9 * size_t(t) + 3 * v]);
                    }
                }
                return c;
            },
            [](ObjectChange a, const ObjectChange& b) {
                a.moved = a.moved || b.moved;
                a.old_box.grow(b.old_box), a.new_box.grow(b.new_box);
                return a;
            });
        ch.is_moved[o] = c.moved ? 1 : 0;
        ch.old_box[o] = c.old_box, ch.new_box[o] = c.new_box;
    }
    for (uint32_t o = 0; o < objects; ++o) {
        ch.old_box[o].pad(), ch.new_box[o].pad();
        if (ch.is_moved[o]) ch.moved.push_back(o);
    }
    ch.material_changed.assign(scene.materials.size() / TS_MATERIAL_FLOATS, 0);
    for (size_t m = 0; m < ch.material_changed.size(); ++m)
        ch.material_changed[m] = differ(scene.materials, prev_materials_, m * TS_MATERIAL_FLOATS, TS_MATERIAL_FLOATS);
    ch.all_paths = scene.light_cdf != prev_light_cdf_ || scene.lights.size() != prev_lights_.size();
    ch.light_changed.assign(scene.light_count, 0);
    if (!ch.all_paths)
        for (size_t l = 0; l < scene.light_count; ++l)
            ch.light_changed[l] = differ(scene.lights, prev_lights_, l * TS_LIGHT_FLOATS, TS_LIGHT_FLOATS);

    // Light paths.
    auto path_invalid = [&](const LightPath& p) {
        if (ch.all_paths || (p.light < ch.light_changed.size() && ch.light_changed[p.light])) return true;
        for (const PathSegment& s : p.segments) {
            if (s.prim != TS_NO_HIT &&
                (ch.is_moved[object_of(s.prim)] || ch.material_changed[scene.tri_mat[s.prim]]))
                return true;
            for (uint32_t o : ch.moved)
                if (ch.new_box[o].meets(s.org, s.dir, 0.0f, s.t)) return true;
        }
        return false;
    };
    std::vector<uint32_t> redo;
    for (uint32_t p = 0; p < paths_.size(); ++p)
        if (path_invalid(paths_[p])) redo.push_back(p);
    std::vector<LightPath> fresh;
    for (uint32_t p : redo) fresh.push_back(untraced(paths_[p]));
    if (!fresh.empty()) stats_.light_path_rays += trace_light_paths(backend, scene, path_settings(), fresh);
    stats_.paths_retraced = redo.size();

    // New VPL columns: each kept VPL maps to its old column (same position, normal, scale).
    std::vector<int64_t> old_column;
    bool weights_changed = false;
    {
        std::vector<uint8_t> redone(paths_.size(), 0);
        for (size_t i = 0; i < redo.size(); ++i) redone[redo[i]] = 1;
        size_t base = 0, k = 0;
        for (uint32_t p = 0; p < paths_.size(); ++p) {
            const size_t old_n = paths_[p].vpls.size() / TS_VPL_FLOATS;
            if (redone[p]) {
                const LightPath& np = fresh[k++];
                const size_t new_n = np.vpls.size() / TS_VPL_FLOATS;
                for (size_t v = 0; v < new_n; ++v) {
                    const float* a = &np.vpls[v * TS_VPL_FLOATS];
                    const float* b = v < old_n ? &paths_[p].vpls[v * TS_VPL_FLOATS] : nullptr;
                    // Same position, normal and offset scale: the same VPL for every record.
                    static_assert(TS_VPL_NORMAL == TS_VPL_POSITION + 3, "position and normal are adjacent");
                    const bool same = b && std::memcmp(a + TS_VPL_POSITION, b + TS_VPL_POSITION, 6 * sizeof(float)) == 0 &&
                                      a[TS_VPL_POS_SCALE] == b[TS_VPL_POS_SCALE];
                    old_column.push_back(same ? int64_t(base + v) : -1);
                    if (!same) ++stats_.vpls_changed;
                    weights_changed = weights_changed || !same || std::memcmp(a + TS_VPL_FLUX, b + TS_VPL_FLUX, 3 * sizeof(float)) != 0;
                }
                weights_changed = weights_changed || new_n != old_n;
                paths_[p] = np;
            } else {
                for (size_t v = 0; v < old_n; ++v) old_column.push_back(int64_t(base + v));
            }
            base += old_n;
        }
    }
    const std::vector<float> old_vpls = vpls_;
    const std::vector<size_t> old_offsets = subset_vpls_;
    concat_vpls();
    const ChangedVpls changed = changed_vpls(old_vpls, vpls_, old_column);
    const size_t words_old = TS_IC_VISIBLE_WORDS(vpl_count(old_vpls));
    const bool by_change = g_clamp == prev_g_clamp_ && changed.added.size() + changed.removed.size() < old_column.size();

    // Records: drop the stale ones, re-map the rest to the new columns.
    std::vector<IcRecord>& records = cache_.records();
    check_pairs(records.size(), widest_subset(subset_vpls_));
    // Usually every VPL keeps its place: the same column, or a new VPL in the column of the
    // old one (a re-traced path with as many VPLs as before). Each row then moves over as it
    // is, without a copy (45k records × 400 VPLs = 72 MB a frame on Sibenik), and only the
    // new columns are marked (`new_columns`).
    bool same_columns = old_offsets == subset_vpls_;
    std::vector<uint32_t> new_columns;
    for (size_t j = 0; same_columns && j < old_column.size(); ++j) {
        same_columns = old_column[j] == int64_t(j) || old_column[j] < 0;
        if (old_column[j] < 0) new_columns.push_back(static_cast<uint32_t>(j));
    }
    std::vector<uint32_t> keep;
    for (size_t i = 0; i < records.size(); ++i) {
        const IcRecord& r = records[i];
        uint32_t prim;
        std::memcpy(&prim, &r.surface[TS_IC_GBUF_PRIM], 4);
        bool stale = ch.is_moved[object_of(prim)] != 0;
        // The radius depends on the probe's nearest hit too: a moved object within it
        // may have been that hit, or now be nearer (the probe's reach caps it).
        const float reach = std::max(r.radius, r.probe);
        for (uint32_t o : ch.moved)
            stale = stale || ch.old_box[o].meets_sphere(r.position(), reach) ||
                    ch.new_box[o].meets_sphere(r.position(), reach);
        if (stale)
            ++stats_.removed;
        else
            keep.push_back(static_cast<uint32_t>(i));
    }
    std::vector<IcRecord> kept(keep.size());
    std::vector<Row> rows(keep.size());
    std::vector<IcGatherSums> sums(keep.size());
    // By change: per kept record, its old row's visible VPLs among those that changed (a
    // mask over the old columns, what to subtract), and below, the same for its new row.
    std::vector<uint32_t> minus(by_change ? keep.size() * words_old : 0, 0u);
    const std::vector<ColumnRun> runs = same_columns ? std::vector<ColumnRun>{} : column_runs(old_column);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, keep.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
            kept[k] = records[keep[k]];
            sums[k] = sums_[keep[k]];
            const Row& old_row = rows_[keep[k]];
            const size_t old_first = row_first(kept[k], old_offsets);
            if (by_change) mark_visible(old_row.data(), old_first, old_row.size(), changed.removed, &minus[k * words_old]);
            const size_t first = row_first(kept[k], subset_vpls_), end = first + row_size(kept[k], subset_vpls_);
            if (same_columns) {
                // Only the new columns of the record's own subset need a ray.
                rows[k] = std::move(rows_[keep[k]]);
                for (const uint32_t j : new_columns)
                    if (j >= first && j < end) rows[k][j - first] = kNeedsTrace;
                continue;
            }
            rows[k].resize(end - first);
            remap_row(runs, old_row.data(), old_first, rows[k].data(), first, end);
        }
    });
    if (!same_columns) stats_.rows_remade = keep.size();
    records.swap(kept);
    rows_.swap(rows);
    sums_.swap(sums);

    // Pairs to re-trace: those never traced, those whose occluder moved, and the visible
    // ones whose shadow ray now meets a moved object's box. That ray is the one
    // ts_vpl_geometry builds (the record's offset origin to the VPL's offset point); its
    // far end depends on the VPL alone, so it is computed once per VPL here, and its
    // origin once per record. (A visible pair faced both ways when it was traced, and
    // neither its record nor its VPL has changed since, so its geometry term is still
    // positive and need not be recomputed.)
    const size_t nv = vpls_.size() / TS_VPL_FLOATS;
    std::vector<float> end[3];  // VPL j's far end: the direction of its ray from the origin
    float t_lo = 0.0f, t_hi = 0.0f;
    for (auto& e : end) e.resize(nv);
    for (size_t j = 0; j < nv; ++j) {
        const ts::TsRay r = ts::ts_vpl_shadow_ray(ts::make_float3(0.0f, 0.0f, 0.0f), &vpls_[j * TS_VPL_FLOATS]);
        end[0][j] = r.dir.x, end[1][j] = r.dir.y, end[2][j] = r.dir.z;
        t_lo = r.tmin, t_hi = r.tmax;  // the same for every VPL
    }
    std::vector<std::vector<Pair>> per_record(records.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, records.size(), 16), [&](const tbb::blocked_range<size_t>& rr) {
        std::vector<int32_t> retrace;  // per VPL of the record's subset: meets a moved box, then: re-trace
        for (size_t i = rr.begin(); i < rr.end(); ++i) {
            const size_t first = row_first(records[i], subset_vpls_), n = rows_[i].size();
            retrace.assign(n, 0);
            if (!ch.moved.empty()) {
                const ts::TsSurface s = ic_record_surface(records[i]);
                const ts::float3 o = ts::ts_offset_ray_origin(s.origin, s.geo_normal, s.pos_scale);
                const float org[3] = {o.x, o.y, o.z};
                for (uint32_t m : ch.moved)
                    ch.new_box[m].meets_many(org, end[0].data() + first, end[1].data() + first, end[2].data() + first,
                                             n, t_lo, t_hi, retrace.data());
            }
            mark_retrace(rows_[i].data(), n, ch.moved, retrace.data());
            for (size_t k = 0; k < n; ++k) {
                if (!retrace[k]) continue;
                const size_t j = first + k;
                per_record[i].push_back({static_cast<uint32_t>(i), static_cast<uint32_t>(j)});
                // A kept VPL's pair re-traced: its old visibility is still in the row.
                if (by_change && old_column[j] >= 0 && rows_[i][k] == kIcVisible)
                    set_bit(&minus[i * words_old], static_cast<uint32_t>(old_column[j]));
            }
        }
    });
    std::vector<Pair> pairs;
    for (const auto& v : per_record) pairs.insert(pairs.end(), v.begin(), v.end());
    stats_.shadow_rays += trace_pairs(backend, vpls_, pairs, g_clamp, rows_);

    if (by_change) {
        resum_by_change(backend, old_vpls, changed, minus, per_record, g_clamp);
        return;
    }
    const bool all = weights_changed || g_clamp != prev_g_clamp_;
    std::vector<uint32_t> resum;
    for (size_t i = 0; i < records.size(); ++i)
        if (all || !per_record[i].empty()) resum.push_back(static_cast<uint32_t>(i));
    const std::vector<float> harmonic = gather(backend, vpls_, subset_vpls_, rows_, records, resum, g_clamp, &sums_);
    for (size_t k = 0; k < resum.size(); ++k) {
        IcRecord& r = records[resum[k]];
        // The visible VPLs may have changed, and with them the harmonic mean distance.
        r.radius = radius_of(r, harmonic[k]);
    }
    stats_.resummed += resum.size();
}

// Each record's sums, minus its old sum over `minus` (a mask over old_vpls' columns per
// record) and plus its new sum over the VPLs that were added and its re-traced pairs,
// where visible now. Records whose masks are both empty keep E and R as they are.
void InstantCache::resum_by_change(Backend& backend, const std::vector<float>& old_vpls, const ChangedVpls& changed,
                                   const std::vector<uint32_t>& minus, const std::vector<std::vector<Pair>>& per_record,
                                   float g_clamp) {
    std::vector<IcRecord>& records = cache_.records();
    const size_t words_old = TS_IC_VISIBLE_WORDS(vpl_count(old_vpls)), words = TS_IC_VISIBLE_WORDS(vpl_count(vpls_));
    std::vector<uint32_t> plus(records.size() * words, 0u);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, records.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
            const size_t first = row_first(records[i], subset_vpls_);
            mark_visible(rows_[i].data(), first, rows_[i].size(), changed.added, &plus[i * words]);
            for (const Pair& p : per_record[i])
                if (rows_[i][p.vpl - first] == kIcVisible) set_bit(&plus[i * words], p.vpl);
        }
    });
    auto with_bits = [&](const std::vector<uint32_t>& masks, size_t w) {
        std::vector<uint32_t> which;
        for (size_t i = 0; i < records.size(); ++i)
            if (std::any_of(&masks[i * w], &masks[i * w] + w, [](uint32_t b) { return b != 0u; }))
                which.push_back(static_cast<uint32_t>(i));
        return which;
    };
    const std::vector<uint32_t> which_minus = with_bits(minus, words_old), which_plus = with_bits(plus, words);
    auto copy_mask = [](const std::vector<uint32_t>& masks, size_t w, const std::vector<uint32_t>& which) {
        return [&masks, w, &which](size_t k, uint32_t* mask) { std::copy_n(&masks[which[k] * w], w, mask); };
    };
    const std::vector<float> out_minus =
        gather_outputs(backend, old_vpls, records, which_minus, g_clamp, copy_mask(minus, words_old, which_minus));
    const std::vector<float> out_plus =
        gather_outputs(backend, vpls_, records, which_plus, g_clamp, copy_mask(plus, words, which_plus));
    // Subtract first: a count that reaches 0 leaves sums of exactly 0 (IcGatherSums).
    std::vector<uint8_t> touched(records.size(), 0);
    for (size_t k = 0; k < which_minus.size(); ++k) {
        sums_[which_minus[k]] -= IcGatherSums::from_output(&out_minus[TS_IC_GATHER_FLOATS * k]);
        touched[which_minus[k]] = 1;
    }
    for (size_t k = 0; k < which_plus.size(); ++k) {
        sums_[which_plus[k]] += IcGatherSums::from_output(&out_plus[TS_IC_GATHER_FLOATS * k]);
        touched[which_plus[k]] = 1;
    }
    for (size_t i = 0; i < records.size(); ++i) {
        if (!touched[i]) continue;
        records[i].e = sums_[i].irradiance();
        records[i].radius = radius_of(records[i], sums_[i].harmonic_mean());
        ++stats_.resummed, ++stats_.resummed_by_change;
    }
}

}  // namespace tessera
