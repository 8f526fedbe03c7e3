/*
 * The registry of material kinds: MT_MATERIAL_KINDS (materia/material.h)
 * expanded into the table that creation by name and the iteration functions
 * read. It is an object of its own so that a program creating materials from
 * their kinds' objects (mt_material_create_kind) does not link every kind.
 */
#include <string.h>
#include "materials/material_impl.h"

#define KIND(name) &mt_##name##_material,
#define NAME(name) #name,
static const mt_material_kind *const material_kinds[] = {MT_MATERIAL_KINDS(KIND)};
static const char *const material_names[] = {MT_MATERIAL_KINDS(NAME) NULL};
#define NKINDS MT_COUNT(material_kinds)

int mt_material_kind_count(void) { return NKINDS; }

const mt_material_kind *mt_material_kind_at(int i) { return i >= 0 && i < NKINDS ? material_kinds[i] : NULL; }

const mt_material_kind *mt_material_kind_find(const char *name)
{
    int i;
    for (i = 0; name && i < NKINDS; ++i)
        if (!strcmp(material_kinds[i]->type, name)) return material_kinds[i];
    return NULL;
}

const char *const *mt_material_types(int *count)
{
    if (count) *count = NKINDS;
    return material_names;
}

mt_material *mt_material_create(const char *type, const mt_transform *mtl2world,
                                const mt_texparams *tp, const mt_material_ctx *ctx, mt_error *err)
{
    const mt_material_kind *k = mt_material_kind_find(type);
    mt_error_clear(err);
    if (!type) return mt_error_set(err, MT_ERR_INVALID, "material: no type given"), NULL;
    if (!k) return mt_error_set(err, MT_ERR_NOT_FOUND, "material type \"%s\" unknown", type), NULL;
    return mt_material_create_kind(k, mtl2world, tp, ctx, err);
}
