/*
 * The texture handle: creation from a kind (registry.c finds kinds by
 * name), allocation, reference counting, evaluation through
 * the class's operations table, and the table of named textures with its two
 * namespaces (pbrt-v2 api.cpp GraphicsState floatTextures and
 * spectrumTextures).
 */
#include <string.h>
#include "core/alloc.h"
#include "textures/kind.h"
#include "textures/tex.h"

mt_texture *mt_texture_create_kind(const mt_texture_kind *k, int is_float, const mt_transform *tex2world,
                                   const mt_texparams *tp, mt_error *err)
{
    mt_transform id = mt_transform_identity();
    mt_error_clear(err);
    if (!k || !tp) {
        mt_error_set(err, MT_ERR_INVALID, "texture: missing kind or parameters");
        return NULL;
    }
    if (is_float && !k->has_float) {
        mt_error_set(err, MT_ERR_INVALID, "pbrt-v2 has no float \"%s\" texture", k->name);
        return NULL;
    }
    return k->create(is_float ? 1 : 0, tex2world ? tex2world : &id, tp, err);
}

const char *mt_texture_kind_name(const mt_texture_kind *k) { return k->name; }
int mt_texture_kind_has_float(const mt_texture_kind *k) { return k->has_float; }

void *mt__texture_alloc(size_t size, const mt_texture_ops *ops, int is_float, mt_mode mode,
                        mt_error *err)
{
    mt_texture *t = mt__calloc(1, size);
    if (!t) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory creating a %s texture", ops->name);
        return NULL;
    }
    t->ops = ops;
    t->is_float = is_float ? 1 : 0;
    t->mode = mode;
    t->refs = 1;
    return t;
}

/* A spectrum texture read as a float gives its luminance (pbrt-v2's y(), as
 * its float image maps store); a float texture read as RGB is gray. */
mt_real mt_texture_eval_float(const mt_texture *t, const mt_diffgeom *dg)
{
    if (t->is_float) return t->ops->eval_float(t, dg);
    return mt_rgb_y(t->ops->eval_rgb(t, dg));
}

mt_rgb mt_texture_eval_rgb(const mt_texture *t, const mt_diffgeom *dg)
{
    if (t->is_float) return mt_rgb_gray(t->ops->eval_float(t, dg));
    return t->ops->eval_rgb(t, dg);
}

int mt_texture_is_float(const mt_texture *t) { return t->is_float; }
const char *mt_texture_class(const mt_texture *t) { return t->ops->name; }

mt_texture *mt_texture_retain(mt_texture *t)
{
    if (t) __atomic_add_fetch(&t->refs, 1, __ATOMIC_RELAXED);
    return t;
}

void mt_texture_destroy(mt_texture *t)
{
    if (!t || __atomic_sub_fetch(&t->refs, 1, __ATOMIC_ACQ_REL) != 0) return;
    if (t->ops->finalize) t->ops->finalize(t);
    mt__free(t);
}

int mt__tex_check_real(mt_real v, const char *param, const char *cls, mt_error *err)
{
    if (mt_is_finite(v)) return 1;
    mt_error_param(err, MT_ERR_INVALID, param, "%s texture: %s is not a finite number", cls,
                   param);
    return 0;
}

int mt__tex_check_rgb(mt_rgb v, const char *param, const char *cls, mt_error *err)
{
    if (mt_rgb_is_finite(v)) return 1;
    mt_error_param(err, MT_ERR_INVALID, param, "%s texture: %s has a component that is not finite",
                   cls, param);
    return 0;
}

int mt__tex_check_child(const mt_texture *t, int is_float, const char *param, const char *cls,
                        mt_error *err)
{
    if (!t) {
        mt_error_param(err, MT_ERR_INVALID, param, "%s texture: %s is missing", cls, param);
        return 0;
    }
    if (!t->is_float != !is_float) {
        mt_error_param(err, MT_ERR_INVALID, param, "%s texture: %s must be a %s texture, not %s",
                       cls, param, is_float ? "float" : "spectrum",
                       is_float ? "a spectrum one" : "a float one");
        return 0;
    }
    return 1;
}

int mt__tex_check_octaves(int octaves, mt_real roughness, const char *cls, mt_error *err)
{
    mt_real o = 1, bound = 1;
    int i;
    if (octaves < 0 || octaves > 128) {
        mt_error_param(err, MT_ERR_INVALID, "octaves",
                       "%s texture: octaves is %d; it must be in [0, 128] (the frequency "
                       "1.99^octaves overflows beyond)", cls, octaves);
        return 0;
    }
    if (!mt__tex_check_real(roughness, "roughness", cls, err)) return 0;
    /* every octave's weight, and their sum (noise is within [-1.04, 1.04]),
     * must be finite */
    for (i = 0; i < octaves; ++i) {
        o *= roughness;
        bound += mt_fabs(o);
    }
    if (!mt_is_finite(bound * 2)) {
        mt_error_param(err, MT_ERR_INVALID, "roughness",
                       "%s texture: roughness %g over %d octaves overflows", cls,
                       (double)roughness, octaves);
        return 0;
    }
    return 1;
}

/* --- named textures --- */

typedef struct table_entry {
    char *name;
    mt_texture *tex;
} table_entry;

