/*
 * The options block of a scene (pbrt-v2 api.cpp RenderOptions::MakeCamera,
 * MakeRenderer): film (film/image.cpp CreateImageFilm), pixel filter,
 * camera (cameras/perspective.cpp, orthographic.cpp Create*Camera), sampler
 * (its pixel sample count), surface and volume integrators, renderer and
 * accelerator, with pbrt-v2's parameter names and defaults.
 */
#include <stdio.h>
#include <string.h>
#include "core/alloc.h"
#include "tracer/scene_load.h"

#define TRY(o, call)                                                                           \
    do {                                                                                       \
        mt_status st_ = (call);                                                                \
        if (st_ != MT_OK) return mt__option_fail((o), st_, err);                               \
    } while (0)

static const char *type_or(const mt__option *o, const char *def) { return o->type ? o->type : def; }

static mt_status build_film(mt__loader *ld, mt_error *err)
{
    mt_scene *s = ld->scene;
    const mt__option *o = &ld->film, *fo = &ld->filter;
    const mt_paramset *ps = o->ps;
    const double *crop;
    int xres, yres, ncrop, display, i;
    const char *name;
    mt_real c[4] = {0, 1, 0, 1};
    mt__filter filter;
    TRY(o, mt_params_int(ps, "xresolution", 640, &xres, err));
    TRY(o, mt_params_int(ps, "yresolution", 480, &yres, err));
    if (xres < 1 || yres < 1 || xres > 65536 || yres > 65536)
        return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, xres < 1 || xres > 65536 ? "xresolution" : "yresolution",
                                                 "Film: the resolution must be between 1 and 65536 (got %dx%d)", xres, yres), err);
    TRY(o, mt_params_floats(ps, "cropwindow", &crop, &ncrop, err));
    if (crop && ncrop != 4)
        return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, "cropwindow",
                                                 "Film: cropwindow needs 4 values (got %d)", ncrop), err);
    for (i = 0; crop && i < 4; ++i) c[i] = (mt_real)crop[i];
    TRY(o, mt_params_string(ps, "filename", "pbrt.exr", &name, err));
    TRY(o, mt_params_bool(ps, "display", 0, &display, err));
    if (!*name) name = "pbrt.exr";
    s->filename = mt__strdup(name);
    if (!s->filename) return mt_error_set(err, MT_ERR_NOMEM, "out of memory");
    TRY(fo, mt__filter_create(&filter, type_or(fo, "box"), fo->ps, err));
    mt__film_init(&s->film, xres, yres, c, &filter);
    return MT_OK;
}

/* pbrt-v2 Camera constructor: warns when CameraToWorld scales. */
static void check_scale(mt__loader *ld, const mt__option *o)
{
    int i;
    for (i = 0; i < 3; ++i) {
        mt_vec3 a = mt_v3(i == 0, i == 1, i == 2);
        mt_real l2 = mt_v3_len2(mt_transform_vector(&ld->camera_to_world, a));
        if (l2 < (mt_real)0.999 || l2 > (mt_real)1.001) {
            mt__loader_warn(ld, o->file, o->line,
                            "Scaling detected in world-to-camera transformation!");
            return;
        }
    }
}

static mt_status build_camera(mt__loader *ld, mt_error *err)
{
    mt_scene *s = ld->scene;
    const mt__option *o = &ld->camera;
    const mt_paramset *ps = o->ps;
    const char *type = type_or(o, "perspective");
    int ortho = strcmp(type, "orthographic") == 0, nsw, i;
    mt_real sopen, sclose, lensr, focal, frame, fov = 90, halffov, screen[4];
    const double *sw;
    TRY(o, mt_params_float(ps, "shutteropen", 0, &sopen, err));
    TRY(o, mt_params_float(ps, "shutterclose", 1, &sclose, err));
    TRY(o, mt_params_float(ps, "lensradius", 0, &lensr, err));
    TRY(o, mt_params_float(ps, "focaldistance", (mt_real)1e30, &focal, err));
    TRY(o, mt_params_float(ps, "frameaspectratio",
                           (mt_real)((float)s->film.xres / (float)s->film.yres), &frame, err));
    TRY(o, mt_params_floats(ps, "screenwindow", &sw, &nsw, err));
    if (!ortho) {
        TRY(o, mt_params_float(ps, "fov", 90, &fov, err));
        TRY(o, mt_params_float(ps, "halffov", -1, &halffov, err));
        if (halffov > 0) fov = 2 * halffov; /* pbrt-v2's structure synth hack */
        if (!(fov > 0 && fov < 180))
            return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, "fov",
                                                     "Camera: fov must be in (0, 180) degrees (got %g)", (double)fov), err);
    }
    if (lensr < 0 || !(focal > 0))
        return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, lensr < 0 ? "lensradius" : "focaldistance",
                                                 "Camera: lensradius must be >= 0 and focaldistance > 0"), err);
    if (!(frame > 0))
        return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, "frameaspectratio",
                                                 "Camera: frameaspectratio must be positive"), err);
    mt__camera_default_screen(frame, screen);
    if (sw && nsw != 4)
        return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, "screenwindow",
                                                 "Camera: screenwindow needs 4 values (got %d)", nsw), err);
    for (i = 0; sw && i < 4; ++i) screen[i] = (mt_real)sw[i];
    if (screen[0] == screen[1] || screen[2] == screen[3])
        return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, "screenwindow",
                                                 "Camera: the screen window is empty"), err);
    check_scale(ld, o);
    mt__camera_init(&s->camera, ortho, fov, screen, lensr, focal, s->film.xres, s->film.yres,
                    &ld->camera_to_world, s->mode);
    return MT_OK;
}

