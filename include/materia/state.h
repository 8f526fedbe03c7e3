/*
 * materia/state.h -- pbrt-v2's graphics state, shared by the scene parser and
 * the query tool: the current transform, named coordinate systems, the
 * attribute stack, named textures and (with the materials) the current and
 * named materials.
 *
 * mt_state_apply handles the statements that change this state -- Identity,
 * Translate, Scale, Rotate, LookAt, CoordinateSystem, CoordSysTransform,
 * Transform, ConcatTransform, ActiveTransform, AttributeBegin/End,
 * TransformBegin/End, Texture, Material, MakeNamedMaterial, NamedMaterial,
 * ReverseOrientation, AreaLightSource -- and leaves every other directive to
 * the caller (*handled = 0). Camera (which defines the coordinate system
 * "camera"), WorldBegin (identity transform, coordinate system "world"),
 * WorldEnd (back to the initial state), ObjectBegin and ObjectEnd (which push
 * and pop the graphics state as AttributeBegin/End do) update the state and
 * still give *handled = 0: the caller has its own work to do with them.
 *
 * Stricter than pbrt-v2 (which warns or ignores): an unbalanced or crossed
 * End (AttributeEnd closing a TransformBegin), CoordSysTransform or
 * NamedMaterial of an undefined name, MakeNamedMaterial without "string
 * type", a Texture type other than float/color/spectrum, and transforms that
 * are singular or not finite (Scale 0, Rotate about a zero axis, a singular
 * Transform) are errors naming the statement's file and line. The state does
 * not enforce pbrt-v2's options/world blocks, so that the query tool can send
 * statements without WorldBegin.
 *
 * Texture creates the texture at once (mt_texture_create) and reports its
 * unused parameters through the warning callback; Material and
 * MakeNamedMaterial only record (mt_state_material, mt_state_named_material):
 * their parameters are checked when the material is made.
 *
 * Thread safety: a state belongs to one thread at a time -- also for the
 * functions that take it const (mt_material_from_state, mt_material_from_params
 * and the like read parameter lists, and a lookup marks a parameter used).
 * What its getters return is borrowed and changes with it. Give each thread
 * its own state, or share the objects made from one (materials and textures
 * are read-only).
 */
#ifndef MATERIA_STATE_H
#define MATERIA_STATE_H

#include "materia/parser.h"
#include "materia/texture.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_state mt_state;

/* A new state: identity transforms, no named textures or materials, the
 * current material "matte", textures and materials made in mode. NULL when
 * out of memory. mt_state_destroy releases everything it holds (objects made
 * from it keep their own references). */
MT_API mt_state *mt_state_create(mt_mode mode);
MT_API void mt_state_destroy(mt_state *s);
/* The mode of what is made from now on (textures at their statement,
 * materials when they are made). */
MT_API void mt_state_set_mode(mt_state *s, mt_mode mode);
MT_API mt_mode mt_state_mode(const mt_state *s);
/* Where warnings go -- unused parameters, redefinitions, pbrt-v2's other
 * warnings -- called on the thread that applies the statement with ctx, the
 * statement's file (may be NULL) and line, and a message without a newline.
 * warn NULL (the default): mt_state_apply and mt_state_apply_text drop
 * redefinitions and the like, mt_state_apply drops unused parameters too,
 * and the embedding entry points (mt_state_apply_text, mt_*_from_text,
 * mt_*_from_params) make an unused parameter an error. */
MT_API void mt_state_set_warning(mt_state *s, mt_warning_fn warn, void *ctx);

/* Applies one parsed statement (see above): MT_OK and *handled = 1 for a
 * statement of the graphics state, *handled = 0 for any other (the caller's;
 * Camera, WorldBegin, WorldEnd, ObjectBegin and ObjectEnd change the state
 * and still give 0). An error names the statement's file and line. */
MT_API mt_status mt_state_apply(mt_state *s, const mt_statement *st, int *handled,
                                mt_error *err);

