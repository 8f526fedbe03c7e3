/*
 * Shading a path vertex and direct lighting, after pbrt-v2's
 * core/intersection.cpp (GetBSDF, Le) and core/integrator.cpp
 * (EstimateDirect, UniformSampleOneLight, UniformSampleAllLights).
 */
#include "materia/sampling.h"
#include "tracer/shading.h"

#define NON_SPECULAR ((unsigned)MT_BSDF_ALL & ~(unsigned)MT_BSDF_SPECULAR)

int mt__vertex_shade(mt__thread_ctx *tc, const mt_hit *hit, const mt_ray *ray,
                     const mt_raydiff *rd, mt__vertex *v)
{
    v->info = mt_shape_user(hit->shape);
    if (v->info->uniform) mt_hit_surface_no_uv(hit, ray, &v->sf);
    else mt_hit_surface(hit, ray, &v->sf);
    if (rd) mt_surface_differentials(&v->sf, rd);
    v->sh = &v->sf.dg;
    if (mt_surface_has_shading(&v->sf)) {
        mt_surface_shading(&v->sf, &v->dgs);
        v->sh = &v->dgs;
    }
    v->bsdf = mt_material_get_bsdf(v->info->material, &v->sf.dg, v->sh, tc->arena, &tc->err);
    if (!v->bsdf) {
        tc->shading_failures++;
        return 0;
    }
    v->p = v->sh->p;
    v->n = mt_bsdf_shading(v->bsdf)->n; /* after bump mapping, as pbrt-v2's dgShading.nn */
    v->wo = mt_v3_normalize(mt_v3_neg(ray->d));
    mt__bsdf_wo_init(v->bsdf, v->wo, &v->bwo);
    v->ncomp = mt_bsdf_num_components(v->bsdf, MT_BSDF_ALL);
    v->ncomp_nonspecular = mt_bsdf_num_components(v->bsdf, NON_SPECULAR);
    return 1;
}

mt_rgb mt__vertex_le(const mt_scene *s, const mt__vertex *v)
{
    if (v->info->light < 0) return mt_rgb_black();
    return mt__area_light_l(&s->lights[v->info->light], v->sf.dg.n, v->wo);
}

/* Lights with at most this many primitives are tested directly by the
 * BSDF-sampled rays of direct lighting (a closest hit over the scene
 * otherwise). */
#define DIRECT_TEST_PRIMS 16u

/* Radiance from `light` arriving along a BSDF-sampled ray: its area light if
 * the ray's first hit is on it, its Le if the ray leaves the scene (pbrt-v2's
 * EstimateDirect traces the ray and compares the primitive it hits). The
 * same answer comes cheaper as "the light's nearest hit, then nothing else
 * before it" -- an any-hit query, and none at all when the ray misses a
 * small light -- or, for an infinite light, "nothing at all in the way". */
static mt_rgb light_along(const mt_scene *s, const mt__light *light, const mt_ray *ray)
{
    mt_hit hit;
    if (light->kind == MT__LIGHT_INFINITE)
        return mt_geometry_occluded(s->geom, ray) ? mt_rgb_black() : mt__light_le(light, ray->d);
    if (light->kind != MT__LIGHT_AREA) return mt_rgb_black();
    if (mt_shape_prim_count(light->shape) <= DIRECT_TEST_PRIMS) {
        mt_ray r = *ray, before;
        uint32_t k, n = mt_shape_prim_count(light->shape);
        int any = 0;
        for (k = 0; k < n; ++k)
            if (!mt_shape_missed(light->shape, k, &r) && mt_shape_intersect(light->shape, k, &r, &hit)) {
                r.tmax = hit.t;
                any = 1;
            }
        if (!any) return mt_rgb_black();
        r.tmax = hit.t; /* the nearest of the light's hits */
        before = *ray;
        before.tmax = hit.t * (1 - (mt_real)1e-4); /* the light itself is not in the way */
        if (mt_geometry_occluded(s->geom, &before)) return mt_rgb_black();
        return mt__area_light_l(light, mt_hit_normal(&hit, &r), mt_v3_neg(ray->d));
    }
    if (mt_geometry_intersect(s->geom, ray, &hit)) {
        const mt__prim_info *info = mt_shape_user(hit.shape);
        if (info->light < 0 || &s->lights[info->light] != light) return mt_rgb_black();
        return mt__area_light_l(light, mt_hit_normal(&hit, ray), mt_v3_neg(ray->d));
    }
    return mt_rgb_black();
}

