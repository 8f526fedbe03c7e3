/*
 * The texture classes by pbrt-v2 name, and their creators: each reads its
 * parameters with pbrt-v2's names and defaults (textures/<class>.cpp) and
 * calls the class's constructor. pbrt-v2's creators print an error and fall
 * back to a default for an unknown "mapping", "aamode" or "wrap", or a
 * missing image; materia reports an error naming the parameter instead.
 */
#include <string.h>
#include "materia/mipmap.h"
#include "textures/probe.h"
#include "textures/tex.h"

typedef mt_texture *(*creator)(int is_float, const mt_transform *tex2world,
                               const mt_texparams *tp, mt_error *err);

/* A float or spectrum child texture with a gray default. */
static mt_texture *child(const mt_texparams *tp, int is_float, const char *name, mt_real def,
                         mt_error *err)
{
    if (is_float) return mt_texparams_float_texture(tp, name, def, err);
    return mt_texparams_spectrum_texture(tp, name, mt_rgb_gray(def), err);
}

/* A float or spectrum value with a gray default, as an RGB. */
static mt_status value(const mt_texparams *tp, int is_float, const char *name, mt_real def,
                       mt_rgb *out, mt_error *err)
{
    mt_real v = def;
    mt_status st;
    if (!is_float) return mt_texparams_rgb(tp, name, mt_rgb_gray(def), out, err);
    st = mt_texparams_float(tp, name, def, &v, err);
    *out = mt_rgb_gray(v);
    return st;
}

/* Names a string parameter's value among choices; its index, or -1 with err. */
static int choice(const mt_texparams *tp, const char *name, const char *def,
                  const char *const *choices, const char *cls, mt_error *err)
{
    const char *s;
    int i;
    if (mt_texparams_string(tp, name, def, &s, err)) return -1;
    mt__texparams_probe(name, "string", def, choices);
    for (i = 0; choices[i]; ++i)
        if (!strcmp(s, choices[i])) return i;
    mt_error_param(err, MT_ERR_INVALID, name, "%s texture: unknown %s \"%s\"", cls, name, s);
    return -1;
}

/* The 2D mapping chosen by "mapping" (pbrt-v2's creators, all alike). */
static mt_status mapping2d(const mt_transform *tex2world, const mt_texparams *tp,
                           const char *cls, mt_map2d *m, mt_error *err)
{
    static const char *const kinds[] = {"uv", "spherical", "cylindrical", "planar", NULL};
    mt_real su, sv, du, dv;
    mt_vec3 v1, v2;
    mt_status st;
    switch (choice(tp, "mapping", "uv", kinds, cls, err)) {
    case 0:
        if ((st = mt_texparams_float(tp, "uscale", 1, &su, err)) ||
            (st = mt_texparams_float(tp, "vscale", 1, &sv, err)) ||
            (st = mt_texparams_float(tp, "udelta", 0, &du, err)) ||
            (st = mt_texparams_float(tp, "vdelta", 0, &dv, err)))
            return st;
        *m = mt__map2d_uv(su, sv, du, dv);
        break;
    case 1:
        *m = mt__map2d_spherical(tex2world, tp->mode);
        break;
    case 2:
        *m = mt__map2d_cylindrical(tex2world, tp->mode);
        break;
    case 3:
        if ((st = mt_texparams_vector(tp, "v1", mt_v3(1, 0, 0), &v1, err)) ||
            (st = mt_texparams_vector(tp, "v2", mt_v3(0, 1, 0), &v2, err)) ||
            (st = mt_texparams_float(tp, "udelta", 0, &du, err)) ||
            (st = mt_texparams_float(tp, "vdelta", 0, &dv, err)))
            return st;
        *m = mt__map2d_planar(v1, v2, du, dv);
        break;
    default:
        return MT_ERR_INVALID;
    }
    return mt__map2d_check(m, cls, err);
}

static mt_texture *create_constant(int is_float, const mt_transform *tex2world,
                                   const mt_texparams *tp, mt_error *err)
{
    mt_rgb v;
    if (value(tp, is_float, "value", 1, &v, err)) return NULL;
    return mt__tex_constant(is_float, v, tp->mode, err);
}

/* The classes made of two child textures: scale, mix (with its amount),
 * checkerboard and dots take theirs through this. */
typedef struct children {
    mt_texture *a, *b, *amount;
} children;

static int get_children(const mt_texparams *tp, int is_float, const char *na, mt_real da,
                        const char *nb, mt_real db, children *c, mt_error *err)
{
    c->amount = NULL;
    c->b = NULL;
    c->a = child(tp, is_float, na, da, err);
    if (c->a) c->b = child(tp, is_float, nb, db, err);
    return c->b != NULL;
}

