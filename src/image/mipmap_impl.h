/*
 * Internal: the MIP-map's representation, shared by mipmap.c (pyramid and
 * lookups), resample.c (pbrt-v2's Lanczos zoom to powers of two) and
 * cache.c (the process-wide texture cache).
 */
#ifndef MT_IMAGE_MIPMAP_IMPL_H
#define MT_IMAGE_MIPMAP_IMPL_H

#include "materia/mipmap.h"

/* pbrt-v2 mipmap.h: the EWA filter's Gaussian table. */
#define MT__WEIGHT_LUT_SIZE 128

/* Texel values are kept within +-MT__TEXEL_MAX (NaN reads 0): pbrt-v2 would
 * carry a NaN or Inf texel into every lookup that touches it (0 * Inf in the
 * bilinear weights), and sums of up to 2^24 weighted texels stay finite. */
#define MT__TEXEL_MAX ((mt_real)1e30)

typedef struct mt__level {
    int w, h;
    mt_real *texels; /* w * h * nc values, row by row */
} mt__level;

/* The mode bits a cached pyramid depends on: its lookups' (the trilinear
 * width) and those of the reading of its file. The image-map cache keys on
 * these only, so that modes differing elsewhere share a pyramid. */
#define MT__MIPMAP_MODE_BITS (MT_FIX_TRILINEAR_WIDTH | MT_IMAGE_MODE_BITS)

struct mt_mipmap {
    int nc;          /* 1 (float) or 3 (RGB) values per texel */
    int levels;
    int trilinear;
    mt_real maxaniso;
    mt_wrap wrap;
    mt_mode mode;
    mt_real weight_lut[MT__WEIGHT_LUT_SIZE];
    mt__level level[]; /* levels entries, level 0 the finest */
};

/* The pyramid over w x h texels of nc (1 or 3) values each (copied, and
 * sanitized as MT__TEXEL_MAX says). */
mt_mipmap *mt__mipmap_create_raw(int w, int h, int nc, const mt_real *texels, int trilinear,
                                 mt_real maxaniso, mt_wrap wrap, mt_mode mode, mt_error *err);

/* pbrt-v2 MIPMap constructor, first step: the w x h image zoomed to
 * *pw x *ph (the next powers of two) with resampleWeights' Lanczos taps,
 * negative results clamped to 0. Returns a new array (mt__malloc), or NULL
 * when out of memory. */
mt_real *mt__resample_pow2(int w, int h, int nc, const mt_real *texels, mt_wrap wrap, int *pw,
                           int *ph);

/* pbrt-v2's integer helpers (pbrt.h). */
int mt__is_pow2(int v);
int mt__round_up_pow2(int v);
int mt__mod(int a, int b);

#endif
