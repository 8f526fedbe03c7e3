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

#endif
