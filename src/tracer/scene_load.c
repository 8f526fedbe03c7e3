/*
 * Loading a pbrt-v2 scene (pbrt-v2 api.cpp): every statement goes to the
 * graphics state (transforms, attributes, textures, materials, area lights);
 * options are recorded until WorldBegin; LightSource and Shape build lights,
 * shapes and materials as they come; WorldEnd builds the BVH. What materia
 * does not support is an error located at the statement.
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include "core/alloc.h"
#include "tracer/scene_load.h"
#include "materials/uniform.h"

/* ---- messages ------------------------------------------------------------ */

void mt__loader_warn(mt__loader *ld, const char *file, int line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    if (!ld->warn) return;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    ld->warn(ld->warn_ctx, file, line, msg);
}

mt_status mt__option_fail(const mt__option *o, mt_status st, mt_error *err)
{
    if (err && !err->file[0] && o->file) mt_error_locate(err, o->file, o->line, o->column);
    return st;
}

void mt__loader_report_unused(mt__loader *ld, const mt_paramset *ps)
{
    int i;
    if (!ps) return;
    for (i = 0; i < ld->nreported; ++i)
        if (ld->reported[i] == ps) return;
    if (ld->nreported == ld->cap_reported) {
        int cap = ld->cap_reported ? 2 * ld->cap_reported : 16;
        const void **r = mt__realloc((void *)ld->reported, (size_t)cap * sizeof *r);
        if (!r) return; /* a warning the less */
        ld->reported = r;
        ld->cap_reported = cap;
    }
    ld->reported[ld->nreported++] = ps;
    mt_paramset_report_unused(ps, ld->warn, ld->warn_ctx);
}

/* ---- the scene's growing arrays ------------------------------------------- */

static int grow(void **arr, int *cap, int n, size_t elem)
{
    void *p;
    int c;
    if (n < *cap) return 1;
    c = *cap ? 2 * *cap : 8;
    p = mt__realloc(*arr, (size_t)c * elem);
    if (!p) return 0;
    *arr = p;
    *cap = c;
    return 1;
}

static mt__light *new_light(mt_scene *s, mt_error *err)
{
    if (!grow((void **)&s->lights, &s->cap_lights, s->nlights, sizeof *s->lights)) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory for lights");
        return NULL;
    }
    memset(&s->lights[s->nlights], 0, sizeof *s->lights);
    return &s->lights[s->nlights];
}

/* ---- statements ------------------------------------------------------------- */

static int is_animated(const mt_state *st)
{
    return memcmp(mt_state_transform(st), mt_state_transform_end(st), sizeof(mt_transform)) != 0;
}

static mt_status load_fail(mt_error *err, mt_status st, const char *fmt, const char *a, const char *b)
{
    return mt_error_set(err, st, fmt, a, b ? b : "");
}

static mt_status record_option(mt__option *o, const mt_statement *st, mt_error *err)
{
    mt_paramset *ps = mt_paramset_clone(st->params);
    char *type = st->nargs > 0 && st->args[0].is_string ? mt__strdup(st->args[0].string) : NULL;
    char *file = mt__strdup(st->file ? st->file : "");
    if (!ps || !file || (st->nargs > 0 && !type)) {
        mt_paramset_destroy(ps);
        mt__free(type);
        mt__free(file);
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory");
    }
    mt_paramset_destroy(o->ps);
    mt__free(o->type);
    mt__free(o->file);
    o->ps = ps;
    o->type = type;
    o->file = file;
    o->line = st->line;
    o->column = st->column;
    return MT_OK;
}

static int name_in(const char *name, const char *const *list)
{
    for (; *list; ++list)
        if (strcmp(name, *list) == 0) return 1;
    return 0;
}

