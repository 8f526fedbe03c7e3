/*
 * Typed parameter lists (pbrt-v2 paramset.cpp). Each parameter is one entry
 * with its own copies of the name, the values and the place it was written.
 * A lookup marks the entry used -- through a const list, as pbrt-v2's
 * "mutable lookedUp" does -- so that unused parameters can be reported.
 *
 * Unlike pbrt-v2, whose FindOne* quietly return the default for a parameter
 * of another type or with the wrong number of values, a lookup here fails
 * with a message that names the parameter and where it was written.
 */
#include <stdio.h>
#include <string.h>
#include "core/alloc.h"
#include "params/report.h"
#include "materia/params.h"
#include "params/numcheck.h"
#include "params/path.h"
#include "params/paramset_internal.h"

typedef struct entry {
    mt_param p; /* every pointer in p is owned by the entry */
    int used;
} entry;

struct mt_paramset {
    entry *e;
    int n, cap;
};

static const char *const type_names[] = {"float",  "integer", "bool",     "string", "point",
                                          "vector", "normal",  "spectrum", "texture"};

/* How a type is named in messages: what a scene writes to get it. */
static const char *type_desc(mt_param_type t)
{
    switch (t) {
    case MT_PARAM_FLOAT: return "float";
    case MT_PARAM_INTEGER: return "integer";
    case MT_PARAM_BOOL: return "bool";
    case MT_PARAM_STRING: return "string";
    case MT_PARAM_POINT: return "point";
    case MT_PARAM_VECTOR: return "vector";
    case MT_PARAM_NORMAL: return "normal";
    case MT_PARAM_SPECTRUM: return "spectrum (rgb, color, xyz, spectrum or blackbody)";
    case MT_PARAM_TEXTURE: return "texture";
    }
    return "unknown";
}

/* Values per element: 3 for points, vectors, normals and RGB spectra. */
static int type_width(mt_param_type t)
{
    return t == MT_PARAM_POINT || t == MT_PARAM_VECTOR || t == MT_PARAM_NORMAL ||
                   t == MT_PARAM_SPECTRUM
               ? 3
               : 1;
}

static int is_real_type(mt_param_type t)
{
    return t == MT_PARAM_FLOAT || type_width(t) == 3;
}
static int is_int_type(mt_param_type t) { return t == MT_PARAM_INTEGER || t == MT_PARAM_BOOL; }
static int is_string_type(mt_param_type t) { return t == MT_PARAM_STRING || t == MT_PARAM_TEXTURE; }

static void entry_free(entry *e)
{
    int i;
    if (e->p.strings)
        for (i = 0; i < e->p.count; ++i) mt__free((void *)e->p.strings[i]);
    mt__free((void *)e->p.strings);
    mt__free((void *)e->p.reals);
    mt__free((void *)e->p.ints);
    mt__free((void *)e->p.name);
    mt__free((void *)e->p.type_name);
    mt__free((void *)e->p.file);
    mt__free((void *)e->p.dir);
    memset(e, 0, sizeof *e);
}

static char *dup_or_null(const char *s, int *ok)
{
    char *d;
    if (!s) return NULL;
    d = mt__strdup(s);
    if (!d) *ok = 0;
    return d;
}

static void *dup_bytes(const void *src, size_t n, int *ok)
{
    void *d = mt__malloc(n);
    if (!d) {
        *ok = 0;
        return NULL;
    }
    memcpy(d, src, n);
    return d;
}

