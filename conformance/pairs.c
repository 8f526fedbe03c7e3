/*
 * Pairs of directions, each asked both ways: uniform over the sphere and
 * where the implementation's own samples went (its lobes), per incoming
 * direction, and pairs of uniform directions.
 *
 *  reciprocity  physics: on the same side of the surface (by the geometric
 *               normal), f(a, b) = f(b, a); across it, the generalized
 *               reciprocity of the implementation's transport (Veach 1997,
 *               section 5.2; docs/CONFORMANCE-SUITE.md derives both forms):
 *                 importance  f(a, b) / eta_b^2 = f(b, a) / eta_a^2
 *                 radiance    f(a, b) / eta_a^2 = f(b, a) / eta_b^2
 *               eta_x the index on x's side; the ratio of the two indices is
 *               the one Snell's law of its specular refractions gives, or,
 *               without them, the one its pairs give (f(a, b) = k f(b, a)
 *               for every pair across the surface, k its median). Its
 *               tolerance is its own conditioning: how much its f changes
 *               when wo or wi turns by 4 of its epsilons. Not where the
 *               shading and geometric normals disagree on the side (shading
 *               normals are not reciprocal).
 *  agree f, agree pdf
 *               agreement: eval equals materia's, within materia's
 *               conditioning at the query (below).
 *
 * The tolerance of a comparison with materia: an implementation computing in
 * float differs from the exact answer by its roundings, which act like
 * relative perturbations of a few float epsilons of its inputs and
 * intermediate values. So at every query materia is evaluated with wo, then
 * wi, rotated by 4 float epsilons four ways, and, under a bump map, with
 * both turned together by the tilt rounding can give the shading frame; the
 * bound is 4 times the largest change this makes, plus (64 + 3 e) float
 * epsilons of the value (a lobe cos^e) and 1e-6 of the configuration's
 * largest value (where a tail underflows in float).
 */
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pass.h"

/* pairs per incoming direction: half uniform, half where its samples went */
#define PAIRS_PER_WO 96
#define PAIRS_UNIFORM 512
/* values below this fraction of the largest across the surface do not
 * decide the ratio of the generalized form */
#define KAPPA_FLOOR 1e-3

cf_v3 cf_perturb(cf_v3 w, int k, double eps)
{
    double x = w.x, y = w.y, z = w.z, t1[3], t2[3], l, s = (k & 1) ? -4 * eps : 4 * eps;
    const double *t;
    if (fabs(x) < 0.6) { /* t1 = w x e_x */
        t1[0] = 0;
        t1[1] = z;
        t1[2] = -y;
    } else { /* w x e_y */
        t1[0] = -z;
        t1[1] = 0;
        t1[2] = x;
    }
    l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    if (!(l > 0)) return w;
    t1[0] /= l;
    t1[1] /= l;
    t1[2] /= l;
    t2[0] = y * t1[2] - z * t1[1];
    t2[1] = z * t1[0] - x * t1[2];
    t2[2] = x * t1[1] - y * t1[0];
    t = k < 2 ? t1 : t2;
    x += s * t[0];
    y += s * t[1];
    z += s * t[2];
    l = sqrt(x * x + y * y + z * z);
    return cf_v3_make(x / l, y / l, z / l);
}

/* v rotated by angle t about the unit axis a (Rodrigues). */
static mt_vec3 rotate(mt_vec3 v, const double a[3], double t)
{
    double c = cos(t), sn = sin(t), d = (a[0] * v.x + a[1] * v.y + a[2] * v.z) * (1 - c);
    double x = v.x * c + (a[1] * v.z - a[2] * v.y) * sn + a[0] * d;
    double y = v.y * c + (a[2] * v.x - a[0] * v.z) * sn + a[1] * d;
    double z = v.z * c + (a[0] * v.y - a[1] * v.x) * sn + a[2] * d;
    return mt_v3((mt_real)x, (mt_real)y, (mt_real)z);
}

static mt_vec3 mv(cf_v3 v) { return mt_v3((mt_real)v.x, (mt_real)v.y, (mt_real)v.z); }

/* How far rounding can tilt materia's shading frame, in radians: 0, except
 * under a bump map: pbrt-v2's Bump() takes the forward difference
 * (d(p + du dpdu) - d(p)) / du, so the roundings of the shifted point and of
 * d (a few eps times 1 + |p|) are divided by the step du (0.01 without
 * differentials, bump.c): measured float against double, `matte with a bump
 * map` at its point tilts by 6e-6 = 50 eps with du 0.01, and this gives
 * 4 eps (1 + |p|) / du = 700 eps there. */
