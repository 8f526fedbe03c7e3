/* PCG32 (XSH-RR 64/32), after O'Neill's reference description. */
#include "materia/rng.h"

#define PCG_MULT 6364136223846793005ULL

void mt_rng_seed(mt_rng *r, uint64_t seed, uint64_t stream)
{
    r->state = 0;
    r->inc = (stream << 1) | 1u;
    (void)mt_rng_u32(r);
    r->state += seed;
    (void)mt_rng_u32(r);
}

uint32_t mt_rng_u32(mt_rng *r)
{
    uint64_t old = r->state;
    uint32_t xorshifted, rot;
    r->state = old * PCG_MULT + r->inc;
    xorshifted = (uint32_t)(((old >> 18) ^ old) >> 27);
    rot = (uint32_t)(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
}

mt_real mt_rng_uniform(mt_rng *r)
{
#if MT_USE_DOUBLE
    return (mt_real)mt_rng_uniform_d(r);
#else
    /* 24 random bits: every value is exact and below one. */
    return (mt_real)(mt_rng_u32(r) >> 8) * 0x1p-24f;
#endif
}

double mt_rng_uniform_d(mt_rng *r)
{
    uint64_t hi = mt_rng_u32(r) >> 5, lo = mt_rng_u32(r) >> 6; /* 27 + 26 bits */
    return (double)(hi * 67108864.0 + lo) * 0x1p-53;
}

uint32_t mt_rng_bounded(mt_rng *r, uint32_t bound)
{
    /* Rejection of the low remainder (PCG's pcg32_boundedrand_r). */
    uint32_t threshold = (uint32_t)(-bound) % bound;
    for (;;) {
        uint32_t v = mt_rng_u32(r);
        if (v >= threshold) return v % bound;
    }
}
