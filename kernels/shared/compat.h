/* Portability layer: lets the shading and sampling sources in kernels/shared compile
 * both as OpenCL C 1.2 (device kernels) and as C++20 (the Embree CPU backend), so the
 * light transport is written once (the approach Cycles takes for its devices).
 *
 * Rules for shared code:
 *   - vectors are `float3`, built with make_float3(); use dot/cross/normalize/length,
 *     fmin/fmax/fabs/sqrt and the helpers below;
 *   - buffers are `TS_GLOBAL const float*` / `TS_GLOBAL const uint*`; never float3 in a
 *     buffer (OpenCL pads float3 to 16 bytes, C++ does not);
 *   - functions are `TS_INLINE` (`TS_COLD` for a rare path the C++ build keeps out of
 *     line); no recursion, no dynamic allocation;
 *   - bit casts use as_uint()/as_float()/as_int().
 */
#ifndef TS_COMPAT_H
#define TS_COMPAT_H

#ifdef __OPENCL_VERSION__
/* ---------------------------------------------------------------- OpenCL C */
/* No contraction into FMA, so device and C++ (-ffp-contract=off) round alike. */
#pragma OPENCL FP_CONTRACT OFF
#define TS_GLOBAL __global
/* 64-byte alignment of a struct (rtcOccluded16's valid mask wants it on Embree; one
 * cache line per 16-lane row), a restrict-qualified pointer, and a branch the caller
 * guarantees is never taken (a hint: OpenCL C has no portable form, so none). */
#define TS_ALIGN64 __attribute__((aligned(64)))
#define TS_RESTRICT restrict
#define TS_UNREACHABLE() ((void)0)
/* A read-only table at program scope (OpenCL 1.2 allows only __constant there). */
#define TS_CONSTANT_TABLE __constant
/* static: C99 gives a plain `inline` function no external definition, so a driver that
 * does not inline it (clang-based ones at -cl-opt-disable) fails to link. */
#define TS_INLINE static inline
#define TS_COLD static inline
#define make_float3(x, y, z) ((float3)((x), (y), (z)))
#define make_float2(x, y) ((float2)((x), (y)))
#define TS_INF INFINITY
#define TS_NAN NAN
#define TS_NAMESPACE_BEGIN
#define TS_NAMESPACE_END
static inline float3 ts_f3_load(TS_GLOBAL const float* p) { return vload3(0, p); }
/* Writes v to p[0..2] of a work-item's own (private) output record. */
static inline void ts_f3_store(float* p, float3 v) { p[0] = v.x; p[1] = v.y; p[2] = v.z; }
/* Trailing zero bits of x != 0 (OpenCL 1.2 has clz but not ctz) and set bits of x. */
static inline int ts_ctz64(ulong x) { return (int)(63ul - clz(x & (0ul - x))); }
static inline int ts_popcount64(ulong x) { return (int)popcount(x); }
/* min(a, b) for a bound b that is never NaN (a clamp): fmin's value whenever b is not NaN. */
static inline float ts_min_bound(float a, float b) { return fmin(a, b); }
/* TS_HAS_DOUBLE: `double` may be used (always in C++; in OpenCL 1.2 only where the device
 * has cl_khr_fp64). Code using it keeps a float form for the other devices, which
 * -DTS_NO_DOUBLE selects on any device (tests run the float forms on PoCL that way). */
#if defined(cl_khr_fp64) && !defined(TS_NO_DOUBLE)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define TS_HAS_DOUBLE 1
#endif
#ifdef TS_HAS_DOUBLE
/* A double's low and high 32 bits (for a kernel output of floats that carries a double). */
static inline void ts_double_words(double d, uint* lo, uint* hi) {
    const uint2 b = as_uint2(d);
    *lo = b.x;
    *hi = b.y;
}
/* The double of those words. */
static inline double ts_double_of_words(uint lo, uint hi) { return as_double((uint2)(lo, hi)); }
#endif

#else
/* ---------------------------------------------------------------- C++ */
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#define TS_GLOBAL
#define TS_ALIGN64 alignas(64)
#define TS_RESTRICT __restrict
#define TS_UNREACHABLE() __builtin_unreachable()
#define TS_CONSTANT_TABLE inline constexpr
#define TS_INLINE inline
/* A rarely taken path kept out of its caller's body, so that it leaves the caller's
 * inlining and register choices as they were (OpenCL C inlines it like any other). */
#define TS_COLD [[gnu::noinline, gnu::cold]] inline
#define TS_HAS_DOUBLE 1
#define TS_NAMESPACE_BEGIN namespace tessera::ts {
#define TS_NAMESPACE_END }