/* The types each options directive accepts, checked at the statement. */
static mt_status check_option_type(const mt_statement *st, mt_error *err)
{
    static const char *const cameras[] = {"perspective", "orthographic", NULL};
    static const char *const filters[] = {"box", "gaussian", "mitchell", "triangle", "sinc", NULL};
    static const char *const samplers[] = {"lowdiscrepancy", "halton", "random", "stratified",
                                           "bestcandidate", "adaptive", NULL};
    static const char *const surf[] = {"path", "directlighting", "dipolesubsurface", NULL};
    static const char *const surf_v2[] = {"whitted", "photonmap", "exphotonmap", "irradiancecache",
                                          "igi", "ambientocclusion", "useprobes", "diffuseprt",
                                          "glossyprt", NULL};
    static const char *const vol[] = {"emission", "single", NULL};
    static const char *const accel[] = {"bvh", "grid", "kdtree", NULL};
    const char *d = st->directive, *t = st->args[0].string;
    if (strcmp(d, "Camera") == 0 && !name_in(t, cameras))
        return load_fail(err, MT_ERR_UNSUPPORTED, "Camera \"%s\" is not supported (perspective, orthographic)%s", t, NULL);
    if (strcmp(d, "Film") == 0 && strcmp(t, "image") != 0)
        return load_fail(err, MT_ERR_NOT_FOUND, "Film \"%s\" unknown (\"image\")%s", t, NULL);
    if (strcmp(d, "PixelFilter") == 0 && !name_in(t, filters))
        return load_fail(err, MT_ERR_NOT_FOUND, "PixelFilter \"%s\" unknown (box, gaussian, mitchell, triangle, sinc)%s", t, NULL);
    if (strcmp(d, "Sampler") == 0 && !name_in(t, samplers))
        return load_fail(err, MT_ERR_NOT_FOUND, "Sampler \"%s\" unknown%s", t, NULL);
    if (strcmp(d, "SurfaceIntegrator") == 0 && !name_in(t, surf)) {
        return load_fail(err, name_in(t, surf_v2) ? MT_ERR_UNSUPPORTED : MT_ERR_NOT_FOUND,
                    name_in(t, surf_v2) ? "SurfaceIntegrator \"%s\" is not supported (path, directlighting, dipolesubsurface)%s"
                                        : "SurfaceIntegrator \"%s\" unknown%s", t, NULL);
    }
    if (strcmp(d, "VolumeIntegrator") == 0 && !name_in(t, vol))
        return load_fail(err, MT_ERR_NOT_FOUND, "VolumeIntegrator \"%s\" unknown (emission, single)%s", t, NULL);
    if (strcmp(d, "Renderer") == 0 && strcmp(t, "sampler") != 0)
        return load_fail(err, MT_ERR_UNSUPPORTED, "Renderer \"%s\" is not supported (\"sampler\")%s", t, NULL);
    if (strcmp(d, "Accelerator") == 0 && !name_in(t, accel))
        return load_fail(err, MT_ERR_NOT_FOUND, "Accelerator \"%s\" unknown (bvh, grid, kdtree)%s", t, NULL);
    return MT_OK;
}

static mt__option *option_slot(mt__loader *ld, const char *d)
{
    if (strcmp(d, "Camera") == 0) return &ld->camera;
    if (strcmp(d, "Film") == 0) return &ld->film;
    if (strcmp(d, "PixelFilter") == 0) return &ld->filter;
    if (strcmp(d, "Sampler") == 0) return &ld->sampler;
    if (strcmp(d, "SurfaceIntegrator") == 0) return &ld->surface;
    if (strcmp(d, "VolumeIntegrator") == 0) return &ld->volume;
    if (strcmp(d, "Renderer") == 0) return &ld->renderer;
    if (strcmp(d, "Accelerator") == 0) return &ld->accelerator;
    return NULL;
}

static mt_status do_light_source(mt__loader *ld, const mt_statement *st, mt_error *err)
{
    mt_scene *s = ld->scene;
    mt__light *l;
    mt_status rc;
    if (is_animated(ld->state))
        return mt_error_set(err, MT_ERR_UNSUPPORTED, "LightSource: animated transforms are not supported");
    if (!(l = new_light(s, err))) return err->status;
    rc = mt__light_create(l, st->args[0].string, st->params, mt_state_transform(ld->state), s->mode, err);
    if (rc != MT_OK) {
        mt__light_free(l);
        return rc;
    }
    s->nlights++;
    mt_paramset_report_unused(st->params, ld->warn, ld->warn_ctx);
    return MT_OK;
}

