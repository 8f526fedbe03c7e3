/*
 * pbrt-v2's graphics state (api.cpp): the current transform pair
 * (curTransform[0] at the start time, [1] at the end time, each changed
 * only while its ActiveTransform bit is set), named coordinate systems, and
 * a stack of what AttributeBegin, TransformBegin and ObjectBegin save. Every
 * transform statement post-multiplies, as pbrt-v2's curTransform[i] =
 * curTransform[i] * T does. The Texture, Material and named-material
 * statements are in state_material.c.
 */
#include <string.h>
#include "core/alloc.h"
#include "params/numcheck.h"
#include "params/state_internal.h"

#define START_BIT 1u
#define END_BIT 2u
#define ALL_BITS 3u

typedef enum frame_kind { FRAME_ATTRIBUTE, FRAME_TRANSFORM, FRAME_OBJECT } frame_kind;
static const char *const frame_begin[] = {"AttributeBegin", "TransformBegin", "ObjectBegin"};
static const char *const frame_end[] = {"AttributeEnd", "TransformEnd", "ObjectEnd"};

struct mt__frame {
    frame_kind kind;
    mt_transform t[2];
    unsigned active;
    mt__gstate g; /* not for TransformBegin */
    char *file;   /* where the Begin was */
    int line;
};

struct mt__coordsys {
    char *name;
    mt_transform t[2];
};

static void reset_transforms(mt_state *s)
{
    s->t[0] = s->t[1] = mt_transform_identity();
    s->active = ALL_BITS;
}

mt_state *mt_state_create(mt_mode mode)
{
    mt_state *s = mt__calloc(1, sizeof *s);
    if (!s) return NULL;
    s->mode = mode;
    reset_transforms(s);
    if (!mt__gstate_init(&s->g)) {
        mt_state_destroy(s);
        return NULL;
    }
    return s;
}

static void pop_frame(mt_state *s, int restore)
{
    struct mt__frame *f = &s->stack[--s->depth];
    if (restore) {
        s->t[0] = f->t[0];
        s->t[1] = f->t[1];
        s->active = f->active;
    }
    if (f->kind != FRAME_TRANSFORM) {
        if (restore) {
            mt__gstate_free(&s->g);
            s->g = f->g;
        } else {
            mt__gstate_free(&f->g);
        }
    }
    mt__free(f->file);
}

static void clear_coordsys(mt_state *s)
{
    int i;
    for (i = 0; i < s->ncs; ++i) mt__free(s->cs[i].name);
    s->ncs = 0;
}

void mt_state_destroy(mt_state *s)
{
    if (!s) return;
    while (s->depth) pop_frame(s, 0);
    mt__free(s->stack);
    mt__gstate_free(&s->g);
    clear_coordsys(s);
    mt__free(s->cs);
    mt__free(s);
}

void mt_state_set_mode(mt_state *s, mt_mode mode) { s->mode = mode; }
mt_mode mt_state_mode(const mt_state *s) { return s->mode; }

void mt_state_set_warning(mt_state *s, mt_warning_fn warn, void *ctx)
{
    s->warn = warn;
    s->warn_ctx = ctx;
}

const mt_transform *mt_state_transform(const mt_state *s) { return &s->t[0]; }
const mt_transform *mt_state_transform_end(const mt_state *s) { return &s->t[1]; }
const mt_texture_table *mt_state_textures(const mt_state *s) { return s->g.textures; }
int mt_state_depth(const mt_state *s) { return s->depth; }
int mt_state_reverse_orientation(const mt_state *s) { return s->g.reverse_orientation; }

const char *mt_state_area_light(const mt_state *s, const mt_paramset **params)
{
    if (params) *params = s->g.area_params ? s->g.area_params->ps : NULL;
    return s->g.area_light;
}

/* ---- transforms ---------------------------------------------------------- */

static int transform_finite(const mt_transform *t)
{
    int i, j;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j)
            if (!isfinite(t->m.m[i][j]) || !isfinite(t->minv.m[i][j])) return 0;
    return 1;
}

/* curTransform[i] = curTransform[i] * x (or = x) for the active times. */
static mt_status apply_transform(mt_state *s, const mt_statement *st, const mt_transform *x, int replace,
                       mt_error *err)
{
    mt_transform nt[2];
    int i;
    for (i = 0; i < 2; ++i) {
        nt[i] = s->t[i];
        if (!(s->active & (1u << i))) continue;
        nt[i] = replace ? *x : mt_transform_compose(&s->t[i], x);
        if (!transform_finite(&nt[i]))
            return mt__state_fail(st, err, MT_ERR_INVALID,
                                  "%s: the current transform (or its inverse) overflows",
                                  st->directive);
    }
    s->t[0] = nt[0];
    s->t[1] = nt[1];
    return MT_OK;
}