static int is_pow2(int v) { return v > 0 && (v & (v - 1)) == 0; }
static int options_round_up_pow2(int v)
{
    int p = 1;
    while (p < v && p < (1 << 24)) p <<= 1;
    return p;
}

static mt_status build_sampler(mt__loader *ld, mt_error *err)
{
    mt_scene *s = ld->scene;
    const mt__option *o = &ld->sampler;
    const mt_paramset *ps = o->ps;
    const char *type = type_or(o, "lowdiscrepancy");
    int spp = 4, x, y, jitter, lo;
    const char *method;
    if (strcmp(type, "stratified") == 0) {
        TRY(o, mt_params_int(ps, "xsamples", 2, &x, err));
        TRY(o, mt_params_int(ps, "ysamples", 2, &y, err));
        TRY(o, mt_params_bool(ps, "jitter", 1, &jitter, err));
        spp = x * y;
    } else if (strcmp(type, "adaptive") == 0) {
        /* pbrt-v2's adaptive sampler takes between minsamples and maxsamples
         * (both rounded up to powers of two); materia takes maxsamples */
        TRY(o, mt_params_int(ps, "minsamples", 4, &lo, err));
        TRY(o, mt_params_int(ps, "maxsamples", 32, &spp, err));
        TRY(o, mt_params_string(ps, "method", "contrast", &method, err));
        spp = options_round_up_pow2(spp);
    } else {
        TRY(o, mt_params_int(ps, "pixelsamples", 4, &spp, err));
    }
    if (spp < 1 || spp > (1 << 24))
        return mt__option_fail(o, mt_error_set(err, MT_ERR_INVALID,
                                               "Sampler: the pixel sample count must be between 1 and 2^24 (got %d)", spp), err);
    s->round_pow2 = strcmp(type, "lowdiscrepancy") == 0;
    if (s->round_pow2 && !is_pow2(spp)) {
        mt__loader_warn(ld, o->file, o->line, "Pixel samples being rounded up to power of 2");
        spp = options_round_up_pow2(spp);
    }
    s->spp = spp;
    s->sampler_name = mt__strdup(type);
    if (!s->sampler_name) return mt_error_set(err, MT_ERR_NOMEM, "out of memory");
    mt__loader_warn(ld, o->file, o->line,
                    "Sampler \"%s\" (%d samples per pixel unless the renderer is told otherwise): "
                    "materia draws them from its own deterministic low-discrepancy sampler "
                    "(Owen-scrambled Sobol' points)",
                    type, spp);
    return MT_OK;
}

