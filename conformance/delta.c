/*
 * Delta lobes, found by probing the sampler with stratified random numbers:
 *
 *  the lobes    at each incoming direction, the distinct (direction, f)
 *               answers of delta samples; a lobe's contribution to the
 *               albedo is f |cos theta_i| whatever probability the sampler
 *               gives it (pbrt-v2's f |cos| / pdf is the throughput and pdf
 *               the probability of the lobe), so the delta part of the
 *               albedo is their sum, without noise (pass.c)
 *  agree delta  each delta sample is one of materia's delta lobes, direction
 *               and f; each lobe of materia's carrying 1/16 of the weight is
 *               produced
 *  helmholtz    specular transmission there and back: T(T(w)) = w; the
 *               contributions of the two ways in the implementation's
 *               transport, importance c(o->i) = c(i->o), radiance
 *               c(o->i) (eta_i/eta_o)^2 = c(i->o) (eta_o/eta_i)^2, with
 *               eta_i/eta_o = sin theta_o / sin theta_i, Snell's law of its
 *               own answers; and one index for every pair
 *
 * The probes stratify uc and vary u1 too: a pbrt-v2 sampler chooses its
 * component with uc (every component gets 1/n of the strata, n <= 8), a
 * one-lobe Fresnel sampler chooses reflection or transmission with the
 * rescaled uc (sample-numbers 2) or with u1 (a three-number one), and u = 0
 * reaches a branch of probability F however small F is.
 */
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pass.h"

#define PROBE_UC 32
static const float probe_u1[] = {0, 0.125f, 0.375f, 0.625f, 0.875f};
#define NU1 ((int)(sizeof probe_u1 / sizeof probe_u1[0]))
/* two delta answers are one lobe when their directions are this close (a
 * float direction's rounding is 1e-7; distinct lobes of one wo are far
 * apart) and their f agree to this fraction */
#define LOBE_DIR_TOL 1e-4
#define LOBE_F_TOL 1e-4
/* below this sin theta, Snell's law of float directions says little */
#define SNELL_MIN_SIN 1e-4
/* Helmholtz: random incoming directions beside the configuration's */
#define HELM_RANDOM 24

int cf_probe_count(void) { return 2 * PROBE_UC * NU1; }

int cf_probe_grid(float (*u)[3], int max)
{
    int k, j, n = 0;
    for (k = 0; k < 2 * PROBE_UC; ++k)
        for (j = 0; j < NU1 && n < max; ++j) {
            /* the left edge of each stratum, then its middle */
            u[n][0] = (float)((k / 2 + 0.5 * (k & 1)) / PROBE_UC);
            u[n][1] = probe_u1[j];
            u[n++][2] = 0.5f;
        }
    return n;
}

double cf_sin_about(cf_v3 w, cf_v3 n)
{
    double c = cf_dot(w, n);
    cf_v3 p = cf_v3_make(w.x - c * n.x, w.y - c * n.y, w.z - c * n.z);
    return sqrt(cf_dot(p, p));
}

static int is_delta(const cf_samp *s)
{
    return (s->flags & CF_SPECULAR) && s->pdf > 0 && isfinite(s->pdf) && isfinite(s->wi[0]) && isfinite(s->wi[1]) &&
           isfinite(s->wi[2]) && isfinite(s->f[0]) && isfinite(s->f[1]) && isfinite(s->f[2]);
}