/* A statement argument as pbrt-v2 has it: the lexer's (float)atof. */
static mt_real arg(const mt_statement *st, int i) { return (mt_real)st->args[i].number; }

/* The 16 numbers of Transform/ConcatTransform: pbrt-v2 builds
 * Matrix4x4(tr[0], tr[4], tr[8], tr[12], tr[1], ...), the transpose of the
 * list read row by row. */
static mt_status matrix_arg(const mt_statement *st, mt_transform *out, mt_error *err)
{
    double m[16];
    int i, j;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j) {
            volatile mt_real v = arg(st, j * 4 + i); /* rounded as pbrt-v2's float */
            m[i * 4 + j] = v;
        }
    if (mt_transform_from_matrix(m, out, err) != MT_OK)
        return mt__state_fail(st, err, MT_ERR_INVALID, "%s: %s", st->directive,
                              "the matrix is singular or not finite");
    return MT_OK;
}

static mt_status do_transform(mt_state *s, const mt_statement *st, mt_error *err)
{
    const char *d = st->directive;
    mt_transform x;
    mt_status rc;
    if (strcmp(d, "Identity") == 0) {
        x = mt_transform_identity();
        return apply_transform(s, st, &x, 1, err);
    }
    if (strcmp(d, "Translate") == 0) {
        x = mt_translate(mt_v3(arg(st, 0), arg(st, 1), arg(st, 2)));
        return apply_transform(s, st, &x, 0, err);
    }
    if (strcmp(d, "Scale") == 0) {
        if (arg(st, 0) == 0 || arg(st, 1) == 0 || arg(st, 2) == 0)
            return mt__state_fail(st, err, MT_ERR_INVALID,
                                  "Scale by zero: the transform would have no inverse");
        x = mt_scale(arg(st, 0), arg(st, 1), arg(st, 2));
        return apply_transform(s, st, &x, 0, err);
    }
    if (strcmp(d, "Rotate") == 0) {
        if (arg(st, 1) == 0 && arg(st, 2) == 0 && arg(st, 3) == 0)
            return mt__state_fail(st, err, MT_ERR_INVALID, "Rotate about a zero axis");
        x = mt_rotate(arg(st, 0), mt_v3(arg(st, 1), arg(st, 2), arg(st, 3)));
        return apply_transform(s, st, &x, 0, err);
    }
    if (strcmp(d, "LookAt") == 0) {
        mt_error why;
        mt_error_clear(&why);
        if (mt_look_at(mt_v3(arg(st, 0), arg(st, 1), arg(st, 2)),
                       mt_v3(arg(st, 3), arg(st, 4), arg(st, 5)),
                       mt_v3(arg(st, 6), arg(st, 7), arg(st, 8)), &x, &why) != MT_OK)
            return mt__state_fail(st, err, MT_ERR_INVALID, "%s", why.message);
        return apply_transform(s, st, &x, 0, err);
    }
    rc = matrix_arg(st, &x, err);
    if (rc != MT_OK) return rc;
    return apply_transform(s, st, &x, strcmp(d, "Transform") == 0, err);
}

static struct mt__coordsys *find_coordsys(const mt_state *s, const char *name)
{
    int i;
    for (i = 0; i < s->ncs; ++i)
        if (strcmp(s->cs[i].name, name) == 0) return &s->cs[i];
    return NULL;
}

/* namedCoordinateSystems[name] = t (both times). */
static mt_status define_coordsys(mt_state *s, const mt_statement *st, const char *name,
                                 const mt_transform t[2], mt_error *err)
{
    struct mt__coordsys *c = find_coordsys(s, name);
    if (!c) {
        struct mt__coordsys *cs = mt__grow(s->cs, &s->cap_cs, s->ncs + 1, sizeof *cs);
        if (!cs) return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
        s->cs = cs;
        c = &s->cs[s->ncs];
        c->name = mt__strdup(name);
        if (!c->name) return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
        s->ncs++;
    }
    c->t[0] = t[0];
    c->t[1] = t[1];
    return MT_OK;
}

