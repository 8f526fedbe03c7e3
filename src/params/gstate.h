/*
 * Internal: pbrt-v2's GraphicsState (api.cpp) -- what AttributeBegin saves
 * and AttributeEnd restores: the named textures, the current material and
 * its parameters, the named materials, the selected named material, the
 * orientation flag and the area light. Parameter lists and named materials
 * are immutable once recorded and shared by reference count between a state
 * and the copies AttributeBegin pushes (pbrt-v2 shares them through
 * Reference<> too); the texture table is cloned, since Texture changes it.
 */
#ifndef MT_PARAMS_GSTATE_H
#define MT_PARAMS_GSTATE_H

#include "materia/state.h"

typedef struct mt__shared_params {
    int refs;
    mt_paramset *ps;
} mt__shared_params;

typedef struct mt__named_material {
    int refs;
    char *name, *type;
    mt__shared_params *geom, *material;
    mt_texture_table *textures;
    mt_transform transform;
} mt__named_material;

typedef struct mt__gstate {
    mt_texture_table *textures;
    char *material;
    mt__shared_params *material_params;
    mt__named_material **named;
    int nnamed, cap_named;
    char *current_named; /* NULL when none is selected */
    int reverse_orientation;
    char *area_light; /* NULL when none */
    mt__shared_params *area_params;
} mt__gstate;

/* A clone of ps with a reference count of 1, or NULL. */
mt__shared_params *mt__shared_params_new(const mt_paramset *ps);
void mt__shared_params_release(mt__shared_params *sp);

/* pbrt-v2's GraphicsState(): material "matte", nothing else. 0 when out of
 * memory (g is then empty and may be freed). */
int mt__gstate_init(mt__gstate *g);
/* A copy sharing what is immutable; 0 when out of memory. */
int mt__gstate_copy(mt__gstate *dst, const mt__gstate *src);
void mt__gstate_free(mt__gstate *g);

/* Sets *field to a copy of value (NULL allowed); 0 when out of memory. */
int mt__replace_string(char **field, const char *value);

mt__named_material *mt__gstate_find_named(const mt__gstate *g, const char *name);
/* Binds m (taking the caller's reference) under its name; 0 when out of
 * memory (m is then released). *replaced tells whether one was there. */
int mt__gstate_bind_named(mt__gstate *g, mt__named_material *m, int *replaced);
void mt__named_material_release(mt__named_material *m);

#endif