/* A deep copy of p into e (e zeroed on failure). */
static int entry_copy(entry *e, const mt_param *p, int used)
{
    int ok = 1, i;
    size_t nvals = (size_t)p->count * (size_t)type_width(p->type);
    memset(e, 0, sizeof *e);
    e->used = used;
    e->p.type = p->type;
    e->p.count = p->count;
    e->p.line = p->line;
    e->p.column = p->column;
    e->p.name = dup_or_null(p->name, &ok);
    e->p.type_name = dup_or_null(p->type_name ? p->type_name : type_names[p->type], &ok);
    e->p.file = dup_or_null(p->file, &ok);
    e->p.dir = dup_or_null(p->dir, &ok);
    if (is_real_type(p->type) && nvals)
        e->p.reals = dup_bytes(p->reals, nvals * sizeof *p->reals, &ok);
    if (is_int_type(p->type) && nvals) e->p.ints = dup_bytes(p->ints, nvals * sizeof *p->ints, &ok);
    if (is_string_type(p->type) && nvals && ok) {
        const char **s = mt__calloc(nvals, sizeof *s);
        e->p.strings = s;
        if (!s) ok = 0;
        for (i = 0; ok && i < p->count; ++i) s[i] = dup_or_null(p->strings[i], &ok);
    }
    if (!ok) entry_free(e);
    return ok;
}

/* Whether p is a well-formed parameter; the reason in err when not. */
static mt_status check_param(const mt_param *p, mt_error *err)
{
    size_t i, nvals;
    if (!p || !p->name || !p->name[0])
        return mt_error_set(err, MT_ERR_INVALID, "a parameter needs a name");
    if ((unsigned)p->type > MT_PARAM_TEXTURE)
        return mt_error_param(err, MT_ERR_INVALID, p->name, "unknown parameter type %d",
                              (int)p->type);
    if (p->count < 0 || p->count > MT__MAX_VALUES / 3)
        return mt_error_param(err, MT_ERR_INVALID, p->name, "bad value count %d", p->count);
    nvals = (size_t)p->count * (size_t)type_width(p->type);
    if (nvals && ((is_real_type(p->type) && !p->reals) || (is_int_type(p->type) && !p->ints) ||
                  (is_string_type(p->type) && !p->strings)))
        return mt_error_param(err, MT_ERR_INVALID, p->name, "values missing");
    for (i = 0; is_real_type(p->type) && i < nvals; ++i)
        if (!mt__fits_real(p->reals[i]))
            return mt_error_param(err, MT_ERR_INVALID, p->name,
                                  "value %g is not finite or out of range", p->reals[i]);
    for (i = 0; p->type == MT_PARAM_BOOL && i < nvals; ++i)
        if (p->ints[i] != 0 && p->ints[i] != 1)
            return mt_error_param(err, MT_ERR_INVALID, p->name, "bool values are 0 or 1");
    for (i = 0; is_string_type(p->type) && i < nvals; ++i)
        if (!p->strings[i]) return mt_error_param(err, MT_ERR_INVALID, p->name, "NULL string");
    return MT_OK;
}

mt_paramset *mt_paramset_create(void) { return mt__calloc(1, sizeof(mt_paramset)); }

void mt_paramset_destroy(mt_paramset *ps)
{
    int i;
    if (!ps) return;
    for (i = 0; i < ps->n; ++i) entry_free(&ps->e[i]);
    mt__free(ps->e);
    mt__free(ps);
}

static int reserve(mt_paramset *ps, int n)
{
    entry *ne;
    if (n <= ps->cap) return 1;
    ne = mt__grow(ps->e, &ps->cap, n, sizeof *ne);
    if (ne) ps->e = ne;
    return ne != NULL;
}

mt_paramset *mt_paramset_clone(const mt_paramset *ps)
{
    mt_paramset *c = mt_paramset_create();
    int i;
    if (!c || !ps) return c;
    if (!reserve(c, ps->n)) {
        mt_paramset_destroy(c);
        return NULL;
    }
    for (i = 0; i < ps->n; ++i) {
        if (!entry_copy(&c->e[i], &ps->e[i].p, ps->e[i].used)) {
            mt_paramset_destroy(c);
            return NULL;
        }
        c->n++;
    }
    return c;
}

static int index_of(const mt_paramset *ps, const char *name)
{
    int i;
    if (!ps || !name) return -1;
    for (i = 0; i < ps->n; ++i)
        if (strcmp(ps->e[i].p.name, name) == 0) return i;
    return -1;
}