/* EstimateDirect's light sample: f Li |cos| w / pdf, the power heuristic
 * against the non-specular BSDF pdf unless the light is a delta light; ls
 * receives the sample. */
static inline mt_rgb light_term(const mt_scene *s, const mt__light *light, const mt__vertex *v,
                         const mt_real lu[3], mt__light_sample *ls)
{
    mt__light_sample_l(light, &v->sf, v->p, lu[0], lu[1], lu[2], ls);
    if (ls->pdf > 0 && !mt_rgb_is_black(ls->Li)) {
        mt__bsdf_pair pair;
        mt_rgb f = mt__bsdf_f_pair(v->bsdf, &v->bwo, ls->wi, NON_SPECULAR, &pair);
        if (!mt_rgb_is_black(f) && !mt_geometry_occluded(s->geom, &ls->shadow)) {
            mt_real w = 1;
            if (!mt__light_is_delta(light))
                w = mt_power_heuristic(1, ls->pdf, 1, mt__bsdf_pdf_pair(v->bsdf, &pair, NON_SPECULAR));
            return mt_rgb_scale(mt_rgb_mul(f, ls->Li), mt_v3_absdot(ls->wi, v->n) * w / ls->pdf);
        }
    }
    return mt_rgb_black();
}

mt_rgb mt__estimate_direct(mt__thread_ctx *tc, const mt__light *light, const mt__vertex *v,
                           const mt_real lu[3], const mt_real bu[3])
{
    const mt_scene *s = tc->scene;
    mt__light_sample ls;
    mt_bsdf_sample bs;
    mt_rgb Ld = light_term(s, light, v, lu, &ls);
    if (mt__light_is_delta(light)) return Ld;
    /* sample the BSDF */
    bs = mt__bsdf_sample_f_wo(v->bsdf, &v->bwo, bu[0], bu[1], bu[2], NON_SPECULAR);
    if (!mt_rgb_is_black(bs.f) && bs.pdf > 0) {
        mt_real w = 1;
        mt_rgb Li;
        mt_ray ray;
        if (!(bs.type & MT_BSDF_SPECULAR)) {
            mt_real lpdf = ls.pdf_any_dir ? ls.pdf : mt__light_pdf(light, v->p, bs.wi);
            if (lpdf == 0) return Ld;
            w = mt_power_heuristic(1, bs.pdf, 1, lpdf);
        }
        ray = mt_surface_spawn(&v->sf, bs.wi);
        Li = light_along(s, light, &ray);
        if (!mt_rgb_is_black(Li))
            Ld = mt_rgb_add(Ld, mt_rgb_scale(mt_rgb_mul(bs.f, Li),
                                             mt_v3_absdot(bs.wi, v->n) * w / bs.pdf));
    }
    return Ld;
}

/* A discrete choice among n made with u in [0, 1), and u rescaled to [0, 1)
 * within the chosen interval: the choice and the rescaled value are
 * independent and uniform, so one low-discrepancy coordinate serves both
 * and each choice receives a stratified subset of the samples. */
static mt_real reuse(mt_real u, int n, int *which)
{
    int i = (int)(u * (mt_real)n);
    mt_real r;
    if (i > n - 1) i = n - 1;
    *which = i;
    r = u * (mt_real)n - (mt_real)i;
    return r < 1 ? r : 1 - MT_REAL_EPSILON / 2;
}

