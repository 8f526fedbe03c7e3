/*
 * The embedding entry points (material.h, texture.h, state.h): a material
 * from text and from typed parameters is the material pbrt-v2's statement
 * makes -- its BSDF equals the BxDFs built by hand, bit for bit -- named
 * textures and materials go through a state, and every parameter nothing
 * read reaches the caller: as a warning with a callback, as an error
 * without.
 */
#include <string.h>
#include "support/check.h"

static const mt_vec3 WO = {0, (mt_real)0.6, (mt_real)0.8};
static const mt_vec3 WI = {(mt_real)0.48, (mt_real)-0.36, (mt_real)0.8};

/* f(WO, WI) of a material's BSDF at (u, v), or -1 in every channel. */
static mt_rgb f_at(const mt_material *m, mt_real u, mt_real v)
{
    mt_arena *a = mt_arena_create(0);
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *b;
    mt_rgb f = mt_rgb_gray(-1);
    dg.u = u;
    dg.v = v;
    b = m ? mt_material_get_bsdf(m, &dg, &dg, a, NULL) : NULL;
    if (b) f = mt_bsdf_f(b, WO, WI, MT_BSDF_ALL);
    mt_arena_destroy(a);
    return f;
}

typedef struct warnings {
    int n;
    char last[512];
    int line;
} warnings;

static void collect(void *ctx, const char *file, int line, const char *msg)
{
    warnings *w = ctx;
    (void)file;
    w->n++;
    w->line = line;
    snprintf(w->last, sizeof w->last, "%s", msg);
}

/* pbrt-v2's PlasticMaterial::GetBSDF by hand: Lambertian(Kd) and a Blinn
 * microfacet lobe of exponent 1/roughness with FresnelDielectric(1.5, 1). */
static void plastic(void)
{
    mt_error err = MT_ERROR_INIT;
    mt_arena *a = mt_arena_create(0);
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *b = mt_bsdf_create(a, MT_MODE_PBRT_V2, &dg, dg.n, 1, &err);
    mt_param p[3];
    mt_material *t, *q;
    mt_rgb want, got, gotp;
    /* the text's numbers as mt_real reads them (0.4f is not 0.4 in the
     * double build) */
    mt_bsdf_add(b, mt_lambertian_create(a, 0, mt_rgb_make((mt_real)0.5, (mt_real)0.4, (mt_real)0.3), &err), &err);
    mt_bsdf_add(b, mt_microfacet_create(a, 0, mt_rgb_gray((mt_real)0.2), mt_fresnel_dielectric(1.5f, 1),
                                        mt_blinn(1 / (mt_real)0.05), &err), &err);
    want = mt_bsdf_f(b, WO, WI, MT_BSDF_ALL);
    t = mt_material_from_text("Material \"plastic\" \"rgb Kd\" [0.5 0.4 0.3] \"rgb Ks\" [0.2 0.2 0.2]\n"
                              "  \"float roughness\" 0.05", NULL, &err);
    got = f_at(t, 0.5f, 0.5f);
    t_check(t && mt_rgb_equal(got, want) && !mt_rgb_equal(want, mt_rgb_gray(0)),
            "from text: plastic's BSDF is pbrt-v2's, built by hand", "%s; f %g %g %g, want %g %g %g",
            err.message, got.c[0], got.c[1], got.c[2], want.c[0], want.c[1], want.c[2]);
    p[0] = mt_param_rgb("Kd", 0.5, 0.4, 0.3);
    p[1] = mt_param_rgb("Ks", 0.2, 0.2, 0.2);
    p[2] = mt_param_float("roughness", 0.05);
    q = mt_material_from_params("plastic", p, 3, NULL, &err);
    gotp = f_at(q, 0.5f, 0.5f);
    t_check(q && mt_rgb_equal(gotp, want), "from params: the same plastic", "%s; f %g, want %g", err.message,
            gotp.c[0], want.c[0]);
    mt_material_destroy(t);
    mt_material_destroy(q);
    /* the default plastic differs: the parameters were read */
    q = mt_material_from_params("plastic", NULL, 0, NULL, &err);
    t_check(q && !mt_rgb_equal(f_at(q, 0.5f, 0.5f), want) && !strcmp(mt_material_type(q), "plastic"),
            "from params: no parameters is pbrt-v2's default plastic", "%s", err.message);
    mt_material_destroy(q);
    mt_arena_destroy(a);
}