/* pbrt-v2's ParamSet keeps one list per type (floats, ints, bools, points,
 * vectors, normals, spectra, strings, textures), so "texture Kd" and "rgb Kd"
 * live side by side and each lookup reads its own list (a material's
 * GetSpectrumTexture takes the texture first). The parameter called name of
 * type want, else the first of that name (for the type error), else -1. */
static int index_of_type(const mt_paramset *ps, const char *name, mt_param_type want)
{
    int i;
    if (!ps || !name) return -1;
    for (i = 0; i < ps->n; ++i)
        if (ps->e[i].p.type == want && strcmp(ps->e[i].p.name, name) == 0) return i;
    return index_of(ps, name);
}

mt_status mt_paramset_add(mt_paramset *ps, const mt_param *p, mt_error *err)
{
    mt_status st = check_param(p, err);
    entry e;
    int old;
    if (st != MT_OK) {
        if (p) mt_error_locate(err, p->file, p->line, p->column);
        return st;
    }
    if (!reserve(ps, ps->n + 1) || !entry_copy(&e, p, 0))
        return mt_error_param(err, MT_ERR_NOMEM, p->name, "out of memory");
    /* pbrt-v2 erases the earlier parameter of its list and appends the new
     * one; a parameter of another type keeps its place (index_of_type) */
    old = index_of_type(ps, p->name, p->type);
    if (old >= 0 && ps->e[old].p.type != p->type) old = -1;
    if (old >= 0) {
        entry_free(&ps->e[old]);
        memmove(&ps->e[old], &ps->e[old + 1], (size_t)(ps->n - old - 1) * sizeof *ps->e);
        ps->n--;
    }
    ps->e[ps->n++] = e;
    return MT_OK;
}

int mt_paramset_count(const mt_paramset *ps) { return ps ? ps->n : 0; }

const mt_param *mt_paramset_at(const mt_paramset *ps, int i)
{
    return ps && i >= 0 && i < ps->n ? &ps->e[i].p : NULL;
}

const mt_param *mt_paramset_find(const mt_paramset *ps, const char *name)
{
    int i = index_of(ps, name);
    return i >= 0 ? &ps->e[i].p : NULL;
}

const mt_param *mt__paramset_find_type(const mt_paramset *ps, const char *name, mt_param_type type)
{
    int i = index_of_type(ps, name, type);
    return i >= 0 && ps->e[i].p.type == type ? &ps->e[i].p : NULL;
}

/* Lookups mark through a const list: the used flags are bookkeeping, not
 * part of the list's value (the list itself was allocated writable). */
static void mark(const mt_paramset *ps, int i) { ((mt_paramset *)ps)->e[i].used = 1; }

void mt_paramset_mark_used(const mt_paramset *ps, const char *name)
{
    int i;
    for (i = 0; ps && name && i < ps->n; ++i)
        if (strcmp(ps->e[i].p.name, name) == 0) mark(ps, i);
}

static mt_status fail(const mt_param *p, mt_status st, mt_error *err)
{
    mt_error_locate(err, p->file, p->line, p->column);
    return st;
}

/*
 * The parameter called name, checked to be of type want, and to have one
 * element when single. *found = NULL and MT_OK when absent.
 */
