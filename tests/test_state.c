/*
 * pbrt-v2's graphics state: transform statements against hand-computed
 * matrices, the attribute and transform stacks, named coordinate systems,
 * ActiveTransform, Texture/Material/named materials, and the errors for
 * unbalanced or crossed Ends and degenerate transforms.
 */
#include <stdlib.h>
#include <string.h>
#include "materia/state.h"
#include "support/check.h"

/* ---- stand-ins for the textures module --------------------------------
 * src/textures/ is written in parallel (issue 3); until it is merged the
 * state's texture calls land here. These record what the state asked for
 * and count references, so that the test can check that the state binds,
 * copies and releases textures and tables correctly. Once the real module
 * is in the library, this block can go and the Texture checks can use real
 * textures ("constant" with "float value"). */
struct mt_texture {
    int refs;
    char cls[32];
    int is_float;
};
typedef struct stub_entry {
    char name[64];
    int is_float;
    mt_texture *t;
} stub_entry;
struct mt_texture_table {
    stub_entry *e;
    int n;
};
static int live_textures, live_tables;
static struct {
    int calls;
    char cls[32];
    int is_float;
    mt_transform xf;
    mt_texparams tp;
} created;

mt_texture *mt_texture_create(const char *class_name, int is_float, const mt_transform *tex2world,
                              const mt_texparams *tp, mt_error *err)
{
    mt_texture *t;
    mt_real v;
    created.calls++;
    snprintf(created.cls, sizeof created.cls, "%s", class_name);
    created.is_float = is_float;
    created.xf = *tex2world;
    created.tp = *tp;
    if (strcmp(class_name, "bogus") == 0) {
        mt_error_set(err, MT_ERR_NOT_FOUND, "texture class \"bogus\" unknown");
        return NULL;
    }
    /* a real texture reads its parameters: this one reads "value" */
    if (mt_params_float(tp->geom, "value", 0, &v, err) != MT_OK) return NULL;
    t = calloc(1, sizeof *t);
    t->refs = 1;
    t->is_float = is_float;
    snprintf(t->cls, sizeof t->cls, "%s", class_name);
    live_textures++;
    return t;
}

void mt_texture_destroy(mt_texture *t)
{
    if (t && --t->refs == 0) {
        live_textures--;
        free(t);
    }
}

mt_texture_table *mt_texture_table_create(void)
{
    mt_texture_table *t = calloc(1, sizeof *t);
    live_tables++;
    return t;
}

mt_texture_table *mt_texture_table_clone(const mt_texture_table *src)
{
    mt_texture_table *t = mt_texture_table_create();
    int i;
    t->e = calloc((size_t)src->n + 1, sizeof *t->e);
    for (i = 0; i < src->n; ++i) {
        t->e[i] = src->e[i];
        t->e[i].t->refs++;
    }
    t->n = src->n;
    return t;
}

void mt_texture_table_destroy(mt_texture_table *t)
{
    int i;
    for (i = 0; i < t->n; ++i) mt_texture_destroy(t->e[i].t);
    free(t->e);
    free(t);
    live_tables--;
}

mt_texture *mt_texture_table_get(const mt_texture_table *t, const char *name, int is_float)
{
    int i;
    for (i = 0; i < t->n; ++i)
        if (t->e[i].is_float == is_float && strcmp(t->e[i].name, name) == 0) return t->e[i].t;
    return NULL;
}

mt_status mt_texture_table_set(mt_texture_table *t, const char *name, mt_texture *tex,
                               mt_error *err)
{
    int i;
    tex->refs++; /* the table holds its own reference */
    for (i = 0; i < t->n; ++i)
        if (t->e[i].is_float == tex->is_float && strcmp(t->e[i].name, name) == 0) {
            mt_texture_destroy(t->e[i].t);
            t->e[i].t = tex;
            return MT_OK;
        }
    t->e = realloc(t->e, (size_t)(t->n + 1) * sizeof *t->e);
    snprintf(t->e[t->n].name, sizeof t->e[t->n].name, "%s", name);
    t->e[t->n].is_float = tex->is_float;
    t->e[t->n].t = tex;
    t->n++;
    return MT_OK;
}
/* ---- end of the stand-ins ---------------------------------------------- */