static mt_status do_coordsys(mt_state *s, const mt_statement *st, mt_error *err)
{
    const char *name = st->args[0].string;
    struct mt__coordsys *c;
    if (strcmp(st->directive, "CoordinateSystem") == 0) return define_coordsys(s, st, name, s->t, err);
    c = find_coordsys(s, name);
    if (!c)
        return mt__state_fail(st, err, MT_ERR_NOT_FOUND,
                              "CoordSysTransform: no coordinate system \"%.100s\" (CoordinateSystem "
                              "names one; \"camera\" exists after Camera, \"world\" after "
                              "WorldBegin)", name);
    /* pbrt-v2: curTransform = namedCoordinateSystems[name], both times */
    s->t[0] = c->t[0];
    s->t[1] = c->t[1];
    return MT_OK;
}

/* ---- the stack ----------------------------------------------------------- */

static mt_status push_frame(mt_state *s, const mt_statement *st, frame_kind kind, mt_error *err)
{
    struct mt__frame *f = mt__grow(s->stack, &s->cap, s->depth + 1, sizeof *f);
    if (!f) return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
    s->stack = f;
    f = &s->stack[s->depth];
    memset(f, 0, sizeof *f);
    f->kind = kind;
    f->t[0] = s->t[0];
    f->t[1] = s->t[1];
    f->active = s->active;
    f->line = st->line;
    if ((st->file && !(f->file = mt__strdup(st->file))) ||
        (kind != FRAME_TRANSFORM && !mt__gstate_copy(&f->g, &s->g))) {
        mt__free(f->file);
        return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
    }
    s->depth++;
    return MT_OK;
}

static mt_status pop(mt_state *s, const mt_statement *st, frame_kind kind, mt_error *err)
{
    const struct mt__frame *f = s->depth ? &s->stack[s->depth - 1] : NULL;
    if (!f)
        return mt__state_fail(st, err, MT_ERR_INVALID, "%s without a matching %s",
                              frame_end[kind], frame_begin[kind]);
    if (f->kind != kind)
        return mt__state_fail(st, err, MT_ERR_INVALID, "%s closes the %s of %s:%d (expected %s)",
                              frame_end[kind], frame_begin[f->kind], f->file ? f->file : "?",
                              f->line, frame_end[f->kind]);
    pop_frame(s, 1);
    return MT_OK;
}

static mt_status do_object_begin(mt_state *s, const mt_statement *st, mt_error *err)
{
    int i;
    for (i = 0; i < s->depth; ++i)
        if (s->stack[i].kind == FRAME_OBJECT)
            return mt__state_fail(st, err, MT_ERR_INVALID,
                                  "ObjectBegin inside the object begun at %s:%d",
                                  s->stack[i].file ? s->stack[i].file : "?", s->stack[i].line);
    return push_frame(s, st, FRAME_OBJECT, err);
}

/* pbrt-v2 pbrtWorldEnd: warns of open blocks, then starts afresh. */
static mt_status do_world_end(mt_state *s, const mt_statement *st, mt_error *err)
{
    mt__gstate fresh;
    while (s->depth) {
        const struct mt__frame *f = &s->stack[s->depth - 1];
        mt__state_warn(s, st, "Missing end to %s at %s:%d", frame_begin[f->kind],
                       f->file ? f->file : "?", f->line);
        pop_frame(s, 0);
    }
    if (!mt__gstate_init(&fresh)) {
        mt__gstate_free(&fresh);
        return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
    }
    mt__gstate_free(&s->g);
    s->g = fresh;
    reset_transforms(s);
    clear_coordsys(s);
    return MT_OK;
}

/* ---- dispatch ------------------------------------------------------------ */

/* Whether st's positional arguments have the shape want ('n' number, 's'
 * string, "16" for 16 numbers): statements may come from elsewhere than
 * the parser. */
static int shape_ok(const mt_statement *st, const char *want)
{
    int i, n = strcmp(want, "16") == 0 ? 16 : (int)strlen(want);
    if (st->nargs != n || (n && !st->args)) return 0;
    for (i = 0; i < n; ++i) {
        int is_string = n == 16 ? 0 : want[i] == 's';
        if (st->args[i].is_string != is_string || (is_string && !st->args[i].string) ||
            (!is_string && !mt__fits_real(st->args[i].number)))
            return 0;
    }
    return 1;
}

typedef enum handling { HANDLED, SHARED } handling;

typedef struct verb {
    const char *name;
    const char *args;
    handling handling;
    mt_status (*fn)(mt_state *s, const mt_statement *st, mt_error *err);
} verb;