static mt_status lookup(const mt_paramset *ps, const char *name, mt_param_type want, int single,
                        const mt_param **found, mt_error *err)
{
    int i = index_of_type(ps, name, want);
    const mt_param *p;
    *found = NULL;
    if (i < 0) return MT_OK;
    p = &ps->e[i].p;
    mark(ps, i);
    if (p->type != want) {
        mt_error_param(err, MT_ERR_INVALID, name, "is declared \"%s %s\" but is read as %s",
                       p->type_name, name, type_desc(want));
        return fail(p, MT_ERR_INVALID, err);
    }
    if (single && p->count != 1) {
        if (!strcmp(p->type_name, "blackbody")) /* read as pairs, stored as rgb */
            mt_error_param(err, MT_ERR_INVALID, name,
                           "expected one blackbody (a temperature and a scale), found %d", p->count);
        else if (!strcmp(p->type_name, "spectrum")) /* pairs or a file name, stored as rgb */
            mt_error_param(err, MT_ERR_INVALID, name, "expected one spectrum, found %d", p->count);
        else if (type_width(p->type) == 3)
            mt_error_param(err, MT_ERR_INVALID, name,
                           "expected one %s (3 values), found %d values", p->type_name,
                           p->count * 3);
        else
            mt_error_param(err, MT_ERR_INVALID, name, "expected one %s value, found %d",
                           p->type_name, p->count);
        return fail(p, MT_ERR_INVALID, err);
    }
    *found = p;
    return MT_OK;
}

mt_status mt_params_float(const mt_paramset *ps, const char *name, mt_real def, mt_real *out,
                          mt_error *err)
{
    const mt_param *p;
    mt_status st = lookup(ps, name, MT_PARAM_FLOAT, 1, &p, err);
    *out = p ? (mt_real)p->reals[0] : def;
    return st;
}

static mt_status one_int(const mt_paramset *ps, const char *name, mt_param_type t, int def,
                         int *out, mt_error *err)
{
    const mt_param *p;
    mt_status st = lookup(ps, name, t, 1, &p, err);
    *out = p ? p->ints[0] : def;
    return st;
}

mt_status mt_params_int(const mt_paramset *ps, const char *name, int def, int *out,
                        mt_error *err)
{
    return one_int(ps, name, MT_PARAM_INTEGER, def, out, err);
}

mt_status mt_params_bool(const mt_paramset *ps, const char *name, int def, int *out,
                         mt_error *err)
{
    return one_int(ps, name, MT_PARAM_BOOL, def, out, err);
}

static mt_status one_string(const mt_paramset *ps, const char *name, mt_param_type t,
                            const char *def, const char **out, mt_error *err)
{
    const mt_param *p;
    mt_status st = lookup(ps, name, t, 1, &p, err);
    *out = p ? p->strings[0] : def;
    return st;
}

mt_status mt_params_string(const mt_paramset *ps, const char *name, const char *def,
                           const char **out, mt_error *err)
{
    return one_string(ps, name, MT_PARAM_STRING, def, out, err);
}

mt_status mt_params_texture(const mt_paramset *ps, const char *name, const char **out,
                            mt_error *err)
{
    return one_string(ps, name, MT_PARAM_TEXTURE, NULL, out, err);
}

mt_status mt_params_filename(const mt_paramset *ps, const char *name, const char *def,
                             char *out, size_t size, mt_error *err)
{
    const mt_param *p;
    mt_status st = lookup(ps, name, MT_PARAM_STRING, 1, &p, err);
    if (st != MT_OK) return st;
    /* pbrt-v2 FindOneFilename: an absent or empty name gives the default as
     * it is; any other is resolved against the statement's directory. */
    if (!p || !p->strings[0][0]) {
        if (!def) def = "";
        if (strlen(def) + 1 > size)
            return mt_error_param(err, MT_ERR_LIMIT, name, "default file name too long");
        memcpy(out, def, strlen(def) + 1);
        return MT_OK;
    }
    {
        mt_error why;
        mt_error_clear(&why);
        st = mt__path_join(p->dir, p->strings[0], out, size, &why);
        if (st != MT_OK) {
            mt_error_param(err, st, name, "%s", why.message);
            return fail(p, st, err);
        }
    }
    return MT_OK;
}

static mt_status one_vec(const mt_paramset *ps, const char *name, mt_param_type t, mt_vec3 def,
                         mt_vec3 *out, mt_error *err)
{
    const mt_param *p;
    mt_status st = lookup(ps, name, t, 1, &p, err);
    *out = p ? mt_v3((mt_real)p->reals[0], (mt_real)p->reals[1], (mt_real)p->reals[2]) : def;
    return st;
}

