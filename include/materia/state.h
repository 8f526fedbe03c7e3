/*
 * materia/state.h -- pbrt-v2's graphics state, shared by the scene parser and
 * the query tool: the current transform, named coordinate systems, the
 * attribute stack, named textures and (with the materials) the current and
 * named materials.
 *
 * mt_state_apply handles the statements that change this state -- Identity,
 * Translate, Scale, Rotate, LookAt, CoordinateSystem, CoordSysTransform,
 * Transform, ConcatTransform, AttributeBegin/End, TransformBegin/End,
 * Texture, Material, MakeNamedMaterial, NamedMaterial -- and leaves every
 * other directive to the caller (*handled = 0).
 */
#ifndef MATERIA_STATE_H
#define MATERIA_STATE_H

#include "materia/parser.h"
#include "materia/texture.h"

typedef struct mt_state mt_state;

MT_API mt_state *mt_state_create(mt_mode mode);
MT_API void mt_state_destroy(mt_state *s);
MT_API void mt_state_set_mode(mt_state *s, mt_mode mode);
MT_API mt_mode mt_state_mode(const mt_state *s);
/* Where warnings (unused parameters, redefinitions) go; NULL drops them. */
MT_API void mt_state_set_warning(mt_state *s, mt_warning_fn warn, void *ctx);

MT_API mt_status mt_state_apply(mt_state *s, const mt_statement *st, int *handled,
                                mt_error *err);

MT_API const mt_transform *mt_state_transform(const mt_state *s);
MT_API const mt_texture_table *mt_state_textures(const mt_state *s);
/* Attribute/transform stack depth (0 at the top level). */
MT_API int mt_state_depth(const mt_state *s);

#endif
