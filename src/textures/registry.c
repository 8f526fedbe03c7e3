/*
 * The registry of texture kinds: MT_TEXTURE_KINDS (materia/texture.h)
 * expanded into the table that creation by name and the iteration functions
 * read. Each kind -- its creator, its parameters and their descriptions --
 * is in its class's own file. The registry is an object of its own so that a
 * program creating textures from their kinds' objects does not link every
 * kind (imagemap and the image files it reads among them).
 */
#include <string.h>
#include "textures/kind.h"

#define KIND(name) &mt_##name##_texture,
#define NAME(name) #name,
static const mt_texture_kind *const texture_kinds[] = {MT_TEXTURE_KINDS(KIND)};
static const char *const texture_names[] = {MT_TEXTURE_KINDS(NAME) NULL};
#define NKINDS MT_COUNT(texture_kinds)

int mt_texture_kind_count(void) { return NKINDS; }

const mt_texture_kind *mt_texture_kind_at(int i) { return i >= 0 && i < NKINDS ? texture_kinds[i] : NULL; }

const mt_texture_kind *mt_texture_kind_find(const char *name)
{
    int i;
    for (i = 0; name && i < NKINDS; ++i)
        if (!strcmp(texture_kinds[i]->name, name)) return texture_kinds[i];
    return NULL;
}

const char *const *mt_texture_classes(int *count)
{
    if (count) *count = NKINDS;
    return texture_names;
}

mt_texture *mt_texture_create(const char *class_name, int is_float, const mt_transform *tex2world,
                              const mt_texparams *tp, mt_error *err)
{
    const mt_texture_kind *k = mt_texture_kind_find(class_name);
    mt_error_clear(err);
    if (!class_name || !tp) {
        mt_error_set(err, MT_ERR_INVALID, "texture: missing class name or parameters");
        return NULL;
    }
    if (!k) {
        mt_error_set(err, MT_ERR_NOT_FOUND, "unknown texture class \"%s\"", class_name);
        return NULL;
    }
    return mt_texture_create_kind(k, is_float, tex2world, tp, err);
}
