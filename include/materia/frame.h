/*
 * materia/frame.h -- orthonormal shading frames.
 *
 * A frame (s, t, n) maps world directions to the local coordinates in which
 * every BxDF is written: the normal is +z (pbrt-v2 BSDF::WorldToLocal).
 *
 * Thread safety: functions of their arguments alone.
 */
#ifndef MATERIA_FRAME_H
#define MATERIA_FRAME_H

#include "materia/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_frame {
    mt_vec3 s, t, n;
} mt_frame;

static inline mt_vec3 mt_frame_to_local(const mt_frame *f, mt_vec3 v)
{
    return mt_v3(mt_v3_dot(v, f->s), mt_v3_dot(v, f->t), mt_v3_dot(v, f->n));
}
static inline mt_vec3 mt_frame_to_world(const mt_frame *f, mt_vec3 v)
{
    return mt_v3(f->s.x * v.x + f->t.x * v.y + f->n.x * v.z,
                 f->s.y * v.x + f->t.y * v.y + f->n.y * v.z,
                 f->s.z * v.x + f->t.z * v.y + f->n.z * v.z);
}

/* pbrt-v2 geometry.h CoordinateSystem: two unit vectors perpendicular to the
 * unit vector v1 (v2 in the plane of v1 and one axis, v3 = v1 x v2). */
MT_API void mt_coordinate_system(mt_vec3 v1, mt_vec3 *v2, mt_vec3 *v3);

/* A frame with the unit normal n as its z axis, built by mt_coordinate_system. */
MT_API mt_frame mt_frame_from_normal(mt_vec3 n);

#ifdef __cplusplus
}
#endif

#endif
