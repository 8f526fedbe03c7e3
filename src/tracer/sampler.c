/*
 * materia's low-discrepancy sampler: Owen-scrambled, index-shuffled 2D
 * Sobol' points (see sampler.h for the construction and its properties).
 */
#include "tracer/sampler.h"

/* A 32-bit integer hash with good avalanche (Wellons' "lowbias32"). */
uint32_t mt__hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

uint32_t mt__hash_combine(uint32_t a, uint32_t b)
{
    return mt__hash32(a ^ (b + 0x9e3779b9u + (a << 6) + (a >> 2)));
}

void mt__sobol_tables_init(mt__sobol_tables *st)
{
    /* column j of the reversed matrix: bit j of the index contributes v_j,
     * v_0 = 1, v_{j+1} = v_j ^ (v_j << 1) (Sobol's second dimension, whose
     * direction numbers are v_j = v_{j-1} ^ (v_{j-1} >> 1) from the top bit) */
    uint32_t col[32], v = 1;
    int j, b, k;
    for (j = 0; j < 32; ++j) {
        col[j] = v;
        v ^= v << 1;
    }
    for (b = 0; b < 4; ++b)
        for (k = 0; k < 256; ++k) {
            uint32_t r = 0;
            for (j = 0; j < 8; ++j)
                if (k & (1 << j)) r ^= col[8 * b + j];
            st->t[b][k] = r;
        }
}

void mt__pixel_sampler_init(mt__pixel_sampler *ps, const mt__sobol_tables *tables,
                            uint64_t seed, int x, int y)
{
    uint32_t h = mt__hash32((uint32_t)seed ^ 0x5bd1e995u);
    h = mt__hash_combine(h, (uint32_t)(seed >> 32));
    h = mt__hash_combine(h, (uint32_t)x);
    h = mt__hash_combine(h, (uint32_t)y);
    ps->tables = tables;
    ps->seed = h;
}

void mt__dim_seeds_init(const mt__pixel_sampler *ps, uint32_t dim, mt__dim_seeds *ds)
{
    uint32_t s = mt__hash_combine(ps->seed, dim);
    ds->shuffle = s;
    ds->sx = mt__hash32(s ^ 0x68e31da4u);
    ds->sy = mt__hash32(s ^ 0xb5297a4du);
}

void mt__sample_2d_seeded_bits(const mt__sobol_tables *t, const mt__dim_seeds *ds, uint32_t index,
                               uint32_t out[2])
{
    uint64_t both = mt__sample_bits(t, ds, mt__reverse_bits(index));
    out[0] = (uint32_t)both;
    out[1] = (uint32_t)(both >> 32);
}

void mt__sample_2d_seeded(const mt__sobol_tables *t, const mt__dim_seeds *ds, uint32_t index,
                          mt_real out[2])
{
    mt__sample_2d_rev(t, ds, mt__reverse_bits(index), out);
}

void mt__sample_2d_bits(const mt__pixel_sampler *ps, uint32_t dim, uint32_t index,
                        uint32_t out[2])
{
    mt__dim_seeds ds;
    mt__dim_seeds_init(ps, dim, &ds);
    mt__sample_2d_seeded_bits(ps->tables, &ds, index, out);
}

void mt__sample_2d(const mt__pixel_sampler *ps, uint32_t dim, uint32_t index, mt_real out[2])
{
    mt__dim_seeds ds;
    mt__dim_seeds_init(ps, dim, &ds);
    mt__sample_2d_seeded(ps->tables, &ds, index, out);
}
