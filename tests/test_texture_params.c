/*
 * Textures created from parameters (mt_texture_create, TextureParams):
 * every class by name with pbrt-v2's defaults, parameter names, the
 * "mapping" choice, geometry-before-material precedence, texture names
 * resolved in the table's two namespaces, the errors that name their
 * parameter, the used marks, and the mode and transform given.
 */
#include "materia/parser.h"
#include "support/tex_util.h"
#include "textures/texparams.h"

static mt_paramset *kept;

static mt_status keep(void *ctx, const mt_statement *st, mt_error *err)
{
    (void)ctx;
    mt_paramset_destroy(kept);
    kept = mt_paramset_clone(st->params);
    return kept ? MT_OK : mt_error_set(err, MT_ERR_NOMEM, "clone");
}

/* The parameter list written in text (pbrt-v2 syntax); a new list. */
static mt_paramset *params(const char *text)
{
    char buf[2048];
    mt_error err;
    mt_paramset *ps;
    snprintf(buf, sizeof buf, "Shape \"s\" %s\n", text);
    kept = NULL;
    if (mt_parse_string(buf, "test.pbrt", NULL, 1, NULL, keep, NULL, &err) != MT_OK) {
        printf("  cannot parse %s: %s\n", text, err.message);
        return mt_paramset_create();
    }
    ps = kept;
    kept = NULL;
    return ps;
}

static mt_texture_table *table;
static mt_error err;

static mt_texparams tparams(const mt_paramset *geom, const mt_paramset *mat, mt_mode mode)
{
    mt_texparams tp;
    tp.geom = geom;
    tp.material = mat;
    tp.textures = table;
    tp.mode = mode;
    return tp;
}

/* Creates class from material parameters mat (and geometry ones geom). */
static mt_texture *make(const char *cls, int is_float, const char *geom, const char *mat,
                        mt_mode mode, const mt_transform *xf)
{
    mt_paramset *g = geom ? params(geom) : NULL, *m = params(mat);
    mt_texparams tp = tparams(g, m, mode);
    mt_texture *t;
    mt_error_clear(&err);
    t = mt_texture_create(cls, is_float, xf, &tp, &err);
    mt_paramset_destroy(g);
    mt_paramset_destroy(m);
    return t;
}

static mt_real at(const mt_texture *t, mt_real u, mt_real v)
{
    mt_diffgeom dg = tu_dg(u, v, mt_v3(u, v, (mt_real)0.3));
    return mt_texture_eval_float(t, &dg);
}

static void check_value(const char *cls, int is_float, const char *mat, mt_real u, mt_real v,
                        double want, const char *name)
{
    mt_texture *t = make(cls, is_float, NULL, mat, MT_MODE_PBRT_V2, NULL);
    if (!t) {
        t_fail(name, "not created: %s", err.message);
        return;
    }
    t_near(at(t, u, v), want, 1e-6, name);
    mt_texture_destroy(t);
}

static void test_classes(void)
{
    int n, i, k, ok = 1;
    const char *const *names = mt_texture_classes(&n);
    for (i = 0; i < n; ++i)
        for (k = 0; k < 2; ++k) {
            mt_texture *t = make(names[i], k, NULL, "", MT_MODE_PBRT_V2, NULL);
            const mt_texture_kind *kind = mt_texture_kind_find(names[i]);
            /* imagemap needs a file */
            int expect_fail = (k && !mt_texture_kind_has_float(kind)) || !strcmp(names[i], "imagemap");
            if (!expect_fail && (!t || strcmp(mt_texture_class(t), names[i]) ||
                                 mt_texture_is_float(t) != k)) {
                printf("  %s %s: %s\n", names[i], k ? "float" : "spectrum", err.message);
                ok = 0;
            }
            if (expect_fail && t) ok = 0;
            mt_texture_destroy(t);
        }
    t_check(ok && n == mt_texture_kind_count() && n >= 12 && names[n] == NULL,
            "registry: every class (pbrt-v2's 12 at least), float and spectrum where pbrt-v2 has them", "-");
    t_check(!mt_texture_kind_has_float(&mt_uv_texture) && !mt_texture_kind_has_float(&mt_marble_texture) &&
                mt_texture_kind_has_float(&mt_checkerboard_texture),
            "registry: pbrt-v2 has no float uv or marble", "-");
    t_check(!make("uv", 1, NULL, "", MT_MODE_PBRT_V2, NULL) && strstr(err.message, "no float"),
            "registry: pbrt-v2 has no float uv texture", "%s", err.message);
    t_check(!make("marble", 1, NULL, "", MT_MODE_PBRT_V2, NULL) && strstr(err.message, "no float"),
            "registry: pbrt-v2 has no float marble texture", "%s", err.message);
    t_check(!make("bricks", 0, NULL, "", MT_MODE_PBRT_V2, NULL) && err.status == MT_ERR_NOT_FOUND,
            "registry: unknown class", "%s", err.message);
    t_check(!make("imagemap", 0, NULL, "", MT_MODE_PBRT_V2, NULL) &&
                !strcmp(err.param, "filename"),
            "imagemap: no filename is an error naming it", "%s", err.message);
}

