/*
 * pbrt-v2's surface integrators with their estimands:
 *   path            integrators/path.cpp: emission at the first vertex and
 *                   after specular bounces, one light per vertex
 *                   (UniformSampleOneLight with MIS), Russian roulette after
 *                   the fourth vertex with continuation probability
 *                   min(0.5, y(throughput)), stop when bounces == maxdepth
 *                   (so maxdepth + 1 vertices get direct lighting)
 *   directlighting  integrators/directlighting.cpp: emission, all lights
 *                   (nsamples each) or one, and specular reflection and
 *                   transmission followed while depth + 1 < maxdepth, with
 *                   pbrt-v2's ray differentials (core/integrator.cpp
 *                   SpecularReflect, SpecularTransmit)
 *   dipolesubsurface integrators/dipolesubsurface.cpp: directlighting with
 *                   every light, the dipole's multiple scattering at
 *                   surfaces with a BSSRDF (the octree built by dipole.c),
 *                   specular light followed while depth < maxdepth
 * and SamplerRenderer::Li: rays that leave the scene see the lights' Le.
 */
#include <string.h>
#include "materia/bxdf.h"
#include "tracer/shading.h"

#define SPECULAR_ONLY ((unsigned)MT_BSDF_SPECULAR | (unsigned)MT_BSDF_REFLECTION | (unsigned)MT_BSDF_TRANSMISSION)

uint64_t mt__x_rand;

void mt__thread_start_pixel(mt__thread_ctx *tc, const mt__sobol_tables *tables, uint64_t seed,
                            int x, int y)
{
    mt__pixel_sampler_init(&tc->sampler, tables, seed, x, y);
    if (++tc->pixel_gen == 0) {
        memset(tc->seed_cache, 0, sizeof tc->seed_cache);
        tc->pixel_gen = 1;
    }
}

void mt__seed_slot_fill(mt__thread_ctx *tc, int vertex, unsigned k)
{
    mt__seed_slot *slot = &tc->seed_cache[vertex][k];
    mt__dim_seeds_init(&tc->sampler, MT__DIM_VERTEX0 + (uint32_t)vertex * 0x10000u + k, &slot->seeds);
    slot->gen = tc->pixel_gen;
}

void mt__vertex_sample_slow(mt__thread_ctx *tc, int vertex, unsigned k, int j, int n, mt_real out[2])
{
    uint32_t dim = MT__DIM_VERTEX0 + (uint32_t)vertex * 0x10000u + k;
    uint32_t rindex = n == 1 ? tc->rindex : mt__reverse_bits(tc->index * (uint32_t)n + (uint32_t)j);
    mt__dim_seeds local, *ds = &local;
    if (vertex < MT__SEED_CACHE_VERTICES && k < MT__SEED_CACHE_PAIRS) {
        mt__seed_slot *slot = &tc->seed_cache[vertex][k];
        if (slot->gen != tc->pixel_gen) {
            mt__dim_seeds_init(&tc->sampler, dim, &slot->seeds);
            slot->gen = tc->pixel_gen;
        }
        ds = &slot->seeds;
    } else {
        mt__dim_seeds_init(&tc->sampler, dim, ds);
    }
    mt__sample_2d_rev(tc->sampler.tables, ds, rindex, out);
    if (tc->any_independent && k < 8) {
        const uint16_t *ind = tc->scene->independent;
        unsigned mask = (ind[vertex < MT__INDEPENDENT_VERTICES ? vertex : MT__INDEPENDENT_VERTICES - 1] >> (2 * k)) & 3u;
        if (mask) mt__independent_pair(tc, dim, tc->index * (uint32_t)n + (uint32_t)j, mask, out);
    }
}

void mt__independent_pair(const mt__thread_ctx *tc, uint32_t dim, uint32_t element, unsigned mask,
                          mt_real out[2])
{
    uint32_t h = mt__hash_combine(mt__hash_combine(tc->sampler.seed, dim), element);
    if (mask & 1u) out[0] = mt__u32_to_unit(mt__hash_combine(h, 0x3c6ef372u));
    if (mask & 2u) out[1] = mt__u32_to_unit(mt__hash_combine(h, 0xa54ff53au));
}