/* Applies pbrt-v2 statements given as text (several, over several lines):
 * Texture, Material, MakeNamedMaterial, NamedMaterial, the transforms,
 * CoordinateSystem, CoordSysTransform, AttributeBegin/End and
 * TransformBegin/End. Any other directive (Shape, WorldBegin, ...) is an
 * error. A Texture statement's unused parameters go to the warning
 * callback, or are an error when there is none; a Material's are reported
 * when the material is made (mt_material_from_text). Relative file names
 * resolve against the current directory. MT_OK, or an error naming the line
 * and column; the statements before the failing one stay applied. */
MT_API mt_status mt_state_apply_text(mt_state *s, const char *text, mt_error *err);

/* Binds tex under name in the state's named textures (in tex's namespace,
 * float or spectrum), as a Texture statement would: a "texture" parameter
 * naming it finds it from now on. The state takes its own reference; an
 * earlier binding of the name is released. */
MT_API mt_status mt_state_set_texture(mt_state *s, const char *name, mt_texture *tex, mt_error *err);

/* The getters below return what the state holds now, borrowed: valid until
 * the state's next change (mt_state_apply, mt_state_apply_text,
 * mt_state_set_texture) or its destruction.
 *
 * The current transform (pbrt-v2's curTransform[0], the start-time
 * transform that textures, materials and static shapes use). */
MT_API const mt_transform *mt_state_transform(const mt_state *s);
/* The end-time transform (curTransform[1]): the same as the start one unless
 * ActiveTransform limited a change to one of them. */
MT_API const mt_transform *mt_state_transform_end(const mt_state *s);
/* The named textures in scope. */
MT_API const mt_texture_table *mt_state_textures(const mt_state *s);
/* Attribute/transform/object stack depth (0 at the top level). */
MT_API int mt_state_depth(const mt_state *s);
/* ReverseOrientation's flag (toggled by each, restored by AttributeEnd). */
MT_API int mt_state_reverse_orientation(const mt_state *s);
/* The current AreaLightSource's type name, NULL when none; *params (may be
 * NULL) receives its parameters. */
MT_API const char *mt_state_area_light(const mt_state *s, const mt_paramset **params);

/*
 * What a material is built from (pbrt-v2 api.cpp: pbrtMaterial records a
 * type and its parameters; pbrtMakeNamedMaterial builds at once from its
 * parameters, the current Material's parameters, the textures and transform
 * of that moment; GraphicsState::CreateMaterial uses the NamedMaterial if one
 * is selected, else the Material). geom and material are the two lists of
 * pbrt-v2's TextureParams. Everything points into the state and stays valid
 * until the next mt_state_apply or mt_state_destroy.
 */
typedef struct mt_material_spec {
    const char *name;     /* the named material's name; NULL for a Material statement */
    const char *type;     /* "matte", "plastic", ... (MakeNamedMaterial's "string type") */
    const mt_paramset *geom;     /* named: MakeNamedMaterial's parameters; otherwise NULL,
                                    for the caller's shape parameters */
    const mt_paramset *material; /* the current Material's parameters (for a named material:
                                    those current when it was made); never NULL */
    const mt_texture_table *textures; /* named: as when it was made; otherwise the current */
    mt_transform transform;           /* material to world, likewise */
} mt_material_spec;

/* The material a Shape would get now: the one NamedMaterial selected, else
 * the last Material statement's ("matte" with no parameters at first). */
MT_API void mt_state_material(const mt_state *s, mt_material_spec *out);
/* The material MakeNamedMaterial defined as name (for "mix"'s
 * namedmaterial1/2); MT_ERR_NOT_FOUND when there is none in scope. */
MT_API mt_status mt_state_named_material(const mt_state *s, const char *name,
                                         mt_material_spec *out, mt_error *err);

#ifdef __cplusplus
}
#endif

#endif
