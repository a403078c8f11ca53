/* Random numbers for the shared shading code. Counter-based: the stream for a pixel
 * and pass is seeded by hashing (seed, pixel, pass), so every backend and every
 * dispatch order draws the same numbers for the same sample, bit for bit.
 * Generator: PCG-RXS-M-XS-32 as a hash and PCG32 (LCG step + output permutation) as the
 * stream (O'Neill 2014; Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020).
 */
#ifndef TS_RNG_H
#define TS_RNG_H
#include "shared/compat.h"

TS_NAMESPACE_BEGIN

TS_INLINE uint ts_pcg_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/* The state of one sample's stream. */
typedef struct TsRng {
    uint state;
} TsRng;

TS_INLINE TsRng ts_rng_seed(uint seed, uint pixel, uint pass) {
    TsRng r;
    r.state = ts_pcg_hash(seed ^ ts_pcg_hash(pixel ^ ts_pcg_hash(pass + 0x9e3779b9u)));
    return r;
}

TS_INLINE uint ts_rng_next_uint(TsRng* r) {
    r->state = r->state * 747796405u + 2891336453u;
    uint s = r->state;
    uint word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (word >> 22u) ^ word;
}

/* Uniform in [0, 1): the top 24 bits, exactly representable, never 1. */
TS_INLINE float ts_rng_next(TsRng* r) {
    return (float)(ts_rng_next_uint(r) >> 8) * 5.9604644775390625e-8f; /* 2^-24 */
}

/* Van der Corput radical inverse in base 2 (bit reversal), in [0, 1). */
TS_INLINE float ts_radical_inverse2(uint i) {
    i = (i << 16u) | (i >> 16u);
    i = ((i & 0x00ff00ffu) << 8u) | ((i & 0xff00ff00u) >> 8u);
    i = ((i & 0x0f0f0f0fu) << 4u) | ((i & 0xf0f0f0f0u) >> 4u);
    i = ((i & 0x33333333u) << 2u) | ((i & 0xccccccccu) >> 2u);
    i = ((i & 0x55555555u) << 1u) | ((i & 0xaaaaaaaau) >> 1u);
    return (float)(i >> 8) * 5.9604644775390625e-8f;
}

/* Radical inverse in base 3, in [0, 1). */
TS_INLINE float ts_radical_inverse3(uint i) {
    float inv = 1.0f / 3.0f, f = inv, r = 0.0f;
    while (i > 0u) {
        r += f * (float)(i % 3u);
        i /= 3u;
        f *= inv;
    }
    return fmin(r, 0.99999994f);
}

/* Adds a Cranley–Patterson rotation and wraps into [0, 1). */
TS_INLINE float ts_rotate01(float x, float offset) {
    float y = x + offset;
    return y >= 1.0f ? y - 1.0f : y;
}

TS_NAMESPACE_END
#endif /* TS_RNG_H */
