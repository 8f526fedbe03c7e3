/*
 * materia/transform.h -- 4x4 transforms with their inverses (pbrt-v2
 * transform.h/.cpp): the scene description's Translate, Scale, Rotate,
 * LookAt, ..., and their application to points, vectors and normals.
 *
 * Matrices are double precision whatever mt_real is: transforms are composed
 * once per statement, and accumulating them in double keeps deep transform
 * stacks exact to float. Application rounds to mt_real.
 *
 * Thread safety: functions of their arguments alone.
 */
#ifndef MATERIA_TRANSFORM_H
#define MATERIA_TRANSFORM_H

#include "materia/error.h"
#include "materia/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_matrix4 {
    double m[4][4];
} mt_matrix4;

typedef struct mt_transform {
    mt_matrix4 m, minv;
} mt_transform;

/* The identity. */
MT_API mt_transform mt_transform_identity(void);
/* From a row-major matrix; MT_ERR_INVALID when it is singular or not finite. */
MT_API mt_status mt_transform_from_matrix(const double m[16], mt_transform *out, mt_error *err);
/* The inverse (the stored matrices swapped). */
MT_API mt_transform mt_transform_inverse(const mt_transform *t);
/* a * b: b is applied first. */
MT_API mt_transform mt_transform_compose(const mt_transform *a, const mt_transform *b);
/* 1 when the matrix is exactly the identity. */
MT_API int mt_transform_is_identity(const mt_transform *t);
/* The upper 3x3 has a negative determinant (pbrt-v2 SwapsHandedness). */
MT_API int mt_transform_swaps_handedness(const mt_transform *t);

/* pbrt-v2 Translate and Scale (a zero factor gives a singular transform: the
 * state rejects Scale 0; a caller of these checks). */
MT_API mt_transform mt_translate(mt_vec3 d);
MT_API mt_transform mt_scale(mt_real x, mt_real y, mt_real z);
/* Rotation by angle degrees about axis (normalized here); pbrt-v2 Rotate. */
MT_API mt_transform mt_rotate(mt_real angle_deg, mt_vec3 axis);
/* pbrt-v2 LookAt: the camera-to-world inverse, i.e. world to camera.
 * MT_ERR_INVALID when up is parallel to the viewing direction. */
MT_API mt_status mt_look_at(mt_vec3 pos, mt_vec3 look, mt_vec3 up, mt_transform *out,
                            mt_error *err);
/* pbrt-v2 Perspective(fov, n, f) and Orthographic(n, f). */
MT_API mt_transform mt_perspective(mt_real fov_deg, mt_real znear, mt_real zfar);
MT_API mt_transform mt_orthographic(mt_real znear, mt_real zfar);

/* t applied to a point (divided by w when w is not 1) and to a vector. */
MT_API mt_vec3 mt_transform_point(const mt_transform *t, mt_vec3 p);
MT_API mt_vec3 mt_transform_vector(const mt_transform *t, mt_vec3 v);
/* Normals transform by the inverse transpose. */
MT_API mt_vec3 mt_transform_normal(const mt_transform *t, mt_vec3 n);

#ifdef __cplusplus
}
#endif

#endif
