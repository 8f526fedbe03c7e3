/*
 * materia/rng.h -- PCG32 (O'Neill, "PCG: A Family of Simple Fast
 * Space-Efficient Statistically Good Algorithms for Random Number Generation",
 * 2014; the pcg32 XSH-RR variant), for tests, tools and the renderer.
 *
 * Nothing in materia's BSDF code draws random numbers itself: every sampling
 * routine takes its uniform numbers as arguments.
 *
 * Thread safety: a generator belongs to one thread at a time (give each
 * thread its own stream); the functions touch only the generator they are
 * given.
 */
#ifndef MATERIA_RNG_H
#define MATERIA_RNG_H

#include <stdint.h>
#include "materia/real.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_rng {
    uint64_t state, inc;
} mt_rng;

/* Seeds the generator: seed picks the starting point, stream one of 2^63
 * independent sequences. */
MT_API void mt_rng_seed(mt_rng *r, uint64_t seed, uint64_t stream);
/* The next 32 random bits. */
MT_API uint32_t mt_rng_u32(mt_rng *r);
/* Uniform in [0, 1), never 1 (at most MT_ONE_MINUS_EPSILON). */
MT_API mt_real mt_rng_uniform(mt_rng *r);
/* Uniform double in [0, 1) with 53 random bits, whatever mt_real is. */
MT_API double mt_rng_uniform_d(mt_rng *r);
/* Uniform integer in [0, bound), without modulo bias. */
MT_API uint32_t mt_rng_bounded(mt_rng *r, uint32_t bound);

#ifdef __cplusplus
}
#endif

#endif