static mt_status do_shape(mt__loader *ld, const mt_statement *st, mt_error *err)
{
    mt_scene *s = ld->scene;
    const mt_paramset *alps = NULL;
    const char *al = mt_state_area_light(ld->state, &alps);
    mt_material_spec spec;
    mt_shape_options opt;
    mt__prim_info *info;
    mt_material *m;
    mt_shape *shape;
    mt_status rc;
    if (is_animated(ld->state))
        return mt_error_set(err, MT_ERR_UNSUPPORTED, "Shape: animated transforms are not supported");
    if (!grow((void **)&s->prims, &s->cap_prims, s->nprims, sizeof *s->prims) ||
        !grow((void **)&s->materials, &s->cap_materials, s->nmaterials, sizeof *s->materials) ||
        (al && !new_light(s, err)))
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for shapes");
    /* the material first, so that the shape's unused parameters exclude the
     * material's (pbrt-v2's TextureParams reads the shape's list first) */
    m = mt_material_from_state(ld->state, st->params, err);
    if (!m) return err->status;
    s->materials[s->nmaterials++] = m;
    mt_state_material(ld->state, &spec);
    mt__loader_report_unused(ld, spec.name ? spec.geom : spec.material);
    memset(&opt, 0, sizeof opt);
    opt.warn = ld->warn;
    opt.warn_ctx = ld->warn_ctx;
    opt.mode = s->mode; /* the geometry errata, as the materials' */
    shape = mt_shape_from_statement(st, mt_state_transform(ld->state),
                                    mt_state_reverse_orientation(ld->state), &opt, err);
    if (!shape) return err->status;
    info = mt__malloc(sizeof *info);
    if (!info) {
        mt_shape_destroy(shape);
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for a shape");
    }
    info->material = m;
    info->light = -1;
    info->uniform = mt__material_is_uniform(m);
    s->prims[s->nprims++] = info;
    mt_shape_set_user(shape, info);
    if ((rc = mt_geometry_attach(s->geom, shape, err)) != MT_OK) return rc;
    if (al) {
        mt__light *l = &s->lights[s->nlights];
        if ((rc = mt__area_light_create(l, al, alps, shape, err)) != MT_OK) return rc;
        info->light = s->nlights++;
        mt__loader_report_unused(ld, alps);
    }
    return MT_OK;
}

static mt_status world_end(mt__loader *ld, mt_error *err)
{
    mt_scene *s = ld->scene;
    mt_status rc;
    int i;
    if ((rc = mt_geometry_commit(s->geom, err)) != MT_OK) return rc;
    s->light_samples = mt__malloc(((size_t)s->nlights + 1) * sizeof *s->light_samples);
    s->infinite = mt__malloc(((size_t)s->nlights + 1) * sizeof *s->infinite);
    if (!s->light_samples || !s->infinite) return mt_error_set(err, MT_ERR_NOMEM, "out of memory");
    for (i = 0; i < s->nlights; ++i) {
        int n = s->lights[i].nsamples, p = 1;
        /* pbrt-v2's Sampler::RoundSize (powers of two for lowdiscrepancy) */
        if (s->round_pow2) {
            while (p < n) p <<= 1;
            n = p;
        }
        s->light_samples[i] = n;
        if (s->lights[i].kind == MT__LIGHT_INFINITE) s->infinite[s->ninfinite++] = i;
    }
    if (s->nlights == 0)
        mt__loader_warn(ld, NULL, 0, "No light sources defined in scene; possibly rendering a black image.");
    ld->phase = MT__PHASE_DONE;
    return MT_OK;
}

static const char *const options_only[] = {"Camera", "Film", "PixelFilter", "Sampler",
                                           "SurfaceIntegrator", "VolumeIntegrator", "Renderer",
                                           "Accelerator", "TransformTimes", "WorldBegin", NULL};
static const char *const world_only[] = {"AttributeBegin", "AttributeEnd", "TransformBegin",
                                         "TransformEnd", "Texture", "Material",
                                         "MakeNamedMaterial", "NamedMaterial", "LightSource",
                                         "AreaLightSource", "Shape", "ReverseOrientation",
                                         "WorldEnd", NULL};