mt_bsdf_sample mt__sample_bsdf_pair(const mt__vertex *v, const mt_real u[2], unsigned flags)
{
    int m = mt_bsdf_num_components(v->bsdf, flags), which = 0;
    /* pbrt-v2's BSDF::Sample_f picks component floor(uc * m) of the m that
     * match; the same uc, rescaled within that choice, is the direction's
     * first coordinate */
    mt_real u1 = m > 1 ? reuse(u[0], m, &which) : u[0];
    return mt__bsdf_sample_f_wo(v->bsdf, &v->bwo, u[0], u1, u[1], flags);
}

/* Up to this many primitives, a ShapeSet light's primitive is chosen by the
 * light sample's first value, rescaled within the choice; each choice costs
 * the value log2(count) of its bits (24 in float), so larger sets (meshes)
 * take a value of their own. */
#define MT__SET_REUSE_MAX 256

/* The light of one-light direct lighting and its sample: pair 0's first
 * value chooses it and, rescaled, is the sample's first coordinate (or, for
 * measurements, pair 5's first value chooses it, as pbrt-v2's separate 1D
 * sample does); the primitive of a ShapeSet is chosen by that coordinate
 * too, rescaled again (up to MT__SET_REUSE_MAX primitives), or by pair 1's
 * first value. */
static inline const mt__light *choose_light(mt__thread_ctx *tc, int vertex, mt_real lu[3])
{
    const mt_scene *s = tc->scene;
    const mt__light *light;
    mt_real lpos[2], comp[2];
    int i;
    mt__vertex_sample(tc, vertex, 0, 0, 1, lpos);
    if (s->measure_own_choice) {
        mt_real sel[2];
        mt__vertex_sample(tc, vertex, 5, 0, 1, sel);
        reuse(sel[0], s->nlights, &i);
        lu[1] = lpos[0];
    } else {
        lu[1] = reuse(lpos[0], s->nlights, &i);
    }
    lu[2] = lpos[1];
    light = &s->lights[i];
    comp[0] = 0;
    if (light->kind == MT__LIGHT_AREA && mt_shape_prim_count(light->shape) > 1) {
        if (mt_shape_prim_count(light->shape) <= MT__SET_REUSE_MAX) {
            /* the same value chooses the primitive and, rescaled within it,
             * is the sample's first coordinate: the samples over the whole
             * set stay one stratified set, where a value of its own would
             * give each primitive a random subset of them (a quad light's
             * two triangles) */
            comp[0] = lu[1];
            lu[1] = mt__shape_set_rescale(light->shape, lu[1]);
        } else {
            mt__vertex_sample(tc, vertex, 1, 0, 1, comp);
        }
    }
    lu[0] = comp[0];
    return light;
}

mt_rgb mt__light_strategy_one(mt__thread_ctx *tc, const mt__vertex *v, int vertex)
{
    const mt_scene *s = tc->scene;
    const mt__light *light;
    mt_real lu[3];
    mt__light_sample ls;
    /* without a non-specular component f is 0 in every direction */
    if (s->nlights == 0 || v->ncomp_nonspecular == 0) return mt_rgb_black();
    light = choose_light(tc, vertex, lu);
    return mt_rgb_scale(light_term(s, light, v, lu, &ls), (mt_real)s->nlights);
}

mt_rgb mt__one_light_chosen_bsdf(mt__thread_ctx *tc, const mt__vertex *v, int vertex)
{
    const mt_scene *s = tc->scene;
    const mt__light *light;
    mt_real lu[3], bu[3], u[2];
    int m = v->ncomp_nonspecular, which;
    if (s->nlights == 0 || m == 0) return mt_rgb_black();
    light = choose_light(tc, vertex, lu);
    mt__vertex_sample(tc, vertex, 3, 0, 1, u);
    bu[0] = u[0];
    bu[1] = m > 1 ? reuse(u[0], m, &which) : u[0];
    bu[2] = u[1];
    return mt_rgb_scale(mt__estimate_direct(tc, light, v, lu, bu), (mt_real)s->nlights);
}

