#include "gi/discontinuity_filter.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/shared/discontinuity.h"

namespace tessera {
void discontinuity_window(int n, int* lo, int* hi) { ts::ts_discontinuity_window(n, lo, hi); }

std::array<ptrdiff_t, 64> discontinuity_window_offsets(int n, int width) {
    static_assert(std::is_same_v<ptrdiff_t, long>, "ts_discontinuity_mean reads the offsets as long");
    std::array<ptrdiff_t, 64> offset{};
    for (int i = 0; i < n * n && i < 64; ++i) offset[i] = ts::ts_discontinuity_offset(n, width, i);
    return offset;
}

namespace {

// Pixel (x, y)'s mask computed now (shared/discontinuity.h, as the device resolve does).
uint64_t compute_window_mask(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y) {
    const bool plane = !g.position.empty();
    return ts::ts_discontinuity_mask(x, y, g.width, g.height, s.tile, g.depth.data(), g.normal.data(),
                                     plane ? g.position.data() : nullptr, 1, 3, plane, s.normal_cos, s.depth_rel);
}

bool same_settings(const DiscontinuitySettings& a, const DiscontinuitySettings& b) {
    return a.tile == b.tile && a.normal_cos == b.normal_cos && a.depth_rel == b.depth_rel;
}

// The G-buffer's fields one array per coordinate (structure of arrays), so that the
// window test over a run of consecutive pixels loads each operand with one vector load.
struct GeometryArrays {
    std::array<std::vector<float>, 3> n, x;  // unit normal, position (x empty: no positions)
    std::vector<float> z;                    // depth
    std::vector<uint8_t> escaped;            // 1 where the depth is not finite
};

GeometryArrays geometry_arrays(const GeometryBuffer& g) {
    const size_t pixels = size_t(g.width) * g.height;
    const bool plane = !g.position.empty();
    GeometryArrays a;
    for (int k = 0; k < 3; ++k) {
        a.n[k].resize(pixels);
        if (plane) a.x[k].resize(pixels);
    }
    a.z = g.depth;
    a.escaped.resize(pixels);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t p = r.begin(); p < r.end(); ++p) {
            for (int k = 0; k < 3; ++k) {
                a.n[k][p] = g.normal[3 * p + k];
                if (plane) a.x[k][p] = g.position[3 * p + k];
            }
            a.escaped[p] = !std::isfinite(g.depth[p]);
        }
    });
    return a;
}