static void unused(void)
{
    mt_error err = MT_ERROR_INIT;
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    warnings w;
    mt_param p[2];
    mt_material *m;
    mt_texture *t;
    memset(&w, 0, sizeof w);
    m = mt_material_from_text("Material \"plastic\"\n  \"rgb Kdd\" [0.5 0.5 0.5]", NULL, &err);
    t_check(!m && err.status == MT_ERR_INVALID && !strcmp(err.param, "Kdd") && err.line == 2 &&
                err.column == 3 && strstr(err.message, "not used"),
            "unused: a misspelt parameter in text is an error without a callback, at its line", "%d:%d %s",
            err.line, err.column, err.message);
    m = mt_material_from_text("Material \"matte\" \"float Kd\" 0.5", NULL, &err);
    t_check(!m && !strcmp(err.param, "Kd"), "unused: a value of the wrong type is an error too", "%s",
            err.message);
    p[0] = mt_param_rgb("Kd", 0.5, 0.5, 0.5);
    p[1] = mt_param_float("roughnes", 0.1);
    m = mt_material_from_params("plastic", p, 2, NULL, &err);
    t_check(!m && !strcmp(err.param, "roughnes"), "unused: a misspelt parameter in a list is an error", "%s",
            err.message);
    mt_state_set_warning(s, collect, &w);
    m = mt_material_from_params("plastic", p, 2, s, &err);
    t_check(m && w.n == 1 && strstr(w.last, "\"roughnes\" not used"),
            "unused: with a warning callback, a warning and the material", "%d warnings, last \"%s\"; %s", w.n,
            w.last, err.message);
    mt_material_destroy(m);
    w.n = 0;
    m = mt_material_from_text("\nMaterial \"plastic\" \"rgb Kdd\" [0.5 0.5 0.5]", s, &err);
    t_check(m && w.n == 1 && w.line == 2, "unused: text's warning names its line", "%d warnings, line %d", w.n,
            w.line);
    mt_material_destroy(m);
    w.n = 0;
    t = mt_texture_from_text("Texture \"c\" \"color\" \"checkerboard\" \"float uscal\" 4", s, &err);
    t_check(t && w.n == 1, "unused: a texture statement's go to the callback", "%d", w.n);
    mt_texture_destroy(t);
    t = mt_texture_from_text("Texture \"c\" \"color\" \"checkerboard\" \"float uscal\" 4", NULL, &err);
    t_check(!t && !strcmp(err.param, "uscal"), "unused: a texture statement's are an error without one", "%s",
            err.message);
    p[0] = mt_param_float("vscal", 4);
    t = mt_texture_from_params("checkerboard", 0, p, 1, NULL, &err);
    t_check(!t && !strcmp(err.param, "vscal"), "unused: a texture's list too", "%s", err.message);
    mt_state_destroy(s);
}

static void textures(void)
{
    mt_error err = MT_ERROR_INIT;
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_param p[3];
    mt_texture *t, *u;
    mt_material *m, *n;
    mt_diffgeom a = mt_diffgeom_default(), b = a;
    mt_rgb fa, fb;
    a.u = 0.1f, a.v = 0.1f; /* 2 x 2 checks: tex1 (1) in the first, tex2 (0) in the next */
    b.u = 0.6f, b.v = 0.1f;
    t = mt_texture_from_text("Texture \"c\" \"color\" \"checkerboard\" \"float uscale\" 2 \"float vscale\" 2", NULL,
                             &err);
    t_check(t && mt_texture_eval_rgb(t, &a).c[0] == 1 && mt_texture_eval_rgb(t, &b).c[0] == 0 &&
                !mt_texture_is_float(t) && !strcmp(mt_texture_class(t), "checkerboard"),
            "texture from text: a checkerboard", "%s", err.message);
    p[0] = mt_param_float("uscale", 2);
    p[1] = mt_param_float("vscale", 2);
    u = mt_texture_from_params("checkerboard", 0, p, 2, NULL, &err);
    t_check(u && mt_rgb_equal(mt_texture_eval_rgb(u, &a), mt_texture_eval_rgb(t, &a)) &&
                mt_rgb_equal(mt_texture_eval_rgb(u, &b), mt_texture_eval_rgb(t, &b)),
            "texture from params: the same", "%s", err.message);
    /* a named texture in a state, used by a material from params and one from text */
    t_check(mt_state_set_texture(s, "checks", u, &err) == MT_OK, "state: a texture bound by name", "%s",
            err.message);
    p[0] = mt_param_texture("Kd", "checks");
    m = mt_material_from_params("matte", p, 1, s, &err);
    fa = f_at(m, 0.1f, 0.1f);
    fb = f_at(m, 0.6f, 0.1f);
    t_check(m && fa.c[0] > 0.3f && fb.c[0] == 0, "state: a material from params reads the named texture",
            "%s; f %g %g", err.message, fa.c[0], fb.c[0]);
    n = mt_material_from_text("Material \"matte\" \"texture Kd\" \"checks\"", s, &err);
    t_check(n && mt_rgb_equal(f_at(n, 0.1f, 0.1f), fa) && mt_rgb_equal(f_at(n, 0.6f, 0.1f), fb),
            "state: a material from text reads it too", "%s", err.message);
    mt_material_destroy(m);
    mt_material_destroy(n);
    m = mt_material_from_params("matte", p, 1, NULL, &err);
    t_check(!m && err.status == MT_ERR_NOT_FOUND && !strcmp(err.param, "Kd"),
            "no state: a named texture is not found", "%s", err.message);
    /* a texture defined by text in the state, then used by name */
    t_check(mt_state_apply_text(s, "Texture \"half\" \"float\" \"constant\" \"float value\" 0.5", &err) == MT_OK,
            "state: statements applied", "%s", err.message);
    p[0] = mt_param_texture("roughness", "half");
    m = mt_material_from_params("plastic", p, 1, s, &err);
    t_check(m != NULL, "state: a float texture from text used by name", "%s", err.message);
    mt_material_destroy(m);
    mt_texture_destroy(t);
    mt_texture_destroy(u);
    mt_state_destroy(s);
}