static double frame_tilt(const cf_case *c, const mt_bsdf *b)
{
    const mt_diffgeom *dg = mt_bsdf_shading(b);
    double du, dv, p;
    int j, bump = 0;
    for (j = 0; j < c->nlines; ++j) bump |= strstr(c->lines[j], "bumpmap") != NULL;
    if (!bump) return 0;
    du = 0.5 * (fabs((double)dg->dudx) + fabs((double)dg->dudy));
    dv = 0.5 * (fabs((double)dg->dvdx) + fabs((double)dg->dvdy));
    du = fmin(du > 0 ? du : 0.01, dv > 0 ? dv : 0.01);
    p = sqrt((double)mt_v3_dot(dg->p, dg->p));
    return 4 * FLT_EPSILON * (1 + p) / du;
}

/* The spread of materia's f and pdf when wo or wi moves by 4 float
 * epsilons, and when both turn by the frame's tilt. */
static void ref_spread(const mt_bsdf *b, double tilt, cf_v3 wo, cf_v3 wi, const cf_eval *v, double s[4])
{
    int j, k;
    const mt_vec3 n = mt_bsdf_shading(b)->n;
    for (k = 0; k < 4; ++k) s[k] = 0;
    for (j = 0; j < (tilt > 0 ? 12 : 8); ++j) {
        mt_vec3 a = j < 4 ? mv(cf_perturb(wo, j, FLT_EPSILON)) : mv(wo),
                bb = j >= 4 && j < 8 ? mv(cf_perturb(wi, j - 4, FLT_EPSILON)) : mv(wi);
        mt_rgb f;
        double p;
        if (j >= 8) { /* about an axis perpendicular to n: perturb(n) - n */
            cf_v3 tn = cf_perturb(cf_v3_make(n.x, n.y, n.z), j < 10 ? 0 : 2, FLT_EPSILON);
            double ax[3] = {tn.y * n.z - tn.z * n.y, tn.z * n.x - tn.x * n.z, tn.x * n.y - tn.y * n.x}, l;
            l = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
            if (!(l > 0)) continue;
            for (k = 0; k < 3; ++k) ax[k] /= l;
            a = rotate(mv(wo), ax, (j & 1) ? -tilt : tilt);
            bb = rotate(mv(wi), ax, (j & 1) ? -tilt : tilt);
        }
        f = mt_bsdf_f(b, a, bb, MT_BSDF_ALL);
        p = mt_bsdf_pdf(b, a, bb, MT_BSDF_ALL);
        for (k = 0; k < 3; ++k) s[k] = fmax(s[k], fabs(f.c[k] - v->f[k]));
        s[3] = fmax(s[3], fabs(p - v->pdf));
    }
}

double cf_ref_bound(double v, double s, double rel, double vmax) { return 4 * s + rel * fabs(v) + 1e-6 * vmax + 1e-30; }

/* The implementation's own bound at a query: 4 times its spread, its
 * rounding of the value, and 8 of its epsilons of its largest value (a
 * tail that underflows: 1e-6 in float). */