static void put_children(children *c)
{
    mt_texture_destroy(c->a);
    mt_texture_destroy(c->b);
    mt_texture_destroy(c->amount);
}

static mt_texture *create_scale(int is_float, const mt_transform *tex2world,
                                const mt_texparams *tp, mt_error *err)
{
    children c;
    mt_texture *t = NULL;
    if (get_children(tp, is_float, "tex1", 1, "tex2", 1, &c, err))
        t = mt__tex_scale(is_float, c.a, c.b, tp->mode, err);
    put_children(&c);
    return t;
}

static mt_texture *create_mix(int is_float, const mt_transform *tex2world,
                              const mt_texparams *tp, mt_error *err)
{
    children c;
    mt_texture *t = NULL;
    if (get_children(tp, is_float, "tex1", 0, "tex2", 1, &c, err) &&
        (c.amount = mt_texparams_float_texture(tp, "amount", (mt_real)0.5, err)))
        t = mt__tex_mix(is_float, c.a, c.b, c.amount, tp->mode, err);
    put_children(&c);
    return t;
}

static mt_texture *create_bilerp(int is_float, const mt_transform *tex2world,
                                 const mt_texparams *tp, mt_error *err)
{
    static const char *const names[4] = {"v00", "v01", "v10", "v11"};
    static const mt_real defs[4] = {0, 1, 0, 1};
    mt_map2d m;
    mt_rgb v[4];
    int i;
    if (mapping2d(tex2world, tp, "bilerp", &m, err)) return NULL;
    for (i = 0; i < 4; ++i)
        if (value(tp, is_float, names[i], defs[i], &v[i], err)) return NULL;
    return mt__tex_bilerp(is_float, &m, v, tp->mode, err);
}

/* pbrt-v2 CreateImage*Texture: the parameters checked here; the pyramid
 * comes from the process-wide MIP-map cache (each file read once). */
static mt_texture *create_imagemap(int is_float, const mt_transform *tex2world,
                                   const mt_texparams *tp, mt_error *err)
{
    static const char *const wraps[] = {"repeat", "black", "clamp", NULL}; /* mt_wrap order */
    mt_map2d m;
    mt_real maxaniso, scale, gamma;
    int trilinear, wrap;
    char path[4096];
    if (mapping2d(tex2world, tp, "imagemap", &m, err) ||
        mt_texparams_float(tp, "maxanisotropy", 8, &maxaniso, err) ||
        mt_texparams_bool(tp, "trilinear", 0, &trilinear, err) ||
        (wrap = choice(tp, "wrap", "repeat", wraps, "imagemap", err)) < 0 ||
        mt_texparams_float(tp, "scale", 1, &scale, err) ||
        mt_texparams_float(tp, "gamma", 1, &gamma, err) ||
        mt_texparams_filename(tp, "filename", "", path, sizeof path, err))
        return NULL;
    if (!mt__tex_check_real(scale, "scale", "imagemap", err) ||
        !mt__tex_check_real(gamma, "gamma", "imagemap", err))
        return NULL;
    /* pow(0, gamma) is infinite for gamma < 0 */
    if (gamma < 0) {
        mt_error_param(err, MT_ERR_INVALID, "gamma", "imagemap texture: gamma %g is negative",
                       (double)gamma);
        return NULL;
    }
    if (!path[0]) {
        mt_error_param(err, MT_ERR_INVALID, "filename", "imagemap texture: no filename");
        return NULL;
    }
    {
        /* the pyramid is the cache's, shared and read-only */
        const mt_mipmap *mip = mt_mipmap_cache_get(path, trilinear, maxaniso, (mt_wrap)wrap, scale, gamma,
                                                   is_float, tp->mode, err);
        if (!mip) return NULL;
        return mt__tex_imagemap(is_float, &m, mip, tp->mode, err);
    }
}

static mt_texture *create_uv(int is_float, const mt_transform *tex2world,
                             const mt_texparams *tp, mt_error *err)
{
    mt_map2d m;
    if (mapping2d(tex2world, tp, "uv", &m, err)) return NULL;
    return mt__tex_uv(&m, tp->mode, err);
}

