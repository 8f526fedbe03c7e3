/*
 * The measured material (pbrt-v2 measured.cpp) through the material API:
 * pbrt-v2's values for Material "measured" "string filename"
 * ["brdfs/mystique.brdf"] (../shared/reference/pbrt-v2-values), "filename"
 * resolved against the statement's directory, the data shared between
 * materials through the cache, errors that name the parameter and the file,
 * bump mapping, and materia-merl: its library part (mt_merl_write_statements)
 * writing a plastic that a measured material then reads back within the
 * lookup's error, and the program itself (exit status, the same bytes).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/wait.h>
#include "materia/material.h"
#include "materia/measured.h"
#include "materia/state.h"
#include "support/check.h"
#include "support/merl_check.h"
#include "support/pbrt_values.h"
#include "support/tfiles.h"

static mt_status apply(void *ctx, const mt_statement *st, mt_error *err)
{
    int handled;
    return mt_state_apply(ctx, st, &handled, err);
}

/* The material pbrt-v2 statements leave current; relative names against dir. */
static mt_material *from_statements(const char *text, const char *dir, mt_mode mode, mt_error *err)
{
    mt_state *s = mt_state_create(mode);
    mt_material *m = NULL;
    if (s && mt_parse_string(text, "<test>", dir, 1, NULL, apply, s, err) == MT_OK)
        m = mt_material_from_state(s, NULL, err);
    mt_state_destroy(s);
    return m;
}

static mt_bsdf *bsdf_of(const mt_material *m, mt_arena *a, mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    mt_arena_reset(a);
    return mt_material_get_bsdf(m, &dg, &dg, a, err);
}

static mt_bsdf *material_bsdf(void *ctx, mt_arena *a, mt_error *err) { return bsdf_of(ctx, a, err); }

static void test_pbrt_values(void)
{
    const char *shared = t_shared_dir();
    char dir[512];
    mt_error err;
    mt_material *m = NULL;
    if (shared) {
        snprintf(dir, sizeof dir, "%s/reference/scenes", shared);
        m = from_statements("Material \"measured\" \"string filename\" [\"brdfs/mystique.brdf\"]", dir,
                            MT_MODE_PBRT_V2, &err);
        t_check(m && !strcmp(mt_material_type(m), "measured"), "measured material: type", "%s",
                m ? mt_material_type(m) : err.message);
    }
    if (!shared || m)
        t_check_pbrt_rows("measured_mystique", "pbrt-v2 values measured_mystique (material)", material_bsdf, m);
    if (m) {
        /* the query tool's rho: a measured f is discontinuous and gets the
         * quadrature's initial work only (rho_quad.c); 0.0401107 is the
         * value with 64 times the refinement */
        mt_arena *a = mt_arena_create(0);
        mt_bsdf *b = bsdf_of(m, a, &err);
        double r = b ? (double)mt_bsdf_rho_quad(b, mt_v3(0, (mt_real)0.6, (mt_real)0.8), MT_BSDF_ALL, 1e-6).c[0] : -1;
        t_check(fabs(r / 0.0401107 - 1) < 5e-3, "measured material: rho by quadrature within 0.5% of a 64x-refined value",
                "%.7g", r);
        mt_arena_destroy(a);
    }
    mt_material_destroy(m);
}

/* Two materials of one file share its data; "bumpmap" is accepted; the
 * components are pbrt-v2's. */