typedef struct warnings {
    int n;
    char last[512];
} warnings;

static void collect(void *ctx, const char *file, int line, const char *message)
{
    warnings *w = ctx;
    w->n++;
    snprintf(w->last, sizeof w->last, "%s:%d: %s", file ? file : "", line, message);
}

typedef struct run_ctx {
    mt_state *s;
    int handled; /* of the last statement */
} run_ctx;

static mt_status apply_cb(void *ctx, const mt_statement *st, mt_error *err)
{
    run_ctx *r = ctx;
    return mt_state_apply(r->s, st, &r->handled, err);
}

static mt_status run(mt_state *s, const char *text, mt_error *err)
{
    run_ctx r;
    r.s = s;
    r.handled = -1;
    return mt_parse_string(text, "t.pbrt", NULL, 1, NULL, apply_cb, &r, err);
}

static int handled_of(mt_state *s, const char *text)
{
    run_ctx r;
    mt_error err;
    r.s = s;
    r.handled = -1;
    if (mt_parse_string(text, "t.pbrt", NULL, 1, NULL, apply_cb, &r, &err) != MT_OK) return -2;
    return r.handled;
}

/* |m - want| entry by entry (want row-major), and m * minv = identity. */
static void check_matrix(const mt_transform *t, const double want[16], double tol,
                         const char *name)
{
    double worst = 0, inv = 0;
    int i, j, k;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j) {
            double d = fabs(t->m.m[i][j] - want[i * 4 + j]), p = 0;
            if (d > worst) worst = d;
            for (k = 0; k < 4; ++k) p += t->m.m[i][k] * t->minv.m[k][j];
            if (fabs(p - (i == j)) > inv) inv = fabs(p - (i == j));
        }
    t_check(worst <= tol && inv <= tol, name, "largest difference %g, m * minv off by %g", worst,
            inv);
}

static void test_transforms(void)
{
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_error err;
    mt_vec3 p;
    /* T(1,2,3) * S(2,3,4) * Rz(90): x -> 2y... by hand */
    static const double tsr[16] = {0, -2, 0, 1, 3, 0, 0, 2, 0, 0, 4, 3, 0, 0, 0, 1};
    /* LookAt eye (0,0,5) at the origin, up +y: world to camera */
    static const double look[16] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 5, 0, 0, 0, 1};
    static const double tr[16] = {1, 0, 0, 5, 0, 1, 0, 6, 0, 0, 1, 7, 0, 0, 0, 1};
    static const double id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    mt_status rc = run(s, "Translate 1 2 3 Scale 2 3 4 Rotate 90 0 0 1", &err);
    t_check(rc == MT_OK, "transforms: parse and apply", "%s", err.message);
    check_matrix(mt_state_transform(s), tsr, 1e-12, "Translate * Scale * Rotate post-multiply");
    run(s, "Identity", &err);
    check_matrix(mt_state_transform(s), id, 0, "Identity");
    run(s, "LookAt 0 0 5  0 0 0  0 1 0", &err);
    check_matrix(mt_state_transform(s), look, 1e-12, "LookAt: world to camera");
    p = mt_transform_point(mt_state_transform(s), mt_v3(0, 0, 0));
    t_check(p.x == 0 && p.y == 0 && p.z == 5, "LookAt: the target is 5 ahead", "%g %g %g", p.x,
            p.y, p.z);
    /* pbrt-v2's Transform takes the 16 numbers column by column */
    run(s, "Transform [1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1]", &err);
    check_matrix(mt_state_transform(s), tr, 1e-12, "Transform: translation in the last four");
    run(s, "Identity Translate 1 0 0 ConcatTransform [2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1]", &err);
    p = mt_transform_point(mt_state_transform(s), mt_v3(1, 1, 1));
    t_check(p.x == 3 && p.y == 2 && p.z == 2, "ConcatTransform post-multiplies", "%g %g %g", p.x,
            p.y, p.z);
    {
        double start[16];
        int i;
        for (i = 0; i < 16; ++i) start[i] = mt_state_transform(s)->m.m[i / 4][i % 4];
        check_matrix(mt_state_transform_end(s), start, 0,
                     "end transform follows without ActiveTransform");
    }
    mt_state_destroy(s);
}