static mt_status v_push_attr(mt_state *s, const mt_statement *st, mt_error *err)
{
    return push_frame(s, st, FRAME_ATTRIBUTE, err);
}
static mt_status v_pop_attr(mt_state *s, const mt_statement *st, mt_error *err)
{
    return pop(s, st, FRAME_ATTRIBUTE, err);
}
static mt_status v_push_xf(mt_state *s, const mt_statement *st, mt_error *err)
{
    return push_frame(s, st, FRAME_TRANSFORM, err);
}
static mt_status v_pop_xf(mt_state *s, const mt_statement *st, mt_error *err)
{
    return pop(s, st, FRAME_TRANSFORM, err);
}
static mt_status v_pop_obj(mt_state *s, const mt_statement *st, mt_error *err)
{
    return pop(s, st, FRAME_OBJECT, err);
}

static mt_status v_active(mt_state *s, const mt_statement *st, mt_error *err)
{
    const char *k = st->args[0].string;
    if (strcmp(k, "All") == 0)
        s->active = ALL_BITS;
    else if (strcmp(k, "StartTime") == 0)
        s->active = START_BIT;
    else if (strcmp(k, "EndTime") == 0)
        s->active = END_BIT;
    else
        return mt__state_fail(st, err, MT_ERR_INVALID,
                              "ActiveTransform: expected All, StartTime or EndTime");
    return MT_OK;
}

static mt_status v_camera(mt_state *s, const mt_statement *st, mt_error *err)
{
    /* pbrt-v2 pbrtCamera: namedCoordinateSystems["camera"] = Inverse(curTransform) */
    mt_transform inv[2];
    inv[0] = mt_transform_inverse(&s->t[0]);
    inv[1] = mt_transform_inverse(&s->t[1]);
    return define_coordsys(s, st, "camera", inv, err);
}

static mt_status v_world_begin(mt_state *s, const mt_statement *st, mt_error *err)
{
    reset_transforms(s);
    return define_coordsys(s, st, "world", s->t, err);
}

static mt_status v_reverse(mt_state *s, const mt_statement *st, mt_error *err)
{
    s->g.reverse_orientation = !s->g.reverse_orientation;
    return MT_OK;
}

static const verb verbs[] = {
    {"Identity", "", HANDLED, do_transform},
    {"Translate", "nnn", HANDLED, do_transform},
    {"Scale", "nnn", HANDLED, do_transform},
    {"Rotate", "nnnn", HANDLED, do_transform},
    {"LookAt", "nnnnnnnnn", HANDLED, do_transform},
    {"Transform", "16", HANDLED, do_transform},
    {"ConcatTransform", "16", HANDLED, do_transform},
    {"CoordinateSystem", "s", HANDLED, do_coordsys},
    {"CoordSysTransform", "s", HANDLED, do_coordsys},
    {"ActiveTransform", "s", HANDLED, v_active},
    {"AttributeBegin", "", HANDLED, v_push_attr},
    {"AttributeEnd", "", HANDLED, v_pop_attr},
    {"TransformBegin", "", HANDLED, v_push_xf},
    {"TransformEnd", "", HANDLED, v_pop_xf},
    {"ReverseOrientation", "", HANDLED, v_reverse},
    {"Texture", "sss", HANDLED, mt__state_texture},
    {"Material", "s", HANDLED, mt__state_material},
    {"MakeNamedMaterial", "s", HANDLED, mt__state_make_named},
    {"NamedMaterial", "s", HANDLED, mt__state_named},
    {"AreaLightSource", "s", HANDLED, mt__state_area_light},
    {"Camera", "s", SHARED, v_camera},
    {"WorldBegin", "", SHARED, v_world_begin},
    {"WorldEnd", "", SHARED, do_world_end},
    {"ObjectBegin", "s", SHARED, do_object_begin},
    {"ObjectEnd", "", SHARED, v_pop_obj},
};

mt_status mt_state_apply(mt_state *s, const mt_statement *st, int *handled, mt_error *err)
{
    size_t i;
    mt_error_clear(err);
    if (handled) *handled = 0;
    if (!s || !st || !st->directive)
        return mt_error_set(err, MT_ERR_INVALID, "mt_state_apply: no state or statement");
    for (i = 0; i < sizeof verbs / sizeof verbs[0]; ++i) {
        const verb *v = &verbs[i];
        mt_status rc;
        if (strcmp(v->name, st->directive) != 0) continue;
        if (!shape_ok(st, v->args))
            return mt__state_fail(st, err, MT_ERR_INVALID, "%s: wrong arguments (expected %s)",
                                  v->name, v->args[0] ? v->args : "none");
        rc = v->fn(s, st, err);
        if (rc == MT_OK && handled) *handled = v->handling == HANDLED;
        return rc;
    }
    return MT_OK;
}