static mt_status build_integrators(mt__loader *ld, mt_error *err)
{
    mt_scene *s = ld->scene;
    const mt__option *o = &ld->surface, *v = &ld->volume;
    const char *type = type_or(o, "directlighting"), *strategy, *vtype = type_or(v, "emission");
    mt_real step;
    TRY(o, mt_params_int(o->ps, "maxdepth", 5, &s->maxdepth, err));
    if (s->maxdepth < 0 || s->maxdepth > 1000)
        return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, "maxdepth",
                                                 "SurfaceIntegrator: maxdepth must be between 0 and 1000 (got %d)", s->maxdepth), err);
    if (strcmp(type, "path") == 0) {
        s->integrator = MT__INTEGRATOR_PATH;
    } else if (strcmp(type, "dipolesubsurface") == 0) {
        /* pbrt-v2 CreateDipoleSubsurfaceIntegrator; direct lighting from every
         * light as UniformSampleAllLights */
        char points[4096];
        s->integrator = MT__INTEGRATOR_DIPOLE;
        s->strategy_all = 1;
        TRY(o, mt_params_float(o->ps, "maxerror", (mt_real)0.05, &s->dipole.maxerror, err));
        TRY(o, mt_params_float(o->ps, "minsampledistance", (mt_real)0.25, &s->dipole.min_dist, err));
        TRY(o, mt_params_filename(o->ps, "pointsfile", "", points, sizeof points, err));
        if (!(s->dipole.maxerror >= 0) || !mt_is_finite(s->dipole.maxerror))
            return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, "maxerror",
                                                     "SurfaceIntegrator \"dipolesubsurface\": maxerror must be >= 0 (got %g)", (double)s->dipole.maxerror), err);
        if (!(s->dipole.min_dist > 0) || !mt_is_finite(s->dipole.min_dist))
            return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, "minsampledistance",
                                                     "SurfaceIntegrator \"dipolesubsurface\": minsampledistance must be positive (got %g)", (double)s->dipole.min_dist), err);
        if (points[0]) {
            mt_status st = mt__dipole_read_points(points, &s->dipole.file_pts, &s->dipole.nfile_pts, err);
            if (st != MT_OK) {
                char msg[sizeof err->message];
                /* a file that cannot be read: at the statement that names it */
                if (!err->file[0]) {
                    if (!err->param[0]) snprintf(err->param, sizeof err->param, "pointsfile");
                    return mt__option_fail(o, st, err);
                }
                if (strcmp(err->file, points) != 0) return st;
                /* the points file's own line, and the statement that named it */
                snprintf(msg, sizeof msg, "%.300s (read for SurfaceIntegrator \"dipolesubsurface\" at %.150s:%d)", err->message, o->file ? o->file : "", o->line);
                memcpy(err->message, msg, sizeof msg);
                return st;
            }
        }
    } else {
        s->integrator = MT__INTEGRATOR_DIRECT;
        TRY(o, mt_params_string(o->ps, "strategy", "all", &strategy, err));
        if (strcmp(strategy, "all") != 0 && strcmp(strategy, "one") != 0)
            return mt__option_fail(o, mt_error_param(err, MT_ERR_INVALID, "strategy",
                                                     "SurfaceIntegrator \"directlighting\": strategy \"%s\" unknown (\"all\" or \"one\")", strategy), err);
        s->strategy_all = strcmp(strategy, "all") == 0;
    }
    /* without volume regions both volume integrators contribute nothing and
     * transmit everything: their step size is read and has no effect */
    TRY(v, mt_params_float(v->ps, "stepsize", 1, &step, err));
    (void)vtype;
    return MT_OK;
}

static void mark_all_used(const mt_paramset *ps)
{
    int i;
    for (i = 0; ps && i < mt_paramset_count(ps); ++i)
        mt_paramset_mark_used(ps, mt_paramset_at(ps, i)->name);
}

mt_status mt__scene_build_options(mt__loader *ld, mt_error *err)
{
    mt_status st;
    int visids;
    const mt__option *all[] = {&ld->film, &ld->filter, &ld->camera, &ld->sampler,
                               &ld->surface, &ld->volume, &ld->renderer, &ld->accelerator};
    size_t i;
    if ((st = build_film(ld, err)) != MT_OK || (st = build_camera(ld, err)) != MT_OK ||
        (st = build_sampler(ld, err)) != MT_OK || (st = build_integrators(ld, err)) != MT_OK)
        return st;
    if (mt_params_bool(ld->renderer.ps, "visualizeobjectids", 0, &visids, err) != MT_OK)
        return mt__option_fail(&ld->renderer, err->status, err);
    if (visids)
        return mt__option_fail(&ld->renderer, mt_error_param(err, MT_ERR_UNSUPPORTED, "visualizeobjectids",
                                                             "Renderer: visualizeobjectids is not supported"), err);
    /* the accelerator's parameters only tune pbrt-v2's structure; materia's
     * BVH has its own build (the image does not depend on it) */
    mark_all_used(ld->accelerator.ps);
    for (i = 0; i < sizeof all / sizeof all[0]; ++i)
        if (all[i]->ps) mt_paramset_report_unused(all[i]->ps, ld->warn, ld->warn_ctx);
    return MT_OK;
}
