/* Geometry helpers for tests and benchmarks (see tgeom.h). */
#include <string.h>
#include "support/tgeom.h"

typedef struct one_shape {
    const mt_transform *o2w;
    int ro, nwarn;
    mt_mode mode;
    mt_shape *shape;
} one_shape;

static void count_warning(void *ctx, const char *file, int line, const char *msg)
{
    (void)file;
    (void)line;
    (void)msg;
    ((one_shape *)ctx)->nwarn++;
}

static mt_status take_shape(void *ctx, const mt_statement *st, mt_error *err)
{
    one_shape *o = ctx;
    mt_shape_options opt;
    memset(&opt, 0, sizeof opt);
    opt.warn = count_warning;
    opt.warn_ctx = o;
    opt.mode = o->mode;
    if (strcmp(st->directive, "Shape") != 0 || o->shape) return MT_OK;
    o->shape = mt_shape_from_statement(st, o->o2w, o->ro, &opt, err);
    return o->shape ? MT_OK : err->status;
}

mt_shape *t_shape(const char *text, const mt_transform *o2w, int reverse_orientation,
                  int *nwarn, mt_error *err)
{
    return t_shape_mode(text, o2w, reverse_orientation, MT_MODE_PBRT_V2, nwarn, err);
}

mt_shape *t_shape_mode(const char *text, const mt_transform *o2w, int reverse_orientation,
                       mt_mode mode, int *nwarn, mt_error *err)
{
    mt_transform id = mt_transform_identity();
    one_shape o;
    o.o2w = o2w ? o2w : &id;
    o.ro = reverse_orientation;
    o.mode = mode;
    o.nwarn = 0;
    o.shape = NULL;
    mt_error_clear(err);
    if (mt_parse_string(text, "<test>", NULL, 1, NULL, take_shape, &o, err) != MT_OK) {
        mt_shape_destroy(o.shape);
        return NULL;
    }
    if (nwarn) *nwarn = o.nwarn;
    if (!o.shape && err->status == MT_OK) mt_error_set(err, MT_ERR_NOT_FOUND, "no Shape in text");
    return o.shape;
}

/* ---- scene files -------------------------------------------------------------- */

#define DEPTH 64

typedef struct loader {
    mt_geometry *g;
    mt_transform stack[DEPTH];
    int ro_stack[DEPTH];
    int depth, ro, nshapes;
    mt_transform cur;
} loader;

static mt_status arg_numbers(const mt_statement *st, int n, double *v, mt_error *err)
{
    int i;
    if (st->nargs != n)
        return mt_error_set(err, MT_ERR_PARSE, "%s:%d: %s takes %d numbers", st->file, st->line,
                            st->directive, n);
    for (i = 0; i < n; ++i) v[i] = st->args[i].number;
    return MT_OK;
}

static mt_status load_statement(void *ctx, const mt_statement *st, mt_error *err)
{
    loader *l = ctx;
    const char *d = st->directive;
    double v[16];
    mt_transform t;
    mt_status rc;
    if (strcmp(d, "AttributeBegin") == 0 || strcmp(d, "TransformBegin") == 0) {
        if (l->depth == DEPTH) return mt_error_set(err, MT_ERR_LIMIT, "nesting too deep");
        l->stack[l->depth] = l->cur;
        l->ro_stack[l->depth++] = l->ro;
    } else if (strcmp(d, "AttributeEnd") == 0 || strcmp(d, "TransformEnd") == 0) {
        if (l->depth == 0) return mt_error_set(err, MT_ERR_PARSE, "unbalanced %s", d);
        l->cur = l->stack[--l->depth];
        if (d[0] == 'A') l->ro = l->ro_stack[l->depth];
    } else if (strcmp(d, "Identity") == 0 || strcmp(d, "WorldBegin") == 0) {
        l->cur = mt_transform_identity();
    } else if (strcmp(d, "ReverseOrientation") == 0) {
        l->ro = !l->ro;
    } else if (strcmp(d, "Translate") == 0 || strcmp(d, "Scale") == 0 ||
               strcmp(d, "Rotate") == 0) {
        if ((rc = arg_numbers(st, d[0] == 'R' ? 4 : 3, v, err)) != MT_OK) return rc;
        if (d[0] == 'T') t = mt_translate(mt_v3((mt_real)v[0], (mt_real)v[1], (mt_real)v[2]));
        else if (d[0] == 'S') t = mt_scale((mt_real)v[0], (mt_real)v[1], (mt_real)v[2]);
        else t = mt_rotate((mt_real)v[0], mt_v3((mt_real)v[1], (mt_real)v[2], (mt_real)v[3]));
        l->cur = mt_transform_compose(&l->cur, &t);
    } else if (strcmp(d, "Transform") == 0 || strcmp(d, "ConcatTransform") == 0) {
        double m[16];
        int i, j;
        if ((rc = arg_numbers(st, 16, v, err)) != MT_OK) return rc;
        /* pbrt-v2 reads the 16 numbers column by column */
        for (i = 0; i < 4; ++i)
            for (j = 0; j < 4; ++j) m[4 * i + j] = v[4 * j + i];
        if ((rc = mt_transform_from_matrix(m, &t, err)) != MT_OK) return rc;
        l->cur = d[0] == 'T' ? t : mt_transform_compose(&l->cur, &t);
    } else if (strcmp(d, "Shape") == 0) {
        mt_shape *s = mt_shape_from_statement(st, &l->cur, l->ro, NULL, err);
        if (!s) return err->status;
        if ((rc = mt_geometry_attach(l->g, s, err)) != MT_OK) return rc;
        l->nshapes++;
    }
    return MT_OK;
}

int t_load_shapes(const char *path, mt_geometry *g, mt_error *err)
{
    static loader l; /* large: kept off the stack (tests are single-threaded here) */
    memset(&l, 0, sizeof l);
    l.g = g;
    l.cur = mt_transform_identity();
    mt_error_clear(err);
    if (mt_parse_file(path, NULL, load_statement, &l, err) != MT_OK) return -1;
    return l.nshapes;
}

int t_brute_intersect(const mt_geometry *g, const mt_ray *r, mt_hit *hit)
{
    uint32_t si, ns = mt_geometry_shape_count(g), id = 0;
    mt_ray rr = *r;
    int found = 0;
    for (si = 0; si < ns; ++si) {
        const mt_shape *s = mt_geometry_shape(g, si);
        uint32_t j, n = mt_shape_prim_count(s);
        for (j = 0; j < n; ++j, ++id) {
            mt_hit h;
            if (!mt_shape_intersect(s, j, &rr, &h)) continue;
            if (h.t < rr.tmax || !found) {
                *hit = h;
                hit->id = id;
                rr.tmax = h.t;
                found = 1;
            }
        }
    }
    return found;
}