void cf_find_lobes(const cf_ctx *x, cf_v3 wo, const cf_samp *s, int n, cf_lobe *lobes, int *nlobes)
{
    int i, j, k;
    *nlobes = 0;
    for (i = 0; i < n; ++i) {
        const cf_samp *y = s + i;
        cf_v3 wi;
        double c[3], cm = 0;
        if (!is_delta(y)) continue;
        wi = cf_v3_make(y->wi[0], y->wi[1], y->wi[2]);
        for (k = 0; k < 3; ++k) {
            c[k] = y->f[k] * fabs(cf_dot(wi, x->ns));
            cm = fmax(cm, c[k]);
        }
        for (j = 0; j < *nlobes; ++j) {
            cf_lobe *b = lobes + j;
            double d = sqrt((b->wi[0] - wi.x) * (b->wi[0] - wi.x) + (b->wi[1] - wi.y) * (b->wi[1] - wi.y) +
                            (b->wi[2] - wi.z) * (b->wi[2] - wi.z)),
                   df = 0;
            for (k = 0; k < 3; ++k) df = fmax(df, fabs(b->c[k] - c[k]));
            if (d <= LOBE_DIR_TOL && df <= LOBE_F_TOL * fmax(cm, 1e-30)) break;
        }
        if (j < *nlobes) {
            lobes[j].count++;
            continue;
        }
        if (*nlobes == CF_MAX_LOBES) continue;
        {
            cf_lobe *b = lobes + (*nlobes)++;
            double so = cf_sin_about(wo, x->ns), si = cf_sin_about(wi, x->ns);
            memcpy(b->wi, y->wi, sizeof b->wi);
            memcpy(b->c, c, sizeof c);
            memcpy(b->f, y->f, sizeof b->f);
            b->flags = y->flags;
            b->count = 1;
            b->ratio = (y->flags & CF_TRANSMISSION) && so > SNELL_MIN_SIN && si > SNELL_MIN_SIN ? so / si : 0;
        }
    }
}

/* ---- agree delta ------------------------------------------------------------ */
static double delta_err(const cf_samp *t, const cf_samp *m, double tdir, const double *tf)
{
    double d = 0, e;
    int k;
    for (k = 0; k < 3; ++k) d += (t->wi[k] - m->wi[k]) * (t->wi[k] - m->wi[k]);
    e = sqrt(d) / tdir;
    for (k = 0; k < 3; ++k) e = fmax(e, fabs(t->f[k] - m->f[k]) / tf[k]);
    return isfinite(e) ? e : 1e30;
}


