/* A device AIS frame's item lists compacted where the kernels run
 * (docs/ray-batches.md §5).
 *
 * The host path lists the extra sets' items and the edge samples on the host
 * (host/gi/ais_schedule.h, ais_edges.h). A device frame keeps each pixel's set
 * masks (TsSceneView.ais_masks, KernelId::AisSchedule's output) and edge-sample
 * counts (edge_counts, EdgeSchedule's) where they were computed and lists
 * nothing: per TS_AIS_TILE² pixel tile (and, for the edges, per tile row) the
 * kernels below count what it holds, the host reads those counts back (12 floats
 * per set and tile and 2 per tile row: at tile 3 about 0.5 floats a pixel, not the
 * 8 a pixel of the masks and counts) and uploads their exclusive prefix
 * sums (ais_item_offsets, edge_segment_offsets), and then work item i of the extra
 * sets' and edge samples' kernels finds its own pixel from the sums and the
 * tile's bits or the segment's counts (ts_ais_compact_decode, ts_edge_compact_decode): no item list is
 * read back, built or uploaded, and every work item has work. The resolve finds
 * a pixel's items the same way (ts_ais_compact_index, ts_edge_compact_first).
 *
 * The order is the host list's (host/gi/ais_schedule.h, schedule_items): by
 * set, then by tile in rows of tiles, then by pixel row-major in the tile, so
 * item i here is the host list's item i; the edge samples run by tile, then
 * pixel, then sample, where the host lists them by pixel row-major (an edge
 * sample's value depends on its pixel and index, not on its place in the list).
 */
#ifndef TS_AIS_COMPACT_H
#define TS_AIS_COMPACT_H

#include "shared/compat.h"
#include "shared/frame.h"
#include "shared/geometry.h"
#include "shared/layout_igi.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

TS_INLINE uint ts_ais_tiles_x(const TsFrame* f) { return (f->width + TS_AIS_TILE - 1u) / TS_AIS_TILE; }

/* T, the frame's tiles. */
TS_INLINE uint ts_ais_tile_count(const TsFrame* f) {
    return ts_ais_tiles_x(f) * ((f->height + TS_AIS_TILE - 1u) / TS_AIS_TILE);
}

/* Component c's set mask of a pixel (m: its TS_AIS_MASK_FLOATS): bit k, set k evaluated. */
TS_INLINE ulong ts_ais_component_mask(TS_GLOBAL const float* m, int c) {
    return (ulong)as_uint(m[TS_AIS_MASK_SETS(c)]) | (ulong)as_uint(m[TS_AIS_MASK_SETS(c) + 1]) << 32;
}

/* The TS_COMPONENT_* bits of the components whose masks hold set k. */
TS_INLINE uint ts_ais_set_components(TS_GLOBAL const float* m, uint k) {
    uint bits = 0u;
    for (int c = 0; c < 3; ++c)
        if ((ts_ais_component_mask(m, c) >> k) & 1ul) bits |= 1u << c;
    return bits;
}

/* Pixel (x, y)'s sets beyond its own over all components. */
TS_INLINE ulong ts_ais_extra_sets(TS_GLOBAL const float* m, uint x, uint y, uint tile) {
    ulong all = 0ul;
    for (int c = 0; c < 3; ++c) all |= ts_ais_component_mask(m, c);
    return all & ~((ulong)1 << ts_igi_set(x, y, tile));
}

/* The entry of set k and tile t in AisTileSets: tile-major, so that the n² work items of a
 * tile, neighbours in a launch, read the same pixels' masks (on a GPU one load serves
 * them, where set-major neighbours would read n² tiles apart). */
TS_INLINE size_t ts_ais_tile_set_entry(const TsFrame* f, uint k, uint t) {
    return ((size_t)t * (f->igi_tile * f->igi_tile) + k) * TS_AIS_TILE_SET_FLOATS;
}

/* Work item j = t·n² + k of KernelId::AisTileSets (layout_igi.h, TS_AIS_TILE_SET_*): which
 * pixels of tile t evaluate set k beyond their own, their number, and (set 0's item only)
 * the tile's pixels each component flags. */