static void fails(mt_state *s, const char *text, int line, mt_status status, const char *word,
                  const char *name)
{
    mt_error err;
    mt_status rc = run(s, text, &err);
    t_check(rc == status && strcmp(err.file, "t.pbrt") == 0 && err.line == line &&
                strstr(err.message, word) != NULL,
            name, "got %d at %s:%d: %s", rc, err.file, err.line, err.message);
}

static void test_transform_errors(void)
{
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_error err;
    int i;
    mt_status rc = MT_OK;
    fails(s, "Identity\nScale 1 0 1", 2, MT_ERR_INVALID, "Scale by zero", "Scale 0: error");
    fails(s, "Rotate 30 0 0 0", 1, MT_ERR_INVALID, "zero axis", "Rotate about a zero axis: error");
    fails(s, "Transform [1 0 0 0 0 1 0 0 0 0 0 0 0 0 0 1]", 1, MT_ERR_INVALID, "singular",
          "singular Transform: error");
    fails(s, "LookAt 0 0 0 0 0 1 0 0 1", 1, MT_ERR_INVALID, "parallel",
          "LookAt with up along the view: error");
    fails(s, "LookAt 1 1 1 1 1 1 0 0 1", 1, MT_ERR_INVALID, "coincide",
          "LookAt with eye at the target: error");
    run(s, "Identity", &err);
    for (i = 0; i < 12 && rc == MT_OK; ++i) rc = run(s, "Scale 1e38 1e38 1e38", &err);
    t_check(rc == MT_ERR_INVALID && strstr(err.message, "overflows") && i >= 8,
            "a transform that overflows double: error", "after %d: %s", i, err.message);
    t_check(mt_transform_is_identity(mt_state_transform(s)) == 0 &&
                isfinite(mt_state_transform(s)->m.m[0][0]),
            "after the error the transform is unchanged and finite", "%g",
            mt_state_transform(s)->m.m[0][0]);
    mt_state_destroy(s);
}

