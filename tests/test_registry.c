/*
 * The registries of material and texture kinds (MT_MATERIAL_KINDS,
 * MT_TEXTURE_KINDS) are the one list of what materia has: the iteration
 * functions agree with the names and the kinds' objects, creation from a
 * kind's object equals creation by name, and every registered kind has what
 * the rest of the tree needs of it -- a golden scene and image (materials),
 * a section of docs/REFERENCE.md (generated, checked by "reference"), a row
 * or a mention in docs/MATERIALS.md or docs/TEXTURES.md. A kind added
 * without them fails here, naming what is missing (docs/CONTRIBUTING.md,
 * "Adding a material or a texture"). Run from the source tree (make check).
 */
#include <stdlib.h>
#include <string.h>
#include "support/check.h"

/* The whole file, or NULL. */
static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    char *s = NULL;
    long n;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (s = malloc((size_t)n + 1)) != NULL) {
        if (fread(s, 1, (size_t)n, f) != (size_t)n) {
            free(s);
            s = NULL;
        } else
            s[n] = 0;
    }
    fclose(f);
    return s;
}

/* text contains the formatted string. */
static int has(const char *text, const char *fmt, const char *name)
{
    char want[256];
    snprintf(want, sizeof want, fmt, name);
    return text && strstr(text, want) != NULL;
}

static void test_material_iteration(void)
{
    int n, i, ok = 1;
    const char *const *names = mt_material_types(&n);
    for (i = 0; i < n; ++i) {
        const mt_material_kind *k = mt_material_kind_at(i);
        if (!k || strcmp(mt_material_kind_name(k), names[i]) || mt_material_kind_find(names[i]) != k) ok = 0;
    }
    t_check(ok && n == mt_material_kind_count() && n >= 13 && names[n] == NULL,
            "material registry: mt_material_types, _kind_at and _kind_find agree", "%d names", n);
    t_check(!mt_material_kind_at(-1) && !mt_material_kind_at(n) && !mt_material_kind_find("no-such-material") &&
                !mt_material_kind_find(NULL),
            "material registry: no kind outside it", "-");
    t_check(mt_material_kind_find("plastic") == &mt_plastic_material &&
                mt_material_kind_find("kdsubsurface") == &mt_kdsubsurface_material,
            "material registry: the kinds' objects are what it lists", "-");
    t_check(mt_material_kind_has_bssrdf(&mt_subsurface_material) &&
                mt_material_kind_has_bssrdf(&mt_kdsubsurface_material) &&
                !mt_material_kind_has_bssrdf(&mt_plastic_material),
            "material registry: the subsurface kinds have a BSSRDF, plastic none", "-");
}

/* A plastic from its kind's object and one by name give the same BSDF. */
static void test_create_kind(void)
{
    mt_param p = mt_param_rgb("Kd", 0.2, 0.4, 0.6);
    mt_paramset *ps = mt_paramset_create();
    mt_texparams tp;
    mt_diffgeom dg = mt_diffgeom_default();
    mt_arena *arena = mt_arena_create(0);
    mt_material *a, *b;
    mt_error err;
    mt_rgb fa = mt_rgb_black(), fb = mt_rgb_gray(1);
    memset(&tp, 0, sizeof tp);
    mt_error_clear(&err);
    if (!ps || !arena || mt_paramset_add(ps, &p, &err)) {
        t_fail("create_kind", "setup: %s", err.message);
        return;
    }
    tp.material = ps;
    a = mt_material_create_kind(&mt_plastic_material, NULL, &tp, NULL, &err);
    b = mt_material_create("plastic", NULL, &tp, NULL, &err);
    if (a && b) {
        mt_vec3 wo = mt_v3(0, 0.6f, 0.8f), wi = mt_v3(0.48f, -0.36f, 0.8f);
        mt_bsdf *ba = mt_material_get_bsdf(a, &dg, &dg, arena, &err);
        mt_bsdf *bb = mt_material_get_bsdf(b, &dg, &dg, arena, &err);
        if (ba && bb) {
            fa = mt_bsdf_f(ba, wo, wi, MT_BSDF_ALL);
            fb = mt_bsdf_f(bb, wo, wi, MT_BSDF_ALL);
        }
    }
    t_check(a && b && !strcmp(mt_material_type(a), "plastic") && fa.c[0] == fb.c[0] && fa.c[2] == fb.c[2] &&
                fa.c[2] > fa.c[0],
            "mt_material_create_kind(&mt_plastic_material) is mt_material_create(\"plastic\")",
            "%g %g against %g %g: %s", (double)fa.c[0], (double)fa.c[2], (double)fb.c[0], (double)fb.c[2],
            err.message);
    mt_material_destroy(a);
    mt_material_destroy(b);
    a = mt_material_create_kind(NULL, NULL, &tp, NULL, &err);
    t_check(!a && err.status == MT_ERR_INVALID, "mt_material_create_kind(NULL) is an error", "%s", err.message);
    mt_paramset_destroy(ps);
    mt_arena_destroy(arena);
}