// Pixel y·w + x's bit `col` of its window row's mask, for x in [x0, x1) of row y and window
// offset (dx, dy): one offset over a run of a row, a branch-free loop over consecutive
// pixels that the compiler runs in SIMD (the per-pixel calls of ts_discontinuity_accepts,
// with its early returns and the G-buffer's interleaved coordinates, took 2.6 times as
// long at tile 8). The same test, term by term as ts_discontinuity_accepts writes it, on
// the same operands: the same bits (the precomputed-masks test checks it). 32-bit lanes,
// as wide as the floats', so a vector of tests needs no widening (a window row has at most
// 8 positions); the caller shifts a row's mask into place. The caller keeps
// (x + dx, y + dy) inside the image. Plane: the arrays have positions (the test's use_plane).
template <bool Plane>
void window_bits_run(const GeometryArrays& a, const DiscontinuitySettings& s, int width, int y, int x0, int x1,
                     int dx, int dy, int col, uint32_t* __restrict row_bits) {
    const ptrdiff_t p0 = static_cast<ptrdiff_t>(y) * width + x0;
    const ptrdiff_t q0 = p0 + static_cast<ptrdiff_t>(dy) * width + dx;
    const float *__restrict zp = a.z.data() + p0, *__restrict zq = a.z.data() + q0;
    const uint8_t *__restrict ep = a.escaped.data() + p0, *__restrict eq = a.escaped.data() + q0;
    const float *__restrict npx = a.n[0].data() + p0, *__restrict nqx = a.n[0].data() + q0;
    const float *__restrict npy = a.n[1].data() + p0, *__restrict nqy = a.n[1].data() + q0;
    const float *__restrict npz = a.n[2].data() + p0, *__restrict nqz = a.n[2].data() + q0;
    const float *__restrict xpx = nullptr, *__restrict xqx = nullptr, *__restrict xpy = nullptr;
    const float *__restrict xqy = nullptr, *__restrict xpz = nullptr, *__restrict xqz = nullptr;
    if constexpr (Plane) {
        xpx = a.x[0].data() + p0, xqx = a.x[0].data() + q0;
        xpy = a.x[1].data() + p0, xqy = a.x[1].data() + q0;
        xpz = a.x[2].data() + p0, xqz = a.x[2].data() + q0;
    }
    uint32_t* __restrict out = row_bits + x0;
    const float cos_min = s.normal_cos, depth_rel = s.depth_rel;
    const int count = x1 - x0;
    for (int j = 0; j < count; ++j) {
        const float c = npx[j] * nqx[j] + npy[j] * nqy[j] + npz[j] * nqz[j];
        float dist;
        if constexpr (Plane)
            dist = npx[j] * (xqx[j] - xpx[j]) + npy[j] * (xqy[j] - xpy[j]) + npz[j] * (xqz[j] - xpz[j]);
        else
            dist = zp[j] - zq[j];
        // !(c < cos_min), not c >= cos_min: a NaN c goes on to the distance, as there.
        // Integer ands and ors, not && and ?:, which would be branches.
        const uint32_t surface = uint32_t(!(c < cos_min)) & uint32_t(std::fabs(dist) <= depth_rel * zp[j]);
        // Escaped pixels accept only each other.
        const uint32_t escaped = uint32_t(ep[j] | eq[j]), both = uint32_t(ep[j] & eq[j]);
        const uint32_t ok = both | (surface & (escaped ^ 1u));
        out[j] |= ok << col;
    }
}

// Four pixels' window means at once, for pixels p..p+3 whose windows lie inside the image
// (masks bits[0..3]), C channels: ts_discontinuity_mean's double sums over the positions
// in window order, then sum / count, as 4·C lanes that one position's 4·C contiguous input
// floats add into (a rejected position adds +0, its value's bits masked off, which leaves
// a sum that starts at +0 as it was). The same floats; pixel by pixel over the mask's bits
// the filter took 1.6 times as long (perf, 512², tile 3 and tile 8 alike).
// GCC's and Clang's vector types: AVX2 registers on x86-64-v3, pairs of SSE2 registers
// without it.
using Double4 = double __attribute__((vector_size(32)));
using Float4 = float __attribute__((vector_size(16)));
using Bits4 = uint64_t __attribute__((vector_size(32)));

template <int C>
void mean4(const float* in, size_t p, const ptrdiff_t* offset, int positions, const uint64_t* bits, float* out) {
    static_assert(C == 1 || C == 3, "1 or 3 channels");
    Double4 sum[C] = {};
    const Bits4 masks = {bits[0], bits[1], bits[2], bits[3]};
    for (int i = 0; i < positions; ++i) {
        const float* q = in + (static_cast<ptrdiff_t>(p) + offset[i]) * C;
        const Bits4 keep = Bits4{} - ((masks >> i) & 1u);  // lane j: all ones where pixel j accepts i
        // Lane e of vector v holds pixel (4v + e) / C's channel: the pixels' keeps spread so.
        // (Built from keep's elements: GCC makes each a vpermq, and Clang, which has no
        // __builtin_shuffle, takes it too.)
        Bits4 k[C];
        if constexpr (C == 1) {
            k[0] = keep;
        } else {
            k[0] = Bits4{keep[0], keep[0], keep[0], keep[1]};
            k[1] = Bits4{keep[1], keep[1], keep[2], keep[2]};
            k[2] = Bits4{keep[2], keep[3], keep[3], keep[3]};
        }
        for (int v = 0; v < C; ++v) {
            Float4 f;
            std::memcpy(&f, q + 4 * v, sizeof f);
            sum[v] += reinterpret_cast<Double4>(reinterpret_cast<Bits4>(__builtin_convertvector(f, Double4)) & k[v]);
        }
    }
    double lanes[4 * C];
    std::memcpy(lanes, sum, sizeof lanes);
    for (int j = 0; j < 4; ++j) {
        const int count = std::popcount(bits[j]);
        for (int c = 0; c < C; ++c) out[j * C + c] = static_cast<float>(lanes[j * C + c] / count);
    }
}

