/*
 * The two measured BxDFs of pbrt-v2 (reflection.h/.cpp): IrregIsotropicBRDF,
 * a weighted average of the irregular samples near the remapped direction
 * pair, and RegularHalfangleBRDF, a lookup in a MERL table. Both are glossy
 * reflection and keep the BxDF base's cosine sampling and pdf, as in
 * pbrt-v2. Arithmetic follows pbrt-v2's order, so the float build gives
 * pbrt-v2's floats.
 */
#include "materia/sampling.h"
#include "measured/measured_impl.h"

typedef struct measured_bxdf {
    mt_bxdf base;
    const mt_measured *data;
} measured_bxdf;

/* pbrt-v2 reflection.cpp BRDFRemap; with MT_FIX_MEASURED_SYMMETRY the
 * azimuth difference is folded from |phi_i - phi_o|, which is the same for
 * (wo, wi) and (wi, wo) to the bit (pbrt-v2's "+ 2 pi, then 2 pi - dphi"
 * path rounds twice). */
static mt_vec3 remap(mt_vec3 wo, mt_vec3 wi, mt_mode mode)
{
    mt_real cosi = mt_cos_theta(wi), coso = mt_cos_theta(wo);
    mt_real sini = mt_sin_theta(wi), sino = mt_sin_theta(wo);
    mt_real phii = mt_spherical_phi(wi), phio = mt_spherical_phi(wo);
    mt_real dphi = phii - phio;
    if (mode & MT_FIX_MEASURED_SYMMETRY) {
        dphi = mt_fabs(dphi);
    } else {
        if (dphi < 0) dphi += 2 * MT_PI;
        if (dphi > 2 * MT_PI) dphi -= 2 * MT_PI;
    }
    if (dphi > MT_PI) dphi = 2 * MT_PI - dphi;
    return mt_v3(sini * sino, dphi / MT_PI, cosi * coso);
}

mt_vec3 mt_brdf_remap(mt_vec3 wo, mt_vec3 wi) { return remap(wo, wi, MT_MODE_PBRT_V2); }

/* pbrt-v2 reflection.cpp IrregIsoProc: the running weighted sum. */
typedef struct irreg_sum {
    const mt_rgb *values;
    mt_rgb v;
    mt_real sum_weights;
    int found;
} irreg_sum;

static void irreg_sum_init(irreg_sum *s, const mt_rgb *values)
{
    s->values = values;
    s->v = mt_rgb_black();
    s->sum_weights = 0;
    s->found = 0;
}

static void irreg_add(void *ctx, int item, mt_real d2, mt_real *max_d2)
{
    irreg_sum *s = ctx;
    mt_real w = mt_exp(-100 * d2);
    (void)max_d2;
    s->v = mt_rgb_add(s->v, mt_rgb_scale(s->values[item], w));
    s->sum_weights += w;
    s->found++;
}

/* The most samples kept from the wide search (below). */
#define IRREG_KEEP 32

/* pbrt-v2's value from the sum of the try that ends the search. */
static mt_rgb irreg_result(const irreg_sum *s)
{
    /* erratum measured-empty: pbrt-v2 returns 0/0 when no sample has weight
     * (none found, or every exp(-100 d2) underflowed) */
    if (s->sum_weights == 0) return mt_rgb_black();
    return mt_rgb_divs(mt_rgb_clamp0(s->v), s->sum_weights);
}

/* pbrt-v2 IrregIsotropicBRDF::f: squared search radius 0.001, doubled until
 * more than 2 samples are found or it exceeds 1.5 (the last try is 2.048).
 *
 * Most directions need two to four tries (radii 0.001 to 0.008), and each
 * try searched the tree again. Here one search at eight times the radius
 * keeps the samples it finds in visiting order, and the four tries within
 * it are read from that list: a try at radius r hands pbrt-v2's callback
 * exactly the kept samples with d2 < r, in the same order, because the
 * visiting order does not depend on the radius and a subtree the smaller
 * search skips (squared distance to its plane >= r) holds no sample with
 * d2 < r (the rounded d2 is at least the rounded plane distance). Sums and
 * counts are therefore the same bits. More than IRREG_KEEP samples within
 * the wide radius end that search, and its tries are made one by one as
 * pbrt-v2 makes them. (Callgrind, measured scene at 4 spp: 1148 M
 * instructions before, 1073 M with 8x and 32 kept; 4x or 16x, or 16, 64 or
 * 128 kept, do less well.) The wide search is mt__kdtree_ball, answered from
 * a grid (core/kdball.c); the counts of the tries need no order, and only
 * the samples of the try that ends the search are put in the tree's order
 * and summed. */