static void test_stack(void)
{
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_error err;
    mt_material_spec m;
    const mt_paramset *alp;
    mt_status rc = run(s,
                       "Translate 1 0 0\n"
                       "AttributeBegin\n"
                       "  Translate 0 1 0 Material \"plastic\" ReverseOrientation\n"
                       "  AreaLightSource \"area\" \"rgb L\" [1 1 1]\n"
                       "  TransformBegin Translate 0 0 1 Material \"glass\" TransformEnd\n",
                       &err);
    mt_vec3 p = mt_transform_point(mt_state_transform(s), mt_v3(0, 0, 0));
    t_check(rc == MT_OK && mt_state_depth(s) == 1 && p.x == 1 && p.y == 1 && p.z == 0,
            "TransformEnd restores the transform only", "%s: %g %g %g", err.message, p.x, p.y, p.z);
    mt_state_material(s, &m);
    t_check(strcmp(m.type, "glass") == 0 && mt_state_reverse_orientation(s) == 1 &&
                strcmp(mt_state_area_light(s, &alp), "area") == 0 && mt_paramset_find(alp, "L"),
            "inside: material, orientation, area light as set", "%s", m.type);
    rc = run(s, "AttributeEnd", &err);
    p = mt_transform_point(mt_state_transform(s), mt_v3(0, 0, 0));
    mt_state_material(s, &m);
    t_check(rc == MT_OK && mt_state_depth(s) == 0 && p.x == 1 && p.y == 0 &&
                strcmp(m.type, "matte") == 0 && mt_paramset_count(m.material) == 0 &&
                mt_state_reverse_orientation(s) == 0 && mt_state_area_light(s, NULL) == NULL,
            "AttributeEnd restores transform and graphics state", "%s %g %g", m.type, p.x, p.y);
    fails(s, "AttributeEnd", 1, MT_ERR_INVALID, "without a matching AttributeBegin",
          "unbalanced AttributeEnd: error");
    fails(s, "TransformEnd", 1, MT_ERR_INVALID, "without a matching TransformBegin",
          "unbalanced TransformEnd: error");
    fails(s, "ObjectEnd", 1, MT_ERR_INVALID, "without a matching ObjectBegin",
          "unbalanced ObjectEnd: error");
    fails(s, "AttributeBegin\nTransformBegin\nAttributeEnd", 3, MT_ERR_INVALID,
          "closes the TransformBegin of t.pbrt:2", "crossed AttributeEnd: error");
    run(s, "TransformEnd AttributeEnd", &err);
    fails(s, "ObjectBegin \"a\"\nObjectBegin \"b\"", 2, MT_ERR_INVALID, "inside the object",
          "ObjectBegin inside an object: error");
    t_check(handled_of(s, "ObjectEnd") == 0 && mt_state_depth(s) == 0,
            "ObjectEnd pops and is left to the caller too", "depth %d", mt_state_depth(s));
    mt_state_destroy(s);
}

static void test_deep_nesting(void)
{
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    const int n = 20000;
    size_t len = (size_t)n * 40 + 16;
    char *text = malloc(len), *q = text;
    mt_error err;
    mt_status rc;
    int i;
    for (i = 0; i < n; ++i) q += sprintf(q, "AttributeBegin Translate 1 0 0\n");
    rc = run(s, text, &err);
    t_check(rc == MT_OK && mt_state_depth(s) == n &&
                mt_state_transform(s)->m.m[0][3] == n,
            "20000 nested AttributeBegin", "%s depth %d", err.message, mt_state_depth(s));
    q = text;
    for (i = 0; i < n; ++i) q += sprintf(q, "AttributeEnd\n");
    rc = run(s, text, &err);
    t_check(rc == MT_OK && mt_state_depth(s) == 0 && mt_state_transform(s)->m.m[0][3] == 0,
            "... and as many AttributeEnd", "%s", err.message);
    free(text);
    mt_state_destroy(s);
}

static void test_coordsys(void)
{
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_error err;
    mt_status rc;
    static const double cam2world[16] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 5, 0, 0, 0, 1};
    fails(s, "CoordSysTransform \"camera\"", 1, MT_ERR_NOT_FOUND, "no coordinate system \"camera\"",
          "CoordSysTransform camera before Camera: error");
    rc = run(s, "Translate 4 0 0 CoordinateSystem \"four\" Identity Scale 2 2 2\n"
                "CoordSysTransform \"four\"", &err);
    t_check(rc == MT_OK && mt_state_transform(s)->m.m[0][3] == 4 &&
                mt_state_transform(s)->m.m[0][0] == 1,
            "CoordinateSystem / CoordSysTransform", "%s", err.message);
    t_check(handled_of(s, "Identity LookAt 0 0 5 0 0 0 0 1 0 Camera \"perspective\"") == 0,
            "Camera is left to the caller", "handled");
    run(s, "Identity CoordSysTransform \"camera\"", &err);
    check_matrix(mt_state_transform(s), cam2world, 1e-12,
                 "CoordSysTransform camera: the inverse of the camera transform");
    t_check(handled_of(s, "Translate 1 1 1 WorldBegin") == 0 &&
                mt_transform_is_identity(mt_state_transform(s)),
            "WorldBegin resets the transform, left to the caller", "not identity");
    rc = run(s, "Translate 1 1 1 CoordSysTransform \"world\"", &err);
    t_check(rc == MT_OK && mt_transform_is_identity(mt_state_transform(s)),
            "coordinate system world", "%s", err.message);
    mt_state_destroy(s);
}

