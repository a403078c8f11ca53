/* Arctangent, tangent and exponential in float without branches, for loops over 16 lanes
 * that GCC vectorises (the ray lights' links of the media march, shared/igi_march16.h;
 * every link's transmittance, ts_medium_exp_lanes in shared/medium.h), and for the
 * one-lane code that must give those lanes' numbers bit for bit (both call
 * ts_igi_march_vrl_weight, shared/igi_ray_lights.h; ts_exp3 is this exponential). The
 * equiangular sampler (shared/medium.h) takes its arctangent and tangent from here, for
 * every caller. libm's forms are calls GCC cannot vectorise, and
 * glibc's vector forms (libmvec) are reached only with finite-math flags, which must stay
 * off here (NaN and Inf are caught). The methods and coefficients are Cephes' single
 * precision atanf, tanf and expf (S. L. Moshier, "Methods and Programs for Mathematical
 * Functions", 1989; the Cephes library, cephes/single), with the range reductions' tests
 * written as selects. Accuracy against double (tests/kernels/math_lanes_test.cpp, with
 * correctly rounded division and square root): the arctangent within 2.1e-7 relative
 * (2.8 ulp, near x = 0.428), the tangent 1.7e-7 on |x| <= π/2 (its only use), the
 * exponential 8.2e-8. Special values: NaN gives NaN; atan(±Inf) = ±π/2; exp(-Inf) = 0,
 * exp(+Inf) = Inf. The exponential flushes results below 2^-126 (x < -87.3365) to 0 where
 * libm returns subnormals (at most 1.2e-38 apart). Every C++ file that includes this is
 * built with -ffp-contract=off (CMakeLists.txt), so the lanes' and one lane's numbers
 * agree. */
#ifndef TS_MATH_LANES_H
#define TS_MATH_LANES_H
#include "shared/compat.h"

TS_NAMESPACE_BEGIN

/* x with the sign bit of s added (r >= +0 or NaN). */
TS_INLINE float ts_lanes_with_sign(float r, float s) { return as_float(as_uint(r) | (as_uint(s) & 0x80000000u)); }

/* arctan(x), radians in [-π/2, π/2]. Reduction to |z| <= tan(π/8): above tan(3π/8),
 * π/2 + atan(-1/|x|); above tan(π/8), π/4 + atan((|x| - 1)/(|x| + 1)). */
TS_INLINE float ts_lanes_atan(float x) {
    float ax = fabs(x);
    float inv = -1.0f / ax, mob = (ax - 1.0f) / (ax + 1.0f);
    int big = ax > 2.414213562373095f, mid = ax > 0.4142135623730950f;
    float y0 = big ? 1.5707963267948966f : (mid ? 0.7853981633974483f : 0.0f);
    float z = big ? inv : (mid ? mob : ax);
    float z2 = z * z;
    float p = ((8.05374449538e-2f * z2 - 1.38776856032e-1f) * z2 + 1.99777106478e-1f) * z2 - 3.33329491539e-1f;
    return ts_lanes_with_sign(y0 + (p * z2 * z + z), x);
}

/* tan(x), radians: reduction to |z| <= π/4 by j·π/4, j the even integer nearest
 * |x|·4/π (π/4 in three parts, the first two of whose products with j are exact below
 * 8192), then -1/tan(z) where j is 2 modulo 4. Accurate to 1.7e-7 relative for
 * |x| <= π/2, the only use here; beyond, valid below 8192 with a relative error that grows
 * near the multiples of π/2. */
TS_INLINE float ts_lanes_tan(float x) {
    float ax = fabs(x);
    float j = floor(ax * 1.27323954473516f);
    j = j + (j - 2.0f * floor(j * 0.5f)); /* an odd j to the next even one */
    float z = ((ax - j * 0.78515625f) - j * 2.4187564849853515625e-4f) - j * 3.77489497744594108e-8f;
    float zz = z * z;
    float p = (((((9.38540185543e-3f * zz + 3.11992232697e-3f) * zz + 2.44301354525e-2f) * zz +
                 5.34112807005e-2f) * zz + 1.33387994085e-1f) * zz + 3.33331568548e-1f);
    float t = p * zz * z + z;
    float cot = -1.0f / t;
    int second = j - 4.0f * floor(j * 0.25f) == 2.0f;
    float r = second ? cot : t;
    return as_float(as_uint(r) ^ (as_uint(x) & 0x80000000u));
}

/* e^x. x = n ln 2 + r with |r| <= ln 2 / 2 (ln 2 in two parts), e^r by a degree-7
 * polynomial, 2^n as two powers of two built from exponent bits (n reaches 128). */
TS_INLINE float ts_lanes_exp(float x) {
    float xc = x > 88.72283f ? 88.72283f : (x < -87.33654f ? -87.33654f : x);
    float n = floor(xc * 1.44269504088896341f + 0.5f);
    n = xc == xc ? n : 0.0f; /* a NaN x: any n, kept finite for the conversion below */
    float r = (xc - n * 0.693359375f) - n * -2.12194440e-4f;
    float p = ((((1.9875691500e-4f * r + 1.3981999507e-3f) * r + 8.3334519073e-3f) * r + 4.1665795894e-2f) * r +
               1.6666665459e-1f) * r + 5.0000001201e-1f;
    float e = p * (r * r) + r + 1.0f;
    int n1 = (int)n / 2, n2 = (int)n - n1;
    e = e * as_float((uint)(n1 + 127) << 23) * as_float((uint)(n2 + 127) << 23);
    e = x < -87.33654f ? 0.0f : e;
    return x > 88.72283f ? TS_INF : e;
}

/* x[i] = e^x[i] (ts_lanes_exp) for i < n, in one loop: GCC vectorises it where n is known
 * once inlined (a row of the gathers' 16 links' transmittances). */
TS_INLINE void ts_lanes_exp_n(float* x, int n) {
    for (int i = 0; i < n; ++i) x[i] = ts_lanes_exp(x[i]);
}

TS_NAMESPACE_END
#endif /* TS_MATH_LANES_H */
