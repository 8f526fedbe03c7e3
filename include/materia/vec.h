/*
 * materia/vec.h -- three-component vectors (points, vectors and normals).
 *
 * One value type serves all three, as C cannot tell them apart anyway; the
 * operations follow pbrt-v2's geometry.h, including its cross product in
 * double precision and Normalize as a multiplication by 1/length.
 *
 * Thread safety: inline functions of their arguments alone.
 */
#ifndef MATERIA_VEC_H
#define MATERIA_VEC_H

#include "materia/real.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_vec3 {
    mt_real x, y, z;
} mt_vec3;

static inline mt_vec3 mt_v3(mt_real x, mt_real y, mt_real z)
{
    mt_vec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}
static inline mt_vec3 mt_v3_add(mt_vec3 a, mt_vec3 b) { return mt_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline mt_vec3 mt_v3_sub(mt_vec3 a, mt_vec3 b) { return mt_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline mt_vec3 mt_v3_scale(mt_vec3 a, mt_real s) { return mt_v3(a.x * s, a.y * s, a.z * s); }
static inline mt_vec3 mt_v3_neg(mt_vec3 a) { return mt_v3(-a.x, -a.y, -a.z); }
static inline mt_real mt_v3_dot(mt_vec3 a, mt_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline mt_real mt_v3_absdot(mt_vec3 a, mt_vec3 b) { return mt_fabs(mt_v3_dot(a, b)); }
static inline mt_real mt_v3_len2(mt_vec3 a) { return mt_v3_dot(a, a); }
static inline mt_real mt_v3_len(mt_vec3 a) { return mt_sqrt(mt_v3_len2(a)); }

/* pbrt-v2 geometry.h computes Cross in double and rounds the result. */
static inline mt_vec3 mt_v3_cross(mt_vec3 a, mt_vec3 b)
{
    double ax = a.x, ay = a.y, az = a.z, bx = b.x, by = b.y, bz = b.z;
    return mt_v3((mt_real)(ay * bz - az * by), (mt_real)(az * bx - ax * bz),
                 (mt_real)(ax * by - ay * bx));
}

/* v / |v| as pbrt-v2 computes it (v * (1/|v|)). The caller guarantees v != 0. */
static inline mt_vec3 mt_v3_normalize(mt_vec3 a)
{
    mt_real inv = 1 / mt_v3_len(a);
    return mt_v3_scale(a, inv);
}
static inline mt_vec3 mt_v3_faceforward(mt_vec3 n, mt_vec3 v)
{
    return mt_v3_dot(n, v) < 0 ? mt_v3_neg(n) : n;
}
static inline int mt_v3_is_finite(mt_vec3 a)
{
    return mt_is_finite(a.x) && mt_is_finite(a.y) && mt_is_finite(a.z);
}
static inline int mt_v3_is_zero(mt_vec3 a) { return a.x == 0 && a.y == 0 && a.z == 0; }

#ifdef __cplusplus
}
#endif

#endif