static mt_status on_statement(void *ctx, const mt_statement *st, mt_error *err)
{
    mt__loader *ld = ctx;
    const char *d = st->directive;
    mt__option *slot;
    mt_status rc;
    int handled;
    snprintf(ld->last_file, sizeof ld->last_file, "%s", st->file ? st->file : "");
    ld->last_line = st->line;
    if (ld->phase == MT__PHASE_DONE)
        return load_fail(err, MT_ERR_UNSUPPORTED,
                    "%s after WorldEnd: materia renders one WorldBegin/WorldEnd block%s", d, NULL);
    if (strcmp(d, "Volume") == 0 || strcmp(d, "ObjectBegin") == 0 || strcmp(d, "ObjectEnd") == 0 ||
        strcmp(d, "ObjectInstance") == 0)
        return load_fail(err, MT_ERR_UNSUPPORTED, "%s is not supported by materia%s",
                    d, d[0] == 'V' ? " (no participating media)" : " (no object instancing)");
    if (ld->phase == MT__PHASE_WORLD && name_in(d, options_only))
        return load_fail(err, MT_ERR_INVALID, "%s is not allowed inside the world block%s", d, NULL);
    if (ld->phase == MT__PHASE_OPTIONS && name_in(d, world_only))
        return load_fail(err, MT_ERR_INVALID, "%s must be inside WorldBegin/WorldEnd%s", d, NULL);
    if ((slot = option_slot(ld, d)) != NULL && (rc = check_option_type(st, err)) != MT_OK) return rc;
    if (strcmp(d, "Camera") == 0 && is_animated(ld->state))
        return mt_error_set(err, MT_ERR_UNSUPPORTED, "Camera: animated transforms are not supported");
    if ((rc = mt_state_apply(ld->state, st, &handled, err)) != MT_OK) return rc;
    if (handled && strcmp(d, "MakeNamedMaterial") == 0) {
        /* pbrt-v2 makes the material here: a wrong parameter fails at this
         * line even when no shape uses the material */
        mt_material *m = mt_material_named_from_state(ld->state, st->args[0].string, err);
        if (!m) return err->status;
        mt_material_destroy(m);
    }
    if (handled) return MT_OK;
    if (slot) {
        /* pbrt-v2 pbrtCamera: CameraToWorld = Inverse(curTransform) */
        if (slot == &ld->camera) ld->camera_to_world = mt_transform_inverse(mt_state_transform(ld->state));
        return record_option(slot, st, err);
    }
    if (strcmp(d, "TransformTimes") == 0) return MT_OK; /* shutter times: no motion blur */
    if (strcmp(d, "WorldBegin") == 0) {
        ld->phase = MT__PHASE_WORLD;
        return mt__scene_build_options(ld, err);
    }
    if (strcmp(d, "WorldEnd") == 0) return world_end(ld, err);
    if (strcmp(d, "LightSource") == 0) return do_light_source(ld, st, err);
    if (strcmp(d, "Shape") == 0) return do_shape(ld, st, err);
    return load_fail(err, MT_ERR_UNSUPPORTED, "%s is not supported by materia%s", d, NULL);
}

/* ---- scenes --------------------------------------------------------------- */

void mt_render_options_default(mt_render_options *o)
{
    memset(o, 0, sizeof *o);
    o->mode = MT_MODE_PBRT_V2;
}

static void option_free(mt__option *o)
{
    mt_paramset_destroy(o->ps);
    mt__free(o->type);
    mt__free(o->file);
}

static void loader_free(mt__loader *ld)
{
    mt__option *all[] = {&ld->camera, &ld->film, &ld->filter, &ld->sampler,
                         &ld->surface, &ld->volume, &ld->renderer, &ld->accelerator};
    size_t i;
    for (i = 0; i < sizeof all / sizeof all[0]; ++i) option_free(all[i]);
    mt_state_destroy(ld->state);
    mt__free((void *)ld->reported);
}

