/*
 * Internal: a texture kind (one of pbrt-v2's texture classes) -- its name,
 * whether it has a float variant, its creator from a statement's parameters
 * and what each parameter it reads is. Each class's file defines its kind,
 * mt_<name>_texture, with designated initializers; the registry is the list
 * MT_TEXTURE_KINDS in materia/texture.h. textures/create.h has the readers
 * that several creators share.
 */
#ifndef MT_TEXTURES_KIND_H
#define MT_TEXTURES_KIND_H

#include "materia/texture.h"

/* What a parameter a creator reads is and the values it takes, for
 * docs/REFERENCE.md (its name, type and default come from the reader
 * itself, through textures/probe.h; the check that the committed file is
 * current also checks that every parameter read is described and every one
 * described is read). */
typedef struct mt__texture_param_doc {
    const char *name, *range, *what;
} mt__texture_param_doc;

struct mt_texture_kind {
    const char *name; /* pbrt-v2's class name: "checkerboard", ... */
    int has_float;    /* pbrt-v2 has a float variant (not uv or marble) */
    /* Reads the parameters with pbrt-v2's names and defaults and builds the
     * texture (the float variant when is_float); NULL with err naming the
     * parameter. tex2world is never NULL. */
    mt_texture *(*create)(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err);
    /* the parameters this class reads that the shared readers
     * (textures/create.h) do not */
    const mt__texture_param_doc *params;
    int nparams;
};

#define MT_COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* The shared readers' parameters ("mapping" and its own, "octaves",
 * "roughness"), described once (textures/create.c). */
const mt__texture_param_doc *mt__texture_common_docs(int *count);

#endif