/* pbrt-v2's defaults (the Create functions of its textures) and parameter names. */
static void test_defaults(void)
{
    mt_vec3 p = mt_v3((mt_real)0.4, (mt_real)0.7, (mt_real)0.3), zero = mt_v3(0, 0, 0);
    mt_texture *t;
    check_value("constant", 1, "", 0, 0, 1, "constant: value 1 by default");
    check_value("constant", 1, "\"float value\" 0.37", 0, 0, 0.37f, "constant: \"value\"");
    check_value("scale", 1, "", 0, 0, 1, "scale: tex1 = tex2 = 1 by default");
    check_value("scale", 1, "\"float tex1\" 0.5 \"float tex2\" 3", 0, 0, 1.5, "scale: tex1 tex2");
    check_value("mix", 1, "", 0, 0, 0.5, "mix: (1 - 0.5) 0 + 0.5 1 by default");
    check_value("mix", 1, "\"float amount\" 0.25 \"float tex1\" 2", 0, 0, 1.75,
                "mix: amount tex1 tex2");
    check_value("bilerp", 1, "", (mt_real)0.3, (mt_real)0.6, 0.6,
                "bilerp: v00 = v10 = 0, v01 = v11 = 1 by default");
    check_value("bilerp", 1, "\"float v10\" 2 \"float uscale\" 0.5 \"float udelta\" 0.25", 1, 0,
                1.5, "bilerp: v10, uscale, udelta");
    check_value("checkerboard", 1, "", (mt_real)0.5, (mt_real)0.5, 1,
                "checkerboard: tex1 = 1 on even checks by default");
    check_value("checkerboard", 1, "", (mt_real)1.5, (mt_real)0.5, 0,
                "checkerboard: tex2 = 0 on odd checks by default");
    check_value("checkerboard", 1, "\"float vscale\" 4 \"float vdelta\" 0.5", (mt_real)0.5,
                (mt_real)0.2, 0, "checkerboard: vscale, vdelta");
    check_value("checkerboard", 1, "\"integer dimension\" 3", (mt_real)0.5, (mt_real)1.5, 0,
                "checkerboard: dimension 3 checks the point");
    check_value("checkerboard", 1,
                "\"string mapping\" \"planar\" \"vector v1\" [0 0 1] \"vector v2\" [0 1 0]",
                (mt_real)1.5, (mt_real)0.5, 1, "checkerboard: planar mapping with v1 v2");
    t = make("fbm", 1, NULL, "", MT_MODE_PBRT_V2, NULL);
    t_near(at(t, p.x, p.y), mt__fbm(p, zero, zero, (mt_real)0.5, 8), 1e-7,
           "fbm: 8 octaves, roughness 0.5 by default");
    mt_texture_destroy(t);
    t = make("wrinkled", 1, NULL, "\"integer octaves\" 3 \"float roughness\" 0.7",
             MT_MODE_PBRT_V2, NULL);
    t_near(at(t, p.x, p.y), mt__turbulence(p, zero, zero, (mt_real)0.7, 3), 1e-7,
           "wrinkled: octaves, roughness");
    mt_texture_destroy(t);
    {
        mt_transform id = mt_transform_identity();
        mt_map3d m3 = mt__map3d(&id, MT_MODE_PBRT_V2);
        mt_texture *ref = mt__tex_marble(&m3, 8, (mt_real)0.5, 1, (mt_real)0.2, MT_MODE_PBRT_V2,
                                         &err);
        t = make("marble", 0, NULL, "", MT_MODE_PBRT_V2, NULL);
        t_check(t && at(t, p.x, p.y) == at(ref, p.x, p.y),
                "marble: octaves 8, roughness 0.5, scale 1, variation 0.2 by default", "-");
        mt_texture_destroy(t);
        mt_texture_destroy(ref);
    }
}