void mt_scene_destroy(mt_scene *s)
{
    int i;
    if (!s) return;
    mt_geometry_destroy(s->geom);
    for (i = 0; i < s->nlights; ++i) mt__light_free(&s->lights[i]);
    for (i = 0; i < s->nprims; ++i) mt__free(s->prims[i]);
    for (i = 0; i < s->nmaterials; ++i) mt_material_destroy(s->materials[i]);
    mt__free(s->lights);
    mt__free(s->prims);
    mt__free(s->materials);
    mt__free(s->light_samples);
    mt__free(s->dipole.file_pts);
    mt__free(s->infinite);
    mt__free(s->filename);
    mt__free(s->sampler_name);
    mt__free(s);
}

typedef mt_status (*parse_fn)(const void *src, const mt_parse_options *po, mt__loader *ld,
                              mt_error *err);

static mt_scene *load(parse_fn parse, const void *src, const char *name,
                      const mt_render_options *o, mt_error *err)
{
    mt_render_options def;
    mt__loader ld;
    mt_parse_options po;
    mt__option *all[8];
    mt_status rc = MT_OK;
    size_t i;
    if (!o) {
        mt_render_options_default(&def);
        o = &def;
    }
    mt_error_clear(err);
    memset(&ld, 0, sizeof ld);
    ld.warn = o->warn;
    ld.warn_ctx = o->warn_ctx;
    ld.camera_to_world = mt_transform_identity();
    ld.scene = mt__calloc(1, sizeof *ld.scene);
    ld.state = mt_state_create(o->mode);
    all[0] = &ld.camera, all[1] = &ld.film, all[2] = &ld.filter, all[3] = &ld.sampler;
    all[4] = &ld.surface, all[5] = &ld.volume, all[6] = &ld.renderer, all[7] = &ld.accelerator;
    for (i = 0; i < 8; ++i)
        if (!(all[i]->ps = mt_paramset_create())) rc = MT_ERR_NOMEM;
    if (!ld.scene || !ld.state || rc != MT_OK || !(ld.scene->geom = mt_geometry_create())) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory loading %s", name);
        mt_scene_destroy(ld.scene);
        loader_free(&ld);
        return NULL;
    }
    ld.scene->mode = o->mode;
    mt_state_set_warning(ld.state, o->warn, o->warn_ctx);
    memset(&po, 0, sizeof po);
    po.warn = o->warn;
    po.warn_ctx = o->warn_ctx;
    rc = parse(src, &po, &ld, err);
    if (rc == MT_OK && ld.phase != MT__PHASE_DONE) {
        rc = mt_error_set(err, MT_ERR_INVALID, "the scene ends without %s",
                          ld.phase == MT__PHASE_OPTIONS ? "WorldBegin" : "WorldEnd");
        mt_error_locate(err, ld.last_file[0] ? ld.last_file : name, ld.last_line, 0);
    }
    loader_free(&ld);
    if (rc != MT_OK) {
        mt_scene_destroy(ld.scene);
        return NULL;
    }
    return ld.scene;
}

static mt_status parse_path(const void *src, const mt_parse_options *po, mt__loader *ld, mt_error *err)
{
    return mt_parse_file((const char *)src, po, on_statement, ld, err);
}

typedef struct text_src {
    const char *text, *name, *dir;
} text_src;

static mt_status parse_text(const void *src, const mt_parse_options *po, mt__loader *ld, mt_error *err)
{
    const text_src *t = src;
    return mt_parse_string(t->text, t->name, t->dir, 1, po, on_statement, ld, err);
}

mt_scene *mt_scene_load(const char *path, const mt_render_options *o, mt_error *err)
{
    mt_error_clear(err);
    return load(parse_path, path, path, o, err);
}

mt_scene *mt_scene_load_string(const char *text, const char *name, const char *dir,
                               const mt_render_options *o, mt_error *err)
{
    text_src t;
    mt_error_clear(err);
    t.text = text;
    t.name = name ? name : "<string>";
    t.dir = dir;
    return load(parse_text, &t, t.name, o, err);
}

const char *mt_scene_filename(const mt_scene *s) { return s->filename; }

void mt_scene_image_size(const mt_scene *s, int *width, int *height)
{
    *width = s->film.width;
    *height = s->film.height;
}

int mt_scene_spp(const mt_scene *s) { return s->spp; }