int cf_delta_agree(cf_ctx *x)
{
    cf_result *res = &x->out->res[CK_AGREE_DELTA];
    const mt_bsdf *rb = x->ref->bsdf;
    const double epsf = FLT_EPSILON;
    int w, i, j, k, tested = 0, bad = 0, np = cf_probe_count();
    float (*u)[3] = malloc((size_t)np * sizeof *u);
    double *tdir = malloc((size_t)np * sizeof *tdir), *tf = malloc((size_t)np * 3 * sizeof *tf), worst = 0;
    char q[200], ex[400], got[240];
    if (!u || !tdir || !tf) {
        free(u);
        free(tdir);
        free(tf);
        return CF_NOMEM;
    }
    cf_probe_grid(u, np);
    for (w = 0; w < x->nwo; ++w) {
        const cf_wo_data *d = x->w + w;
        const cf_samp *st = d->probe, *sr = d->probe_ref;
        double fm = 0, wsum = 0;
        if (!st || !sr) continue;
        for (i = 0; i < d->nprobe; ++i)
            for (k = 0; k < 3; ++k) fm = fmax(fm, sr[i].f[k]);
        /* materia's conditioning: its delta sample under a perturbed wo */
        for (i = 0; i < d->nprobe; ++i) {
            double dd = 0, sf[3] = {0, 0, 0};
            int p;
            tdir[i] = 1;
            if (!is_delta(sr + i)) continue;
            for (p = 0; p < 4; ++p) {
                cf_v3 pw = cf_perturb(d->wo, p, epsf);
                mt_bsdf_sample s = mt_bsdf_sample_f(rb, mt_v3((mt_real)pw.x, (mt_real)pw.y, (mt_real)pw.z), u[i][0],
                                                    u[i][1], u[i][2], MT_BSDF_ALL);
                if (!(s.pdf > 0) || !(s.type & MT_BSDF_SPECULAR)) continue;
                dd = fmax(dd, sqrt((s.wi.x - sr[i].wi[0]) * (s.wi.x - sr[i].wi[0]) +
                                   (s.wi.y - sr[i].wi[1]) * (s.wi.y - sr[i].wi[1]) +
                                   (s.wi.z - sr[i].wi[2]) * (s.wi.z - sr[i].wi[2])));
                for (k = 0; k < 3; ++k) sf[k] = fmax(sf[k], fabs(s.f.c[k] - sr[i].f[k]));
            }
            tdir[i] = 4 * dd + 1e-5;
            for (k = 0; k < 3; ++k) tf[3 * i + k] = cf_ref_bound(sr[i].f[k], sf[k], 64 * epsf, fm);
        }
        /* each of its delta samples is one of materia's at this wo */
        for (i = 0; i < d->nprobe; ++i) {
            double best = 1e300;
            if (!is_delta(st + i)) continue;
            tested++;
            for (j = 0; j < d->nprobe; ++j)
                if (is_delta(sr + j)) best = fmin(best, delta_err(st + i, sr + j, tdir[j], tf + 3 * j));
            if (best > 1) {
                bad++;
                cf_q_sample(q, sizeof q, d->wo, u[i]);
                cf_a_sample(got, sizeof got, st + i);
                snprintf(ex, sizeof ex, "one of materia's delta lobes (direction and f)");
                cf_worst_add(res->worst, best, q, ex, got, NULL);
            }
            worst = fmax(worst, best < 1e299 ? best : 1e30);
        }
        /* materia's lobes it never produced */
        for (j = 0; j < d->nprobe; ++j)
            if (is_delta(sr + j)) wsum += sr[j].f[0] + sr[j].f[1] + sr[j].f[2];
        for (j = 0; j < d->nprobe; ++j) {
            int found = 0;
            if (!is_delta(sr + j) || sr[j].f[0] + sr[j].f[1] + sr[j].f[2] < wsum / d->nprobe / 16) continue;
            for (i = 0; i < d->nprobe && !found; ++i) found = is_delta(st + i) && delta_err(st + i, sr + j, tdir[j], tf + 3 * j) <= 1;
            if (!found) {
                bad++;
                cf_q_sample(q, sizeof q, d->wo, u[j]);
                cf_a_sample(ex, sizeof ex, sr + j);
                cf_worst_add(res->worst, 1e3, q, ex, "never produced by the implementation at this wo", NULL);
                break; /* one lobe missing is enough to say */
            }
        }
    }
    free(u);
    free(tdir);
    free(tf);
    if (tested || bad)
        cf_set(res, bad == 0, "err/tol <= 1", "worst err/tol %.3g over %d delta samples, %d off", worst, tested, bad);
    return 0;
}

