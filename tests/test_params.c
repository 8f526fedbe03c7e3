/*
 * Typed parameter lists: every type pbrt-v2 declares, lookups with defaults,
 * replacement, the errors for a wrong type or count, unused reporting, file
 * names relative to the statement's directory.
 */
#include <string.h>
#include "materia/parser.h"
#include "materia/spectrum.h"
#include "support/check.h"
#include "support/tfiles.h"

/* The parameter list of the last statement parsed, kept. */
static mt_paramset *kept;

static mt_status keep(void *ctx, const mt_statement *st, mt_error *err)
{
    mt_paramset_destroy(kept);
    kept = mt_paramset_clone(st->params);
    return kept ? MT_OK : mt_error_set(err, MT_ERR_NOMEM, "clone");
}

/* Parses `Shape "s" <params>` from "test.pbrt" in dir; NULL on error (err). */
static const mt_paramset *params_of(const char *params, const char *dir, mt_error *err)
{
    char text[4096];
    snprintf(text, sizeof text, "Shape \"s\" %s\n", params);
    mt_paramset_destroy(kept);
    kept = NULL;
    if (mt_parse_string(text, "test.pbrt", dir, 1, NULL, keep, NULL, err) != MT_OK) return NULL;
    return kept;
}

/* Whether declaring params fails at file:line:column with the parameter and
 * a keyword in the message. */
static void declare_fails(const char *params, int column, const char *param, const char *word,
                          const char *name)
{
    mt_error err;
    const mt_paramset *ps = params_of(params, NULL, &err);
    t_check(!ps && err.status != MT_OK && strcmp(err.file, "test.pbrt") == 0 && err.line == 1 &&
                err.column == column && (!param || strcmp(err.param, param) == 0) &&
                strstr(err.message, word) != NULL,
            name, "got %s:%d:%d param \"%s\": %s", err.file, err.line, err.column, err.param,
            err.message);
}