mt_rgb mt__escaped(const mt_scene *s, mt_vec3 d)
{
    mt_rgb L = mt_rgb_black();
    int i;
    for (i = 0; i < s->ninfinite; ++i) L = mt_rgb_add(L, mt__light_le(&s->lights[s->infinite[i]], d));
    return L;
}

/* The next direction at a vertex whose BSDF has only specular components,
 * two or more of them (glass: reflection and transmission). pbrt-v2's
 * BSDF::Sample_f picks one of the m with probability 1/m and returns its
 * f with pdf 1/m, so a path through glass is weighted by m F or m (1 - F)
 * and is killed half the time where F is small. Each component's sample is
 * a fixed direction here (a specular BxDF reads neither u1 nor u2), so all m
 * are drawn -- the component k through u_component = (k + 1/2) / m, the same
 * f and direction that pbrt-v2's choice of k gives -- and one is chosen
 * with probability p_k proportional to the sum of the channels of its
 * weight f_k |cos| / pdf_k, using u; the sample's pdf is set to p_k, so that
 * f |cos| / pdf = f_k |cos| / p_k. The expectation, sum over k of
 * f_k |cos|, is BSDF::Sample_f's; only the noise of the choice goes (the
 * Fresnel-weighted choice of pbrt-v3's FresnelSpecular). A component that
 * gives nothing (total internal reflection) is never chosen. */
static mt_bsdf_sample sample_specular_only(const mt__vertex *v, const mt_real u[2])
{
    mt_bsdf_sample cand[MT_MAX_BXDFS], none;
    mt_real w[MT_MAX_BXDFS], total = 0, x;
    int m = v->ncomp, k, last = 0;
    memset(&none, 0, sizeof none);
    if (m > MT_MAX_BXDFS) m = MT_MAX_BXDFS;
    for (k = 0; k < m; ++k) {
        mt_bsdf_sample *c = &cand[k];
        *c = mt__bsdf_sample_f_wo(v->bsdf, &v->bwo, ((mt_real)k + (mt_real)0.5) / (mt_real)m, u[1], u[1],
                                  MT_BSDF_ALL);
        w[k] = 0;
        if (c->pdf > 0 && !mt_rgb_is_black(c->f)) {
            mt_rgb g = mt_rgb_scale(c->f, mt_v3_absdot(c->wi, v->n) / c->pdf);
            w[k] = mt_fabs(g.c[0]) + mt_fabs(g.c[1]) + mt_fabs(g.c[2]);
            if (!mt_is_finite(w[k])) w[k] = 0;
        }
        total += w[k];
    }
    if (!(total > 0) || !mt_is_finite(total)) return none;
    x = u[0] * total;
    for (k = 0; k < m; ++k) {
        if (!(w[k] > 0)) continue;
        last = k;
        if (x < w[k]) break;
        x -= w[k];
    }
    /* rounding may leave x at or above the last weight: that component */
    if (k == m) k = last;
    cand[k].pdf = w[k] / total;
    return cand[k];
}