/* ---- helmholtz -------------------------------------------------------------- */
static const cf_samp *first_transmission(const cf_samp *s, int n)
{
    int i;
    for (i = 0; i < n; ++i)
        if (is_delta(s + i) && (s[i].flags & CF_TRANSMISSION)) return s + i;
    return NULL;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int cf_helmholtz(cf_ctx *x)
{
    cf_result *res = &x->out->res[CK_HELMHOLTZ];
    cf_impl *t = x->test;
    int any = 0, nw = 0, w, i, np = cf_probe_count(), pairs = 0, r = 0, radiance = t->conv.transport == CF_RADIANCE;
    cf_v3 wo[CF_MAX_WO + HELM_RANDOM], *ws = NULL;
    float (*u)[3] = NULL;
    cf_samp *s1 = NULL, *s2 = NULL;
    const cf_samp *there[CF_MAX_WO + HELM_RANDOM];
    double *etas = NULL, worst = 0, worst_dir = 0, worst_eta = 0;
    mt_rng rng;
    char q[200], ex[200], got[240], q2[200];
    /* is there specular transmission at all? */
    for (w = 0; w < x->nwo; ++w) {
        any |= x->w[w].delta_trans > 0;
        for (i = 0; i < x->w[w].nlobes; ++i) any |= (x->w[w].lobes[i].flags & CF_TRANSMISSION) != 0;
    }
    if (!any) return 0;
    mt_rng_seed(&rng, cf_seed(x->c->name, 3), 11);
    for (w = 0; w < x->nwo; ++w) wo[nw++] = x->w[w].wo;
    for (i = 0; i < HELM_RANDOM; ++i) {
        double a = mt_rng_uniform_d(&rng), b = mt_rng_uniform_d(&rng), z = 1 - 2 * a, s = sqrt(fmax(0, 1 - z * z));
        wo[nw++] = cf_v3_float(cf_v3_make(s * cos(6.283185307179586 * b), s * sin(6.283185307179586 * b), z));
    }
    u = malloc((size_t)np * nw * sizeof *u);
    ws = malloc((size_t)np * nw * sizeof *ws);
    s1 = malloc((size_t)np * nw * sizeof *s1);
    s2 = malloc((size_t)np * nw * sizeof *s2);
    etas = malloc((size_t)nw * sizeof *etas);
    if (!u || !ws || !s1 || !s2 || !etas) {
        r = CF_NOMEM;
        goto out;
    }
    for (w = 0; w < nw; ++w) {
        cf_probe_grid(u + (size_t)w * np, np);
        for (i = 0; i < np; ++i) ws[w * np + i] = wo[w];
    }
    if ((r = t->ops->sample(t, np * nw, ws, (const float(*)[3])u, s1))) goto out;
    /* the first transmission of each wo, and back from where it went */
    for (w = 0; w < nw; ++w) {
        there[w] = first_transmission(s1 + (size_t)w * np, np);
        for (i = 0; i < np; ++i) ws[w * np + i] = there[w] ? cf_v3_make(there[w]->wi[0], there[w]->wi[1], there[w]->wi[2]) : wo[w];
    }
    if ((r = t->ops->sample(t, np * nw, ws, (const float(*)[3])u, s2))) goto out;
    /* the index inside / outside each pair gives, by Snell's law (inside:
     * below the shading normal, about which the BSDF refracts) */
    for (w = 0; w < nw; ++w) {
        const cf_samp *a = there[w];
        cf_v3 wi;
        double so, si;
        if (!a) continue;
        wi = cf_v3_make(a->wi[0], a->wi[1], a->wi[2]);
        so = cf_sin_about(wo[w], x->ns);
        si = cf_sin_about(wi, x->ns);
        if (so > SNELL_MIN_SIN && si > SNELL_MIN_SIN) etas[x->eta_n++] = cf_dot(wo[w], x->ns) > 0 ? so / si : si / so;
    }
    if (x->eta_n) {
        qsort(etas, (size_t)x->eta_n, sizeof *etas, cmp_double);
        x->eta = etas[x->eta_n / 2];
    }
    for (w = 0; w < nw; ++w) {
        const cf_samp *a = there[w], *b = first_transmission(s2 + (size_t)w * np, np);
        cf_v3 wi;
        double so, si, ratio, eta, cmin, tol, dd, c1, c2, e, ee = 0;
        int k;
        if (!a || !b) continue;
        pairs++;
        wi = cf_v3_make(a->wi[0], a->wi[1], a->wi[2]);
        so = cf_sin_about(wo[w], x->ns);
        si = cf_sin_about(wi, x->ns);
        ratio = so > SNELL_MIN_SIN && si > SNELL_MIN_SIN ? so / si : 0; /* eta_i / eta_o */
        eta = x->eta > 0 ? x->eta : 1;
        if (ratio == 0) ratio = cf_dot(wo[w], x->ns) > 0 ? eta : 1 / eta;
        /* Snell's law is ill-conditioned near grazing refraction: an error
         * e in cos on one side is e (eta cos / cos')^2 on the other, and
         * (1 - F) / cos' shares it; the tolerance follows the pair. The
         * suite's directions are floats, unit only to a float epsilon, and
         * a refraction that scales x and y but takes z from 1 - sin^2
         * carries that: a float epsilon at least, whatever the precision */
        cmin = fmin(fabs(cf_dot(wo[w], x->ns)), fabs(cf_dot(wi, x->ns)));
        tol = 64 * fmax(t->eps, FLT_EPSILON) * fmax(eta * eta, 1 / (eta * eta)) / fmax(cmin * cmin, 1e-12);
        dd = sqrt((b->wi[0] - wo[w].x) * (b->wi[0] - wo[w].x) + (b->wi[1] - wo[w].y) * (b->wi[1] - wo[w].y) +
                  (b->wi[2] - wo[w].z) * (b->wi[2] - wo[w].z)) /
             tol;
        if (!isfinite(dd)) dd = 1e30;
        worst_dir = fmax(worst_dir, dd);
        for (k = 0; k < 3; ++k) {
            c1 = a->f[k] * fabs(cf_dot(wi, x->ns));
            c2 = b->f[k] * fabs(cf_dot(wo[w], x->ns));
            e = radiance ? cf_rel(c1 * ratio * ratio, c2 / (ratio * ratio)) / tol : cf_rel(c1, c2) / tol;
            ee = fmax(ee, isfinite(e) ? e : 1e30);
        }
        worst = fmax(worst, ee);
        if (x->eta > 0 && so > SNELL_MIN_SIN && si > SNELL_MIN_SIN) {
            double pe = cf_dot(wo[w], x->ns) > 0 ? so / si : si / so, de = fabs(pe - x->eta) / x->eta / tol;
            worst_eta = fmax(worst_eta, isfinite(de) ? de : 1e30);
            if (de > 1) {
                cf_q_sample(q, sizeof q, wo[w], u[(size_t)w * np + (size_t)(a - (s1 + (size_t)w * np))]);
                snprintf(ex, sizeof ex, "refraction with the configuration's index %.9g (median over %d pairs)", x->eta,
                         x->eta_n);
                snprintf(got, sizeof got, "index %.9g by Snell's law of this answer", pe);
                cf_worst_add(res->worst, de, q, ex, got, NULL);
            }
        }
        if (ee > 1 || dd > 1) {
            size_t at = (size_t)(a - (s1 + (size_t)w * np)), bt = (size_t)(b - (s2 + (size_t)w * np));
            cf_q_sample(q, sizeof q, wo[w], u[(size_t)w * np + at]);
            cf_q_sample(q2, sizeof q2, wi, u[(size_t)w * np + bt]);
            snprintf(ex, sizeof ex, "%s, and the way back to wo",
                     radiance ? "c(o->i) (eta_i/eta_o)^2 = c(i->o) (eta_o/eta_i)^2" : "c(o->i) = c(i->o)");
            snprintf(got, sizeof got, "c(o->i) %.9g, c(i->o) %.9g, eta_i/eta_o %.9g, back at %.9g %.9g %.9g",
                     a->f[0] * fabs(cf_dot(wi, x->ns)), b->f[0] * fabs(cf_dot(wo[w], x->ns)), ratio, b->wi[0], b->wi[1],
                     b->wi[2]);
            cf_worst_add(res->worst, fmax(ee, dd), q, ex, got, q2);
        }
    }
    if (pairs && (x->stages & ST_HELM))
        cf_set(res, worst <= 1 && worst_dir <= 1 && worst_eta <= 1, "<= 1 (64 eps cond.)",
               "err/tol %.3g (%s), |T(T(w)) - w| %.2g, index %.6g by Snell (spread %.2g), %d pairs", worst,
               radiance ? "radiance" : "importance", worst_dir, x->eta, worst_eta, pairs);
out:
    free(u);
    free(ws);
    free(s1);
    free(s2);
    free(etas);
    return r;
}