// Exact window sums from column sums. A float v ≠ 0 with exponent field E (E' = max(E, 1))
// is a multiple of 2^(E' − 150) below 2^(E' − 126) in magnitude, so any partial sum of k
// window values whose E' span D = E'max − E'min is an integer multiple of 2^(E'min − 150) of
// at most k · 2^(D + 24) of them: exact in double while that is ≤ 2^53, D ≤ 29 − ⌈log2 k⌉.
// Then every order of summing gives the same double, and a window's sum is that of its n
// column sums (each a sum of n values): 2n additions a pixel and channel, not n², in loops
// over a row's consecutive values that run in SIMD. The filter takes this path where all of
// a window's n² positions are accepted and its values meet the bound, else the
// window-order sums (mean4); the floats are the same either way (the filter's tests
// compare with ts_discontinuity_mean bit for bit, and build a window the bound rejects).
constexpr int16_t kNoExponent = 1000;   // E'min of values without a nonzero one
constexpr int16_t kNotFinite = 2000;    // E'max of values with a NaN or an infinity

// Per pixel of an image: the E' range of its nonzero channels, with E'max = kNotFinite
// where one is not finite (any window holding it then fails the bound).
struct PixelExponents {
    std::vector<int16_t> emax, emin;
};

// The PixelExponents of `in` (C channels a pixel).
template <int C>
PixelExponents pixel_exponents(const float* in, size_t pixels) {
    PixelExponents e;
    std::vector<int16_t>&emax = e.emax, &emin = e.emin;
    emax.resize(pixels);
    emin.resize(pixels);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t p = r.begin(); p < r.end(); ++p) {
            int hi = 0, lo = kNoExponent;
            for (int c = 0; c < C; ++c) {
                const uint32_t bits = std::bit_cast<uint32_t>(in[p * C + c]);
                const int e = static_cast<int>(bits >> 23 & 0xffu), e1 = std::max(e, 1);
                const bool nonzero = (bits & 0x7fffffffu) != 0;
                hi = std::max(hi, e == 255 ? int(kNotFinite) : nonzero ? e1 : 0);
                lo = std::min(lo, nonzero ? e1 : int(kNoExponent));
            }
            emax[p] = static_cast<int16_t>(hi);
            emin[p] = static_cast<int16_t>(lo);
        }
    });
    return e;
}

// A row's window sums from column sums, and their E' ranges.
struct RowSums {
    std::vector<double> column, window;           // C per pixel
    std::vector<int16_t> cmax, cmin, wmax, wmin;  // per pixel
};