namespace tessera::ts {

typedef uint32_t uint;
typedef uint64_t ulong;

struct float2 {
    float x, y;
};
struct float3 {
    float x, y, z;
};

inline float2 make_float2(float x, float y) { return float2{x, y}; }
inline float3 make_float3(float x, float y, float z) { return float3{x, y, z}; }

inline float3 operator+(float3 a, float3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline float3 operator-(float3 a, float3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline float3 operator-(float3 a) { return {-a.x, -a.y, -a.z}; }
inline float3 operator*(float3 a, float3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline float3 operator*(float3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline float3 operator*(float s, float3 a) { return {a.x * s, a.y * s, a.z * s}; }
inline float3 operator/(float3 a, float s) { return {a.x / s, a.y / s, a.z / s}; }
inline float3 operator/(float3 a, float3 b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }
inline float3& operator+=(float3& a, float3 b) { return a = a + b; }
inline float3& operator*=(float3& a, float3 b) { return a = a * b; }
inline float3& operator*=(float3& a, float s) { return a = a * s; }

inline float dot(float3 a, float3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float3 cross(float3 a, float3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(float3 a) { return std::sqrt(dot(a, a)); }
inline float3 normalize(float3 a) { return a * (1.0f / length(a)); }
inline float3 fabs(float3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
/* fmin/fmax inline, with the results of glibc's x86-64 fminf/fmaxf (minss/maxss: of equal
 * operands, ±0 included, the second; a NaN operand yields the other): the library calls
 * cost about 3% of an Embree igi frame (bench/results/host_filter_masks.md), and GCC
 * inlines them only under finite-math flags, which we do not use. */
inline float fmin(float x, float y) { return (x < y || y != y) ? x : y; }
inline float fmax(float x, float y) { return (x > y || y != y) ? x : y; }
inline float3 fmin(float3 a, float3 b) {
    return {fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z)};
}
inline float3 exp(float3 a) { return {std::exp(a.x), std::exp(a.y), std::exp(a.z)}; }
inline float3 fmax(float3 a, float3 b) {
    return {fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z)};
}
using std::cos;
using std::exp;
using std::log;
using std::fabs;
using std::floor;
using std::ceil;
using std::sin;
using std::sqrt;
using std::tan;
using std::atan2;
using std::asinh;
using std::sinh;
using std::pow;
using std::isfinite;
inline float clamp(float x, float lo, float hi) { return fmin(fmax(x, lo), hi); }
inline float3 clamp(float3 x, float3 lo, float3 hi) { return fmin(fmax(x, lo), hi); }
inline float mix(float a, float b, float t) { return a + (b - a) * t; }

/* Trailing zero bits of x != 0 and set bits of x, as the OpenCL side's. */
inline int ts_ctz64(ulong x) { return std::countr_zero(x); }
inline int ts_popcount64(ulong x) { return std::popcount(x); }
/* min(a, b) for a bound b that is never NaN (a clamp): fmin's value whenever b is not NaN
 * (a NaN a gives b, as fmin does), written as a select, which GCC vectorises where it
 * cannot vectorise fmin (host/gi/vpl_importance.cpp). */
inline float ts_min_bound(float a, float b) { return a < b ? a : b; }
inline uint as_uint(float f) { return std::bit_cast<uint>(f); }
inline int as_int(float f) { return std::bit_cast<int>(f); }
inline float as_float(uint u) { return std::bit_cast<float>(u); }
inline float as_float(int i) { return std::bit_cast<float>(i); }
inline void ts_double_words(double d, uint* lo, uint* hi) {
    const uint64_t b = std::bit_cast<uint64_t>(d);
    *lo = static_cast<uint>(b);
    *hi = static_cast<uint>(b >> 32);
}
inline double ts_double_of_words(uint lo, uint hi) { return std::bit_cast<double>((uint64_t(hi) << 32) | lo); }
inline float3 ts_f3_load(const float* p) { return {p[0], p[1], p[2]}; }
inline void ts_f3_store(float* p, float3 v) { p[0] = v.x, p[1] = v.y, p[2] = v.z; }

constexpr float TS_INF = std::numeric_limits<float>::infinity();
constexpr float TS_NAN = std::numeric_limits<float>::quiet_NaN();

}  // namespace tessera::ts
#endif

TS_NAMESPACE_BEGIN
/* Neumaier's compensated sum (for long float sums where double is missing): *s the
 * running sum, *c the rounding error it lost; the result is *s + *c. */
TS_INLINE void ts_sum_compensated_add(float* s, float* c, float x) {
    float t = *s + x;
    *c += fabs(*s) >= fabs(x) ? (*s - t) + x : (x - t) + *s;
    *s = t;
}
TS_NAMESPACE_END

#endif /* TS_COMPAT_H */