static mt_texture *create_checkerboard(int is_float, const mt_transform *tex2world,
                                       const mt_texparams *tp, mt_error *err)
{
    static const char *const aamodes[] = {"none", "closedform", NULL};
    children c;
    mt_texture *t = NULL;
    mt_map2d m2;
    mt_map3d m3;
    int dim, aa;
    if (mt_texparams_int(tp, "dimension", 2, &dim, err)) return NULL;
    if (dim != 2 && dim != 3) {
        mt_error_param(err, MT_ERR_INVALID, "dimension",
                       "checkerboard texture: %d dimensions (2 or 3 are supported)", dim);
        return NULL;
    }
    if (!get_children(tp, is_float, "tex1", 1, "tex2", 0, &c, err)) {
        put_children(&c);
        return NULL;
    }
    if (dim == 3) {
        m3 = mt__map3d(tex2world, tp->mode);
        t = mt__tex_checker3d(is_float, &m3, c.a, c.b, tp->mode, err);
    } else if (!mapping2d(tex2world, tp, "checkerboard", &m2, err) &&
               (aa = choice(tp, "aamode", "closedform", aamodes, "checkerboard", err)) >= 0) {
        t = mt__tex_checker2d(is_float, &m2, c.a, c.b, aa, tp->mode, err);
    }
    put_children(&c);
    return t;
}

static mt_texture *create_dots(int is_float, const mt_transform *tex2world,
                               const mt_texparams *tp, mt_error *err)
{
    children c;
    mt_map2d m;
    mt_texture *t = NULL;
    if (mapping2d(tex2world, tp, "dots", &m, err)) return NULL;
    if (get_children(tp, is_float, "inside", 1, "outside", 0, &c, err))
        t = mt__tex_dots(is_float, &m, c.a, c.b, tp->mode, err);
    put_children(&c);
    return t;
}

/* "octaves" (8) and "roughness" (0.5) of fbm, wrinkled and marble. */
static mt_status octaves(const mt_texparams *tp, int *oct, mt_real *rough, mt_error *err)
{
    mt_status st = mt_texparams_int(tp, "octaves", 8, oct, err);
    return st ? st : mt_texparams_float(tp, "roughness", (mt_real)0.5, rough, err);
}

typedef mt_texture *(*octave_ctor)(int is_float, const mt_map3d *map, int octaves,
                                   mt_real roughness, mt_mode mode, mt_error *err);

/* fbm and wrinkled: a 3D mapping, "octaves" and "roughness". */
static mt_texture *create_octaves(octave_ctor ctor, int is_float, const mt_transform *tex2world,
                                  const mt_texparams *tp, mt_error *err)
{
    mt_map3d m = mt__map3d(tex2world, tp->mode);
    mt_real rough;
    int oct;
    if (octaves(tp, &oct, &rough, err)) return NULL;
    return ctor(is_float, &m, oct, rough, tp->mode, err);
}

static mt_texture *create_fbm(int is_float, const mt_transform *tex2world,
                              const mt_texparams *tp, mt_error *err)
{
    return create_octaves(mt__tex_fbm, is_float, tex2world, tp, err);
}

static mt_texture *create_wrinkled(int is_float, const mt_transform *tex2world,
                                   const mt_texparams *tp, mt_error *err)
{
    return create_octaves(mt__tex_wrinkled, is_float, tex2world, tp, err);
}

static mt_texture *create_windy(int is_float, const mt_transform *tex2world,
                                const mt_texparams *tp, mt_error *err)
{
    mt_map3d m = mt__map3d(tex2world, tp->mode);
    return mt__tex_windy(is_float, &m, tp->mode, err);
}

static mt_texture *create_marble(int is_float, const mt_transform *tex2world,
                                 const mt_texparams *tp, mt_error *err)
{
    mt_map3d m = mt__map3d(tex2world, tp->mode);
    mt_real rough, scale, variation;
    int oct;
    if (octaves(tp, &oct, &rough, err) || mt_texparams_float(tp, "scale", 1, &scale, err) ||
        mt_texparams_float(tp, "variation", (mt_real)0.2, &variation, err))
        return NULL;
    return mt__tex_marble(&m, oct, rough, scale, variation, tp->mode, err);
}

/* What each parameter the creators read is and the values it takes, for
 * docs/REFERENCE.md (the names, types and defaults come from the readers
 * themselves, through textures/probe.h; the check that the committed file
 * is current also checks that every parameter read is described here and
 * every one described is read). cls NULL: the same in every class. */