mt_status mt_params_point(const mt_paramset *ps, const char *name, mt_vec3 def, mt_vec3 *out,
                          mt_error *err)
{
    return one_vec(ps, name, MT_PARAM_POINT, def, out, err);
}

mt_status mt_params_vector(const mt_paramset *ps, const char *name, mt_vec3 def, mt_vec3 *out,
                           mt_error *err)
{
    return one_vec(ps, name, MT_PARAM_VECTOR, def, out, err);
}

mt_status mt_params_normal(const mt_paramset *ps, const char *name, mt_vec3 def, mt_vec3 *out,
                           mt_error *err)
{
    return one_vec(ps, name, MT_PARAM_NORMAL, def, out, err);
}

mt_status mt_params_rgb(const mt_paramset *ps, const char *name, mt_rgb def, mt_rgb *out,
                        mt_error *err)
{
    const mt_param *p;
    mt_status st = lookup(ps, name, MT_PARAM_SPECTRUM, 1, &p, err);
    *out = p ? mt_rgb_make((mt_real)p->reals[0], (mt_real)p->reals[1], (mt_real)p->reals[2]) : def;
    return st;
}

static mt_status array_of(const mt_paramset *ps, const char *name, mt_param_type t,
                          const double **values, int *count, mt_error *err)
{
    const mt_param *p;
    mt_status st = lookup(ps, name, t, 0, &p, err);
    *values = p ? p->reals : NULL;
    *count = p ? p->count : 0;
    return st;
}

mt_status mt_params_floats(const mt_paramset *ps, const char *name, const double **values,
                           int *count, mt_error *err)
{
    return array_of(ps, name, MT_PARAM_FLOAT, values, count, err);
}

mt_status mt_params_points(const mt_paramset *ps, const char *name, const double **values,
                           int *count, mt_error *err)
{
    return array_of(ps, name, MT_PARAM_POINT, values, count, err);
}

mt_status mt_params_normals(const mt_paramset *ps, const char *name, const double **values,
                            int *count, mt_error *err)
{
    return array_of(ps, name, MT_PARAM_NORMAL, values, count, err);
}

mt_status mt_params_vectors(const mt_paramset *ps, const char *name, const double **values,
                            int *count, mt_error *err)
{
    return array_of(ps, name, MT_PARAM_VECTOR, values, count, err);
}

mt_status mt_params_ints(const mt_paramset *ps, const char *name, const int **values,
                         int *count, mt_error *err)
{
    const mt_param *p;
    mt_status st = lookup(ps, name, MT_PARAM_INTEGER, 0, &p, err);
    *values = p ? p->ints : NULL;
    *count = p ? p->count : 0;
    return st;
}

void mt_paramset_report_unused(const mt_paramset *ps, mt_warning_fn warn, void *ctx)
{
    /* pbrt-v2 ParamSet::ReportUnused goes through its per-type lists in this
     * order; within a type, in the order the parameters were given. */
    static const mt_param_type order[] = {MT_PARAM_INTEGER, MT_PARAM_BOOL,    MT_PARAM_FLOAT,
                                          MT_PARAM_POINT,   MT_PARAM_VECTOR,  MT_PARAM_NORMAL,
                                          MT_PARAM_SPECTRUM, MT_PARAM_STRING, MT_PARAM_TEXTURE};
    char msg[320];
    size_t k;
    int i;
    if (!ps || !warn) return;
    for (k = 0; k < sizeof order / sizeof order[0]; ++k)
        for (i = 0; i < ps->n; ++i) {
            const entry *e = &ps->e[i];
            if (e->used || e->p.type != order[k]) continue;
            snprintf(msg, sizeof msg, "Parameter \"%s\" not used", e->p.name);
            warn(ctx, e->p.file, e->p.line, msg);
        }
}