static void test_types(void)
{
    mt_error err;
    const mt_paramset *ps = params_of(
        "\"float f\" 0.25 \"integer i\" [1 -2 3] \"bool b\" \"true\" \"bool nb\" [\"false\"]\n"
        " \"string s\" \"hello\" \"point P\" [1 2 3 4 5 6] \"vector v\" [0 0 1]\n"
        " \"normal N\" [0 1 0] \"rgb Kd\" [0.1 0.2 0.3] \"color Ks\" [0.5 0.5 0.5]\n"
        " \"xyz X\" [0.3 0.5 0.7] \"blackbody B\" [6500 2] \"spectrum S\" [400 1 500 2 600 3]\n"
        " \"texture tex\" \"checks\"",
        NULL, &err);
    /* initialized: a check's message may read them before its call runs */
    mt_real f = 0;
    int i = 0, b = 0, nb = 0;
    const int *ints = NULL;
    const double *pts = NULL;
    const char *s = "", *tex = "";
    mt_vec3 v = mt_v3(0, 0, 0), n = v, p = v;
    mt_rgb kd = mt_rgb_black(), ks = kd, x = kd, bb = kd, sp = kd, want = kd;
    double xyz[3] = {0.3, 0.5, 0.7}, sl[3] = {400, 500, 600}, sv[3] = {1, 2, 3};
    if (!t_check(ps != NULL, "params: every type parses", "%s", err.message)) return;
    t_check(mt_paramset_count(ps) == 14, "params: 14 parameters", "%d", mt_paramset_count(ps));
    t_check(mt_params_float(ps, "f", 9, &f, &err) == MT_OK && f == (mt_real)0.25, "float", "%g", f);
    t_check(mt_params_ints(ps, "i", &ints, &i, &err) == MT_OK && i == 3 && ints[1] == -2,
            "integer list", "%d", i);
    t_check(mt_params_bool(ps, "b", 0, &b, &err) == MT_OK && b == 1 &&
                mt_params_bool(ps, "nb", 1, &nb, &err) == MT_OK && nb == 0,
            "bool true/false", "%d %d", b, nb);
    t_check(mt_params_string(ps, "s", "x", &s, &err) == MT_OK && strcmp(s, "hello") == 0,
            "string", "%s", s);
    t_check(mt_params_points(ps, "P", &pts, &i, &err) == MT_OK && i == 2 && pts[5] == 6,
            "point list: 2 triples", "%d", i);
    t_check(mt_params_vector(ps, "v", mt_v3(0, 0, 0), &v, &err) == MT_OK && v.z == 1, "vector",
            "%g", v.z);
    t_check(mt_params_normal(ps, "N", mt_v3(0, 0, 0), &n, &err) == MT_OK && n.y == 1, "normal",
            "%g", n.y);
    t_check(mt_params_rgb(ps, "Kd", mt_rgb_gray(0), &kd, &err) == MT_OK &&
                kd.c[0] == (mt_real)0.1 && kd.c[2] == (mt_real)0.3,
            "rgb as given", "%g %g %g", kd.c[0], kd.c[1], kd.c[2]);
    t_check(mt_params_rgb(ps, "Ks", mt_rgb_gray(0), &ks, &err) == MT_OK && ks.c[1] == (mt_real)0.5,
            "color is rgb", "%g", ks.c[1]);
    want = mt_xyz_to_rgb(xyz);
    t_check(mt_params_rgb(ps, "X", mt_rgb_gray(0), &x, &err) == MT_OK && mt_rgb_equal(x, want),
            "xyz through pbrt-v2's XYZToRGB", "%g vs %g", x.c[0], want.c[0]);
    want = mt_blackbody_rgb(6500, 2);
    t_check(mt_params_rgb(ps, "B", mt_rgb_gray(0), &bb, &err) == MT_OK && mt_rgb_equal(bb, want),
            "blackbody as mt_blackbody_rgb", "%g vs %g", bb.c[0], want.c[0]);
    want = mt_spectrum_from_sampled(sl, sv, 3);
    t_check(mt_params_rgb(ps, "S", mt_rgb_gray(0), &sp, &err) == MT_OK && mt_rgb_equal(sp, want),
            "spectrum pairs: one spectrum", "%g vs %g", sp.c[0], want.c[0]);
    t_check(mt_paramset_find(ps, "S")->count == 1 &&
                strcmp(mt_paramset_find(ps, "S")->type_name, "spectrum") == 0 &&
                strcmp(mt_paramset_find(ps, "Ks")->type_name, "color") == 0,
            "type names as written", "%s", mt_paramset_find(ps, "Ks")->type_name);
    t_check(mt_params_texture(ps, "tex", &tex, &err) == MT_OK && strcmp(tex, "checks") == 0,
            "texture", "%s", tex ? tex : "(null)");
    p = mt_v3(7, 8, 9);
    t_check(mt_params_point(ps, "absent", p, &p, &err) == MT_OK && p.x == 7,
            "absent: the default", "%g", p.x);
    t_check(mt_params_texture(ps, "absent", &tex, &err) == MT_OK && tex == NULL,
            "absent texture: NULL", "%p", (const void *)tex);
    t_check(mt_params_float(NULL, "f", 3, &f, &err) == MT_OK && f == 3, "no list: the default",
            "%g", f);
}

/* pbrt-v2's ParamSet keeps a list per type: "texture Kd" and "rgb Kd" live
 * side by side (a material's GetSpectrumTexture takes the texture), while a
 * second "color Kd" replaces the "rgb Kd" (one list of spectra). */
static void test_lists_per_type(void)
{
    mt_error err;
    const char *tex = NULL;
    mt_rgb c = mt_rgb_black();
    mt_real f = 0;
    const mt_paramset *ps = params_of("\"texture Kd\" \"checks\" \"rgb Kd\" [0.9 0.9 0.9] \"color Kd\" [0.5 0.25 0.125] "
                                      "\"float Kd\" 3",
                                      NULL, &err);
    if (!t_check(ps != NULL, "lists per type: parse", "%s", err.message)) return;
    t_check(mt_paramset_count(ps) == 3 && mt_params_texture(ps, "Kd", &tex, &err) == MT_OK && tex &&
                !strcmp(tex, "checks") && mt_params_rgb(ps, "Kd", mt_rgb_gray(0), &c, &err) == MT_OK &&
                c.c[1] == (mt_real)0.25 && mt_params_float(ps, "Kd", 0, &f, &err) == MT_OK && f == 3,
            "params: texture, spectrum and float of one name side by side; the second spectrum replaces the first",
            "%d parameters, texture %s, rgb %g, float %g", mt_paramset_count(ps), tex ? tex : "(none)", c.c[1], f);
}