static double own_bound(double v, double s, double allow, double eps, double vmax)
{
    return 4 * s + allow * fabs(v) + 8 * eps * vmax + 1e-300;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int cf_pairs(cf_ctx *x)
{
    const cf_case *c = x->c;
    cf_impl *t = x->test, *ref = x->ref;
    cf_result *res = x->out->res;
    int np = x->nwo * PAIRS_PER_WO + PAIRS_UNIFORM, i, k, j, m = 0, r = 0, nk = 0;
    cf_v3 *a = malloc((size_t)np * 2 * sizeof *a), *b = malloc((size_t)np * 2 * sizeof *b);
    cf_v3 *pa = malloc((size_t)np * 16 * sizeof *pa), *pb = malloc((size_t)np * 16 * sizeof *pb);
    cf_eval *et = malloc((size_t)np * 2 * sizeof *et), *er = ref ? malloc((size_t)np * 2 * sizeof *er) : NULL;
    cf_eval *ep = malloc((size_t)np * 16 * sizeof *ep);
    double *kap = malloc((size_t)np * 3 * sizeof *kap), *spr = malloc((size_t)np * 2 * 3 * sizeof *spr);
    double fmaxv = 0, pmax = 0, tmax = 0, worst_f = 0, worst_p = 0, worst_r = 0, tilt = 0, kappa = 1, rrel;
    long bad_f = 0, bad_p = 0, bad_r = 0, nonzero = 0, skipped = 0, across = 0, nonzero_across = 0;
    int eta_known = x->eta > 0, radiance = t->conv.transport == CF_RADIANCE;
    mt_rng rng;
    char q[200], ex[200], got[240], q2[200];
    if (!a || !b || !pa || !pb || !et || (ref && !er) || !ep || !kap || !spr) {
        r = CF_NOMEM;
        goto out;
    }
    mt_rng_seed(&rng, cf_seed(c->name, 99), 5);
    for (i = 0; i < x->nwo; ++i) {
        const cf_wo_data *d = x->w + i;
        long own = 0;
        for (k = 0; k < PAIRS_PER_WO; ++k) {
            cf_v3 wi;
            if (k >= PAIRS_PER_WO / 2 && own < d->ndirs && own < CF_KEEP_DIRS) {
                wi = d->first[own++];
            } else {
                double u1 = mt_rng_uniform_d(&rng), u2 = mt_rng_uniform_d(&rng), z = 1 - 2 * u1, s = sqrt(fmax(0, 1 - z * z));
                wi = cf_v3_make(s * cos(6.283185307179586 * u2), s * sin(6.283185307179586 * u2), z);
            }
            if (!d->n) continue; /* a direction not run (--wo) */
            a[m] = d->wo;
            b[m++] = cf_v3_float(wi);
        }
    }
    for (i = 0; i < PAIRS_UNIFORM; ++i) {
        cf_v3 v[2];
        for (k = 0; k < 2; ++k) {
            double u1 = mt_rng_uniform_d(&rng), u2 = mt_rng_uniform_d(&rng), z = 1 - 2 * u1, s = sqrt(fmax(0, 1 - z * z));
            v[k] = cf_v3_float(cf_v3_make(s * cos(6.283185307179586 * u2), s * sin(6.283185307179586 * u2), z));
        }
        a[m] = v[0];
        b[m++] = v[1];
    }
    for (i = 0; i < m; ++i) { /* the reversed pairs after */
        a[m + i] = b[i];
        b[m + i] = a[i];
    }
    /* its answers, and its answers with wo or wi turned by 4 epsilons */
    for (i = 0; i < 2 * m; ++i)
        for (j = 0; j < 8; ++j) {
            pa[8 * i + j] = j < 4 ? cf_perturb(a[i], j, t->eps) : a[i];
            pb[8 * i + j] = j >= 4 ? cf_perturb(b[i], j - 4, t->eps) : b[i];
        }
    if ((r = t->ops->eval(t, 2 * m, a, b, et)) || (r = t->ops->eval(t, 16 * m, pa, pb, ep))) goto out;
    for (i = 0; i < 2 * m; ++i) {
        for (k = 0; k < 3; ++k) {
            double s = 0;
            tmax = fmax(tmax, isfinite(et[i].f[k]) ? fabs(et[i].f[k]) : 0);
            for (j = 0; j < 8; ++j) s = fmax(s, fabs(ep[8 * i + j].f[k] - et[i].f[k]));
            spr[3 * i + k] = isfinite(s) ? s : 0;
        }
        /* a density its samples did not show: eval is not 0 */
        if (et[i].pdf != 0 || et[i].f[0] != 0 || et[i].f[1] != 0 || et[i].f[2] != 0) x->density = 1;
    }
    /* reciprocity: the ratio across the surface */
    rrel = x->allow_own;
    if (eta_known) {
        /* f(a, b) = kappa f(b, a) for a outside: importance eta^2, radiance 1 / eta^2 */
        kappa = radiance ? 1 / (x->eta * x->eta) : x->eta * x->eta;
    } else {
        double big = 0;
        for (i = 0; i < m; ++i)
            if (cf_dot(a[i], x->ng) * cf_dot(b[i], x->ng) < 0)
                for (k = 0; k < 3; ++k) big = fmax(big, fmax(fabs(et[i].f[k]), fabs(et[m + i].f[k])));
        for (i = 0; i < m; ++i) {
            int out_first = cf_dot(a[i], x->ng) > 0;
            if (cf_dot(a[i], x->ng) * cf_dot(b[i], x->ng) >= 0) continue;
            for (k = 0; k < 3; ++k) {
                double f1 = et[out_first ? i : m + i].f[k], f2 = et[out_first ? m + i : i].f[k];
                if (f1 > KAPPA_FLOOR * big && f2 > KAPPA_FLOOR * big && isfinite(f1 / f2)) kap[nk++] = f1 / f2;
            }
        }
        if (nk) {
            qsort(kap, (size_t)nk, sizeof *kap, cmp_double);
            kappa = kap[nk / 2];
        }
    }
    for (i = 0; i < m; ++i) {
        int refl_g = cf_dot(a[i], x->ng) * cf_dot(b[i], x->ng) > 0, refl_s = cf_dot(a[i], x->ns) * cf_dot(b[i], x->ns) > 0;
        double e = 0, kk = 1;
        if (refl_g != refl_s) {
            skipped++;
            continue;
        }
        if (!refl_g) {
            across++;
            kk = cf_dot(a[i], x->ng) > 0 ? kappa : 1 / kappa;
        }
        for (k = 0; k < 3; ++k) {
            double f1 = et[i].f[k], f2 = et[m + i].f[k];
            double tl = fmax(own_bound(f1, spr[3 * i + k], rrel, t->eps, tmax),
                             kk * own_bound(f2, spr[3 * (m + i) + k], rrel, t->eps, tmax));
            double dd = fabs(f1 - kk * f2) / tl;
            e = fmax(e, isfinite(dd) ? dd : 1e30);
            nonzero += f1 != 0;
            nonzero_across += !refl_g && f1 != 0;
            cf_measure_add(&res[CK_RECIPROCITY], f1 - kk * f2, 0, tl, i, "f(wo, wi) - k f(wi, wo) on pair %g");
        }
        worst_r = fmax(worst_r, e);
        if (e > 1) {
            char e2[240];
            bad_r++;
            cf_q_eval(q, sizeof q, a[i], b[i]);
            cf_q_eval(q2, sizeof q2, b[i], a[i]);
            cf_a_eval(ex, sizeof ex, et + m + i);
            cf_a_eval(got, sizeof got, et + i);
            if (kk != 1)
                snprintf(e2, sizeof e2, "%.9g times %.100s (its answer to the reverse query)", kk, ex);
            else
                snprintf(e2, sizeof e2, "%.100s (its answer to the reverse query)", ex);
            cf_worst_add(res[CK_RECIPROCITY].worst, e, q, e2, got, q2);
        }
    }
    {
        char k2[160] = "";
        if (across && (nk || (eta_known && nonzero_across))) {
            double eta = radiance ? 1 / sqrt(kappa) : sqrt(kappa);
            snprintf(k2, sizeof k2, "; across: f(out, in) = %.6g f(in, out), index %.6g (%s)", kappa, eta,
                     eta_known ? "Snell" : "its pairs");
            if (!eta_known && x->out->eta == 0) x->out->eta = eta;
        }
        cf_set(&res[CK_RECIPROCITY], bad_r == 0, "err/tol <= 1", "worst err/tol %.3g over %ld pairs (%ld values != 0)%s%s",
               worst_r, (long)m - skipped, nonzero, skipped ? ", not where n and ng disagree" : "", k2);
    }
    /* agreement with materia */
    if (ref) {
        double rel = x->allow_own / t->eps * FLT_EPSILON; /* (64 + 3 e) float epsilons */
        ref->ops->eval(ref, 2 * m, a, b, er);
        tilt = frame_tilt(c, ref->bsdf);
        for (i = 0; i < 2 * m; ++i) {
            for (k = 0; k < 3; ++k) fmaxv = fmax(fmaxv, fabs(er[i].f[k]));
            pmax = fmax(pmax, fabs(er[i].pdf));
        }
        for (i = 0; i < 2 * m; ++i) {
            double s[4], ef = 0, epd;
            ref_spread(ref->bsdf, tilt, a[i], b[i], er + i, s);
            for (k = 0; k < 3; ++k) {
                double tt = cf_ref_bound(er[i].f[k], s[k], rel, fmaxv), e = fabs(et[i].f[k] - er[i].f[k]) / tt;
                ef = fmax(ef, isfinite(e) ? e : 1e30);
            }
            epd = fabs(et[i].pdf - er[i].pdf) / cf_ref_bound(er[i].pdf, s[3], rel, pmax);
            if (!isfinite(epd)) epd = 1e30;
            worst_f = fmax(worst_f, ef);
            worst_p = fmax(worst_p, epd);
            if (ef > 1 || epd > 1) {
                cf_q_eval(q, sizeof q, a[i], b[i]);
                cf_a_eval(ex, sizeof ex, er + i);
                cf_a_eval(got, sizeof got, et + i);
                if (ef > 1) {
                    bad_f++;
                    cf_worst_add(res[CK_AGREE_F].worst, ef, q, ex, got, NULL);
                }
                if (epd > 1) {
                    bad_p++;
                    cf_worst_add(res[CK_AGREE_PDF].worst, epd, q, ex, got, NULL);
                }
            }
        }
        cf_set(&res[CK_AGREE_F], bad_f == 0, "err/tol <= 1", "worst err/tol %.3g, %ld of %d queries off", worst_f, bad_f,
               2 * m);
        cf_set(&res[CK_AGREE_PDF], bad_p == 0, "err/tol <= 1", "worst err/tol %.3g, %ld of %d queries off", worst_p,
               bad_p, 2 * m);
    }
out:
    free(a);
    free(b);
    free(pa);
    free(pb);
    free(et);
    free(er);
    free(ep);
    free(kap);
    free(spr);
    return r;
}