// Row y's window sums (valid for pixels x with x + lo ≥ 0 and x + hi < w; rows y + lo ..
// y + hi inside the image) and their values' E' ranges.
template <int C>
void row_sums(const float* in, const PixelExponents& e, int w, int y, int lo, int hi, RowSums& r) {
    const size_t k = size_t(w) * C;
    r.column.assign(k, 0.0);
    r.cmax.assign(w, 0);
    r.cmin.assign(w, kNoExponent);
    for (int dy = lo; dy <= hi; ++dy) {
        const float* row = in + (size_t(y) + dy) * k;
        const int16_t *hx = e.emax.data() + (size_t(y) + dy) * w, *lx = e.emin.data() + (size_t(y) + dy) * w;
        for (size_t i = 0; i < k; ++i) r.column[i] += row[i];
        for (int x = 0; x < w; ++x) {
            r.cmax[x] = std::max(r.cmax[x], hx[x]);
            r.cmin[x] = std::min(r.cmin[x], lx[x]);
        }
    }
    r.window.assign(k, 0.0);
    r.wmax.assign(w, 0);
    r.wmin.assign(w, kNoExponent);
    const int x0 = -lo, x1 = w - hi;  // pixels whose window lies inside the row
    for (int dx = lo; dx <= hi; ++dx) {
        const double* col = r.column.data() + ptrdiff_t(dx) * C;
        for (size_t i = size_t(x0) * C; i < size_t(x1) * C; ++i) r.window[i] += col[i];
        for (int x = x0; x < x1; ++x) {
            r.wmax[x] = std::max(r.wmax[x], r.cmax[x + dx]);
            r.wmin[x] = std::min(r.wmin[x], r.cmin[x + dx]);
        }
    }
}

// The filter of rows [y0, y1) with C channels: each pixel's mean over its accepted window
// positions, four at a time where the windows lie inside the image (mean4, or the row's
// column sums where all four windows are whole and exact: `exponents` of `in`, given for
// n ≥ 4, where they save work), else ts_discontinuity_mean (the device resolve's) pixel by
// pixel.
template <int C>
void filter_rows(const GeometryBuffer& g, const DiscontinuitySettings& s, bool precomputed, const float* __restrict in,
                 float* __restrict out, uint8_t* accepted, const PixelExponents* exponents, int y0, int y1) {
    const int w = g.width, h = g.height, n = s.tile;
    const std::array<ptrdiff_t, 64> offset = discontinuity_window_offsets(n, w);
    int lo, hi;
    discontinuity_window(n, &lo, &hi);
    const int positions = n * n;
    const uint64_t whole = positions == 64 ? ~0ull : (1ull << positions) - 1u;
    const int span = 29 - std::bit_width(static_cast<unsigned>(positions - 1));  // 29 − ⌈log2 n²⌉
    RowSums rs;
    for (int y = y0; y < y1; ++y) {
        const bool rows_inside = y + lo >= 0 && y + hi < h;
        const bool columns = exponents && rows_inside;
        if (columns) row_sums<C>(in, *exponents, w, y, lo, hi, rs);
        for (int x = 0; x < w;) {
            const size_t p = size_t(y) * w + x;
            if (rows_inside && x + lo >= 0 && x + 3 + hi < w) {
                uint64_t bits[4];
                for (int j = 0; j < 4; ++j)
                    bits[j] = precomputed ? g.accepted[p + j] : compute_window_mask(g, s, x + j, y);
                bool exact = columns;
                for (int j = 0; exact && j < 4; ++j)
                    exact = bits[j] == whole && (rs.wmin[x + j] == kNoExponent || rs.wmax[x + j] - rs.wmin[x + j] <= span);
                if (exact)
                    for (int i = 0; i < 4 * C; ++i)
                        out[p * C + i] = static_cast<float>(rs.window[size_t(x) * C + i] / positions);
                else
                    mean4<C>(in, p, offset.data(), positions, bits, out + p * C);
                if (accepted)
                    for (int j = 0; j < 4; ++j) accepted[p + j] = static_cast<uint8_t>(std::popcount(bits[j]));
                x += 4;
                continue;
            }
            const uint64_t bits = precomputed ? g.accepted[p] : compute_window_mask(g, s, x, y);
            // A border pixel's window is moved inward (ts_discontinuity_lo_at): its positions
            // lie `shift` pixels from the centred window's.
            const size_t base = size_t(ptrdiff_t(p) + ts::ts_discontinuity_shift(x, y, w, h, n));
            ts::ts_discontinuity_mean(in, C, C, base, offset.data(), bits, out + p * C);
            if (accepted) accepted[p] = static_cast<uint8_t>(std::popcount(bits));
            ++x;
        }
    }
}

}  // namespace