static void test_active_transform(void)
{
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_error err;
    mt_status rc = run(s, "ActiveTransform EndTime Translate 1 0 0 ActiveTransform All\n"
                          "Translate 0 1 0 ActiveTransform StartTime Translate 0 0 1", &err);
    const mt_transform *a = mt_state_transform(s), *b = mt_state_transform_end(s);
    t_check(rc == MT_OK && a->m.m[0][3] == 0 && a->m.m[1][3] == 1 && a->m.m[2][3] == 1 &&
                b->m.m[0][3] == 1 && b->m.m[1][3] == 1 && b->m.m[2][3] == 0,
            "ActiveTransform limits changes to one time", "start %g %g %g end %g %g %g",
            a->m.m[0][3], a->m.m[1][3], a->m.m[2][3], b->m.m[0][3], b->m.m[1][3], b->m.m[2][3]);
    run(s, "AttributeBegin ActiveTransform All AttributeEnd Translate 5 0 0", &err);
    t_check(mt_state_transform(s)->m.m[0][3] == 5 && mt_state_transform_end(s)->m.m[0][3] == 1,
            "AttributeEnd restores the active transforms", "%g %g",
            mt_state_transform(s)->m.m[0][3], mt_state_transform_end(s)->m.m[0][3]);
    mt_state_destroy(s);
}

static void test_textures(void)
{
    mt_state *s = mt_state_create(MT_MODE_CORRECTED);
    warnings w;
    mt_error err;
    mt_status rc;
    memset(&w, 0, sizeof w);
    mt_state_set_warning(s, collect, &w);
    memset(&created, 0, sizeof created);
    rc = run(s, "Scale 2 2 2\nTexture \"t\" \"float\" \"constant\" \"float value\" 0.5\n"
                "  \"float extra\" 1", &err);
    t_check(rc == MT_OK && created.calls == 1 && strcmp(created.cls, "constant") == 0 &&
                created.is_float == 1 && created.xf.m.m[0][0] == 2 &&
                created.tp.mode == MT_MODE_CORRECTED && created.tp.geom &&
                created.tp.geom == created.tp.material &&
                created.tp.textures == mt_state_textures(s),
            "Texture: class, type, transform, and the statement's list as both lists",
            "%s calls %d", err.message, created.calls);
    t_check(mt_texture_table_get(mt_state_textures(s), "t", 1) != NULL &&
                mt_texture_table_get(mt_state_textures(s), "t", 0) == NULL,
            "Texture: bound in the float namespace", "not bound");
    t_check(w.n == 1 && strstr(w.last, "t.pbrt:3: Parameter \"extra\" not used"),
            "Texture: unused parameters reported", "%d: %s", w.n, w.last);
    rc = run(s, "Texture \"t\" \"float\" \"constant\"", &err);
    t_check(rc == MT_OK && w.n == 2 && strstr(w.last, "Texture \"t\" being redefined"),
            "Texture: redefinition warned", "%s", w.last);
    rc = run(s, "AttributeBegin Texture \"c\" \"color\" \"checkerboard\" Texture \"d\" \"spectrum\" \"dots\"",
             &err);
    t_check(rc == MT_OK && mt_texture_table_get(mt_state_textures(s), "c", 0) &&
                mt_texture_table_get(mt_state_textures(s), "d", 0),
            "Texture: color and spectrum types", "%s", err.message);
    run(s, "AttributeEnd", &err);
    t_check(mt_texture_table_get(mt_state_textures(s), "c", 0) == NULL &&
                mt_texture_table_get(mt_state_textures(s), "t", 1) != NULL,
            "AttributeEnd restores the named textures", "c still bound");
    fails(s, "Texture \"t\" \"colour\" \"constant\"", 1, MT_ERR_INVALID, "type \"colour\" unknown",
          "Texture type other than float/color/spectrum: error");
    fails(s, "\nTexture \"t\" \"float\" \"bogus\"", 2, MT_ERR_NOT_FOUND, "bogus",
          "Texture: the texture module's error, located at the statement");
    rc = run(s, "Texture \"t\" \"float\" \"constant\"\n \"string value\" \"x\"", &err);
    t_check(rc == MT_ERR_INVALID && err.line == 2 && err.column == 2 &&
                strcmp(err.param, "value") == 0,
            "Texture: a parameter error keeps the parameter's location", "%d:%d %s", err.line,
            err.column, err.message);
    mt_state_destroy(s);
}

