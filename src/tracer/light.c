/*
 * pbrt-v2's point, spot, distant and diffuse area lights (the files in lights/):
 * parameters, Sample_L, Pdf, L; infinite lights are in light_infinite.c.
 */
#include <string.h>
#include "tracer/light.h"

/* "L" or "I" times "scale" (both spectra, default 1). */
static mt_status radiance(const mt_paramset *ps, const char *name, mt_rgb *out, mt_error *err)
{
    mt_rgb v, sc;
    mt_status st;
    if ((st = mt_params_rgb(ps, name, mt_rgb_gray(1), &v, err)) != MT_OK ||
        (st = mt_params_rgb(ps, "scale", mt_rgb_gray(1), &sc, err)) != MT_OK)
        return st;
    *out = mt_rgb_mul(v, sc);
    return MT_OK;
}

static mt_status nsamples(const mt_paramset *ps, int *out, mt_error *err)
{
    mt_status st = mt_params_int(ps, "nsamples", 1, out, err);
    if (st == MT_OK && (*out < 1 || *out > 65536))
        return mt_error_param(err, MT_ERR_INVALID, "nsamples",
                              "nsamples must be between 1 and 65536 (got %d)", *out);
    return st;
}

/* A unit direction from two points given by parameters (default from
 * (0,0,0), to (0,0,1)); *dir = to - from normalized. */
static mt_status direction(const mt_paramset *ps, mt_vec3 *from, mt_vec3 *dir, mt_error *err)
{
    mt_vec3 to, d;
    mt_status st;
    if ((st = mt_params_point(ps, "from", mt_v3(0, 0, 0), from, err)) != MT_OK ||
        (st = mt_params_point(ps, "to", mt_v3(0, 0, 1), &to, err)) != MT_OK)
        return st;
    d = mt_v3_sub(to, *from);
    if (mt_v3_len2(d) == 0)
        return mt_error_param(err, MT_ERR_INVALID, "to", "\"from\" and \"to\" are the same point");
    *dir = mt_v3_normalize(d);
    return MT_OK;
}

static mt_status spot_create(mt__light *l, const mt_paramset *ps, const mt_transform *l2w,
                             mt_error *err)
{
    mt_real cone, delta;
    mt_vec3 from;
    mt_status st;
    if ((st = radiance(ps, "I", &l->L, err)) != MT_OK ||
        (st = mt_params_float(ps, "coneangle", 30, &cone, err)) != MT_OK ||
        (st = mt_params_float(ps, "conedeltaangle", 5, &delta, err)) != MT_OK ||
        (st = direction(ps, &from, &l->dir, err)) != MT_OK)
        return st;
    /* pbrt-v2: light2world = l2w * Translate(from) * Inverse(dirToZ), with
     * dirToZ a rotation taking dir to +z; only the light-space z of a
     * direction matters (Falloff), which is dir . (l2w^-1 w) / |l2w^-1 w| */
    l->pos = mt_transform_point(l2w, from);
    l->w2l = mt_transform_inverse(l2w);
    l->l2w = *l2w;
    l->cos_total = mt_cos(mt_radians(cone));
    l->cos_falloff = mt_cos(mt_radians(cone - delta));
    return MT_OK;
}

