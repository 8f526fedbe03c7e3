/*
 * materia/mipmap.h -- pbrt-v2's MIPMap (mipmap.h): an image pyramid with
 * trilinear and EWA filtering, and the process-wide cache of image maps.
 *
 * Images whose sides are not powers of two are first resampled up to powers
 * of two with pbrt-v2's Lanczos weights (resampleWeights, 4 taps, tau 2,
 * negative results clamped to 0); each level is the box-filtered half of the
 * one below it. Texel lookups honour the wrap mode. Lookups follow pbrt-v2
 * exactly, in its float order of operations, including its Gaussian weight
 * table for EWA and its maxanisotropy clamp; the trilinear filter's doubled
 * width is pbrt-v2 mode's (erratum trilinear-width, MT_FIX_TRILINEAR_WIDTH).
 * Texture coordinates are pbrt-v2's: (s, t) = (0, 0) is the first texel of
 * the first row (the image's top-left corner), one unit spans the image.
 *
 * Defined values where pbrt-v2 has none: a NaN texel reads 0 and texels are
 * clamped to +-1e30 (pbrt-v2 carries NaN/Inf into every lookup touching
 * them); a NaN or infinite s or t gives black; a NaN or infinite
 * differential or width gives the whole image's average (the top level,
 * the limit of an infinite footprint); an EWA box of more than 2^24 texels
 * (only reachable with a huge maxanisotropy) falls back to the isotropic
 * filter over the ellipse's bounding square.
 *
 * A pyramid is read-only once created: any number of threads may look it up.
 */
#ifndef MATERIA_MIPMAP_H
#define MATERIA_MIPMAP_H

#include "materia/image.h"
#include "materia/mode.h"
#include "materia/rgb.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mt_wrap { MT_WRAP_REPEAT, MT_WRAP_BLACK, MT_WRAP_CLAMP } mt_wrap;

typedef struct mt_mipmap mt_mipmap;

/* A pyramid over img's RGB (channels >= 3; alpha is ignored) or its single
 * channel. maxaniso must be positive when trilinear is 0 (EWA). */
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

/* The process-wide cache of image maps (pbrt-v2 imagemap.cpp GetTexture):
 * the pyramid for an image file read and converted as pbrt-v2's
 * ImageTexture does, made once per process for each key (path as given,
 * trilinear, maxaniso, wrap, scale, gamma, float_texture, and the bits of
 * mode that change the pyramid: MT_FIX_TRILINEAR_WIDTH and
 * MT_IMAGE_MODE_BITS) and shared. Texels are pow(scale * rgb, gamma) per
 * component for an RGB texture and pow(scale * y(rgb), gamma) for a float
 * texture (float_texture != 0; y() is mt_rgb_y); a one-channel file is gray
 * RGB first. The image is read with mt_image_read_mode(path, mode) (.exr,
 * .png, .pfm): in pbrt-v2 mode as pbrt-v2's ReadImage reads it (EXR colour
 * through half, Y before R, G, B, PFM upside down). Concurrent requests for
 * one key read the file once; different keys are read at the same time.
 * The pyramid belongs to the cache: never
 * destroy it; it stays valid until mt_mipmap_cache_clear. Thread-safe.
 * Returns NULL with err filled when the file cannot be read (pbrt-v2 prints
 * an error and uses a 1x1 texture of value pow(scale, gamma) instead: a
 * caller that wants that behaviour builds it with mt_mipmap_create).
 * Parameters as pbrt-v2's imagemap reads them: "filename", "trilinear"
 * (default false), "maxanisotropy" (8), "wrap" ("repeat"), "scale" (1),
 * "gamma" (1). */
MT_API mt_mipmap *mt_mipmap_cache_get(const char *path, int trilinear, mt_real maxaniso,
                                      mt_wrap wrap, mt_real scale, mt_real gamma,
                                      int float_texture, mt_mode mode, mt_error *err);
/* The number of pyramids in the cache. */
MT_API int mt_mipmap_cache_size(void);
/* Destroys every cached pyramid (teardown, tests): no texture may use one
 * afterwards. */
MT_API void mt_mipmap_cache_clear(void);

#ifdef __cplusplus
}
#endif

#endif