static void test_lookup_errors(void)
{
    mt_error err;
    mt_real f = 0;
    mt_rgb c;
    mt_vec3 v;
    int i = 0;
    const mt_paramset *ps =
        params_of("\"float three\" [1 2 3]\n\"rgb Kd\" [1 2 3 4 5 6] \"float r\" 1 "
                  "\"blackbody bb\" [3000 0.5 6500 0.5]", NULL, &err);
    if (!t_check(ps != NULL, "lookup errors: parse", "%s", err.message)) return;
    mt_status rc;
    /* each call before its check: the check's arguments are read in any order */
    rc = mt_params_float(ps, "three", 5, &f, &err);
    t_check(rc == MT_ERR_INVALID && f == 5 && strcmp(err.param, "three") == 0 &&
                strcmp(err.file, "test.pbrt") == 0 && err.line == 1 && err.column == 11 &&
                strstr(err.message, "found 3"),
            "one float, three given: error at the declaration", "%s:%d:%d %s: %s", err.file,
            err.line, err.column, err.param, err.message);
    rc = mt_params_rgb(ps, "Kd", mt_rgb_gray(0), &c, &err);
    t_check(rc == MT_ERR_INVALID && strstr(err.message, "6 values") && err.line == 2 &&
                err.column == 1,
            "one rgb, two given: error", "%d:%d: %s", err.line, err.column, err.message);
    /* pbrt-v2's FindOneSpectrum ignores a parameter of two items (the default
     * is used); materia says how many it found, counted as written */
    rc = mt_params_rgb(ps, "bb", mt_rgb_gray(0), &c, &err);
    t_check(rc == MT_ERR_INVALID && strstr(err.message, "one blackbody (a temperature and a scale), found 2"),
            "one blackbody, two given: error counting pairs", "%s", err.message);
    rc = mt_params_rgb(ps, "r", mt_rgb_gray(0), &c, &err);
    t_check(rc == MT_ERR_INVALID && strstr(err.message, "float r") &&
                strstr(err.message, "spectrum") && strcmp(err.param, "r") == 0 &&
                err.column == 24,
            "float read as a colour: error naming both", "%d %s", err.column, err.message);
    rc = mt_params_int(ps, "r", 0, &i, &err);
    t_check(rc == MT_ERR_INVALID && strstr(err.message, "integer"),
            "float read as an integer: error", "%s", err.message);
    rc = mt_params_point(ps, "r", mt_v3(0, 0, 0), &v, &err);
    t_check(rc == MT_ERR_INVALID, "float read as a point: error", "%s", err.message);
}

