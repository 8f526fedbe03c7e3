/*
 * materia/mipmap.h -- pbrt-v2's MIPMap (mipmap.h): an image pyramid with
 * trilinear and EWA filtering.
 *
 * Images whose sides are not powers of two are first resampled up to powers
 * of two with pbrt-v2's Lanczos weights (resampleWeights, 4 taps, tau 2);
 * each level is the box-filtered half of the one below it. Texel lookups
 * honour the wrap mode. Lookups follow pbrt-v2 exactly, including its
 * Gaussian weight table for EWA and its maxanisotropy clamp; the trilinear
 * filter's doubled width is pbrt-v2 mode's (erratum trilinear-width).
 */
#ifndef MATERIA_MIPMAP_H
#define MATERIA_MIPMAP_H

#include "materia/image.h"
#include "materia/mode.h"
#include "materia/rgb.h"

typedef enum mt_wrap { MT_WRAP_REPEAT, MT_WRAP_BLACK, MT_WRAP_CLAMP } mt_wrap;

typedef struct mt_mipmap mt_mipmap;

/* A pyramid over img's RGB (channels >= 3) or its single channel. */
MT_API mt_mipmap *mt_mipmap_create(const mt_image *img, int trilinear, mt_real maxaniso,
                                   mt_wrap wrap, mt_mode mode, mt_error *err);
MT_API void mt_mipmap_destroy(mt_mipmap *m);

MT_API int mt_mipmap_levels(const mt_mipmap *m);
MT_API int mt_mipmap_width(const mt_mipmap *m, int level);
MT_API int mt_mipmap_height(const mt_mipmap *m, int level);
MT_API int mt_mipmap_channels(const mt_mipmap *m);

/* The texel at integer (s, t) of a level, with the wrap mode applied. */
MT_API mt_rgb mt_mipmap_texel(const mt_mipmap *m, int level, int s, int t);
/* pbrt-v2 MIPMap::Lookup(st, width): the isotropic (trilinear) filter. */
MT_API mt_rgb mt_mipmap_lookup_width(const mt_mipmap *m, mt_real s, mt_real t, mt_real width);
/* pbrt-v2 MIPMap::Lookup(st, dst0, dst1): trilinear or EWA, as created. */
MT_API mt_rgb mt_mipmap_lookup(const mt_mipmap *m, mt_real s, mt_real t, mt_real ds0,
                               mt_real dt0, mt_real ds1, mt_real dt1);

/* Float and single-channel lookups return the value in all three components. */

#endif