static const mt__texture_param_doc docs[] = {
    {NULL, "mapping", "uv, spherical, cylindrical or planar", "how (u, v) are found at a point"},
    {NULL, "uscale", "finite", "uv mapping: u times uscale"},
    {NULL, "vscale", "finite", "uv mapping: v times vscale"},
    {NULL, "udelta", "finite", "uv and planar mappings: added to u"},
    {NULL, "vdelta", "finite", "uv and planar mappings: added to v"},
    {NULL, "v1", "finite", "planar mapping: u is the point's projection on v1"},
    {NULL, "v2", "finite", "planar mapping: v is the point's projection on v2"},
    {NULL, "octaves", "0 to 128", "noise octaves (fewer where the filter width asks)"},
    {NULL, "roughness", "finite; the octaves' total weight finite", "weight of each octave relative to the last"},
    {"constant", "value", "finite", "the value everywhere"},
    {"scale", "tex1", "any", "tex1 times tex2"},
    {"scale", "tex2", "any", "tex1 times tex2"},
    {"mix", "tex1", "any", "(1 - amount) tex1 + amount tex2"},
    {"mix", "tex2", "any", "(1 - amount) tex1 + amount tex2"},
    {"mix", "amount", "any (used as it is)", "the weight of tex2"},
    {"bilerp", "v00", "finite", "the value at (u, v) = (0, 0)"},
    {"bilerp", "v01", "finite", "the value at (0, 1)"},
    {"bilerp", "v10", "finite", "the value at (1, 0)"},
    {"bilerp", "v11", "finite", "the value at (1, 1)"},
    {"imagemap", "filename", "an .exr, .png or .pfm file (required)", "the image, read once per process"},
    {"imagemap", "maxanisotropy", "> 0 (with EWA filtering)", "the longest ellipse axis over the shortest"},
    {"imagemap", "trilinear", "true or false", "trilinear filtering instead of EWA"},
    {"imagemap", "wrap", "repeat, black or clamp", "lookups outside [0, 1]"},
    {"imagemap", "scale", "finite", "texel values times scale"},
    {"imagemap", "gamma", ">= 0", "texel values to the power gamma (after scale)"},
    {"checkerboard", "dimension", "2 or 3", "2: on (u, v); 3: in space (no mapping, no antialiasing)"},
    {"checkerboard", "tex1", "any", "the even squares"},
    {"checkerboard", "tex2", "any", "the odd squares"},
    {"checkerboard", "aamode", "none or closedform", "2D antialiasing: none, or the closed-form box filter"},
    {"dots", "inside", "any", "inside the dots"},
    {"dots", "outside", "any", "between the dots"},
    {"marble", "scale", "finite", "the point's coordinates times scale"},
    {"marble", "variation", "finite", "the strength of the noise in the marble's bands"},
};

const mt__texture_param_doc *mt__texture_param_docs(int *count)
{
    *count = (int)(sizeof docs / sizeof docs[0]);
    return docs;
}

static const struct {
    const char *name;
    creator create;
    int has_float; /* pbrt-v2 has no float uv or marble */
} classes[] = {
    {"constant", create_constant, 1}, {"scale", create_scale, 1},
    {"mix", create_mix, 1},           {"bilerp", create_bilerp, 1},
    {"imagemap", create_imagemap, 1}, {"uv", create_uv, 0},
    {"checkerboard", create_checkerboard, 1}, {"dots", create_dots, 1},
    {"fbm", create_fbm, 1},           {"wrinkled", create_wrinkled, 1},
    {"windy", create_windy, 1},       {"marble", create_marble, 0},
};

#define NCLASSES ((int)(sizeof classes / sizeof classes[0]))

mt_texture *mt_texture_create(const char *class_name, int is_float,
                              const mt_transform *tex2world, const mt_texparams *tp,
                              mt_error *err)
{
    mt_transform id = mt_transform_identity();
    int i;
    mt_error_clear(err);
    if (!class_name || !tp) {
        mt_error_set(err, MT_ERR_INVALID, "texture: missing class name or parameters");
        return NULL;
    }
    for (i = 0; i < NCLASSES; ++i) {
        if (strcmp(classes[i].name, class_name)) continue;
        if (is_float && !classes[i].has_float) {
            mt_error_set(err, MT_ERR_INVALID, "pbrt-v2 has no float \"%s\" texture", class_name);
            return NULL;
        }
        return classes[i].create(is_float ? 1 : 0, tex2world ? tex2world : &id, tp, err);
    }
    mt_error_set(err, MT_ERR_NOT_FOUND, "unknown texture class \"%s\"", class_name);
    return NULL;
}

const char *const *mt_texture_classes(int *count)
{
    static const char *const names[] = {"constant", "scale",        "mix",  "bilerp",
                                        "imagemap", "uv",           "checkerboard", "dots",
                                        "fbm",      "wrinkled",     "windy", "marble", NULL};
    if (count) *count = NCLASSES;
    return names;
}