static mt_rgb path_li(mt__thread_ctx *tc, const mt_raydiff *rd, mt_real diff_scale, const mt_hit *first)
{
    const mt_scene *s = tc->scene;
    mt_rgb L = mt_rgb_black(), beta = mt_rgb_gray(1);
    mt_ray ray = rd->ray;
    mt_hit hit;
    const mt_hit *next = first;
    int bounces, specular = 0;
    for (bounces = 0;; ++bounces) {
        mt__vertex v;
        mt_real dir[2];
        mt_bsdf_sample bs;
        mt_raydiff scaled;
        const mt_raydiff *vrd = NULL;
        int traced = 0;
        /* the camera ray's differentials, for the first vertex's textures */
        if (bounces == 0 && !((const mt__prim_info *)mt_shape_user(next->shape))->uniform) {
            scaled = *rd;
            mt_raydiff_scale(&scaled, diff_scale);
            vrd = &scaled;
        }
        if (!mt__vertex_shade(tc, next, &ray, vrd, &v)) break;
        if (bounces == 0 || specular) L = mt_rgb_add(L, mt_rgb_mul(beta, mt__vertex_le(s, &v)));
        if (s->measure_chosen_bsdf) L = mt_rgb_add(L, mt_rgb_mul(beta, mt__one_light_chosen_bsdf(tc, &v, bounces)));
        else L = mt_rgb_add(L, mt_rgb_mul(beta, mt__light_strategy_one(tc, &v, bounces)));
        /* the next direction (pair 2), which is also direct lighting's BSDF
         * sample whenever it comes from a non-specular component */
        mt__vertex_sample(tc, bounces, 2, 0, 1, dir);
        if (v.ncomp_nonspecular == 0 && v.ncomp > 1) bs = sample_specular_only(&v, dir);
        else bs = mt__sample_bsdf_pair(&v, dir, MT_BSDF_ALL);
        if (mt_rgb_is_black(bs.f) || bs.pdf == 0) break;
        specular = (bs.type & MT_BSDF_SPECULAR) != 0;
        beta = mt_rgb_mul(beta, mt_rgb_scale(bs.f, mt_v3_absdot(bs.wi, v.n) / bs.pdf));
        ray = mt_surface_spawn(&v.sf, bs.wi);
        next = NULL;
        if (!specular && s->nlights > 0 && !s->measure_chosen_bsdf) {
            mt_real c = 1, pdf_ns = bs.pdf;
            if (v.ncomp != v.ncomp_nonspecular) {
                /* Given a non-specular component (probability ncomp_ns /
                 * ncomp), the direction and f are EstimateDirect's BSDF
                 * sample's (non-specular components only); its pdf is bs.pdf
                 * times ncomp without the specular components' Pdf() (0,
                 * but not for pbrt-v2's ScaledBxDF: erratum scaled-pdf), over
                 * ncomp_ns. Divided by that probability, the term below
                 * has EstimateDirect's expectation whatever the pdfs. */
                mt_real spec = mt_bsdf_pdf(v.bsdf, v.wo, bs.wi, SPECULAR_ONLY) *
                               (mt_real)(v.ncomp - v.ncomp_nonspecular);
                pdf_ns = (bs.pdf * (mt_real)v.ncomp - spec) / (mt_real)v.ncomp_nonspecular;
                c = pdf_ns > 0 ? bs.pdf * (mt_real)v.ncomp / (pdf_ns * (mt_real)v.ncomp_nonspecular) : 0;
            }
            /* traced before Russian roulette and the depth limit: its light
             * belongs to this vertex's direct lighting */
            traced = 1;
            if (mt_geometry_intersect(s->geom, &ray, &hit)) next = &hit;
            if (c > 0)
                L = mt_rgb_add(L, mt_rgb_mul(mt_rgb_scale(beta, c), mt__mis_emission(s, &v, pdf_ns, &ray, next)));
        }
        if (bounces > 3) {
            mt_real rr[2], q = mt_min((mt_real)0.5, mt_rgb_y(beta));
            mt__vertex_sample(tc, bounces, 1, 0, 1, rr);
            if (rr[1] > q) break;
            beta = mt_rgb_divs(beta, q);
        }
        if (bounces == s->maxdepth) break;
        if (!traced && mt_geometry_intersect(s->geom, &ray, &hit)) next = &hit;
        if (!next) {
            if (specular) L = mt_rgb_add(L, mt_rgb_mul(beta, mt__escaped(s, ray.d)));
            break;
        }
    }
    return L;
}

static mt_rgb direct_li(mt__thread_ctx *tc, const mt_raydiff *rd, const mt_hit *hit, int depth);

/* The radiance along a ray spawned by a specular bounce. */
static mt_rgb trace(mt__thread_ctx *tc, const mt_raydiff *rd, int depth)
{
    mt_hit hit;
    if (!mt_geometry_intersect(tc->scene->geom, &rd->ray, &hit))
        return mt__escaped(tc->scene, rd->ray.d);
    return direct_li(tc, rd, &hit, depth);
}