/* Every material kind: its golden scene (which uses it, with the dipole
 * integrator exactly when it has a BSSRDF), its golden image, its section
 * of the reference and its row of docs/MATERIALS.md. */
static void test_material_files(void)
{
    char *ref = slurp("docs/REFERENCE.md"), *mats = slurp("docs/MATERIALS.md");
    int i;
    for (i = 0; i < mt_material_kind_count(); ++i) {
        const mt_material_kind *k = mt_material_kind_at(i);
        const char *name = mt_material_kind_name(k);
        char path[256], check[512], *scene;
        FILE *f;
        snprintf(path, sizeof path, "golden/scenes/%s.pbrt", name);
        scene = slurp(path);
        snprintf(check, sizeof check, "material %s: golden scene %s", name, path);
        t_check(scene && has(scene, "\"%s\"", name) &&
                    (strstr(scene, "\"dipolesubsurface\"") != NULL) == mt_material_kind_has_bssrdf(k),
                check, "%s", scene ? "does not use the material, or the wrong integrator" : "missing (tools/make-golden.sh)");
        free(scene);
        snprintf(path, sizeof path, "golden/%s.exr", name);
        f = fopen(path, "rb");
        snprintf(check, sizeof check, "material %s: golden image %s", name, path);
        t_check(f != NULL, check, "missing: make golden writes it");
        if (f) fclose(f);
        snprintf(check, sizeof check, "material %s: a section of docs/REFERENCE.md", name);
        t_check(has(ref, "\n### %s\n", name), check, "missing: make reference writes it");
        snprintf(check, sizeof check, "material %s: a row of docs/MATERIALS.md's lobe table", name);
        t_check(has(mats, "\n| `%s`", name) || has(mats, ", `%s` |", name), check, "missing");
    }
    free(ref);
    free(mats);
}

static void test_texture_registry(void)
{
    char *ref = slurp("docs/REFERENCE.md"), *tex = slurp("docs/TEXTURES.md");
    int n, i, ok = 1;
    const char *const *names = mt_texture_classes(&n);
    for (i = 0; i < n; ++i) {
        const mt_texture_kind *k = mt_texture_kind_at(i);
        char check[128];
        if (!k || strcmp(mt_texture_kind_name(k), names[i]) || mt_texture_kind_find(names[i]) != k) ok = 0;
        snprintf(check, sizeof check, "texture %s: a section of docs/REFERENCE.md", names[i]);
        t_check(has(ref, "\n### %s (", names[i]), check, "missing: make reference writes it");
        snprintf(check, sizeof check, "texture %s: named in docs/TEXTURES.md", names[i]);
        t_check(has(tex, "`%s`", names[i]), check, "missing");
    }
    t_check(ok && n == mt_texture_kind_count() && names[n] == NULL,
            "texture registry: mt_texture_classes, _kind_at and _kind_find agree", "%d names", n);
    t_check(!mt_texture_kind_at(-1) && !mt_texture_kind_at(n) && !mt_texture_kind_find("no-such-texture") &&
                mt_texture_kind_find("checkerboard") == &mt_checkerboard_texture,
            "texture registry: the kinds' objects are what it lists, nothing else", "-");
    free(ref);
    free(tex);
}

/* A checkerboard from its kind's object is the one made by name. */
static void test_texture_create_kind(void)
{
    mt_paramset *ps = mt_paramset_create();
    mt_texture_table *tt = mt_texture_table_create();
    mt_texparams tp;
    mt_diffgeom dg = mt_diffgeom_default();
    mt_texture *a, *b;
    mt_error err;
    memset(&tp, 0, sizeof tp);
    mt_error_clear(&err);
    tp.material = ps;
    tp.textures = tt;
    dg.u = 0.7f;
    dg.v = 0.2f;
    a = mt_texture_create_kind(&mt_checkerboard_texture, 1, NULL, &tp, &err);
    b = mt_texture_create("checkerboard", 1, NULL, &tp, &err);
    t_check(a && b && mt_texture_eval_float(a, &dg) == mt_texture_eval_float(b, &dg) &&
                !strcmp(mt_texture_class(a), "checkerboard"),
            "mt_texture_create_kind(&mt_checkerboard_texture) is mt_texture_create(\"checkerboard\")", "%s",
            err.message);
    mt_texture_destroy(a);
    mt_texture_destroy(b);
    a = mt_texture_create_kind(&mt_uv_texture, 1, NULL, &tp, &err);
    t_check(!a && strstr(err.message, "no float"), "mt_texture_create_kind: pbrt-v2 has no float uv", "%s",
            err.message);
    mt_paramset_destroy(ps);
    mt_texture_table_destroy(tt);
}

int main(void)
{
    test_material_iteration();
    test_create_kind();
    test_material_files();
    test_texture_registry();
    test_texture_create_kind();
    return t_status();
}