static void named_materials(void)
{
    mt_error err = MT_ERROR_INIT;
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_param p[3];
    mt_material *m;
    t_check(mt_state_apply_text(s, "MakeNamedMaterial \"a\" \"string type\" \"matte\"\n"
                                   "MakeNamedMaterial \"b\" \"string type\" \"mirror\"", &err) == MT_OK,
            "named: defined by text", "%s", err.message);
    p[0] = mt_param_string("namedmaterial1", "a");
    p[1] = mt_param_string("namedmaterial2", "b");
    p[2] = mt_param_rgb("amount", 0.5, 0.5, 0.5);
    m = mt_material_from_params("mix", p, 3, s, &err);
    t_check(m && !strcmp(mt_material_type(m), "mix"), "named: a mix from params finds them", "%s", err.message);
    mt_material_destroy(m);
    m = mt_material_from_text("NamedMaterial \"a\"", s, &err);
    t_check(m && !strcmp(mt_material_type(m), "matte"), "named: NamedMaterial selects one", "%s", err.message);
    mt_material_destroy(m);
    m = mt_material_from_params("mix", p, 3, NULL, &err);
    t_check(!m && err.status == MT_ERR_NOT_FOUND, "named: none without a state", "%s", err.message);
    mt_state_destroy(s);
}

static void errors(void)
{
    mt_error err = MT_ERROR_INIT;
    mt_material *m;
    m = mt_material_from_text("Material \"plastik\"", NULL, &err);
    t_check(!m && err.status == MT_ERR_NOT_FOUND && strstr(err.message, "plastik"),
            "errors: an unknown type is MT_ERR_NOT_FOUND", "%d %s", err.status, err.message);
    m = mt_material_from_text("Material \"matte\"\nShape \"sphere\"", NULL, &err);
    t_check(!m && err.status == MT_ERR_INVALID && err.line == 2 && strstr(err.message, "Shape"),
            "errors: a statement about something else, at its line", "%d %s", err.line, err.message);
    m = mt_material_from_text("Material \"matte\" \"rgb Kd\" [0.5 0.5", NULL, &err);
    t_check(!m && err.status == MT_ERR_PARSE, "errors: malformed text is MT_ERR_PARSE", "%d %s", err.status,
            err.message);
    m = mt_material_from_text("Texture \"t\" \"float\" \"constant\"", NULL, &err);
    t_check(!m && strstr(err.message, "no Material"), "errors: text without a Material statement", "%s",
            err.message);
    m = mt_material_from_params(NULL, NULL, 0, NULL, &err);
    t_check(!m && err.status == MT_ERR_INVALID, "errors: no type", "%s", err.message);
    m = mt_material_from_params("matte", NULL, 2, NULL, &err);
    t_check(!m && err.status == MT_ERR_INVALID, "errors: a count without a list", "%s", err.message);
}

int main(void)
{
    plastic();
    unused();
    textures();
    named_materials();
    errors();
    return t_status();
}
