/*
 * Geometry helpers for the tracer's tests and benchmarks: shapes from scene
 * text, scene files loaded into a geometry, and a brute-force closest hit.
 */
#ifndef MT_TEST_TGEOM_H
#define MT_TEST_TGEOM_H

#include "tracer/geometry.h"

/* The shape of the first Shape statement in text (scene syntax), placed by
 * o2w (NULL: identity); NULL with err set on failure. Warnings are counted
 * in *nwarn when nwarn is not NULL. */
mt_shape *t_shape(const char *text, const mt_transform *o2w, int reverse_orientation,
                  int *nwarn, mt_error *err);
/* The same in a given mode (t_shape: pbrt-v2 mode). */
mt_shape *t_shape_mode(const char *text, const mt_transform *o2w, int reverse_orientation,
                       mt_mode mode, int *nwarn, mt_error *err);

/* Attaches every Shape of a scene file to g (not committed). Only the
 * statements that place shapes are followed -- AttributeBegin/End,
 * TransformBegin/End, Identity, Translate, Scale, Rotate, Transform,
 * ConcatTransform, ReverseOrientation -- the rest is ignored (the graphics
 * state of materia/state.h needs the texture module, which these tests do
 * not link). Returns the number of shapes, -1 on error. */
int t_load_shapes(const char *path, mt_geometry *g, mt_error *err);

/* The closest hit over every primitive of g, one by one, with the BVH's tie
 * rule (equal t: the smaller global id). */
int t_brute_intersect(const mt_geometry *g, const mt_ray *r, mt_hit *hit);

#endif
