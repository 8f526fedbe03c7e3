/*
 * materia's low-discrepancy sampler: Owen-scrambled, index-shuffled 2D
 * Sobol' points (see sampler.h for the construction and its properties).
 */
#include "tracer/sampler.h"

static uint32_t reverse_bits(uint32_t v)
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

/* Both halves of v bit-reversed in place (two 32-bit reversals at once). */
static uint64_t reverse_bits_pairs(uint64_t v)
{
    v = ((v & 0x0000ffff0000ffffull) << 16) | ((v >> 16) & 0x0000ffff0000ffffull);
    v = ((v & 0x00ff00ff00ff00ffull) << 8) | ((v >> 8) & 0x00ff00ff00ff00ffull);
    v = ((v & 0x0f0f0f0f0f0f0f0full) << 4) | ((v >> 4) & 0x0f0f0f0f0f0f0f0full);
    v = ((v & 0x3333333333333333ull) << 2) | ((v >> 2) & 0x3333333333333333ull);
    v = ((v & 0x5555555555555555ull) << 1) | ((v >> 1) & 0x5555555555555555ull);
    return v;
}

/* The Laine-Karras permutation with Burley's constants: each output bit
 * depends only on the input bits below it, so in bit-reversed order it is a
 * nested uniform (Owen) scramble. */
static uint32_t lk_permute(uint32_t x, uint32_t seed)
{
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

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

/* Point `index` of a pair: x in the high half, y in the low half. */
static uint64_t sample_bits(const mt__sobol_tables *t, const mt__dim_seeds *ds, uint32_t index)
{
    /* nested uniform shuffle of the index (Burley section 4) */
    uint32_t i = reverse_bits(lk_permute(reverse_bits(index), ds->shuffle));
    /* the Sobol' coordinates in bit-reversed order: van der Corput reversed is
     * the index itself; the second dimension through the byte tables */
    uint32_t y = t->t[0][i & 0xff] ^ t->t[1][(i >> 8) & 0xff] ^ t->t[2][(i >> 16) & 0xff] ^
                 t->t[3][i >> 24];
    /* Owen scrambling of each coordinate, then back to natural bit order */
    return reverse_bits_pairs(((uint64_t)lk_permute(i, ds->sx) << 32) | lk_permute(y, ds->sy));
}

void mt__sample_2d_seeded_bits(const mt__sobol_tables *t, const mt__dim_seeds *ds, uint32_t index,
                               uint32_t out[2])
{
    uint64_t both = sample_bits(t, ds, index);
    out[0] = (uint32_t)(both >> 32);
    out[1] = (uint32_t)both;
}

void mt__sample_2d_seeded(const mt__sobol_tables *t, const mt__dim_seeds *ds, uint32_t index,
                          mt_real out[2])
{
    uint64_t both = sample_bits(t, ds, index);
    out[0] = mt__u32_to_unit((uint32_t)(both >> 32));
    out[1] = mt__u32_to_unit((uint32_t)both);
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