static void test_lookup_rules(void)
{
    mt_texture *a = tu_const(1, (mt_real)0.125, 0, 0), *c = tu_const(0, 1, 0, 0), *t;
    mt_texparams tp;
    mt_paramset *m;
    mt_texture_table_set(table, "a", a, &err);
    mt_texture_table_set(table, "c", c, &err);
    /* geometry first, then material */
    t = make("scale", 1, "\"float tex1\" 0.25", "\"float tex1\" 0.75", MT_MODE_PBRT_V2, NULL);
    t_check(t && at(t, 0, 0) == (mt_real)0.25, "texparams: geometry parameters first", "-");
    mt_texture_destroy(t);
    /* a texture anywhere beats a value (pbrt-v2 looks for textures first) */
    t = make("scale", 1, "\"float tex1\" 0.25", "\"texture tex1\" \"a\"", MT_MODE_PBRT_V2, NULL);
    t_check(t && at(t, 0, 0) == (mt_real)0.125, "texparams: a named texture before a value", "-");
    mt_texture_destroy(t);
    /* unknown name, and the other namespace */
    t = make("scale", 1, NULL, "\"texture tex2\" \"nope\"", MT_MODE_PBRT_V2, NULL);
    t_check(!t && err.status == MT_ERR_NOT_FOUND && !strcmp(err.param, "tex2") && err.line == 1,
            "texparams: an unknown texture name is an error naming the parameter", "%s",
            err.message);
    t = make("scale", 1, NULL, "\"texture tex2\" \"c\"", MT_MODE_PBRT_V2, NULL);
    t_check(!t && !strcmp(err.param, "tex2") && strstr(err.message, "spectrum"),
            "texparams: a spectrum texture where a float one is needed is an error", "%s",
            err.message);
    t = make("scale", 0, NULL, "\"texture tex1\" \"a\"", MT_MODE_PBRT_V2, NULL);
    t_check(!t && !strcmp(err.param, "tex1"),
            "texparams: a float texture where a spectrum one is needed is an error", "%s",
            err.message);
    t = make("scale", 1, NULL, "\"rgb tex1\" [1 1 1]", MT_MODE_PBRT_V2, NULL);
    t_check(!t && !strcmp(err.param, "tex1"), "texparams: a value of the wrong type is an error",
            "%s", err.message);
    /* the errors of the creators */
    t_check(!make("bilerp", 1, NULL, "\"string mapping\" \"polar\"", MT_MODE_PBRT_V2, NULL) &&
                !strcmp(err.param, "mapping"),
            "texparams: unknown mapping", "%s", err.message);
    t_check(!make("checkerboard", 1, NULL, "\"string aamode\" \"supersample\"", MT_MODE_PBRT_V2,
                  NULL) && !strcmp(err.param, "aamode"),
            "texparams: unknown aamode", "%s", err.message);
    t_check(!make("checkerboard", 1, NULL, "\"integer dimension\" 4", MT_MODE_PBRT_V2, NULL) &&
                !strcmp(err.param, "dimension"),
            "texparams: checkerboard dimension 4", "%s", err.message);
    t_check(!make("fbm", 1, NULL, "\"integer octaves\" -2", MT_MODE_PBRT_V2, NULL) &&
                !strcmp(err.param, "octaves"),
            "texparams: negative octaves", "%s", err.message);
    t_check(!make("imagemap", 0, NULL, "\"string filename\" \"x.png\" \"string wrap\" \"mirror\"",
                  MT_MODE_PBRT_V2, NULL) && !strcmp(err.param, "wrap"),
            "texparams: unknown wrap", "%s", err.message);
    /* the optional float texture (bumpmap) */
    m = params("\"texture bumpmap\" \"a\" \"float unused\" 1");
    tp = tparams(NULL, m, MT_MODE_PBRT_V2);
    t = NULL;
    t_check(mt_texparams_float_texture_opt(&tp, "bumpmap", &t, &err) == MT_OK && t == a,
            "texparams: an optional float texture present", "-");
    mt_texture_destroy(t);
    t_check(mt_texparams_float_texture_opt(&tp, "displacement", &t, &err) == MT_OK && !t,
            "texparams: an optional float texture absent", "-");
    mt_paramset_destroy(m);
    m = params("\"float bumpmap\" 0.5");
    tp.material = m;
    t_check(mt_texparams_float_texture_opt(&tp, "bumpmap", &t, &err) != MT_OK &&
                !strcmp(err.param, "bumpmap"),
            "texparams: a value where only a texture is read is an error", "%s", err.message);
    mt_paramset_destroy(m);
    mt_texture_destroy(a);
    mt_texture_destroy(c);
}