mt_status mt__light_create(mt__light *l, const char *type, const mt_paramset *ps,
                           const mt_transform *l2w, mt_mode mode, mt_error *err)
{
    mt_status st;
    int i, j;
    memset(l, 0, sizeof *l);
    l->nsamples = 1;
    l->l2w = *l2w;
    l->w2l = mt_transform_inverse(l2w);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            l->l2w3[i][j] = (mt_real)l->l2w.m.m[i][j];
            l->w2l3[i][j] = (mt_real)l->w2l.m.m[i][j];
        }
    if (strcmp(type, "point") == 0) {
        mt_vec3 from;
        l->kind = MT__LIGHT_POINT;
        if ((st = radiance(ps, "I", &l->L, err)) != MT_OK ||
            (st = mt_params_point(ps, "from", mt_v3(0, 0, 0), &from, err)) != MT_OK)
            return st;
        /* pbrt-v2: Translate(from) * light2world -- "from" moves the light in
         * world space, after the current transform */
        l->pos = mt_v3_add(mt_transform_point(l2w, mt_v3(0, 0, 0)), from);
        return MT_OK;
    }
    if (strcmp(type, "spot") == 0) {
        l->kind = MT__LIGHT_SPOT;
        return spot_create(l, ps, l2w, err);
    }
    if (strcmp(type, "distant") == 0) {
        mt_vec3 from, d;
        l->kind = MT__LIGHT_DISTANT;
        if ((st = radiance(ps, "L", &l->L, err)) != MT_OK ||
            (st = direction(ps, &from, &d, err)) != MT_OK)
            return st;
        /* pbrt-v2: lightDir = Normalize(LightToWorld(from - to)) */
        l->dir = mt_v3_normalize(mt_transform_vector(l2w, mt_v3_neg(d)));
        return MT_OK;
    }
    if (strcmp(type, "infinite") == 0 || strcmp(type, "exinfinite") == 0) {
        char map[4096];
        l->kind = MT__LIGHT_INFINITE;
        if ((st = radiance(ps, "L", &l->L, err)) != MT_OK ||
            (st = nsamples(ps, &l->nsamples, err)) != MT_OK ||
            (st = mt_params_filename(ps, "mapname", "", map, sizeof map, err)) != MT_OK)
            return st;
        return mt__infinite_init(l, map, mode, err);
    }
    if (strcmp(type, "goniometric") == 0 || strcmp(type, "projection") == 0)
        return mt_error_set(err, MT_ERR_UNSUPPORTED,
                            "LightSource \"%s\" is not supported by materia (point, spot, "
                            "distant, infinite)", type);
    return mt_error_set(err, MT_ERR_UNSUPPORTED, "LightSource \"%s\" unknown", type);
}

mt_status mt__area_light_create(mt__light *l, const char *type, const mt_paramset *ps,
                                const mt_shape *shape, mt_error *err)
{
    mt_status st;
    memset(l, 0, sizeof *l);
    if (strcmp(type, "area") != 0 && strcmp(type, "diffuse") != 0)
        return mt_error_set(err, MT_ERR_UNSUPPORTED,
                            "AreaLightSource \"%s\" unknown (\"area\" or \"diffuse\")", type);
    l->kind = MT__LIGHT_AREA;
    l->shape = shape;
    if ((st = radiance(ps, "L", &l->L, err)) != MT_OK ||
        (st = nsamples(ps, &l->nsamples, err)) != MT_OK)
        return st;
    if (!(mt_shape_total_area(shape) > 0))
        return mt_error_set(err, MT_ERR_INVALID, "AreaLightSource on a shape of zero area");
    return MT_OK;
}

void mt__light_free(mt__light *l)
{
    if (l->kind == MT__LIGHT_INFINITE) {
        mt__distrib2d_free(&l->distrib);
        mt_mipmap_destroy(l->map);
        l->map = NULL;
    }
}

/* pbrt-v2 SpotLight::Falloff: smooth quartic between the two cones. */
static mt_real spot_falloff(const mt__light *l, mt_vec3 w)
{
    mt_vec3 v = mt_transform_vector(&l->w2l, w);
    mt_real len = mt_v3_len(v), c, delta;
    if (!(len > 0)) return 0;
    c = mt_v3_dot(l->dir, v) / len;
    if (c < l->cos_total) return 0;
    if (c > l->cos_falloff) return 1;
    delta = (c - l->cos_total) / (l->cos_falloff - l->cos_total);
    return delta * delta * delta * delta;
}

static mt_ray ray_to(const mt_surface *sf, mt_vec3 p, mt_vec3 target)
{
    if (sf) return mt_surface_spawn_to(sf, target);
    return mt_ray_make(p, mt_v3_sub(target, p), 0, 1 - (mt_real)1e-4);
}

