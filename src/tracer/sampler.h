/*
 * Internal: materia's deterministic low-discrepancy sampler.
 *
 * Every value is a function of (seed, pixel, dimension, index) alone, so an
 * image does not depend on which thread renders which pixel. Each dimension
 * pair of a pixel is the 2D Sobol' sequence -- a (0,2)-sequence in base 2:
 * van der Corput and Sobol's second dimension -- with a hashed Owen
 * scrambling of each coordinate and a hashed nested-uniform shuffle of the
 * point index (Burley, "Practical Hash-based Owen Scrambling", JCGT 2020;
 * the Laine-Karras permutation). The shuffle maps every aligned block of 2^m
 * indices onto an aligned block, so the first 2^m samples of a pixel form a
 * (0,m,2)-net in every dimension pair, and different pairs (and pixels) are
 * decorrelated by their seeds. An array of n values per camera sample (a
 * light's nsamples) takes indices sample * n .. sample * n + n - 1 of one
 * pair: over the pixel they form a net of spp * n points, and each camera
 * sample's block is itself stratified when n is a power of two.
 */
#ifndef MT_TRACER_SAMPLER_H
#define MT_TRACER_SAMPLER_H

#include <stdint.h>
#include "materia/real.h"

/* The reversed Sobol' second-dimension matrix as byte tables (the matrix is
 * linear over GF(2): four lookups replace a 32-step loop). */
typedef struct mt__sobol_tables {
    uint32_t t[4][256];
} mt__sobol_tables;

void mt__sobol_tables_init(mt__sobol_tables *st);

/* The generator of one pixel: its seed mixes the global seed and (x, y). */
typedef struct mt__pixel_sampler {
    const mt__sobol_tables *tables;
    uint32_t seed;
} mt__pixel_sampler;

uint32_t mt__hash32(uint32_t x);
uint32_t mt__hash_combine(uint32_t a, uint32_t b);

void mt__pixel_sampler_init(mt__pixel_sampler *ps, const mt__sobol_tables *tables,
                            uint64_t seed, int x, int y);

/* The scrambling seeds of one dimension pair of one pixel: the index shuffle
 * and the two coordinates' Owen scrambles. A renderer may keep them for the
 * pixel's samples (they depend on the pixel and the pair only). */
typedef struct mt__dim_seeds {
    uint32_t shuffle, sx, sy;
} mt__dim_seeds;

void mt__dim_seeds_init(const mt__pixel_sampler *ps, uint32_t dim, mt__dim_seeds *ds);
/* v with its 32 bits in reverse order. */
static inline uint32_t mt__reverse_bits(uint32_t v)
{
#if defined(__GNUC__) || defined(__clang__)
    v = __builtin_bswap32(v);
#else
    v = (v << 24) | ((v & 0xff00u) << 8) | ((v >> 8) & 0xff00u) | (v >> 24);
#endif
    v = ((v & 0x0f0f0f0fu) << 4) | ((v >> 4) & 0x0f0f0f0fu);
    v = ((v & 0x33333333u) << 2) | ((v >> 2) & 0x33333333u);
    v = ((v & 0x55555555u) << 1) | ((v >> 1) & 0x55555555u);
    return v;
}

/* v with its 64 bits in reverse order: for (a << 32 | b), reversed b in the
 * high half and reversed a in the low half. */
static inline uint64_t mt__reverse_bits64(uint64_t v)
{
#if defined(__GNUC__) || defined(__clang__)
    v = __builtin_bswap64(v);
#else
    v = (v >> 32) | (v << 32);
    v = ((v & 0x0000ffff0000ffffull) << 16) | ((v >> 16) & 0x0000ffff0000ffffull);
    v = ((v & 0x00ff00ff00ff00ffull) << 8) | ((v >> 8) & 0x00ff00ff00ff00ffull);
#endif
    v = ((v & 0x0f0f0f0f0f0f0f0full) << 4) | ((v >> 4) & 0x0f0f0f0f0f0f0f0full);
    v = ((v & 0x3333333333333333ull) << 2) | ((v >> 2) & 0x3333333333333333ull);
    v = ((v & 0x5555555555555555ull) << 1) | ((v >> 1) & 0x5555555555555555ull);
    return v;
}

/* The Laine-Karras permutation with Burley's constants: each output bit
 * depends only on the input bits below it, so in bit-reversed order it is a
 * nested uniform (Owen) scramble. */
static inline uint32_t mt__lk_permute(uint32_t x, uint32_t seed)
{
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/* The point whose index, bits reversed, is rindex (a camera sample's pairs
 * share their index, so its reversal is done once): x in the low half, y in
 * the high half. */
static inline uint64_t mt__sample_bits(const mt__sobol_tables *t, const mt__dim_seeds *ds,
                                       uint32_t rindex)
{
    /* nested uniform shuffle of the index (Burley section 4) */
    uint32_t i = mt__reverse_bits(mt__lk_permute(rindex, ds->shuffle));
    /* the Sobol' coordinates in bit-reversed order: van der Corput reversed is
     * the index itself; the second dimension through the byte tables */
    uint32_t y = t->t[0][i & 0xff] ^ t->t[1][(i >> 8) & 0xff] ^ t->t[2][(i >> 16) & 0xff] ^
                 t->t[3][i >> 24];
    /* Owen scrambling of each coordinate, then both back to natural bit order */
    return mt__reverse_bits64(((uint64_t)mt__lk_permute(i, ds->sx) << 32) | mt__lk_permute(y, ds->sy));
}

/* A 32-bit integer to [0, 1): the top bits that mt_real represents exactly,
 * never 1. */
static inline mt_real mt__u32_to_unit(uint32_t v)
{
#if MT_USE_DOUBLE
    return (mt_real)v * (mt_real)0x1p-32;
#else
    return (mt_real)(v >> 8) * (mt_real)0x1p-24;
#endif
}

/* The point whose reversed index is rindex, in [0, 1). */
static inline void mt__sample_2d_rev(const mt__sobol_tables *t, const mt__dim_seeds *ds,
                                     uint32_t rindex, mt_real out[2])
{
    uint64_t both = mt__sample_bits(t, ds, rindex);
    out[0] = mt__u32_to_unit((uint32_t)both);
    out[1] = mt__u32_to_unit((uint32_t)(both >> 32));
}

/* Point `index` of the pair with seeds ds: 32-bit coordinates, and in [0, 1). */
void mt__sample_2d_seeded_bits(const mt__sobol_tables *t, const mt__dim_seeds *ds, uint32_t index,
                               uint32_t out[2]);
void mt__sample_2d_seeded(const mt__sobol_tables *t, const mt__dim_seeds *ds, uint32_t index,
                          mt_real out[2]);

/* Point `index` of dimension pair `dim`: two values in [0, 1). */
void mt__sample_2d(const mt__pixel_sampler *ps, uint32_t dim, uint32_t index, mt_real out[2]);

/* The raw 32-bit coordinates (tests check the net property on them). */
void mt__sample_2d_bits(const mt__pixel_sampler *ps, uint32_t dim, uint32_t index,
                        uint32_t out[2]);

#endif
