#include "backend/ray_order.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "kernels/shared/layout_rays.h"

namespace tessera {
namespace {

// Cell of t on a grid of `cells` cells over [0, cells): values outside clamp to the ends,
// NaN to 0 (its comparisons fail). Written as compare-selects and converted via int32
// (cells ≤ 1024) so that it compiles to maxss/minss and no branch: std::fmax is a libm
// call, and a float → uint32 conversion branches without AVX-512 (on incoherent rays
// those branches mispredict; keys took 1.5–1.7× as long with either).
uint32_t cell(float t, float cells) {
    t = t > 0.0f ? t : 0.0f;
    t = t < cells - 1.0f ? t : cells - 1.0f;
    return static_cast<uint32_t>(static_cast<int32_t>(t));
}

// morton3(v, 0, 0) for v < 32 (util/morton.h): v's five bits spread to every third bit,
// in shifts and masks the vectoriser takes (a table lookup would be a gather).
uint32_t spread5(uint32_t v) {
    return (v & 1u) | (v & 2u) << 2 | (v & 4u) << 4 | (v & 8u) << 6 | (v & 16u) << 8;
}
static_assert(kRayOrderOriginBits <= 5 && kRayOrderDirectionBits <= 5, "spread5 takes cells below 32");

}  // namespace

RayKeyGrid::RayKeyGrid(const float lo_[3], const float hi_[3]) {
    for (int a = 0; a < 3; ++a) {
        lo[a] = lo_[a];
        scale[a] = float(1u << kRayOrderOriginBits) / std::max(hi_[a] - lo_[a], 1e-30f);
    }
}

void ray_sort_keys(const float* rays, size_t n, const RayKeyGrid& g, uint32_t* keys) {
    constexpr int ob = kRayOrderOriginBits, db = kRayOrderDirectionBits;
    constexpr float oc = 1u << ob, dc = 1u << db;
    constexpr size_t W = 16;  // rays per block: the inner loops run over W lanes in SIMD
    for (size_t first = 0; first < n; first += W) {
        const size_t lanes = std::min(W, n - first);
        alignas(64) float v[6][W] = {};  // org.xyz, dir.xyz per lane; idle lanes zero
        for (size_t l = 0; l < lanes; ++l)
            for (int a = 0; a < 3; ++a) {
                v[a][l] = rays[(first + l) * TS_RAY_FLOATS + TS_RAY_ORG + a];
                v[3 + a][l] = rays[(first + l) * TS_RAY_FLOATS + TS_RAY_DIR + a];
            }
        alignas(64) uint32_t k[W];
        for (size_t l = 0; l < W; ++l) {
            const float dx = v[3][l], dy = v[4][l], dz = v[5][l];
            // The direction's cell from d / max|d_i|, a point on the cube [-1, 1]³: one
            // division, no square root.
            const float m = std::max(std::fabs(dx), std::max(std::fabs(dy), std::fabs(dz)));
            const float s = 0.5f * dc / m;
            const uint32_t origin = spread5(cell((v[0][l] - g.lo[0]) * g.scale[0], oc)) |
                                    spread5(cell((v[1][l] - g.lo[1]) * g.scale[1], oc)) << 1 |
                                    spread5(cell((v[2][l] - g.lo[2]) * g.scale[2], oc)) << 2;
            const uint32_t dir = spread5(cell(dx * s + 0.5f * dc, dc)) | spread5(cell(dy * s + 0.5f * dc, dc)) << 1 |
                                 spread5(cell(dz * s + 0.5f * dc, dc)) << 2;
            const uint32_t octant = uint32_t(dx < 0.0f) | uint32_t(dy < 0.0f) << 1 | uint32_t(dz < 0.0f) << 2;
            k[l] = octant << (3 * (ob + db)) | origin << (3 * db) | dir;
        }
        std::copy(k, k + lanes, keys + first);
    }
}

uint32_t ray_sort_key(const float* ray, const RayKeyGrid& grid) {
    uint32_t key;
    ray_sort_keys(ray, 1, grid, &key);
    return key;
}

const std::vector<uint32_t>& coherent_ray_order(const float* rays, size_t n, const RayKeyGrid& grid,
                                               RaySortBuffers& buf) {
    // Stable LSD radix sort of (key << 32 | index), each pass in parallel: chunk c counts
    // its digits, every (digit, chunk) gets its place in digit-major, chunk-minor order,
    // and chunk c scatters its elements to their places in input order. One 8-byte element
    // per ray: a pass writes one stream, not a key's and an index's.
    constexpr int kDigitBits = 10, kPasses = 3, kDigits = 1 << kDigitBits;
    static_assert(kDigitBits * kPasses == 3 + 3 * (kRayOrderOriginBits + kRayOrderDirectionBits));
    if (n > UINT32_MAX) throw std::length_error("coherent_ray_order: more than 2^32 rays");  // indices are 32-bit
    const size_t chunks = std::max<size_t>(1, std::min<size_t>(tbb::this_task_arena::max_concurrency(), n / 4096));
    const size_t per = (n + chunks - 1) / chunks;
    // Kept between calls: fresh buffers cost page faults and zeroing (the OpenCL backend's
    // sort of 262k rays took 3.2–4.5 ms with them, 2.4–2.6 ms without).
    buf.a.resize(n);
    buf.b.resize(n);
    buf.count.resize(chunks * kDigits);
    buf.order.resize(n);
    uint64_t *a = buf.a.data(), *b = buf.b.data();
    auto each_chunk = [&](auto&& f) {
        tbb::parallel_for(size_t(0), chunks, [&](size_t c) { f(c, c * per, std::min(n, (c + 1) * per)); });
    };
    each_chunk([&](size_t, size_t lo, size_t hi) {
        uint32_t key[16];
        for (size_t i = lo; i < hi; i += 16) {
            const size_t m = std::min<size_t>(16, hi - i);
            ray_sort_keys(rays + i * TS_RAY_FLOATS, m, grid, key);
            for (size_t l = 0; l < m; ++l) a[i + l] = uint64_t(key[l]) << 32 | (i + l);
        }
    });
    for (int pass = 0; pass < kPasses; ++pass) {
        const int shift = 32 + pass * kDigitBits;
        const uint64_t mask = kDigits - 1;
        each_chunk([&](size_t c, size_t lo, size_t hi) {
            uint32_t* h = &buf.count[c * kDigits];
            std::fill(h, h + kDigits, 0u);
            for (size_t i = lo; i < hi; ++i) ++h[a[i] >> shift & mask];
        });
        uint32_t sum = 0;
        for (int d = 0; d < kDigits; ++d)
            for (size_t c = 0; c < chunks; ++c) sum += std::exchange(buf.count[c * kDigits + d], sum);
        each_chunk([&](size_t c, size_t lo, size_t hi) {
            uint32_t* at = &buf.count[c * kDigits];
            for (size_t i = lo; i < hi; ++i) b[at[a[i] >> shift & mask]++] = a[i];
        });
        std::swap(a, b);
    }
    each_chunk([&](size_t, size_t lo, size_t hi) {
        for (size_t i = lo; i < hi; ++i) buf.order[i] = static_cast<uint32_t>(a[i]);
    });
    return buf.order;
}

std::vector<uint32_t> coherent_ray_order(const float* rays, size_t n, const RayKeyGrid& grid) {
    RaySortBuffers buf;
    return coherent_ray_order(rays, n, grid, buf);
}

}  // namespace tessera
