/*
 * materia/rgb.h -- the RGB spectrum with pbrt-v2's RGBSpectrum semantics.
 *
 * pbrt-v2's default build represents every spectrum as linear RGB; y() uses
 * its luminance weights (spectrum.h YWeight), Clamp defaults to [0, inf),
 * IsBlack means every component is exactly zero.
 *
 * Thread safety: inline functions of their arguments alone.
 */
#ifndef MATERIA_RGB_H
#define MATERIA_RGB_H

#include "materia/real.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_rgb {
    mt_real c[3];
} mt_rgb;

static inline mt_rgb mt_rgb_make(mt_real r, mt_real g, mt_real b)
{
    mt_rgb s;
    s.c[0] = r;
    s.c[1] = g;
    s.c[2] = b;
    return s;
}
static inline mt_rgb mt_rgb_gray(mt_real v) { return mt_rgb_make(v, v, v); }
static inline mt_rgb mt_rgb_black(void) { return mt_rgb_make(0, 0, 0); }
static inline mt_rgb mt_rgb_add(mt_rgb a, mt_rgb b)
{
    return mt_rgb_make(a.c[0] + b.c[0], a.c[1] + b.c[1], a.c[2] + b.c[2]);
}
static inline mt_rgb mt_rgb_sub(mt_rgb a, mt_rgb b)
{
    return mt_rgb_make(a.c[0] - b.c[0], a.c[1] - b.c[1], a.c[2] - b.c[2]);
}
static inline mt_rgb mt_rgb_mul(mt_rgb a, mt_rgb b)
{
    return mt_rgb_make(a.c[0] * b.c[0], a.c[1] * b.c[1], a.c[2] * b.c[2]);
}
/* Component-wise quotient; the caller guarantees non-zero divisors. */
static inline mt_rgb mt_rgb_div(mt_rgb a, mt_rgb b)
{
    return mt_rgb_make(a.c[0] / b.c[0], a.c[1] / b.c[1], a.c[2] / b.c[2]);
}
static inline mt_rgb mt_rgb_scale(mt_rgb a, mt_real s)
{
    return mt_rgb_make(a.c[0] * s, a.c[1] * s, a.c[2] * s);
}
/* Division by a scalar, component by component (pbrt-v2's operator/(float)). */
static inline mt_rgb mt_rgb_divs(mt_rgb a, mt_real d)
{
    return mt_rgb_make(a.c[0] / d, a.c[1] / d, a.c[2] / d);
}
/* pbrt-v2 spectrum.h: YWeight = { 0.212671, 0.715160, 0.072169 }. */
static inline mt_real mt_rgb_y(mt_rgb a)
{
    return (mt_real)0.212671 * a.c[0] + (mt_real)0.715160 * a.c[1] + (mt_real)0.072169 * a.c[2];
}
static inline int mt_rgb_is_black(mt_rgb a) { return a.c[0] == 0 && a.c[1] == 0 && a.c[2] == 0; }
static inline mt_rgb mt_rgb_clamp(mt_rgb a, mt_real lo, mt_real hi)
{
    return mt_rgb_make(mt_clamp(a.c[0], lo, hi), mt_clamp(a.c[1], lo, hi), mt_clamp(a.c[2], lo, hi));
}
/* Spectrum::Clamp() with its defaults: from below only. */
static inline mt_rgb mt_rgb_clamp0(mt_rgb a)
{
    return mt_rgb_make(mt_max(a.c[0], 0), mt_max(a.c[1], 0), mt_max(a.c[2], 0));
}
static inline mt_rgb mt_rgb_sqrt(mt_rgb a)
{
    return mt_rgb_make(mt_sqrt(a.c[0]), mt_sqrt(a.c[1]), mt_sqrt(a.c[2]));
}
static inline mt_rgb mt_rgb_exp(mt_rgb a)
{
    return mt_rgb_make(mt_exp(a.c[0]), mt_exp(a.c[1]), mt_exp(a.c[2]));
}
static inline int mt_rgb_is_finite(mt_rgb a)
{
    return mt_is_finite(a.c[0]) && mt_is_finite(a.c[1]) && mt_is_finite(a.c[2]);
}
static inline mt_real mt_rgb_max(mt_rgb a) { return mt_max(a.c[0], mt_max(a.c[1], a.c[2])); }
static inline mt_real mt_rgb_min(mt_rgb a) { return mt_min(a.c[0], mt_min(a.c[1], a.c[2])); }
static inline int mt_rgb_equal(mt_rgb a, mt_rgb b)
{
    return a.c[0] == b.c[0] && a.c[1] == b.c[1] && a.c[2] == b.c[2];
}

#ifdef __cplusplus
}
#endif

#endif
