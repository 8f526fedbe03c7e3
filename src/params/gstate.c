/* pbrt-v2's GraphicsState: its record, copies for AttributeBegin, release. */
#include <string.h>
#include "core/alloc.h"
#include "params/report.h"
#include "params/gstate.h"

mt__shared_params *mt__shared_params_new(const mt_paramset *ps)
{
    mt__shared_params *sp = mt__malloc(sizeof *sp);
    if (!sp) return NULL;
    sp->refs = 1;
    sp->ps = ps ? mt_paramset_clone(ps) : mt_paramset_create();
    if (!sp->ps) {
        mt__free(sp);
        return NULL;
    }
    return sp;
}

static mt__shared_params *retain_params(mt__shared_params *sp)
{
    if (sp) sp->refs++;
    return sp;
}

void mt__shared_params_release(mt__shared_params *sp)
{
    if (!sp || --sp->refs > 0) return;
    mt_paramset_destroy(sp->ps);
    mt__free(sp);
}

void mt__named_material_release(mt__named_material *m)
{
    if (!m || --m->refs > 0) return;
    mt__free(m->name);
    mt__free(m->type);
    mt__shared_params_release(m->geom);
    mt__shared_params_release(m->material);
    if (m->textures) mt_texture_table_destroy(m->textures);
    mt__free(m);
}

int mt__replace_string(char **field, const char *value)
{
    char *c = NULL;
    if (value && !(c = mt__strdup(value))) return 0;
    mt__free(*field);
    *field = c;
    return 1;
}

int mt__gstate_init(mt__gstate *g)
{
    memset(g, 0, sizeof *g);
    g->textures = mt_texture_table_create();
    g->material_params = mt__shared_params_new(NULL);
    return g->textures && g->material_params && mt__replace_string(&g->material, "matte");
}

void mt__gstate_free(mt__gstate *g)
{
    int i;
    if (g->textures) mt_texture_table_destroy(g->textures);
    mt__free(g->material);
    mt__shared_params_release(g->material_params);
    for (i = 0; i < g->nnamed; ++i) mt__named_material_release(g->named[i]);
    mt__free(g->named);
    mt__free(g->current_named);
    mt__free(g->area_light);
    mt__shared_params_release(g->area_params);
    memset(g, 0, sizeof *g);
}

int mt__gstate_copy(mt__gstate *dst, const mt__gstate *src)
{
    int i, ok = 1;
    memset(dst, 0, sizeof *dst);
    dst->reverse_orientation = src->reverse_orientation;
    dst->material_params = retain_params(src->material_params);
    dst->area_params = retain_params(src->area_params);
    dst->textures = mt_texture_table_clone(src->textures);
    ok = dst->textures && mt__replace_string(&dst->material, src->material) &&
         mt__replace_string(&dst->current_named, src->current_named) &&
         mt__replace_string(&dst->area_light, src->area_light);
    if (ok && src->nnamed) {
        dst->named = mt__malloc((size_t)src->nnamed * sizeof *dst->named);
        ok = dst->named != NULL;
        if (ok) dst->cap_named = src->nnamed;
        for (i = 0; ok && i < src->nnamed; ++i) {
            dst->named[i] = src->named[i];
            dst->named[i]->refs++;
            dst->nnamed = i + 1;
        }
    }
    if (!ok) mt__gstate_free(dst);
    return ok;
}

mt__named_material *mt__gstate_find_named(const mt__gstate *g, const char *name)
{
    int i;
    for (i = 0; i < g->nnamed; ++i)
        if (strcmp(g->named[i]->name, name) == 0) return g->named[i];
    return NULL;
}

int mt__gstate_bind_named(mt__gstate *g, mt__named_material *m, int *replaced)
{
    mt__named_material **named;
    int i;
    *replaced = 0;
    for (i = 0; i < g->nnamed; ++i)
        if (strcmp(g->named[i]->name, m->name) == 0) {
            mt__named_material_release(g->named[i]);
            g->named[i] = m;
            *replaced = 1;
            return 1;
        }
    named = mt__grow(g->named, &g->cap_named, g->nnamed + 1, sizeof *named);
    if (!named) {
        mt__named_material_release(m);
        return 0;
    }
    g->named = named;
    g->named[g->nnamed++] = m;
    return 1;
}