static void test_materials(void)
{
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_error err;
    mt_material_spec m;
    mt_real f = 0;
    warnings w;
    mt_status rc = run(s,
                       "Material \"plastic\" \"float roughness\" 0.1\n"
                       "Translate 0 0 3 Texture \"k\" \"color\" \"constant\"\n"
                       "MakeNamedMaterial \"gold\" \"string type\" \"metal\" \"float roughness\" 0.2\n"
                       "Translate 0 0 1\n",
                       &err);
    if (!t_check(rc == MT_OK, "materials: parse and apply", "%s", err.message)) {
        mt_state_destroy(s);
        return;
    }
    mt_state_material(s, &m);
    t_check(m.name == NULL && strcmp(m.type, "plastic") == 0 && m.geom == NULL &&
                mt_params_float(m.material, "roughness", 0, &f, &err) == MT_OK &&
                f == (mt_real)0.1 && m.transform.m.m[2][3] == 4 &&
                m.textures == mt_state_textures(s),
            "Material: type and parameters; transform and textures current", "%s", m.type);
    rc = mt_state_named_material(s, "gold", &m, &err);
    t_check(rc == MT_OK && strcmp(m.name, "gold") == 0 && strcmp(m.type, "metal") == 0 &&
                mt_params_float(m.geom, "roughness", 0, &f, &err) == MT_OK &&
                f == (mt_real)0.2 && mt_paramset_find(m.material, "roughness") &&
                m.transform.m.m[2][3] == 3 && mt_texture_table_get(m.textures, "k", 0),
            "MakeNamedMaterial: its parameters, the current Material's, textures and transform "
            "then",
            "%s", err.message);
    memset(&w, 0, sizeof w);
    mt_paramset_report_unused(m.geom, collect, &w);
    t_check(w.n == 0, "MakeNamedMaterial: \"type\" counts as used", "%d: %s", w.n, w.last);
    run(s, "NamedMaterial \"gold\"", &err);
    mt_state_material(s, &m);
    t_check(m.name && strcmp(m.name, "gold") == 0, "NamedMaterial selects it", "%s", m.type);
    run(s, "Material \"matte\"", &err);
    mt_state_material(s, &m);
    t_check(m.name == NULL && strcmp(m.type, "matte") == 0, "Material clears the selection", "%s",
            m.type);
    fails(s, "NamedMaterial \"nope\"", 1, MT_ERR_NOT_FOUND, "no material of that name",
          "NamedMaterial undefined: error");
    fails(s, "MakeNamedMaterial \"x\" \"float roughness\" 1", 1, MT_ERR_INVALID, "string type",
          "MakeNamedMaterial without a type: error");
    fails(s, "MakeNamedMaterial \"x\" \"float type\" 1", 1, MT_ERR_INVALID, "float type",
          "MakeNamedMaterial with a non-string type: error");
    run(s, "AttributeBegin MakeNamedMaterial \"inner\" \"string type\" \"glass\" AttributeEnd", &err);
    rc = mt_state_named_material(s, "inner", &m, &err);
    t_check(rc == MT_ERR_NOT_FOUND && mt_state_named_material(s, "gold", &m, &err) == MT_OK,
            "named materials are graphics state: AttributeEnd drops inner ones", "%d", rc);
    memset(&w, 0, sizeof w);
    mt_state_set_warning(s, collect, &w);
    run(s, "MakeNamedMaterial \"gold\" \"string type\" \"metal\"", &err);
    t_check(w.n == 1 && strstr(w.last, "redefined"), "named material redefinition warned", "%s",
            w.last);
    mt_state_destroy(s);
}