void mt__specular_differentials(const mt_raydiff *rd, const mt_diffgeom *dg, const mt_diffgeom *dgs,
                                mt_vec3 p, mt_vec3 n, mt_vec3 wo, mt_vec3 wi, int transmit,
                                mt_real eta, mt_raydiff *next)
{
    mt_vec3 dndx = mt_v3_add(mt_v3_scale(dgs->dndu, dgs->dudx), mt_v3_scale(dgs->dndv, dgs->dvdx));
    mt_vec3 dndy = mt_v3_add(mt_v3_scale(dgs->dndu, dgs->dudy), mt_v3_scale(dgs->dndv, dgs->dvdy));
    mt_vec3 dwodx = mt_v3_sub(mt_v3_neg(rd->rx_d), wo), dwody = mt_v3_sub(mt_v3_neg(rd->ry_d), wo);
    next->has_differentials = 1;
    next->rx_o = mt_v3_add(p, dg->dpdx);
    next->ry_o = mt_v3_add(p, dg->dpdy);
    if (!transmit) {
        /* pbrt-v2 SpecularReflect */
        mt_real won = mt_v3_dot(wo, n);
        mt_real dDNdx = mt_v3_dot(dwodx, n) + mt_v3_dot(wo, dndx);
        mt_real dDNdy = mt_v3_dot(dwody, n) + mt_v3_dot(wo, dndy);
        next->rx_d = mt_v3_add(mt_v3_sub(wi, dwodx),
                               mt_v3_scale(mt_v3_add(mt_v3_scale(dndx, won), mt_v3_scale(n, dDNdx)), 2));
        next->ry_d = mt_v3_add(mt_v3_sub(wi, dwody),
                               mt_v3_scale(mt_v3_add(mt_v3_scale(dndy, won), mt_v3_scale(n, dDNdy)), 2));
    } else {
        /* pbrt-v2 SpecularTransmit as released (e6f6334): Igehy's refracted
         * differentials written for the incident direction w = -wo, eta the
         * relative index on the side w comes from (the 2012 snapshot
         * differentiated with wo's signs and the inverted eta) */
        mt_vec3 w = mt_v3_neg(wo), dwdx = mt_v3_neg(dwodx), dwdy = mt_v3_neg(dwody);
        mt_real dDNdx = mt_v3_dot(dwdx, n) + mt_v3_dot(w, dndx);
        mt_real dDNdy = mt_v3_dot(dwdy, n) + mt_v3_dot(w, dndy);
        mt_real wn, win, mu, k;
        if (mt_v3_dot(w, n) < 0) eta = 1 / eta;
        wn = mt_v3_dot(w, n);
        win = mt_v3_dot(wi, n);
        mu = eta * wn - win;
        k = eta - (eta * eta * wn) / win;
        next->rx_d = mt_v3_sub(mt_v3_add(wi, mt_v3_scale(dwdx, eta)),
                               mt_v3_add(mt_v3_scale(dndx, mu), mt_v3_scale(n, k * dDNdx)));
        next->ry_d = mt_v3_sub(mt_v3_add(wi, mt_v3_scale(dwdy, eta)),
                               mt_v3_add(mt_v3_scale(dndy, mu), mt_v3_scale(n, k * dDNdy)));
    }
    if (!mt_v3_is_finite(next->rx_d) || !mt_v3_is_finite(next->ry_d)) next->has_differentials = 0;
}

/* SpecularReflect / SpecularTransmit: one specular direction of type
 * MT_BSDF_REFLECTION or MT_BSDF_TRANSMISSION, the ray differentials of the
 * reflected or refracted neighbours (Igehy), and the radiance brought back. */
static mt_rgb specular(mt__thread_ctx *tc, const mt_raydiff *rd, const mt__vertex *v,
                       unsigned lobe, const mt_real u[3], int depth)
{
    mt_vec3 n = v->n, wi;
    mt_bsdf_sample bs = mt__bsdf_sample_f_wo(v->bsdf, &v->bwo, u[0], u[1], u[2], lobe | MT_BSDF_SPECULAR);
    mt_raydiff next;
    mt_rgb Li;
    if (!(bs.pdf > 0) || mt_rgb_is_black(bs.f) || mt_v3_absdot(bs.wi, n) == 0) return mt_rgb_black();
    wi = bs.wi;
    next = mt_raydiff_from_ray(&rd->ray);
    next.ray = mt_surface_spawn(&v->sf, wi);
    if (rd->has_differentials)
        mt__specular_differentials(rd, &v->sf.dg, mt_bsdf_shading(v->bsdf), v->p, n, v->wo, wi,
                                   lobe == MT_BSDF_TRANSMISSION, mt_bsdf_eta(v->bsdf), &next);
    Li = trace(tc, &next, depth + 1);
    return mt_rgb_scale(mt_rgb_mul(bs.f, Li), mt_v3_absdot(wi, n) / bs.pdf);
}