typedef struct space {
    table_entry *e;
    int n, cap;
} space;

struct mt_texture_table {
    space ns[2]; /* [0] spectrum, [1] float */
};

mt_texture_table *mt_texture_table_create(void) { return mt__calloc(1, sizeof(mt_texture_table)); }

static void space_clear(space *s)
{
    int i;
    for (i = 0; i < s->n; ++i) {
        mt__free(s->e[i].name);
        mt_texture_destroy(s->e[i].tex);
    }
    mt__free(s->e);
    s->e = NULL;
    s->n = s->cap = 0;
}

void mt_texture_table_destroy(mt_texture_table *t)
{
    if (!t) return;
    space_clear(&t->ns[0]);
    space_clear(&t->ns[1]);
    mt__free(t);
}

static int space_copy(space *dst, const space *src)
{
    int i;
    dst->n = dst->cap = 0;
    dst->e = NULL;
    if (!src->n) return 1;
    dst->e = mt__malloc((size_t)src->n * sizeof(table_entry));
    if (!dst->e) return 0;
    dst->cap = src->n;
    for (i = 0; i < src->n; ++i) {
        dst->e[i].name = mt__strdup(src->e[i].name);
        if (!dst->e[i].name) return 0;
        dst->e[i].tex = mt_texture_retain(src->e[i].tex);
        dst->n++;
    }
    return 1;
}

mt_texture_table *mt_texture_table_clone(const mt_texture_table *t)
{
    mt_texture_table *c = mt_texture_table_create();
    if (!c) return NULL;
    if (!space_copy(&c->ns[0], &t->ns[0]) || !space_copy(&c->ns[1], &t->ns[1])) {
        mt_texture_table_destroy(c);
        return NULL;
    }
    return c;
}

static table_entry *space_find(const space *s, const char *name)
{
    int i;
    for (i = 0; i < s->n; ++i)
        if (!strcmp(s->e[i].name, name)) return &s->e[i];
    return NULL;
}

mt_status mt_texture_table_set(mt_texture_table *t, const char *name, mt_texture *tex,
                               mt_error *err)
{
    space *s;
    table_entry *e;
    char *copy;
    mt_error_clear(err);
    if (!t || !name || !tex)
        return mt_error_set(err, MT_ERR_INVALID, "texture table: missing table, name or texture");
    s = &t->ns[tex->is_float ? 1 : 0];
    e = space_find(s, name);
    if (e) { /* pbrt-v2 replaces a redefined texture (with a warning the state gives) */
        mt_texture_retain(tex);
        mt_texture_destroy(e->tex);
        e->tex = tex;
        return MT_OK;
    }
    if (s->n == s->cap) {
        int cap = s->cap ? 2 * s->cap : 8;
        table_entry *grown = mt__realloc(s->e, (size_t)cap * sizeof(table_entry));
        if (!grown) return mt_error_set(err, MT_ERR_NOMEM, "out of memory naming texture \"%s\"", name);
        s->e = grown;
        s->cap = cap;
    }
    copy = mt__strdup(name);
    if (!copy) return mt_error_set(err, MT_ERR_NOMEM, "out of memory naming texture \"%s\"", name);
    s->e[s->n].name = copy;
    s->e[s->n].tex = mt_texture_retain(tex);
    s->n++;
    return MT_OK;
}

mt_texture *mt_texture_table_get(const mt_texture_table *t, const char *name, int is_float)
{
    const table_entry *e;
    if (!t || !name) return NULL;
    e = space_find(&t->ns[is_float ? 1 : 0], name);
    return e ? e->tex : NULL;
}

/* --- layouts shared by several classes --- */

mt_rgb mt__tex_gray_rgb(const mt_texture *t, const mt_diffgeom *dg)
{
    return mt_rgb_gray(t->ops->eval_float(t, dg));
}

void *mt__pair_alloc(size_t size, const mt_texture_ops *ops, int is_float, mt_texture *tex1,
                     const char *name1, mt_texture *tex2, const char *name2, mt_mode mode,
                     mt_error *err)
{
    mt__pair_tex *p;
    if (!mt__tex_check_child(tex1, is_float, name1, ops->name, err) ||
        !mt__tex_check_child(tex2, is_float, name2, ops->name, err))
        return NULL;
    p = mt__texture_alloc(size, ops, is_float, mode, err);
    if (!p) return NULL;
    p->tex1 = mt_texture_retain(tex1);
    p->tex2 = mt_texture_retain(tex2);
    return p;
}

void mt__pair_finalize(mt_texture *t)
{
    mt__pair_tex *p = (mt__pair_tex *)t;
    mt_texture_destroy(p->tex1);
    mt_texture_destroy(p->tex2);
}

mt_real mt__pair_pick_float(const mt_texture *t, const mt_diffgeom *dg)
{
    const mt__pair_tex *p = (const mt__pair_tex *)t;
    return mt__tex_pick_float(p->weight(t, dg), p->tex1, p->tex2, dg);
}

mt_rgb mt__pair_pick_rgb(const mt_texture *t, const mt_diffgeom *dg)
{
    const mt__pair_tex *p = (const mt__pair_tex *)t;
    return mt__tex_pick_rgb(p->weight(t, dg), p->tex1, p->tex2, dg);
}