static void test_handled(void)
{
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_statement st;
    mt_arg args[2];
    mt_error err;
    int handled = -1;
    mt_status rc;
    warnings w;
    t_check(handled_of(s, "Shape \"sphere\"") == 0 && handled_of(s, "Translate 1 0 0") == 1 &&
                handled_of(s, "Material \"matte\"") == 1 && handled_of(s, "WorldBegin") == 0 &&
                handled_of(s, "LightSource \"point\"") == 0,
            "handled: the state's statements only", "wrong flag");
    memset(&st, 0, sizeof st);
    st.directive = "Translate";
    st.nargs = 2;
    args[0].is_string = args[1].is_string = 0;
    args[0].number = args[1].number = 1;
    st.args = args;
    st.file = "hand";
    st.line = 7;
    rc = mt_state_apply(s, &st, &handled, &err);
    t_check(rc == MT_ERR_INVALID && err.line == 7 && strstr(err.message, "wrong arguments"),
            "a hand-built statement with the wrong arguments: error", "%s", err.message);
    memset(&w, 0, sizeof w);
    mt_state_set_warning(s, collect, &w);
    rc = run(s, "AttributeBegin\nTranslate 1 2 3 Material \"glass\" WorldEnd", &err);
    t_check(rc == MT_OK && w.n == 1 && strstr(w.last, "Missing end to AttributeBegin at t.pbrt:1") &&
                mt_state_depth(s) == 0 && mt_transform_is_identity(mt_state_transform(s)),
            "WorldEnd: open blocks warned, state reset", "%d %s", w.n, w.last);
    mt_state_destroy(s);
}

/* Every allocation of a statement sequence fails in turn: MT_OK or
 * MT_ERR_NOMEM each time, and every texture and table released. */
static void test_alloc_failures(void)
{
    const char *text =
        "LookAt 0 0 5 0 0 0 0 1 0 Camera \"perspective\" WorldBegin\n"
        "AttributeBegin Texture \"t\" \"float\" \"constant\" \"float value\" 1\n"
        "Material \"plastic\" \"texture Kd\" \"t\" CoordinateSystem \"here\"\n"
        "MakeNamedMaterial \"m\" \"string type\" \"matte\" NamedMaterial \"m\"\n"
        "AreaLightSource \"area\" \"rgb L\" [1 1 1] TransformBegin Scale 2 2 2 TransformEnd\n"
        "AttributeEnd AttributeBegin WorldEnd\n";
    long n;
    int bad = 0, runs = 0;
    for (n = 0; n < 5000; ++n) {
        mt_state *s;
        mt_error err;
        mt_status rc;
        mt_alloc_fail_after(n);
        s = mt_state_create(MT_MODE_PBRT_V2);
        rc = s ? run(s, text, &err) : MT_ERR_NOMEM;
        mt_alloc_fail_after(-1);
        mt_state_destroy(s);
        if (rc == MT_OK) break;
        runs++;
        if (rc != MT_ERR_NOMEM) {
            bad++;
            printf("# allocation %ld: %d %s\n", n, rc, err.message);
        }
    }
    t_check(bad == 0 && n < 5000 && runs > 20, "state: every allocation failure reported",
            "%d wrong of %d", bad, runs);
    t_check(live_textures == 0 && live_tables == 0, "state: textures and tables all released",
            "%d textures, %d tables left", live_textures, live_tables);
}

int main(void)
{
    test_transforms();
    test_transform_errors();
    test_stack();
    test_deep_nesting();
    test_coordsys();
    test_active_transform();
    test_textures();
    test_materials();
    test_handled();
    test_alloc_failures();
    return t_status();
}