static void test_declare_errors(void)
{
    declare_fails("\"rgb Kd\" [0.5 0.5]", 11, "Kd", "threes", "rgb with 2 values");
    declare_fails("\"point P\" [1 2 3 4]", 11, "P", "threes", "point with 4 values");
    declare_fails("\"spectrum S\" [400 1 500]", 11, "S", "pairs", "spectrum pairs odd");
    declare_fails("\"blackbody B\" [6500]", 11, "B", "pairs", "blackbody without its scale");
    declare_fails("\"blackbody B\" [0 1]", 11, "B", "not positive", "blackbody at 0 K");
    declare_fails("\"blackbody B\" [20 1]", 11, "B", "too low", "blackbody that overflows");
    declare_fails("\"integer n\" 1.5", 11, "n", "not an integer", "integer with a fraction");
    declare_fails("\"integer n\" 3e9", 11, "n", "not an integer", "integer beyond an int");
    declare_fails("\"bool b\" \"yes\"", 11, "b", "\"true\" or \"false\"", "bool other than true/false");
    declare_fails("\"bool b\" 1", 11, "b", "quoted strings", "bool given a number");
    declare_fails("\"float f\" \"abc\"", 11, "f", "takes numbers", "float given a string");
    declare_fails("\"string s\" 2", 11, "s", "quoted strings", "string given a number");
    declare_fails("\"texture t\" [\"a\" \"b\"]", 11, "t", "one texture name", "texture with two names");
    declare_fails("\"point3 P\" [1 2 3]", 11, "P", "unknown parameter type", "point3 is not pbrt-v2");
    declare_fails("\"Kd\" 1", 11, NULL, "\"type name\"", "declaration without a type");
    declare_fails("\"floatKd\" 1", 11, NULL, "\"type name\"", "type glued to the name");
}

static void test_replacement(void)
{
    mt_error err;
    mt_real f = 0;
    mt_rgb c;
    const mt_paramset *ps =
        params_of("\"float a\" 1 \"float b\" 2 \"float a\" 3 \"rgb b\" [1 1 1]", NULL, &err);
    if (!t_check(ps != NULL, "replacement: parse", "%s", err.message)) return;
    t_check(mt_paramset_count(ps) == 3 && mt_params_float(ps, "a", 0, &f, &err) == MT_OK && f == 3,
            "a later parameter replaces an earlier one of its type", "count %d a %g", mt_paramset_count(ps), f);
    /* pbrt-v2 keeps one list per type: "rgb b" replaces no "float b" */
    t_check(mt_params_rgb(ps, "b", mt_rgb_gray(0), &c, &err) == MT_OK && c.c[0] == 1 &&
                mt_params_float(ps, "b", 0, &f, &err) == MT_OK && f == 2 &&
                strcmp(mt_paramset_at(ps, 2)->name, "b") == 0,
            "another type of the same name kept beside it (pbrt-v2's list per type)", "%s", err.message);
}

typedef struct warnings {
    int n;
    char last[256], file[256];
    int line;
} warnings;

static void collect(void *ctx, const char *file, int line, const char *message)
{
    warnings *w = ctx;
    w->n++;
    snprintf(w->last, sizeof w->last, "%s", message);
    snprintf(w->file, sizeof w->file, "%s", file ? file : "");
    w->line = line;
}

static void test_unused(void)
{
    mt_error err;
    warnings w;
    mt_real f;
    mt_paramset *copy;
    const mt_paramset *ps =
        params_of("\"float used\" 1\n \"float unused\" 2 \"float marked\" 3", NULL, &err);
    if (!t_check(ps != NULL, "unused: parse", "%s", err.message)) return;
    mt_params_float(ps, "used", 0, &f, &err);
    mt_paramset_mark_used(ps, "marked");
    memset(&w, 0, sizeof w);
    mt_paramset_report_unused(ps, collect, &w);
    t_check(w.n == 1 && strcmp(w.last, "Parameter \"unused\" not used") == 0 &&
                strcmp(w.file, "test.pbrt") == 0 && w.line == 2,
            "unused: pbrt-v2's message with file and line", "%d: %s at %s:%d", w.n, w.last,
            w.file, w.line);
    copy = mt_paramset_clone(ps);
    memset(&w, 0, sizeof w);
    mt_paramset_report_unused(copy, collect, &w);
    t_check(w.n == 1, "a clone keeps the used marks", "%d warnings", w.n);
    mt_params_float(copy, "unused", 0, &f, &err);
    memset(&w, 0, sizeof w);
    mt_paramset_report_unused(copy, collect, &w);
    t_check(w.n == 0, "a failed or successful lookup marks used", "%d warnings", w.n);
    mt_paramset_destroy(copy);
}