TS_INLINE void ts_ais_tile_sets_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint j,
                                     float* out) {
    (void)tracer;
    const uint sets = f->igi_tile * f->igi_tile, t = j / sets, k = j % sets, tx = ts_ais_tiles_x(f);
    const uint x0 = (t % tx) * TS_AIS_TILE, y0 = (t / tx) * TS_AIS_TILE;
    /* One scalar word at a time: a private array indexed at run time would live in a GPU's
     * local memory. */
    uint flags[3] = {0u, 0u, 0u}, count = 0u;
    for (int w = 0; w < TS_AIS_TILE_SET_WORDS; ++w) {
        uint word = 0u;
        for (uint bit = 0u; bit < 32u; ++bit) {
            const uint b = 32u * (uint)w + bit, x = x0 + b % TS_AIS_TILE, y = y0 + b / TS_AIS_TILE;
            if (x >= f->width || y >= f->height) continue;
            TS_GLOBAL const float* m = sv->ais_masks + ((size_t)y * f->width + x) * TS_AIS_MASK_FLOATS;
            if ((ts_ais_extra_sets(m, x, y, f->igi_tile) >> k) & 1ul) {
                word |= 1u << bit;
                ++count;
            }
            if (k == 0u) {
                const uint flagged = as_uint(m[TS_AIS_MASK_FLAGS]);
                for (int c = 0; c < 3; ++c) flags[c] += (flagged >> c) & 1u;
            }
        }
        out[TS_AIS_TILE_SET_BITS + w] = as_float(word);
    }
    out[TS_AIS_TILE_SET_COUNT] = (float)count;
    for (int c = 0; c < 3; ++c) out[TS_AIS_TILE_SET_FLAGS + c] = (float)flags[c];
}

/* The last index e of offsets[0..n] (non-decreasing, offsets[0] = 0 ≤ i <
 * offsets[n]) with offsets[e] ≤ i: the run that holds item i (runs may be
 * empty). */