static int unused_count;
static void count_unused(void *ctx, const char *file, int line, const char *message)
{
    (void)ctx;
    (void)file;
    (void)line;
    (void)message;
    unused_count++;
}

static void test_used_marks(void)
{
    mt_paramset *g = params("\"float uscale\" 2"), *m = params("\"float uscale\" 3 \"float foo\" 1");
    mt_texparams tp = tparams(g, m, MT_MODE_PBRT_V2);
    mt_texture *t;
    t = mt_texture_create("checkerboard", 1, NULL, &tp, &err);
    unused_count = 0;
    mt_paramset_report_unused(m, count_unused, NULL);
    mt_paramset_report_unused(g, count_unused, NULL);
    t_check(t && unused_count == 1,
            "texparams: both lists' parameters count as used, unknown ones are reported",
            "%d unused", unused_count);
    mt_texture_destroy(t);
    mt_paramset_destroy(g);
    mt_paramset_destroy(m);
}

/* The mode and the declaring transform reach the mappings. */
static void test_mode_and_transform(void)
{
    mt_transform s2 = mt_scale(2, 2, 2);
    mt_texture *v2 = make("checkerboard", 1, NULL, "\"integer dimension\" 3", MT_MODE_PBRT_V2, &s2);
    mt_texture *fix = make("checkerboard", 1, NULL, "\"integer dimension\" 3", MT_MODE_CORRECTED,
                           &s2);
    mt_texture *dv2 = make("dots", 1, NULL, "", MT_MODE_PBRT_V2, NULL);
    mt_texture *dfix = make("dots", 1, NULL, "", MT_MODE_CORRECTED, NULL);
    mt_diffgeom dg = tu_dg(0, 0, mt_v3((mt_real)0.75, (mt_real)0.25, (mt_real)0.25));
    int i, differ = 1;
    /* p = (.75, .25, .25): 2p has floor sum 1 (tex2 = 0); p/2 has 0 (tex1 = 1) */
    t_check(v2 && fix && mt_texture_eval_float(v2, &dg) == 0 &&
                mt_texture_eval_float(fix, &dg) == 1,
            "texparams: 3D mapping by tex2world (pbrt-v2) or its inverse (corrected)", "-");
    for (i = 0; i < 200; ++i) {
        dg = tu_dg((mt_real)i * (mt_real)0.37, (mt_real)i * (mt_real)0.11, mt_v3(0, 0, 0));
        if (mt_texture_eval_float(dv2, &dg) + mt_texture_eval_float(dfix, &dg) != 1) differ = 0;
    }
    t_check(differ, "texparams: dots' inside/outside follow the mode (dots-inside)", "-");
    mt_texture_destroy(v2);
    mt_texture_destroy(fix);
    mt_texture_destroy(dv2);
    mt_texture_destroy(dfix);
}

int main(void)
{
    table = mt_texture_table_create();
    test_classes();
    test_defaults();
    test_lookup_rules();
    test_used_marks();
    test_mode_and_transform();
    mt_texture_table_destroy(table);
    mt_paramset_destroy(kept);
    return t_status();
}