static void test_api(void)
{
    mt_paramset *ps = mt_paramset_create();
    mt_param p;
    mt_error err;
    double vals[3] = {1, 2, 3}, inf = 1e308 * 10;
    int bad_bool = 2;
    memset(&p, 0, sizeof p);
    p.name = "v";
    p.type = MT_PARAM_VECTOR;
    p.count = 1;
    p.reals = vals;
    mt_status rc = mt_paramset_add(ps, &p, &err);
    t_check(rc == MT_OK && strcmp(mt_paramset_find(ps, "v")->type_name, "vector") == 0,
            "api: add with a default type name", "%s", err.message);
    vals[1] = inf;
    rc = mt_paramset_add(ps, &p, &err);
    t_check(rc == MT_ERR_INVALID && strcmp(err.param, "v") == 0, "api: infinite value rejected",
            "%s", err.message);
    p.type = MT_PARAM_BOOL;
    p.ints = &bad_bool;
    rc = mt_paramset_add(ps, &p, &err);
    t_check(rc == MT_ERR_INVALID, "api: bool 2 rejected", "%s", err.message);
    p.name = "";
    rc = mt_paramset_add(ps, &p, &err);
    t_check(rc == MT_ERR_INVALID, "api: empty name rejected", "%s", err.message);
    t_check(mt_paramset_count(ps) == 1 && mt_paramset_at(ps, 1) == NULL, "api: count and at",
            "%d", mt_paramset_count(ps));
    mt_paramset_destroy(ps);
}

static void test_filenames(void)
{
    mt_error err;
    char out[256] = "";
    const char *dir = t_tmpdir_create("params");
    const mt_paramset *ps;
    mt_rgb c, want;
    if (!dir) {
        t_fail("filenames: temp dir", "cannot create");
        return;
    }
    ps = params_of("\"string rel\" \"tex/a.exr\" \"string abs\" \"/x/b.exr\" \"string empty\" \"\"",
                   "/scenes/here", &err);
    if (ps) {
        t_check(mt_params_filename(ps, "rel", "", out, sizeof out, &err) == MT_OK &&
                    strcmp(out, "/scenes/here/tex/a.exr") == 0,
                "filename: relative to the statement's directory", "%s", out);
        t_check(mt_params_filename(ps, "abs", "", out, sizeof out, &err) == MT_OK &&
                    strcmp(out, "/x/b.exr") == 0,
                "filename: absolute kept", "%s", out);
        t_check(mt_params_filename(ps, "empty", "def.exr", out, sizeof out, &err) == MT_OK &&
                    strcmp(out, "def.exr") == 0,
                "filename: empty gives the default, unresolved (pbrt-v2)", "%s", out);
        t_check(mt_params_filename(ps, "rel", "", out, 8, &err) == MT_ERR_LIMIT &&
                    strcmp(err.param, "rel") == 0,
                "filename: too long for the buffer", "%s", err.message);
    } else {
        t_fail("filenames: parse", "%s", err.message);
    }
    {
        double l[2] = {400, 700}, v[2] = {0.25, 0.75};
        t_write_file("spds/x.spd", "400 0.25\n700 0.75\n", (size_t)-1);
        ps = params_of("\"spectrum eta\" \"spds/x.spd\"", dir, &err);
        want = mt_spectrum_from_sampled(l, v, 2);
        t_check(ps && mt_params_rgb(ps, "eta", mt_rgb_gray(0), &c, &err) == MT_OK &&
                    mt_rgb_equal(c, want),
                "spectrum SPD file relative to the statement's directory", "%s", err.message);
        ps = params_of("\"spectrum eta\" [\"spds/x.spd\" \"spds/x.spd\"]", dir, &err);
        t_check(ps && mt_paramset_find(ps, "eta")->count == 2, "spectrum: one per file", "%s",
                err.message);
        declare_fails("\"spectrum eta\" \"missing.spd\"", 11, "eta", "missing.spd",
                      "spectrum: missing SPD file");
    }
    t_tmpdir_remove();
}

int main(void)
{
    test_types();
    test_lists_per_type();
    test_lookup_errors();
    test_declare_errors();
    test_replacement();
    test_unused();
    test_api();
    test_filenames();
    mt_paramset_destroy(kept);
    return t_status();
}