static mt_ray ray_along(const mt_surface *sf, mt_vec3 p, mt_vec3 w)
{
    if (sf) return mt_surface_spawn(sf, w);
    return mt_ray_make(p, w, 0, MT_RAY_TMAX);
}

void mt__light_sample_l(const mt__light *l, const mt_surface *sf, mt_vec3 p, mt_real ucomp,
                        mt_real u1, mt_real u2, mt__light_sample *out)
{
    mt_vec3 d;
    mt_real d2;
    out->Li = mt_rgb_black();
    out->pdf = 0;
    out->pdf_any_dir = 0;
    out->wi = mt_v3(0, 0, 1);
    switch (l->kind) {
    case MT__LIGHT_POINT:
    case MT__LIGHT_SPOT:
        d = mt_v3_sub(l->pos, p);
        d2 = mt_v3_len2(d);
        if (!(d2 > 0)) return;
        out->wi = mt_v3_normalize(d);
        out->pdf = 1;
        out->Li = mt_rgb_divs(l->L, d2);
        if (l->kind == MT__LIGHT_SPOT) out->Li = mt_rgb_scale(out->Li, spot_falloff(l, mt_v3_neg(out->wi)));
        out->shadow = ray_to(sf, p, l->pos);
        return;
    case MT__LIGHT_DISTANT:
        out->wi = l->dir;
        out->pdf = 1;
        out->Li = l->L;
        out->shadow = ray_along(sf, p, l->dir);
        return;
    case MT__LIGHT_INFINITE:
        mt__infinite_sample(l, u1, u2, &out->wi, &out->pdf, &out->Li);
        if (out->pdf > 0) out->shadow = ray_along(sf, p, out->wi);
        return;
    case MT__LIGHT_AREA: {
        mt_vec3 ns, ps;
        mt_real pdf = 0;
        int any_dir = 0;
        mt_shape_kind k = mt_shape_kind_of(l->shape);
        /* pbrt-v2's ShapeSet::Sample (as released, without re-intersection;
         * corrected mode moves the sample to the set's closest point along
         * its ray). A lone sphere answers for itself, with the pdf its cone
         * gives every direction; so does a lone disk, whose sample is the
         * first point of its ray. Corrected, their re-intersection gives the
         * sample back unless a mirror makes the hit's normal differ. */
        if ((k == MT_SHAPE_SPHERE || k == MT_SHAPE_DISK) &&
            (!(mt_shape_mode(l->shape) & MT_FIX_SHAPESET_HIT) ||
             mt_shape_flip(l->shape) == mt_shape_reverse_orientation(l->shape)))
            any_dir = mt_shape_sample_from_pdf(l->shape, p, u1, u2, &ns, &ps, &pdf);
        else
            ps = mt_shape_set_sample_from(l->shape, p, ucomp, u1, u2, &ns);
        d = mt_v3_sub(ps, p);
        if (!(mt_v3_len2(d) > 0) || !mt_v3_is_finite(d)) return;
        out->wi = mt_v3_normalize(d);
        out->pdf = any_dir ? pdf : mt_shape_set_pdf_from(l->shape, p, out->wi);
        out->pdf_any_dir = any_dir;
        out->Li = mt__area_light_l(l, ns, mt_v3_neg(out->wi));
        out->shadow = ray_to(sf, p, ps);
        return;
    }
    }
}

mt_real mt__light_pdf(const mt__light *l, mt_vec3 p, mt_vec3 wi)
{
    if (l->kind == MT__LIGHT_AREA) return mt_shape_set_pdf_from(l->shape, p, wi);
    if (l->kind == MT__LIGHT_INFINITE) return mt__infinite_pdf(l, wi);
    return 0;
}

mt_rgb mt__light_le(const mt__light *l, mt_vec3 d)
{
    return l->kind == MT__LIGHT_INFINITE ? mt__infinite_le(l, d) : mt_rgb_black();
}