static mt_rgb irreg_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const mt_measured *d = ((const measured_bxdf *)b)->data;
    mt_vec3 m = remap(wo, wi, b->mode);
    mt_real p[3], last = MT__IRREG_FIRST_D2;
    p[0] = m.x;
    p[1] = m.y;
    p[2] = m.z;
    for (;;) {
        mt__kdball ball;
        int k;
        mt__kdtree_ball(&d->tree, p, 8 * last, IRREG_KEEP, &ball); /* MT__IRREG_WIDE_D2 first */
        for (k = 0; k < 4; ++k, last *= 2) {
            irreg_sum s;
            int32_t item[IRREG_KEEP];
            mt_real d2[IRREG_KEEP], max_d2 = last;
            int i, n;
            if (ball.n < 0) {
                irreg_sum_init(&s, d->values);
                mt__kdtree_lookup(&d->tree, p, irreg_add, &s, &max_d2);
                if (s.found > 2 || last > (mt_real)1.5) return irreg_result(&s);
                continue;
            }
            /* a try that does not end the search counts for its count
             * alone: its sum is dropped (pbrt-v2 computes and drops it) */
            if (!(mt__kdball_count(&ball, last) > 2 || last > (mt_real)1.5)) continue;
            irreg_sum_init(&s, d->values);
            n = mt__kdball_select(&d->tree, p, &ball, last, item, d2);
            for (i = 0; i < n; ++i) irreg_add(&s, item[i], d2[i], &max_d2);
            return irreg_result(&s);
        }
    }
}

/* pbrt-v2's REMAP macro: Clamp(int(v / max * count), 0, count - 1), with a
 * NaN (not reachable from admitted directions) taken to 0. */
static int remap_index(mt_real v, mt_real max, int count)
{
    mt_real x = v / max * (mt_real)count;
    if (x >= (mt_real)count) return count - 1;
    return x >= 0 ? (int)x : 0;
}

/* pbrt-v2 RegularHalfangleBRDF::f. */
static mt_rgb halfangle_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const mt_real *table = ((const measured_bxdf *)b)->data->table, *c;
    mt_vec3 wh = mt_v3_add(wo, wi), whx, why, wd;
    mt_real wh_theta, cos_phi, sin_phi, cos_theta, sin_theta, wd_theta, wd_phi;
    int ith, itd, ipd;
    if (wh.z < 0) {
        wo = mt_v3_neg(wo);
        wi = mt_v3_neg(wi);
        wh = mt_v3_neg(wh);
    }
    if (mt_v3_is_zero(wh)) return mt_rgb_black();
    wh = mt_v3_normalize(wh);
    /* wi in the half vector's frame */
    wh_theta = mt_spherical_theta(wh);
    cos_phi = mt_cos_phi(wh);
    sin_phi = mt_sin_phi(wh);
    cos_theta = mt_cos_theta(wh);
    sin_theta = mt_sin_theta(wh);
    whx = mt_v3(cos_phi * cos_theta, sin_phi * cos_theta, -sin_theta);
    why = mt_v3(-sin_phi, cos_phi, 0);
    wd = mt_v3(mt_v3_dot(wi, whx), mt_v3_dot(wi, why), mt_v3_dot(wi, wh));
    wd_theta = mt_spherical_theta(wd);
    wd_phi = mt_spherical_phi(wd);
    if (wd_phi > MT_PI) wd_phi -= MT_PI;
    ith = remap_index(mt_sqrt(mt_max(0, wh_theta / (MT_PI / 2))), 1, MT_MERL_THETA_H);
    itd = remap_index(wd_theta, MT_PI / 2, MT_MERL_THETA_D);
    ipd = remap_index(wd_phi, MT_PI, MT_MERL_PHI_D);
    c = table + 3 * (ipd + MT_MERL_PHI_D * (itd + ith * MT_MERL_THETA_D));
    return mt_rgb_make(c[0], c[1], c[2]);
}

static const mt_bxdf_ops irreg_ops = {
    .name = "IrregIsotropicBRDF",
    .f = irreg_f,
    .sample_f = mt_bxdf_default_sample_f,
    .pdf = mt_bxdf_default_pdf,
    .rho_hd = mt_bxdf_default_rho_hd,
    .rho_hh = mt_bxdf_default_rho_hh,
};
static const mt_bxdf_ops halfangle_ops = {
    .name = "RegularHalfangleBRDF",
    .f = halfangle_f,
    .sample_f = mt_bxdf_default_sample_f,
    .pdf = mt_bxdf_default_pdf,
    .rho_hd = mt_bxdf_default_rho_hd,
    .rho_hh = mt_bxdf_default_rho_hh,
};

int mt__bxdf_is_measured(const mt_bxdf *b)
{
    return b->ops == &irreg_ops || b->ops == &halfangle_ops;
}

static mt_bxdf *create(mt_arena *a, mt_mode mode, const mt_measured *data, mt_measured_kind kind,
                       const mt_bxdf_ops *ops, mt_error *err)
{
    measured_bxdf *b;
    if (!data || data->kind != kind) {
        mt_error_set(err, MT_ERR_INVALID, "%s: %s", ops->name,
                     data ? "the measured data is of the other kind" : "no measured data");
        return NULL;
    }
    b = mt_bxdf_alloc(a, sizeof *b, ops, MT_BSDF_REFLECTION | MT_BSDF_GLOSSY, mode, err);
    if (!b) return NULL;
    b->data = data;
    return &b->base;
}

mt_bxdf *mt_irregular_isotropic_brdf_create(mt_arena *a, mt_mode mode, const mt_measured *data,
                                            mt_error *err)
{
    mt_error_clear(err);
    return create(a, mode, data, MT_MEASURED_IRREGULAR, &irreg_ops, err);
}

mt_bxdf *mt_regular_halfangle_brdf_create(mt_arena *a, mt_mode mode, const mt_measured *data,
                                          mt_error *err)
{
    mt_error_clear(err);
    return create(a, mode, data, MT_MEASURED_HALFANGLE, &halfangle_ops, err);
}