/* The dipole's multiple scattering at a vertex whose material has a BSSRDF
 * (pbrt-v2 DipoleSubsurfaceIntegrator::Li): (1/pi) Ft (Fdt Mo), with
 * Ft = 1 - FresnelDielectric(1, eta)(|wo.n|), Fdt = 1 - Fdr(eta) and Mo the
 * octree's sum at the shading point. */
static mt_rgb subsurface(mt__thread_ctx *tc, const mt__vertex *v)
{
    const mt__dipole *d = tc->dipole;
    mt_bssrdf b;
    mt_rgb sigmap_t, Mo, Ft;
    mt__diffusion rd;
    mt_fresnel fr;
    mt_real fdr;
    if (!d || !d->root || !mt__material_get_bssrdf_cached(v->info->material, v->sh, &tc->bssrdf_cache, &b)) return mt_rgb_black();
    sigmap_t = mt_rgb_add(b.sigma_a, b.sigma_prime_s);
    if (mt_rgb_is_black(sigmap_t) || !(b.eta > 0)) return mt_rgb_black();
    if (tc->fdr_valid && tc->fdr_eta == b.eta) {
        fdr = tc->fdr;
    } else {
        fdr = tc->fdr = mt__fdr(b.eta, tc->scene->mode);
        tc->fdr_eta = b.eta;
        tc->fdr_valid = 1;
    }
    mt__diffusion_init(&rd, b.sigma_a, b.sigma_prime_s, fdr);
    Mo = mt__dipole_mo(d, v->p, &rd, d->maxerror);
    fr = mt_fresnel_dielectric(1, b.eta);
    Ft = mt_rgb_sub(mt_rgb_gray(1), mt_fresnel_evaluate(&fr, mt_v3_absdot(v->wo, v->n)));
    return mt_rgb_scale(mt_rgb_mul(Ft, Mo), (1 - fdr) / MT_PI);
}

static mt_rgb direct_li(mt__thread_ctx *tc, const mt_raydiff *rd, const mt_hit *hit, int depth)
{
    const mt_scene *s = tc->scene;
    mt__vertex v;
    mt_rgb L;
    int dipole = s->integrator == MT__INTEGRATOR_DIPOLE;
    if (!mt__vertex_shade(tc, hit, &rd->ray, rd->has_differentials ? rd : NULL, &v))
        return mt_rgb_black();
    L = mt__vertex_le(s, &v);
    if (dipole) L = mt_rgb_add(L, subsurface(tc, &v));
    if (s->nlights > 0) {
        if (s->strategy_all) L = mt_rgb_add(L, mt__sample_all_lights(tc, &v, depth));
        else L = mt_rgb_add(mt_rgb_add(L, mt__light_strategy_one(tc, &v, depth)),
                            mt__bsdf_strategy(tc, &v, depth, 3));
    }
    /* directlighting follows specular light while depth + 1 < maxdepth,
     * dipolesubsurface while depth < maxdepth (pbrt-v2's two tests) */
    if (depth + (dipole ? 0 : 1) < s->maxdepth) {
        mt_real comps[2], r[2], t[2], ur[3], ut[3];
        mt__vertex_sample(tc, depth, 4, 0, 1, comps);
        mt__vertex_sample(tc, depth, 5, 0, 1, r);
        mt__vertex_sample(tc, depth, 6, 0, 1, t);
        mt__u3(ur, comps[0], r);
        mt__u3(ut, comps[1], t);
        L = mt_rgb_add(L, specular(tc, rd, &v, MT_BSDF_REFLECTION, ur, depth));
        L = mt_rgb_add(L, specular(tc, rd, &v, MT_BSDF_TRANSMISSION, ut, depth));
    }
    return L;
}

mt_rgb mt__li(mt__thread_ctx *tc, const mt_raydiff *rd, mt_real diff_scale)
{
    mt_hit hit;
    mt_raydiff scaled;
    if (!mt_geometry_intersect(tc->scene->geom, &rd->ray, &hit))
        return mt__escaped(tc->scene, rd->ray.d);
    if (tc->scene->integrator == MT__INTEGRATOR_PATH) return path_li(tc, rd, diff_scale, &hit);
    scaled = *rd;
    mt_raydiff_scale(&scaled, diff_scale);
    return direct_li(tc, &scaled, &hit, 0);
}
