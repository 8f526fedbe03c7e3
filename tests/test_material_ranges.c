/*
 * Material parameters outside the values pbrt-v2 can use (a negative
 * roughness, a zero index, a negative conductor eta, ...) are errors when the
 * material is created: the query tool answers "error file:line:column:
 * parameter "name": ..." at the statement, a scene fails to load at the
 * parameter's line, and the API names the user's parameter in mt_error.
 * Values pbrt-v2 clamps or uses as they are (a negative Kd, a sigma of 200,
 * an index below 1, a roughness of 0, an opacity above 1) stay accepted.
 */
#include <string.h>
#include "support/check.h"

static mt_query *q;

/* The answer of one statement. */
static const char *ask(const char *line)
{
    static char out[1024];
    out[0] = 0;
    if (!mt_query_line(q, line, out, sizeof out)) snprintf(out, sizeof out, "(no answer)");
    return out;
}

/* stmt is an error naming param of material, located at the column where
 * the parameter is written (the quote opening "type name"). */
static void rejected(const char *stmt, const char *param, const char *material)
{
    char pat[80], want[160], name[300];
    const char *a = ask(stmt), *at;
    int line = 0, col = 0, n = 0, wcol = 0;
    snprintf(pat, sizeof pat, " %s\"", param);
    at = strstr(stmt, pat);
    while (at && at > stmt && *at != '"') at--;
    if (at) wcol = (int)(at - stmt) + 1;
    snprintf(want, sizeof want, "parameter \"%s\": %s material: ", param, material);
    snprintf(name, sizeof name, "rejected: %s", stmt);
    t_check(sscanf(a, "error <input>:%d:%d: %n", &line, &col, &n) == 2 && n > 0 && col == wcol &&
                !strncmp(a + n, want, strlen(want)),
            name, "answer \"%s\", want \"error <input>:N:%d: %s...\"", a, wcol, want);
}

static void accepted(const char *stmt)
{
    char name[300];
    const char *a = ask(stmt);
    snprintf(name, sizeof name, "accepted: %s", stmt);
    t_check(!strcmp(a, "ok"), name, "answer \"%s\"", a);
}

static void query_cases(void)
{
    mt_error err;
    q = mt_query_create(NULL, &err);
    if (!q) {
        t_fail("query session", "%s", err.message);
        return;
    }
    /* the microfacet roughnesses: 1/roughness is the exponent */
    rejected("Material \"plastic\" \"float roughness\" [-0.1]", "roughness", "plastic");
    rejected("Material \"plastic\" \"float roughness\" [-0]", "roughness", "plastic");
    rejected("Material \"metal\" \"float roughness\" [-1]", "roughness", "metal");
    rejected("Material \"shinymetal\" \"float roughness\" [-0.5]", "roughness", "shinymetal");
    rejected("Material \"substrate\" \"float uroughness\" [-0.1]", "uroughness", "substrate");
    rejected("Material \"substrate\" \"float vroughness\" [-0.1]", "vroughness", "substrate");
    rejected("Material \"translucent\" \"float roughness\" [-0.1]", "roughness", "translucent");
    rejected("Material \"uber\" \"float roughness\" [-0.1]", "roughness", "uber");
    /* indices of refraction */
    rejected("Material \"glass\" \"float index\" [0]", "index", "glass");
    rejected("Material \"glass\" \"float index\" [-1.5]", "index", "glass");
    rejected("Material \"uber\" \"float index\" [-1]", "index", "uber");
    rejected("Material \"subsurface\" \"float index\" [0]", "index", "subsurface");
    rejected("Material \"kdsubsurface\" \"float index\" [0]", "index", "kdsubsurface");
    /* a conductor's eta and k, a medium's coefficients and mean free path */
    rejected("Material \"metal\" \"rgb eta\" [0.2 -0.1 1]", "eta", "metal");
    rejected("Material \"metal\" \"rgb k\" [-3 3 3]", "k", "metal");
    rejected("Material \"subsurface\" \"rgb sigma_a\" [0.1 0.1 -0.1]", "sigma_a", "subsurface");
    rejected("Material \"subsurface\" \"rgb sigma_prime_s\" [-1 1 1]", "sigma_prime_s", "subsurface");
    rejected("Material \"subsurface\" \"float scale\" [0]", "scale", "subsurface");
    rejected("Material \"subsurface\" \"float scale\" [-2]", "scale", "subsurface");
    rejected("Material \"subsurface\" \"string name\" \"Ketchupp\"", "name", "subsurface");
    rejected("Material \"kdsubsurface\" \"float meanfreepath\" [0]", "meanfreepath", "kdsubsurface");
    /* a texture of the wrong kind, and a constant texture out of range */
    accepted("Texture \"f\" \"float\" \"constant\" \"float value\" [-2]");
    rejected("Material \"matte\" \"texture Kd\" \"f\"", "Kd", "matte");
    rejected("Material \"plastic\" \"texture roughness\" \"f\"", "roughness", "plastic");
    /* MakeNamedMaterial is created where it is written, as in pbrt-v2 */
    rejected("MakeNamedMaterial \"n\" \"string type\" \"glass\" \"float index\" [0]", "index", "glass");
    /* what pbrt-v2 clamps or uses as it is */
    accepted("Material \"matte\" \"rgb Kd\" [-1 0.5 2]");
    accepted("Material \"matte\" \"float sigma\" [-10]");
    accepted("Material \"matte\" \"float sigma\" [200]");
    accepted("Material \"plastic\" \"float roughness\" [0]");
    accepted("Material \"glass\" \"float index\" [0.5]");
    accepted("Material \"metal\" \"rgb eta\" [0 0 0] \"rgb k\" [0 0 0]");
    accepted("Material \"shinymetal\" \"rgb Ks\" [2 -1 0.5]");
    accepted("Material \"uber\" \"rgb opacity\" [1.5 1.5 1.5]");
    accepted("Material \"subsurface\" \"rgb sigma_a\" [0 0 0]");
    accepted("Material \"kdsubsurface\" \"rgb Kd\" [1.5 -1 0.5]");
    accepted("Texture \"r\" \"float\" \"fbm\"");
    accepted("Material \"plastic\" \"texture roughness\" \"r\""); /* varies: checked where it is used */
    accepted("MakeNamedMaterial \"a\" \"string type\" \"matte\"");
    accepted("MakeNamedMaterial \"b\" \"string type\" \"plastic\"");
    accepted("Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\" "
             "\"rgb amount\" [-1 2 0.5]");
    mt_query_destroy(q);
}