static void test_sharing_and_bump(mt_arena *a)
{
    const char *shared = t_shared_dir();
    char dir[512];
    mt_error err;
    mt_material *m1, *m2, *bumped;
    mt_bsdf *b1, *b2;
    int before;
    mt_vec3 wo = mt_v3(0.6f, 0, 0.8f), wi = mt_v3(-0.6f, 0, 0.8f); /* the mirror pair */
    if (!shared) {
        t_skip("measured material: sharing", "../shared is absent");
        return;
    }
    snprintf(dir, sizeof dir, "%s/reference/scenes", shared);
    m1 = from_statements("Material \"measured\" \"string filename\" \"brdfs/cayman.brdf\"", dir, MT_MODE_PBRT_V2, &err);
    before = mt_measured_cache_size();
    m2 = from_statements("Material \"measured\" \"string filename\" \"brdfs/cayman.brdf\"", dir, MT_MODE_CORRECTED, &err);
    bumped = from_statements("Texture \"b\" \"float\" \"constant\" \"float value\" 0.25\n"
                             "Material \"measured\" \"string filename\" \"brdfs/cayman.brdf\" \"texture bumpmap\" \"b\"",
                             dir, MT_MODE_PBRT_V2, &err);
    t_check(m1 && m2 && bumped && mt_measured_cache_size() == before,
            "measured material: a second material of the same file reads nothing", "%s",
            m1 && m2 && bumped ? "the cache grew" : err.message);
    if (!m1 || !m2 || !bumped) goto done;
    b1 = bsdf_of(m1, a, &err);
    t_check(b1 && mt_bsdf_count(b1) == 1 && !strcmp(mt_bxdf_name(mt_bsdf_component(b1, 0)), "IrregIsotropicBRDF") &&
                mt_bxdf_type(mt_bsdf_component(b1, 0)) == (MT_BSDF_REFLECTION | MT_BSDF_GLOSSY),
            "measured material: one IrregIsotropicBRDF, glossy reflection", "%s",
            b1 ? mt_bxdf_name(mt_bsdf_component(b1, 0)) : err.message);
    if (b1) {
        mt_rgb f1 = mt_bsdf_f(b1, wo, wi, MT_BSDF_ALL), fb;
        b2 = bsdf_of(bumped, a, &err);
        fb = b2 ? mt_bsdf_f(b2, wo, wi, MT_BSDF_ALL) : mt_rgb_gray(-1);
        /* a constant displacement moves the point, not the normal */
        t_check(b2 && mt_rgb_max(f1) > 0 && t_reldiff(f1.c[0], fb.c[0], 1e-30) < 1e-5 &&
                    t_reldiff(f1.c[1], fb.c[1], 1e-30) < 1e-5 && t_reldiff(f1.c[2], fb.c[2], 1e-30) < 1e-5,
                "measured material: a constant bumpmap leaves f as it is", "f (%g %g %g), bumped (%g %g %g)",
                f1.c[0], f1.c[1], f1.c[2], fb.c[0], fb.c[1], fb.c[2]);
    }
done:
    mt_material_destroy(m1);
    mt_material_destroy(m2);
    mt_material_destroy(bumped);
}

static void expect_material_error(const char *name, const char *text, const char *dir,
                                  const char *needle, const char *file)
{
    mt_error err;
    char msg[1024];
    mt_material *m;
    mt_error_clear(&err);
    m = from_statements(text, dir, MT_MODE_PBRT_V2, &err);
    mt_error_format(&err, msg, sizeof msg);
    t_check(!m && strstr(err.message, needle) && (!file || strstr(err.file, file)) &&
                !strcmp(err.param, "filename"),
            name, "%s (wanted \"%s\" in %s, parameter \"filename\")", m ? "created" : msg, needle,
            file ? file : "the message");
    if (!m) printf("    %s\n", msg);
    mt_material_destroy(m);
}

static void test_errors(const char *dir)
{
    expect_material_error("measured material: no filename", "Material \"measured\"", dir,
                          "\"string filename\" is required", NULL);
    expect_material_error("measured material: missing file",
                          "Material \"measured\" \"string filename\" \"absent.brdf\"", dir,
                          "measured material: cannot open", "absent.brdf");
    t_write_file("short.brdf", "2\n500 600\n0.1 0 0.2 0 0.5 0.5\n0.1 0 0.2\n", (size_t)-1);
    expect_material_error("measured material: truncated file, with its line",
                          "Material \"measured\" \"string filename\" \"short.brdf\"", dir,
                          "measured material: measured BRDF file is truncated", "short.brdf");
}

static const char *plastic_text =
    "Material \"plastic\" \"rgb Kd\" [0.3 0.1 0.1] \"float roughness\" [0.05]";

/* materia-merl's library part, then a measured material reading its file. */
static void test_merl_tool_path(mt_arena *a, const char *dir)
{
    mt_merl_options opt = {MT_MODE_PBRT_V2, MT_MERL_AT_CORNER, NULL, NULL, NULL};
    char path[1024];
    mt_error err;
    mt_material *truth_m = from_statements(plastic_text, dir, MT_MODE_PBRT_V2, &err), *table_m = NULL;
    mt_arena *a2 = mt_arena_create(0);
    mt_bsdf *truth, *table;
    snprintf(path, sizeof path, "%s/plastic.binary", dir);
    opt.dir = dir;
    if (!t_check(truth_m && mt_merl_write_statements(plastic_text, &opt, path, &err) == MT_OK,
                 "materia-merl (library): a plastic's table written", "%s", err.message))
        goto done;
    table_m = from_statements("Material \"measured\" \"string filename\" \"plastic.binary\"", dir,
                              MT_MODE_PBRT_V2, &err);
    truth = bsdf_of(truth_m, a, &err);
    mt_arena_reset(a2);
    {
        mt_diffgeom dg = mt_diffgeom_default();
        table = table_m ? mt_material_get_bsdf(table_m, &dg, &dg, a2, &err) : NULL;
    }
    if (!t_check(truth && table && !strcmp(mt_bxdf_name(mt_bsdf_component(table, 0)), "RegularHalfangleBRDF"),
                 "measured material: a MERL file gives a RegularHalfangleBRDF", "%s", err.message))
        goto done;
    t_merl_roundtrip_checks("MERL plastic material (materia-merl)", truth, table, MT_MERL_AT_CORNER);
    {
        mt_status st = mt_merl_write_statements("Shape \"sphere\"", &opt, path, &err);
        t_check(st == MT_ERR_UNSUPPORTED && strstr(err.message, "Shape is not a statement"),
                "materia-merl (library): a statement outside the graphics state is an error", "%s", err.message);
        st = mt_merl_write_statements("Texture \"t\" \"float\" \"constant\"", &opt, path, &err);
        t_check(st != MT_OK && strstr(err.message, "no Material"),
                "materia-merl (library): no material is an error", "%s", err.message);
        st = mt_merl_write_statements("Material \"plastik\"", &opt, path, &err);
        t_check(st != MT_OK && strstr(err.message, "plastik"),
                "materia-merl (library): an unknown material is an error", "%s", err.message);
    }
done:
    mt_material_destroy(truth_m);
    mt_material_destroy(table_m);
    mt_arena_destroy(a2);
    mt_measured_cache_clear();
    remove(path);
}