TS_INLINE uint ts_ais_run_of(TS_GLOBAL const uint* offsets, uint n, uint i) {
    uint lo = 0u, hi = n; /* offsets[lo] <= i < offsets[hi] */
    while (hi - lo > 1u) {
        const uint mid = lo + (hi - lo) / 2u;
        if (offsets[mid] <= i)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* The bit b of the r-th set bit (from 0) of words[0..TS_AIS_TILE_SET_WORDS). */
TS_INLINE uint ts_ais_nth_bit(TS_GLOBAL const float* words, uint r) {
    for (uint w = 0u; w < TS_AIS_TILE_SET_WORDS; ++w) {
        uint v = as_uint(words[w]);
        const uint n = (uint)ts_popcount64((ulong)v);
        if (r >= n) {
            r -= n;
            continue;
        }
        for (; r > 0u; --r) v &= v - 1u;
        return 32u * w + (uint)ts_ctz64((ulong)v);
    }
    return 0u; /* not reached for r below the words' count */
}

/* Item i of a device frame's extra sets (i < ais_item_offsets' last word): its
 * pixel, set k and the components evaluating it (ts_ais_item's mask), as the
 * host list's item i. */
TS_INLINE void ts_ais_compact_decode(const TsSceneView* sv, const TsFrame* f, uint i, uint* px, uint* py, uint* k,
                                     uint* mask) {
    const uint tiles = ts_ais_tile_count(f), runs = f->igi_tile * f->igi_tile * tiles;
    const uint j = ts_ais_run_of(sv->ais_item_offsets, runs, i), t = j % tiles, tx = ts_ais_tiles_x(f);
    *k = j / tiles;
    const uint b = ts_ais_nth_bit(sv->ais_tile_sets + ts_ais_tile_set_entry(f, *k, t) + TS_AIS_TILE_SET_BITS,
                                  i - sv->ais_item_offsets[j]);
    *px = (t % tx) * TS_AIS_TILE + b % TS_AIS_TILE;
    *py = (t / tx) * TS_AIS_TILE + b / TS_AIS_TILE;
    *mask = ts_ais_set_components(sv->ais_masks + ((size_t)*py * f->width + *px) * TS_AIS_MASK_FLOATS, *k);
}

/* The index in a device frame's extra-set items of pixel (x, y)'s item for set
 * k (one of its sets beyond its own): its run's offset plus the tile's pixels
 * before it holding k. */
TS_INLINE uint ts_ais_compact_index(const TsSceneView* sv, const TsFrame* f, uint x, uint y, uint k) {
    const uint tiles = ts_ais_tile_count(f), tx = ts_ais_tiles_x(f);
    const uint t = (y / TS_AIS_TILE) * tx + x / TS_AIS_TILE, j = k * tiles + t;
    const uint b = (y % TS_AIS_TILE) * TS_AIS_TILE + x % TS_AIS_TILE;
    TS_GLOBAL const float* words = sv->ais_tile_sets + ts_ais_tile_set_entry(f, k, t) + TS_AIS_TILE_SET_BITS;
    uint before = 0u;
    for (uint w = 0u; w < b >> 5; ++w) before += (uint)ts_popcount64((ulong)as_uint(words[w]));
    if (b & 31u) before += (uint)ts_popcount64((ulong)(as_uint(words[b >> 5]) & ((1u << (b & 31u)) - 1u)));
    return sv->ais_item_offsets[j] + before;
}

/* Pixel (x, y)'s edge-sample count (EdgeSchedule's output kept as edge_counts).
 */
TS_INLINE uint ts_edge_count_at(const TsSceneView* sv, const TsFrame* f, uint x, uint y) {
    return (uint)sv->edge_counts[(size_t)y * f->width + x];
}

/* S, the frame's edge segments: each tile's rows, TS_AIS_TILE pixels or fewer at the right
 * border, segment s = t·TS_AIS_TILE + r row r of tile t (rows past the bottom border are
 * empty): a sample's or pixel's walk over the counts stays within one segment. */
TS_INLINE uint ts_edge_segment_count(const TsFrame* f) { return ts_ais_tile_count(f) * TS_AIS_TILE; }

/* Segment s's first pixel (x0, y) and its pixel count (0 below the frame). */
TS_INLINE uint ts_edge_segment(const TsFrame* f, uint s, uint* x0, uint* y) {
    const uint t = s / TS_AIS_TILE, tx = ts_ais_tiles_x(f);
    *x0 = (t % tx) * TS_AIS_TILE;
    *y = (t / tx) * TS_AIS_TILE + s % TS_AIS_TILE;
    const uint w = f->width - *x0;
    return *y < f->height ? (w < TS_AIS_TILE ? w : TS_AIS_TILE) : 0u;
}

/* Work item s of KernelId::EdgeSegmentCounts (TS_EDGE_SEGMENT_*): segment s's edge samples
 * and the pixels that take any. */
TS_INLINE void ts_edge_segment_counts_item(const TsSceneView* sv, const TsTracer* tracer, const TsFrame* f, uint s,
                                           float* out) {
    (void)tracer;
    uint x0, y, samples = 0u, flagged = 0u;
    const uint w = ts_edge_segment(f, s, &x0, &y);
    for (uint x = x0; x < x0 + w; ++x) {
        const uint n = ts_edge_count_at(sv, f, x, y);
        samples += n;
        flagged += n > 0u;
    }
    out[TS_EDGE_SEGMENT_SAMPLES] = (float)samples;
    out[TS_EDGE_SEGMENT_FLAGGED] = (float)flagged;
}

/* Edge sample i of a device frame (i < edge_segment_offsets' last word): its pixel
 * (row-major index), its index j ≥ 1 and the pixel's count n. */
TS_INLINE void ts_edge_compact_decode(const TsSceneView* sv, const TsFrame* f, uint i, uint* p, uint* j, uint* n) {
    const uint s = ts_ais_run_of(sv->edge_segment_offsets, ts_edge_segment_count(f), i);
    uint x0, y, r = i - sv->edge_segment_offsets[s];
    const uint w = ts_edge_segment(f, s, &x0, &y);
    *p = 0u, *j = 0u, *n = 0u;
    for (uint x = x0; x < x0 + w; ++x) {
        const uint c = ts_edge_count_at(sv, f, x, y);
        if (r < c) {
            *p = y * f->width + x, *j = r + 1u, *n = c;
            return;
        }
        r -= c;
    }
}

/* The index of pixel (x, y)'s first edge sample in a device frame's edge samples. */
TS_INLINE uint ts_edge_compact_first(const TsSceneView* sv, const TsFrame* f, uint x, uint y) {
    const uint t = (y / TS_AIS_TILE) * ts_ais_tiles_x(f) + x / TS_AIS_TILE;
    uint first = sv->edge_segment_offsets[t * TS_AIS_TILE + y % TS_AIS_TILE];
    for (uint q = (x / TS_AIS_TILE) * TS_AIS_TILE; q < x; ++q) first += ts_edge_count_at(sv, f, q, y);
    return first;
}

TS_NAMESPACE_END
#endif /* TS_AIS_COMPACT_H */