/* The API: mt_material_create names the user's parameter and its line. */
static mt_status keep(void *ctx, const mt_statement *st, mt_error *err)
{
    mt_paramset **out = ctx;
    *out = mt_paramset_clone(st->params);
    return *out ? MT_OK : mt_error_set(err, MT_ERR_NOMEM, "clone");
}

static void api_case(void)
{
    mt_paramset *ps = NULL;
    mt_texture_table *tt = mt_texture_table_create();
    mt_texparams tp;
    mt_material *m;
    mt_error err;
    mt_error_clear(&err);
    if (mt_parse_string("Material \"glass\"\n  \"rgb Kr\" [1 1 1]\n  \"float index\" [0]\n", "scene.pbrt", NULL, 1,
                        NULL, keep, &ps, &err) != MT_OK || !tt) {
        t_fail("api: parse", "%s", err.message);
        mt_paramset_destroy(ps);
        mt_texture_table_destroy(tt);
        return;
    }
    tp.geom = NULL;
    tp.material = ps;
    tp.textures = tt;
    tp.mode = MT_MODE_PBRT_V2;
    mt_error_clear(&err);
    m = mt_material_create("glass", NULL, &tp, NULL, &err);
    t_check(!m && err.status == MT_ERR_INVALID && !strcmp(err.param, "index") && !strcmp(err.file, "scene.pbrt") &&
                err.line == 3 && strstr(err.message, "index is 0"),
            "api: mt_material_create names \"index\" at scene.pbrt:3",
            "material %p, status %d, param \"%s\", at %s:%d, message \"%s\"", (void *)m, (int)err.status, err.param,
            err.file, err.line, err.message);
    mt_material_destroy(m);
    mt_paramset_destroy(ps);
    mt_texture_table_destroy(tt);
}

/* A scene: loading fails at the parameter's line, before any rendering. */
static void scene_case(void)
{
    static const char scene[] = "Camera \"perspective\"\n"
                                "Film \"image\" \"integer xresolution\" [4] \"integer yresolution\" [4]\n"
                                "WorldBegin\n"
                                "LightSource \"distant\"\n"
                                "Material \"plastic\"\n"
                                "    \"float roughness\" [-0.2]\n"
                                "Shape \"sphere\"\n"
                                "WorldEnd\n";
    static const char named[] = "Camera \"perspective\"\n"
                                "WorldBegin\n"
                                "MakeNamedMaterial \"unused\" \"string type\" \"metal\" \"rgb k\" [1 -1 1]\n"
                                "WorldEnd\n";
    mt_render_options o;
    mt_scene *s;
    mt_error err;
    mt_render_options_default(&o);
    mt_error_clear(&err);
    s = mt_scene_load_string(scene, "bad.pbrt", NULL, &o, &err);
    t_check(!s && !strcmp(err.param, "roughness") && !strcmp(err.file, "bad.pbrt") && err.line == 6,
            "scene: a negative roughness fails to load at its line", "scene %p, param \"%s\" at %s:%d: %s",
            (void *)s, err.param, err.file, err.line, err.message);
    mt_scene_destroy(s);
    mt_error_clear(&err);
    s = mt_scene_load_string(named, "named.pbrt", NULL, &o, &err);
    t_check(!s && !strcmp(err.param, "k") && err.line == 3,
            "scene: an unused MakeNamedMaterial with a negative k fails at its line",
            "scene %p, param \"%s\" at %s:%d: %s", (void *)s, err.param, err.file, err.line, err.message);
    mt_scene_destroy(s);
}

int main(void)
{
    query_cases();
    api_case();
    scene_case();
    return t_status();
}
