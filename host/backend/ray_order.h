// An order for an incoherent ray batch in which neighbouring rays start close together
// and head the same way, so that 16 consecutive rays make a packet worth tracing
// together (docs/ray-batches.md §4, "Sorted incoherent batches").
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera {

/// Bits of the sort key (ray_sort_key): per axis of the origin's grid and of the
/// direction's. Chosen by measurement (bench/results/ray_bench_sorted.md): on Sibenik's
/// random and `ic-update` rays 4 and 5 bits traced fastest of the grids tried (2–5 origin
/// bits × 0–6 direction bits); coarser grids leave a packet's lanes spread, finer ones
/// split rays that would share nodes.
inline constexpr int kRayOrderOriginBits = 4;
inline constexpr int kRayOrderDirectionBits = 5;

/// The origin grid of ray_sort_key: 2^kRayOrderOriginBits cells per axis over the box
/// [lo, hi] (scene units; on an axis where lo = hi, origins on the box are in cell 0).
struct RayKeyGrid {
    RayKeyGrid() = default;  ///< every origin in cell 0, until a box is given
    RayKeyGrid(const float lo[3], const float hi[3]);
    float lo[3] = {}, scale[3] = {};  ///< cell of coordinate v on axis a: (v − lo[a]) · scale[a]
};

/// The key of one ray, 30 bits: the octant of its direction (3 bits, highest), then the
/// Morton index of its origin's cell in `grid` (12 bits), then the Morton index of its
/// direction's cell on a 2^5 grid per axis over the cube [-1, 1]³ (d / max|d_i|; 15
/// bits). `ray` holds TS_RAY_FLOATS floats (layout_rays.h); the direction need not be unit
/// length. Values outside the grid clamp to its edge cells and NaN to cell 0 (the key is
/// a hint: every key gives a valid order).
uint32_t ray_sort_key(const float* ray, const RayKeyGrid& grid);

/// ray_sort_key of `n` consecutive rays into keys[0 .. n-1], 16 rays at a time in SIMD.
void ray_sort_keys(const float* rays, size_t n, const RayKeyGrid& grid, uint32_t* keys);

/// The permutation that sorts `n` rays (TS_RAY_FLOATS floats each, at `rays`) by
/// ray_sort_key on `grid` (the OpenCL backend's: the scene's bounding box): element j is
/// the index of the ray traced j-th. Stable (equal keys keep their input order), so the
/// order is a function of the batch alone. LSD radix sort, 3 passes of 10 bits, each in
/// parallel over TBB; O(n) time, 20n bytes of buffers. Throws std::length_error for more
/// than 2^32 rays (the indices are 32-bit). This follows the ray sorting of
/// Garanzha and Loop 2010 ("Fast ray sorting and breadth-first packet traversal for GPU ray
/// tracing": keys from quantised origin and direction) with the octant first, as packet
/// tracers bin rays by their direction signs.
std::vector<uint32_t> coherent_ray_order(const float* rays, size_t n, const RayKeyGrid& grid);

/// The sort's buffers, for callers that sort batch after batch (20 bytes per ray and
/// 4 KB per thread).
struct RaySortBuffers {
    std::vector<uint64_t> a, b;   ///< (key << 32 | index), ping-pong
    std::vector<uint32_t> count;  ///< per chunk and digit
    std::vector<uint32_t> order;  ///< the result
};

/// coherent_ray_order in `buf`'s buffers, reused between calls; returns buf.order.
const std::vector<uint32_t>& coherent_ray_order(const float* rays, size_t n, const RayKeyGrid& grid,
                                               RaySortBuffers& buf);

}  // namespace tessera