void discontinuity_precompute(GeometryBuffer& g, const DiscontinuitySettings& s) {
    const int w = g.width, h = g.height;
    int lo, hi;
    discontinuity_window(s.tile, &lo, &hi);
    const int n = s.tile;  // bit i = row · n + col of the window's positions
    g.accepted.assign(size_t(w) * h, 0);
    const GeometryArrays arrays = geometry_arrays(g);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        std::vector<uint32_t> row_bits(w);
        for (int y = rows.begin(); y < rows.end(); ++y) {
            uint64_t* bits = &g.accepted[size_t(y) * w];
            // Windows moved in at the border (ts_discontinuity_lo_at): a whole row near the
            // top or bottom, else the columns near the sides, tested pixel by pixel.
            const bool row_moved = ts::ts_discontinuity_lo_at(y, h, n) != lo;
            for (int x = 0; x < w; ++x)
                if (row_moved || ts::ts_discontinuity_lo_at(x, w, n) != lo) bits[x] = compute_window_mask(g, s, x, y);
            if (row_moved) continue;
            for (int dy = lo; dy <= hi; ++dy) {
                if (y + dy < 0 || y + dy >= h) continue;
                std::fill(row_bits.begin(), row_bits.end(), 0u);
                for (int dx = lo; dx <= hi; ++dx) {
                    const int col = dx - lo;
                    if (dx == 0 && dy == 0) {  // p accepts itself
                        for (int x = 0; x < w; ++x) row_bits[x] |= 1u << col;
                        continue;
                    }
                    const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
                    if (g.position.empty())
                        window_bits_run<false>(arrays, s, w, y, x0, x1, dx, dy, col, row_bits.data());
                    else
                        window_bits_run<true>(arrays, s, w, y, x0, x1, dx, dy, col, row_bits.data());
                }
                const int shift = (dy - lo) * n;
                for (int x = 0; x < w; ++x)
                    if (ts::ts_discontinuity_lo_at(x, w, n) == lo) bits[x] |= uint64_t(row_bits[x]) << shift;
            }
        }
    });
    g.accepted_for = s;
}

uint64_t discontinuity_window_mask(const GeometryBuffer& g, const DiscontinuitySettings& s, int x, int y) {
    if (!g.accepted.empty() && same_settings(g.accepted_for, s)) return g.accepted[size_t(y) * g.width + x];
    return compute_window_mask(g, s, x, y);
}

void discontinuity_filter(const GeometryBuffer& g, const DiscontinuitySettings& s, int channels,
                          const std::vector<float>& in, std::vector<float>& out, std::vector<uint8_t>* accepted) {
    if (channels != 1 && channels != 3)
        throw std::invalid_argument("discontinuity_filter: 1 or 3 channels, not " + std::to_string(channels));
    const int w = g.width, h = g.height;
    out.resize(in.size());  // every pixel is written: no zero fill
    if (accepted) accepted->resize(size_t(w) * h);
    const bool precomputed = !g.accepted.empty() && same_settings(g.accepted_for, s);
    uint8_t* acc = accepted ? accepted->data() : nullptr;
    // Column sums from n = 4 on: at 3 they would take 2n = 6 additions a pixel against 9.
    PixelExponents exponents;
    const bool columns = s.tile >= 4;
    if (columns)
        exponents = channels == 1 ? pixel_exponents<1>(in.data(), size_t(w) * h)
                                  : pixel_exponents<3>(in.data(), size_t(w) * h);
    const PixelExponents* e = columns ? &exponents : nullptr;
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        if (channels == 1)
            filter_rows<1>(g, s, precomputed, in.data(), out.data(), acc, e, rows.begin(), rows.end());
        else
            filter_rows<3>(g, s, precomputed, in.data(), out.data(), acc, e, rows.begin(), rows.end());
    });
}

}  // namespace tessera
