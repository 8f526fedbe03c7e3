/* Writing rendered images with their provenance, and the one-call render. */
#include <stdio.h>
#include "materia.h"
#include "tracer/scene.h"

mt_status mt_render_write(const char *path, const mt_image *img, const mt_scene *s,
                          const mt_render_options *o, mt_error *err)
{
    char spp[32], seed[32];
    mt_image_attr attrs[5];
    int spp_used = o && o->spp > 0 ? o->spp : s->spp;
    mt_error_clear(err);
    snprintf(spp, sizeof spp, "%d", spp_used);
    snprintf(seed, sizeof seed, "%llu", (unsigned long long)(o ? o->seed : 0));
    attrs[0].name = "materia:spp";
    attrs[0].value = spp;
    attrs[1].name = "materia:seed";
    attrs[1].value = seed;
    attrs[2].name = "materia:mode";
    attrs[2].value = mt_mode_name(s->mode);
    attrs[3].name = "materia:integrator";
    attrs[3].value = s->integrator == MT__INTEGRATOR_PATH     ? "path"
                      : s->integrator == MT__INTEGRATOR_DIPOLE ? "dipolesubsurface"
                                                               : "directlighting";
    attrs[4].name = "materia:version";
    attrs[4].value = mt_version();
    return mt_image_write(path, img, attrs, 5, err);
}

mt_status mt_render_file(const char *path, const mt_render_options *o, mt_image *image,
                         mt_image *variance, mt_render_stats *stats, mt_error *err)
{
    mt_error_clear(err);
    mt_scene *s = mt_scene_load(path, o, err);
    mt_status st;
    if (!s) return err ? err->status : MT_ERR_INVALID;
    st = mt_scene_render(s, o, image, variance, stats, err);
    mt_scene_destroy(s);
    return st;
}
