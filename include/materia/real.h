/*
 * materia/real.h -- the real type, math wrappers and constants.
 *
 * mt_real is float (the default, as in pbrt-v2) or double (PRECISION=double).
 * Every formula in materia is written once against mt_real and the mt_*
 * math wrappers below, so that the two builds differ only in precision.
 * MT_REAL_NAME ("float" or "double") is what mt_precision() returns in a
 * library built for these headers.
 *
 * Thread safety: inline functions of their arguments alone.
 */
#ifndef MATERIA_REAL_H
#define MATERIA_REAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "materia/config.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__) || defined(__clang__)
#define MT_API __attribute__((visibility("default")))
#else
#define MT_API
#endif

#if MT_USE_DOUBLE
typedef double mt_real;
#define MT_REAL_NAME "double"
#define mt_sqrt sqrt
#define mt_pow pow
#define mt_exp exp
#define mt_log log
#define mt_sin sin
#define mt_cos cos
#define mt_tan tan
#define mt_atan atan
#define mt_atan2 atan2
#define mt_acos acos
#define mt_asin asin
#define mt_fabs fabs
#define mt_floor floor
#define mt_ceil ceil
#define mt_fmod fmod
#define MT_ONE_MINUS_EPSILON 0x1.fffffffffffffp-1
#define MT_REAL_MAX 1.7976931348623157e308
#define MT_REAL_EPSILON 2.2204460492503131e-16
#else
typedef float mt_real;
#define MT_REAL_NAME "float"
#define mt_sqrt sqrtf
#define mt_pow powf
#define mt_exp expf
#define mt_log logf
#define mt_sin sinf
#define mt_cos cosf
#define mt_tan tanf
#define mt_atan atanf
#define mt_atan2 atan2f
#define mt_acos acosf
#define mt_asin asinf
#define mt_fabs fabsf
#define mt_floor floorf
#define mt_ceil ceilf
#define mt_fmod fmodf
/* pbrt-v2 montecarlo.h: the largest float below one. */
#define MT_ONE_MINUS_EPSILON 0x1.fffffep-1f
#define MT_REAL_MAX 3.40282347e38f
#define MT_REAL_EPSILON 1.19209290e-7f
#endif

/* pbrt-v2 (pbrt.h) defines M_PI, INV_PI, ... as float literals, and its
 * reference build evaluates "theta * M_PI / 4.f" and the like in float (the
 * reference values show it): the constants are mt_real here too. */
#define MT_PI ((mt_real)3.14159265358979323846)
#define MT_INV_PI ((mt_real)0.31830988618379067154)
#define MT_INV_2PI ((mt_real)0.15915494309189533577)
#define MT_INV_4PI ((mt_real)0.07957747154594766788)

static inline mt_real mt_min(mt_real a, mt_real b) { return a < b ? a : b; }
static inline mt_real mt_max(mt_real a, mt_real b) { return a > b ? a : b; }
static inline mt_real mt_clamp(mt_real v, mt_real lo, mt_real hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}
static inline mt_real mt_lerp(mt_real t, mt_real a, mt_real b) { return (1 - t) * a + t * b; }
/* pbrt-v2 pbrt.h: (M_PI / 180.f) * deg. */
static inline mt_real mt_radians(mt_real deg) { return (MT_PI / 180) * deg; }
static inline mt_real mt_degrees(mt_real rad) { return (180 / MT_PI) * rad; }
/* Classification by the exponent bits: no floating-point comparison, so no
 * FE_INVALID for a NaN whatever instructions the compiler picks (clang's
 * default code for isfinite() may use a signalling compare). */
static inline int mt_is_finite(mt_real v)
{
#if MT_USE_DOUBLE
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    return ((u >> 52) & 0x7ff) != 0x7ff;
#else
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    return ((u >> 23) & 0xff) != 0xff;
#endif
}
static inline int mt_is_nan(mt_real v)
{
#if MT_USE_DOUBLE
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    return ((u >> 52) & 0x7ff) == 0x7ff && (u & 0xfffffffffffffULL) != 0;
#else
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    return ((u >> 23) & 0xff) == 0xff && (u & 0x7fffff) != 0;
#endif
}

#ifdef __cplusplus
}
#endif

#endif