mt_rgb mt__mis_emission(const mt_scene *s, const mt__vertex *v, mt_real bsdf_pdf, const mt_ray *ray,
                        const mt_hit *hit)
{
    mt_rgb Le = mt_rgb_black();
    if (!hit) {
        int j;
        for (j = 0; j < s->ninfinite; ++j) {
            const mt__light *l = &s->lights[s->infinite[j]];
            mt_real lpdf = mt__light_pdf(l, v->p, ray->d);
            if (lpdf > 0)
                Le = mt_rgb_add(Le, mt_rgb_scale(mt__light_le(l, ray->d), mt_power_heuristic(1, bsdf_pdf, 1, lpdf)));
        }
    } else {
        const mt__prim_info *info = mt_shape_user(hit->shape);
        const mt__light *l;
        mt_real lpdf;
        if (info->light < 0) return Le;
        l = &s->lights[info->light];
        Le = mt__area_light_l(l, mt_hit_normal(hit, ray), mt_v3_neg(ray->d));
        if (mt_rgb_is_black(Le)) return Le;
        /* pbrt-v2's EstimateDirect gives nothing where the light's pdf is 0 */
        lpdf = mt__light_pdf(l, v->p, ray->d);
        if (!(lpdf > 0)) return mt_rgb_black();
        Le = mt_rgb_scale(Le, mt_power_heuristic(1, bsdf_pdf, 1, lpdf));
    }
    return Le;
}

mt_rgb mt__bsdf_strategy(mt__thread_ctx *tc, const mt__vertex *v, int vertex, unsigned k)
{
    const mt_scene *s = tc->scene;
    mt_real u[2];
    mt_bsdf_sample bs;
    mt_ray ray;
    mt_hit hit;
    mt_rgb Le;
    if (s->nlights == 0 || v->ncomp_nonspecular == 0) return mt_rgb_black();
    mt__vertex_sample(tc, vertex, k, 0, 1, u);
    bs = mt__sample_bsdf_pair(v, u, NON_SPECULAR);
    if (mt_rgb_is_black(bs.f) || !(bs.pdf > 0)) return mt_rgb_black();
    ray = mt_surface_spawn(&v->sf, bs.wi);
    Le = mt__mis_emission(s, v, bs.pdf, &ray, mt_geometry_intersect(s->geom, &ray, &hit) ? &hit : NULL);
    if (mt_rgb_is_black(Le)) return Le;
    return mt_rgb_scale(mt_rgb_mul(bs.f, Le), mt_v3_absdot(bs.wi, v->n) / bs.pdf);
}

mt_rgb mt__sample_all_lights(mt__thread_ctx *tc, const mt__vertex *v, int vertex)
{
    const mt_scene *s = tc->scene;
    mt_rgb L = mt_rgb_black();
    int i, j;
    if (v->ncomp_nonspecular == 0) return L;
    for (i = 0; i < s->nlights; ++i) {
        int n = s->light_samples[i];
        unsigned k = 8 + 3 * (unsigned)i;
        mt_rgb Ld = mt_rgb_black();
        for (j = 0; j < n; ++j) {
            mt_real comps[2], lpos[2], dir[2], lu[3], bu[3];
            mt__vertex_sample(tc, vertex, k, j, n, comps);
            mt__vertex_sample(tc, vertex, k + 1, j, n, lpos);
            mt__vertex_sample(tc, vertex, k + 2, j, n, dir);
            mt__u3(lu, comps[0], lpos);
            mt__u3(bu, comps[1], dir);
            Ld = mt_rgb_add(Ld, mt__estimate_direct(tc, &s->lights[i], v, lu, bu));
        }
        L = mt_rgb_add(L, mt_rgb_divs(Ld, (mt_real)n));
    }
    return L;
}
