/* Internal: a material from a specification, for the entry points built on
 * the graphics state. */
#ifndef MT_MATERIALS_FROM_STATE_H
#define MT_MATERIALS_FROM_STATE_H

#include "materia/material.h"
#include "materia/state.h"

/* The material spec describes, in mode, with a mix's named materials looked
 * up in s (NULL: none) and shape_params (may be NULL) read first, as
 * mt_material_from_state does. A new reference, or NULL with err filled. */
mt_material *mt__material_from_spec(const mt_state *s, const mt_material_spec *spec, mt_mode mode,
                                    const mt_paramset *shape_params, mt_error *err);

#endif