/* The program: exit status 0 and the library's bytes; 1 on bad input, 2 on
 * bad usage; no temporary file left behind. */
static void test_merl_program(const char *argv0, const char *dir)
{
    char tool[1024], cmd[4096], out[1024], lib[1024];
    const char *slash = strrchr(argv0, '/');
    mt_merl_options opt = {MT_MODE_PBRT_V2, MT_MERL_AT_CENTRE, NULL, NULL, NULL};
    mt_error err;
    FILE *x, *y;
    int same = 0, rc;
    /* build/<precision>/tests/this -> build/<precision>/bin/materia-merl */
    snprintf(tool, sizeof tool, "%.*s/../bin/materia-merl", slash ? (int)(slash - argv0) : 1, slash ? argv0 : ".");
    if (access(tool, X_OK) != 0) {
        t_fail("materia-merl", "%s not found", tool);
        return;
    }
    snprintf(out, sizeof out, "%s/tool.binary", dir);
    snprintf(lib, sizeof lib, "%s/lib.binary", dir);
    snprintf(cmd, sizeof cmd, "'%s' --at centre --out '%s' '%s' > /dev/null", tool, out, plastic_text);
    rc = system(cmd);
    if (mt_merl_write_statements(plastic_text, &opt, lib, &err) == MT_OK && (x = fopen(out, "rb")) != NULL) {
        if ((y = fopen(lib, "rb")) != NULL) {
            int cx, cy;
            do {
                cx = getc(x);
                cy = getc(y);
            } while (cx == cy && cx != EOF);
            same = cx == cy;
            fclose(y);
        }
        fclose(x);
    }
    t_check(rc == 0 && same, "materia-merl: exit 0 and the library's bytes", "exit %d, %s", rc,
            same ? "same bytes" : "different or missing file");
    remove(out);
    remove(lib);
    snprintf(cmd, sizeof cmd, "'%s' --out '%s' 'Material \"plastic\" \"float roughness\" [0.1' 2> /dev/null", tool, out);
    rc = system(cmd);
    t_check(WIFEXITED(rc) && WEXITSTATUS(rc) == 1 && access(out, F_OK) != 0,
            "materia-merl: bad statements exit 1 and write nothing", "status %d", rc);
    snprintf(cmd, sizeof cmd, "'%s' '%s' 2> /dev/null", tool, plastic_text);
    rc = system(cmd);
    t_check(WIFEXITED(rc) && WEXITSTATUS(rc) == 2, "materia-merl: no --out exits 2", "status %d", rc);
    snprintf(cmd, sizeof cmd, "'%s' --out '%s/none/x.binary' '%s' 2> /dev/null", tool, dir, plastic_text);
    rc = system(cmd);
    t_check(WIFEXITED(rc) && WEXITSTATUS(rc) == 1, "materia-merl: an unwritable path exits 1", "status %d", rc);
    snprintf(cmd, sizeof cmd, "'%s' --at middle --out '%s' '%s' 2> /dev/null", tool, out, plastic_text);
    rc = system(cmd);
    t_check(WIFEXITED(rc) && WEXITSTATUS(rc) == 2, "materia-merl: a bad --at exits 2", "status %d", rc);
}

int main(int argc, char **argv)
{
    mt_arena *a = mt_arena_create(0);
    const char *dir;
    (void)argc;
    test_pbrt_values();
    test_sharing_and_bump(a);
    dir = t_tmpdir_create("measured-material");
    if (dir) {
        char d[512];
        snprintf(d, sizeof d, "%s", dir);
        test_errors(d);
        test_merl_tool_path(a, d);
        test_merl_program(argv[0], d);
        t_tmpdir_remove();
    } else {
        t_fail("temporary directory", "cannot create one");
    }
    mt_measured_cache_clear();
    mt_arena_destroy(a);
    return t_status();
}
