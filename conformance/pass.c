/*
 * The pass over one configuration (cf_run_case): for each incoming
 * direction one set of samples, from which
 *
 *  identity      every sample finite, f >= 0, pdf >= 0, wi unit; the f and
 *                pdf of a non-delta sample equal eval at the wi returned
 *  chi2          its sampled directions against its own pdf: cells laid
 *                where a pilot sample fell (cells.c), expected counts by
 *                adaptive cubature of eval's pdf, pooling, delta and failed
 *                samples one more cell, Sidak over the run's tests
 *  pdf integral  its pdf's integral against the fraction of its samples
 *                that land in a cell (succeed and are not a delta lobe's)
 *  chi2 materia  its sampled directions against materia's pdf
 *  furnace MC=quad
 *                the Monte Carlo albedo of its samples (f |cos| / pdf)
 *                against the albedo by cubature of its f plus the
 *                contributions f |cos| of its delta lobes (delta.c); f > 0
 *                where its pdf is 0 fails, except where a shading normal
 *                differs from the geometric one (pbrt-v2 has such a region)
 *  furnace       the energy returned, in the implementation's transport:
 *                importance, the albedo itself; radiance, the light arriving
 *                from wo, whose transmitted part is f(wi, wo) (the
 *                transpose: the adjoint of a radiance BSDF is its importance
 *                BSDF) and a delta transmission's contribution times
 *                (eta_i / eta_o)^2 from Snell's law of its directions;
 *                against the configuration's expectation
 *
 * then the checks of pairs, delta lobes and extremes (pairs.c, delta.c,
 * impl_extremes.c). The implementation is reached only through its
 * batched operations, so materia in this process and any child speaking the
 * protocol go through the same code.
 */
#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pass.h"
#include "power.h"

#define TWO_PI 6.283185307179586476925
#define DEG (180 / 3.14159265358979323846)

/* Sample_f and Pdf compute cos theta_h in two ways (the sampled value, and
 * the normalized wo + wi): in float they differ by about 1e-3 relative
 * where a lobe is steep, in double by 1e-5; a lobe cos^e multiplies the
 * rounding e times (cf_allowance covers that). */
#define IDENTITY_REL_FLOAT 1e-3
#define IDENTITY_REL_DOUBLE 1e-5
/* |wi| - 1: a direction normalized in float, or printed with 9 digits
 * whatever the precision it was computed in, is within a few float
 * epsilons (1e-5 is 84); one computed in double and received as it is (in
 * this process), within 64 double epsilons of the length of the wo it came
 * from: the suite's wo is a float direction, unit to a float epsilon only,
 * and a reflection about a half vector keeps its length (pbrt-v2's
 * microfacet sampling does) */
#define UNIT_TOL_FLOAT 1e-5
#define UNIT_TOL_DOUBLE (64 * DBL_EPSILON)
/* pilot samples per cell at least: the layout's quantiles need a few per
 * column (cells.c) */
#define PILOT_PER_CELL 16
/* the cubature's tolerance, 1e-7 relative per cell, summed over cells and
 * channels and rounded up: the slack of a deterministic albedo */
#define QUAD_SLACK 1e-6
/* samples answered at a time: the memory of a direction's samples is
 * bounded (about 250 bytes each while answered) whatever their number */
#define CHUNK 65536L
/* --power's pilot at most (it lays 20 x 21 cells from 16 per cell) */
#define POWER_PILOT 262144.0

void cf_set(cf_result *r, int ok, const char *bound, const char *fmt, ...)
{
    va_list ap;
    r->ok = ok;
    snprintf(r->bound, sizeof r->bound, "%s", bound);
    va_start(ap, fmt);
    vsnprintf(r->statistic, sizeof r->statistic, fmt, ap);
    va_end(ap);
}

double cf_dot(cf_v3 a, cf_v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

double cf_rel(double a, double b)
{
    double m = fmax(fabs(a), fabs(b));
    return m > 1e-30 ? fabs(a - b) / m : 0;
}

void cf_describe_wo(cf_v3 wo, char *out, size_t n)
{
    double l = sqrt(cf_dot(wo, wo)), phi = atan2(wo.y, wo.x) * DEG;
    if (phi < 0) phi += 360;
    snprintf(out, n, "wo (%.9g, %.9g, %.9g), theta %.4g deg, phi %.4g deg", wo.x, wo.y, wo.z,
             acos(fmax(-1, fmin(1, wo.z / (l > 0 ? l : 1)))) * DEG, phi);
}

/* The rounding allowance of the implementation's values: 64 epsilons, and
 * 3 e for a lobe cos^e, whose cos theta_h rounds by an epsilon that the
 * power multiplies by e. */
static double allowance(const cf_case *c, double eps)
{
    double e = c->lobe_exponent > 1 ? c->lobe_exponent : 1;
    return (3 * e + 64) * eps;
}

static int finite_nonneg(double v) { return isfinite(v) && v >= 0; }

static int sample_valid(const cf_samp *x, double unit_tol)
{
    double len = sqrt(x->wi[0] * x->wi[0] + x->wi[1] * x->wi[1] + x->wi[2] * x->wi[2]);
    int ok = finite_nonneg(x->pdf), k;
    for (k = 0; k < 3; ++k) ok &= finite_nonneg(x->f[k]) && isfinite(x->wi[k]);
    return ok && (!(x->pdf > 0) || fabs(len - 1) <= unit_tol);
}

static cf_v3 wi_of(const cf_samp *s) { return cf_v3_make(s->wi[0], s->wi[1], s->wi[2]); }

/* The shading and geometric normals the "at" lines set (a later key wins). */
static void normals(const cf_case *c, cf_v3 *ns, cf_v3 *ng)
{
    int i;
    *ns = *ng = cf_v3_make(0, 0, 1);
    for (i = 0; i < c->nlines; ++i) {
        const char *s = c->lines[i];
        char key[16];
        int used;
        if (strncmp(s, "at ", 3)) continue;
        s += 3;
        while (sscanf(s, " %15s%n", key, &used) == 1) {
            double v[3];
            int got = 0, k, u2;
            s += used;
            for (k = 0; k < 3 && sscanf(s, " %lf%n", &v[k], &u2) == 1; ++k) {
                s += u2;
                got++;
            }
            if (got == 3 && (!strcmp(key, "n") || !strcmp(key, "ng"))) {
                double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
                if (l > 0) *(!strcmp(key, "n") ? ns : ng) = cf_v3_make(v[0] / l, v[1] / l, v[2] / l);
            }
        }
    }
}

void cf_measure_add(cf_result *r, double s, double se, double sys, double at, const char *what)
{
    cf_measure *m = &r->m;
    if (m->oom) return;
    if (m->n == m->cap) {
        int cap = m->cap ? 2 * m->cap : 16;
        cf_unit *u = realloc(m->u, (size_t)cap * sizeof *u);
        if (!u) {
            m->oom = 1;
            return;
        }
        m->u = u;
        m->cap = cap;
    }
    m->u[m->n].s = s;
    m->u[m->n].se = se;
    m->u[m->n].sys = sys;
    m->u[m->n].at = at;
    m->u[m->n++].what = what;
}

void cf_measure_hist(cf_result *r, const long *counts, int ncell, long other, double at)
{
    cf_measure *m = &r->m;
    size_t total = 0;
    int i;
    long *h;
    if (m->oom) return;
    for (i = 0; i < m->nhist; ++i) total += (size_t)m->hist_bins[i];
    if (m->nhist == m->cap_hist) {
        int cap = m->cap_hist ? 2 * m->cap_hist : 8;
        double *a = realloc(m->hist_at, (size_t)cap * sizeof *a);
        int *b = a ? realloc(m->hist_bins, (size_t)cap * sizeof *b) : NULL;
        if (a) m->hist_at = a;
        if (b) m->hist_bins = b;
        if (!a || !b) {
            m->oom = 1;
            return;
        }
        m->cap_hist = cap;
    }
    if (!(h = realloc(m->hist, (total + (size_t)ncell + 1) * sizeof *h))) {
        m->oom = 1;
        return;
    }
    m->hist = h;
    memcpy(h + total, counts, (size_t)ncell * sizeof *counts);
    h[total + (size_t)ncell] = other;
    m->hist_bins[m->nhist] = ncell + 1;
    m->hist_at[m->nhist++] = at;
}

void cf_results_free(cf_result res[CK_NCHECK])
{
    int k;
    for (k = 0; k < CK_NCHECK; ++k) {
        free(res[k].m.u);
        free(res[k].m.hist);
        free(res[k].m.hist_at);
        free(res[k].m.hist_bins);
        memset(&res[k].m, 0, sizeof res[k].m);
    }
}

void cf_outcome_free(cf_outcome *o)
{
    int w;
    cf_results_free(o->res);
    for (w = 0; w < CF_MAX_WO; ++w) cf_layout_free(&o->layout[w]);
}

/* A fraction k / n as a measure: its binomial standard error (at least that
 * of one event in n, so that 0 of n still has a tolerance). */
static void measure_fraction(cf_result *r, long k, long n, double at, const char *what)
{
    double p = n > 0 ? (double)k / n : 0;
    cf_measure_add(r, p, n > 0 ? sqrt(fmax(p * (1 - p), 1.0 / n) / n) : 0, 0, at, what);
}

/* ---- the samples of one direction ------------------------------------------ */
/* |wi| - 1 allowed of its samples */
static double unit_tol_of(const cf_ctx *x, const cf_wo_data *d)
{
    const cf_impl *t = x->test;
    return t->eps < 1e-10 && t->direct ? UNIT_TOL_DOUBLE + 4 * fabs(sqrt(cf_dot(d->wo, d->wo)) - 1) : UNIT_TOL_FLOAT;
}

/* Its pilot (another stream of random numbers) and the cells laid where
 * the pilot fell, drawn before the samples counted in them: the cells, and
 * with --power the samples per direction, are fixed before those samples
 * exist. The pilot's answers are taken a chunk at a time; its non-delta
 * directions are kept (the cubature starts where they lie). */
static int wo_pilot(cf_ctx *x, cf_wo_data *d, int slot)
{
    const cf_run *run = x->run;
    cf_impl *t = x->test;
    cf_layout *l = &x->out->layout[slot];
    long n = run->cfg.samples, np, i, done, m, chunk;
    double unit_tol = unit_tol_of(x, d);
    float (*u)[3] = NULL;
    cf_samp *s = NULL;
    cf_v3 *wos = NULL;
    mt_rng rng;
    int r = 0;
    /* --power: the samples follow from the pilot, whatever is checked */
    int pilot = (x->stages & ST_CELLS) || run->power > 0;
    if (!pilot && !(x->stages & ST_PROBES)) return 0;
    np = pilot ? (long)fmax((double)n / 4, (double)PILOT_PER_CELL * run->cfg.nphi * run->cfg.nz) : 0;
    if (np > n) np = n;
    /* --power: n is an estimate; the pilot need only lay the cells and
     * tell the shapes */
    if (run->power > 0 && np > POWER_PILOT) np = (long)fmax(POWER_PILOT, (double)PILOT_PER_CELL * run->cfg.nphi * run->cfg.nz);
    d->npilot_drawn = np;
    chunk = np < CHUNK ? np : CHUNK;
    if (np > 0) {
        u = malloc((size_t)chunk * sizeof *u);
        s = malloc((size_t)chunk * sizeof *s);
        wos = malloc((size_t)chunk * sizeof *wos);
        d->pilot = malloc((size_t)np * sizeof *d->pilot);
        if (!u || !s || !wos || !d->pilot) {
            r = CF_NOMEM;
            goto out;
        }
        for (i = 0; i < chunk; ++i) wos[i] = d->wo;
        cf_sample_stream(&rng, x->c->name, d->index, 1);
        for (done = 0; done < np; done += m) {
            m = np - done < chunk ? np - done : chunk;
            cf_sample_next(&rng, run->sample_numbers, m, u);
            if ((r = t->ops->sample(t, (int)m, wos, (const float(*)[3])u, s))) goto out;
            for (i = 0; i < m; ++i)
                if (sample_valid(s + i, unit_tol) && s[i].pdf > 0 && !(s[i].flags & CF_SPECULAR)) {
                    d->pilot[d->npilot++] = wi_of(s + i);
                    d->across += cf_dot(wi_of(s + i), x->ng) * cf_dot(d->wo, x->ng) < 0;
                }
        }
    }
    if (x->fixed && x->fixed->layout[slot].ncell ? cf_layout_copy(l, &x->fixed->layout[slot])
                                                : cf_layout_from(l, d->pilot, d->npilot, run->cfg.nphi, run->cfg.nz)) {
        r = CF_NOMEM;
        goto out;
    }
    if (!(d->counts = calloc((size_t)l->ncell, sizeof *d->counts))) r = CF_NOMEM;
out:
    free(u);
    free(s);
    free(wos);
    return r;
}

/* --power: the samples per direction of the configuration, from its
 * directions' pilots: each reference mismatch caught with probability 0.95
 * by the test most powerful against it (power.h). The rows' probabilities
 * are the pilot's counts in them; the cubature's, after the samples, give
 * the figure the run prints. */
static long power_samples(const cf_ctx *x)
{
    const cf_run *run = x->run;
    cf_power_dir pd[CF_MAX_WO];
    int w, nw = 0;
    memset(pd, 0, sizeof pd);
    for (w = 0; w < x->nwo && w < CF_MAX_WO; ++w) {
        const cf_wo_data *d = x->w + w;
        const cf_layout *l = &x->out->layout[w];
        double *pc;
        long i;
        int mdof;
        if (!l->ncell || !d->npilot_drawn || !(pc = calloc((size_t)l->ncell, sizeof *pc))) continue;
        for (i = 0; i < d->npilot; ++i)
            pc[cf_layout_cell(l, d->pilot[i].x, d->pilot[i].y, d->pilot[i].z)] += 1.0 / (double)d->npilot_drawn;
        pd[nw].dof = l->ncell - 1;
        cf_power_shapes(l, pc, pd[nw].v, &mdof);
        pd[nw++].mdof = mdof;
        free(pc);
    }
    {
        /* nothing the distribution tests could see (delta lobes alone):
         * the run's own samples, not --power's cap */
        long n = cf_power_samples_for(run->power, nw, pd, run->cfg.alpha_test, 0.95, run->power_max);
        return n > 0 ? n : run->cfg.samples;
    }
}

/* Its samples, a chunk at a time (memory bounded whatever their number;
 * the same numbers, answers and sums in the same order as all at once):
 * their validity, the Monte Carlo albedo, counts in the cells, and the f
 * and pdf of the first identity_samples non-delta ones set against eval;
 * then the probes of delta lobes. */
static int wo_main(cf_ctx *x, cf_wo_data *d, int slot)
{
    const cf_run *run = x->run;
    cf_impl *t = x->test;
    const cf_layout *l = &x->out->layout[slot];
    long n = d->n, i, done, m, chunk, nw, *idx = NULL, nidc;
    float (*u)[3] = NULL;
    cf_samp *s = NULL;
    cf_v3 *wos = NULL, *wis = NULL;
    cf_eval *ev = NULL;
    double unit_tol = unit_tol_of(x, d);
    double id_tol = fmax(t->eps < 1e-10 ? IDENTITY_REL_DOUBLE : IDENTITY_REL_FLOAT, x->allow_own);
    cf_result *res = x->out->res;
    char q[200], an[240], ex[400], qs[200];
    mt_rng rng;
    int r = 0, k;
    chunk = n < CHUNK ? n : CHUNK;
    /* wo for every query of a batch: a chunk of samples, and the probes */
    nw = chunk > cf_probe_count() ? chunk : cf_probe_count();
    u = malloc((size_t)chunk * sizeof *u);
    s = malloc((size_t)chunk * sizeof *s);
    wos = malloc((size_t)nw * sizeof *wos);
    idx = malloc((size_t)chunk * sizeof *idx);
    wis = malloc((size_t)chunk * sizeof *wis);
    ev = malloc((size_t)chunk * sizeof *ev);
    if (!u || !s || !wos || !idx || !wis || !ev) {
        r = CF_NOMEM;
        goto out;
    }
    for (i = 0; i < nw; ++i) wos[i] = d->wo;
    cf_sample_stream(&rng, x->c->name, d->index, 0);
    /* checks that need only the first directions sampled (the pairs'; run
     * alone, --check): small chunks, until they are there */
    if (!(x->stages & (ST_IDENTITY | ST_CELLS | ST_PROBES)) && chunk > 1024) chunk = 1024;
    for (done = 0; done < n; done += m) {
        if (!(x->stages & (ST_IDENTITY | ST_CELLS | ST_PROBES)) && d->ndirs >= CF_KEEP_DIRS) break;
        m = n - done < chunk ? n - done : chunk;
        cf_sample_next(&rng, run->sample_numbers, m, u);
        if ((r = t->ops->sample(t, (int)m, wos, (const float(*)[3])u, s))) goto out;
        nidc = 0;
        for (i = 0; i < m; ++i) {
            const cf_samp *y = s + i;
            double c;
            if (!sample_valid(y, unit_tol)) {
                d->invalid++;
                cf_q_sample(q, sizeof q, d->wo, u[i]);
                cf_a_sample(an, sizeof an, y);
                cf_worst_add(res[CK_IDENTITY].worst, 1e30, q, "finite, f >= 0, pdf >= 0, |wi| = 1", an, NULL);
                continue;
            }
            if (!(y->pdf > 0)) continue;
            c = fabs(cf_dot(wi_of(y), x->ns));
            for (k = 0; k < 3; ++k) {
                double wgt = y->f[k] * c / y->pdf;
                d->mc[k] += wgt;
                d->mc2[k] += wgt * wgt;
            }
            if (y->flags & CF_SPECULAR) {
                d->delta++;
                d->delta_trans += (y->flags & CF_TRANSMISSION) != 0;
                continue;
            }
            if (d->nid < run->identity_samples) {
                idx[nidc] = i;
                wis[nidc++] = wi_of(y);
                d->nid++;
            }
            if (d->ndirs < CF_KEEP_DIRS) d->first[d->ndirs] = wi_of(y);
            d->ndirs++;
            d->across += cf_dot(wi_of(y), x->ng) * cf_dot(d->wo, x->ng) < 0;
            if (l->ncell) d->counts[cf_layout_cell(l, y->wi[0], y->wi[1], y->wi[2])]++;
        }
        /* identity: eval where the samples went, at the wi returned */
        if (!(x->stages & ST_IDENTITY) || !nidc) continue;
        if ((r = t->ops->eval(t, (int)nidc, wos, wis, ev))) goto out;
        for (i = 0; i < nidc; ++i) {
            const cf_samp *y = s + idx[i];
            double e = cf_rel(y->pdf, ev[i].pdf);
            for (k = 0; k < 3; ++k) e = fmax(e, cf_rel(y->f[k], ev[i].f[k]));
            if (!(e <= id_tol)) {
                d->unlike++;
                cf_q_eval(q, sizeof q, d->wo, wis[i]);
                cf_a_eval(an, sizeof an, ev + i);
                cf_q_sample(qs, sizeof qs, d->wo, u[idx[i]]);
                snprintf(ex, sizeof ex, "%.9g %.9g %.9g %.9g (the answer to %s)", y->f[0], y->f[1], y->f[2], y->pdf, qs);
                cf_worst_add(res[CK_IDENTITY].worst, isfinite(e) ? e / id_tol : 1e30, q, ex, an, qs);
            }
        }
    }
    /* the delta lobes */
    if (x->stages & ST_PROBES) {
        int npr = cf_probe_count();
        float (*pu)[3] = malloc((size_t)npr * sizeof *pu);
        d->probe = malloc((size_t)npr * sizeof *d->probe);
        if (x->ref) d->probe_ref = malloc((size_t)npr * sizeof *d->probe_ref);
        if (!pu || !d->probe || (x->ref && !d->probe_ref)) {
            free(pu);
            r = CF_NOMEM;
            goto out;
        }
        d->nprobe = cf_probe_grid(pu, npr);
        r = t->ops->sample(t, d->nprobe, wos, (const float(*)[3])pu, d->probe);
        if (!r && x->ref) r = x->ref->ops->sample(x->ref, d->nprobe, wos, (const float(*)[3])pu, d->probe_ref);
        free(pu);
        if (r) goto out;
        cf_find_lobes(x, d->wo, d->probe, d->nprobe, d->lobes, &d->nlobes);
    }
out:
    free(u);
    free(s);
    free(wos);
    free(idx);
    free(wis);
    free(ev);
    return r;
}

/* ---- cells, chi-square, integral and furnace of one direction ------------ */
typedef struct acc {
    long id_bad, id_tested;
    struct {
        double min_p;
        long dof;
        int hard, wo;
        char where[672]; /* wod[200], cells[420] and the count (core.h cf_result.where the same) */
    } chi[2];
    double worst_int, worst_mc, worst_gap, worst_excess, rho_lo, rho_hi, mean_p;
    int int_wo, mc_wo, rho_wo, gap_bad, other, mean_wo, mean_dof;
    char int_what[160], mc_what[200], rho_what[160], gap_what[160], mean_what[160];
} acc;

/* The three cells furthest from their expected count, as a renderer author
 * reads them: the directions they cover and (o - e) / sqrt(e). */
static void worst_cells(const cf_layout *l, const long *counts, const double *pdfc, long n, char *out, size_t size)
{
    int best[3] = {-1, -1, -1}, c, k, j;
    double score[3] = {0, 0, 0};
    size_t at = 0;
    for (c = 0; c < l->ncell; ++c) {
        double e = pdfc[c] * n, o = (double)counts[c], s = e > 0 ? fabs(o - e) / sqrt(e) : (o > 0 ? 1e300 : 0);
        for (k = 0; k < 3; ++k)
            if (s > score[k]) {
                for (j = 2; j > k; --j) {
                    score[j] = score[j - 1];
                    best[j] = best[j - 1];
                }
                score[k] = s;
                best[k] = c;
                break;
            }
    }
    out[0] = 0;
    for (k = 0; k < 3 && best[k] >= 0 && at < size; ++k) {
        double p0, p1, z0, z1, e, o;
        c = best[k];
        cf_layout_bounds(l, c, &p0, &p1, &z0, &z1);
        e = pdfc[c] * n;
        o = (double)counts[c];
        at += (size_t)snprintf(out + at, size - at, "%scell theta %.4g..%.4g deg, phi %.4g..%.4g deg: %.0f samples, %.1f "
                                                    "expected (%s)",
                               k ? "; " : "", acos(fmin(1, z1)) * DEG, acos(fmax(-1, z0)) * DEG, p0 * DEG, p1 * DEG, o, e,
                               "");
        if (at < size) { /* the deviation, in the place left for it */
            char dev[48];
            if (e > 0)
                snprintf(dev, sizeof dev, "%+.1f sd", (o - e) / sqrt(e));
            else
                snprintf(dev, sizeof dev, "its pdf is 0 there");
            at -= 1;
            at += (size_t)snprintf(out + at, size - at, "%s)", dev);
        }
    }
}

static void plot(const cf_ctx *x, int which, const cf_wo_data *d, const cf_layout *l, const long *counts,
                 const double *pdfc, const cf_chi2 *c2)
{
    static const char *const check[2] = {"chi2", "chi2 materia"}, *const label[2] = {"expected (own pdf)",
                                                                                    "expected (materia)"};
    const cf_run *run = x->run;
    char path[4096], slug[128], title[256], sub[300], wod[200];
    mt_error err;
    size_t i, j = 0;
    if (!run->plots || !(run->plots_all || c2->p < run->cfg.alpha_test)) return;
    for (i = 0; x->c->name[i] && j < sizeof slug - 1; ++i) {
        char ch = x->c->name[i];
        slug[j++] = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '.' ? ch : '_';
    }
    slug[j] = 0;
    snprintf(path, sizeof path, "%.3000s/%s-%s-%s-wo%d.png", run->plots, slug, mt_mode_name(run->mode),
             which ? "chi2-materia" : "chi2", d->index);
    snprintf(title, sizeof title, "%.100s, %s: %s, p = %.3g %s %.3g (%s)", x->c->name, mt_mode_name(run->mode),
             check[which], c2->p, c2->p < run->cfg.alpha_test ? "<" : ">=", run->cfg.alpha_test,
             c2->p < run->cfg.alpha_test ? "FAIL" : "pass");
    cf_describe_wo(d->wo, wod, sizeof wod);
    snprintf(sub, sizeof sub, "%s, %ld samples, %d cells, chi2 %.1f, %ld dof", wod, d->n, l->ncell, c2->chi2, c2->dof);
    mt_error_clear(&err);
    if (cf_plot_cells(path, title, sub, label[which], l, counts, pdfc, d->n, &err))
        fprintf(stderr, "materia-conformance: --plots: %s: %s\n", path, err.message);
}

/* The chi-square of the counts against cell probabilities pdfc: the worst p
 * over directions, its cells when it fails. */
static void chi2_of(cf_ctx *x, acc *a, int which, cf_wo_data *d, const cf_layout *l, const long *counts,
                    const double *pdfc, double integral)
{
    cf_chi2 c2;
    cf_chi2_counts(l->ncell, counts, pdfc, d->n, d->ndirs, integral, &c2);
    plot(x, which, d, l, counts, pdfc, &c2);
    if (which == 0 && d->index < CF_MAX_WO) { /* its power (power.c) */
        int mdof;
        x->out->pw_n[d->index] = d->n;
        x->out->pw_dof[d->index] = c2.dof;
        cf_power_shapes(l, pdfc, x->out->pw_v[d->index], &mdof);
        x->out->pw_mdof[d->index] = mdof;
    }
    if (c2.hard) a->chi[which].hard = 1;
    if (c2.p < a->chi[which].min_p) {
        char wod[200], cells[420];
        a->chi[which].min_p = c2.p;
        a->chi[which].dof = c2.dof;
        a->chi[which].wo = d->index;
        cf_describe_wo(d->wo, wod, sizeof wod);
        worst_cells(l, counts, pdfc, d->n, cells, sizeof cells);
        snprintf(a->chi[which].where, sizeof a->chi[which].where, "%s, %ld samples: %s", wod, d->n, cells);
    }
}

/* The mean of its sampled directions against the mean its pdf gives: each
 * non-delta sample counted at its cell's centre, x, y, z and its row's
 * |z| (cf_mean_funcs), so the statistic is a few linear contrasts of the
 * chi-square's counts, whose expectations and covariance under its own pdf
 * come from the same cubature: nothing but the samples is random. Given
 * the N samples in cells, they are N draws of the pdf normalized over the
 * cells; in the functions' combinations orthonormal under it (as many as
 * are independent: 3 above the surface, where z = |z|), N times the
 * squared deviations of the means is a chi-square of that many degrees of
 * freedom. The cubature's error (its total over the cells, relative to
 * the pdf's integral, bounds each mean's error times the combination's
 * coefficients) and the rounding allowance are taken off each deviation
 * first. */
static void mean_of(cf_ctx *x, acc *a, const cf_wo_data *d, const cf_layout *l, const long *counts, const double *pdfc,
                    double cerr)
{
    cf_result *res = &x->out->res[CK_MEAN];
    double p = 0, so[CF_MEAN_DIM] = {0, 0, 0, 0}, h[CF_MEAN_DIM], t = 0, pv, worst = 0;
    static const char *const fname[CF_MEAN_DIM] = {"x", "y", "z", "|z|"};
    static const char *const mean_what[CF_MEAN_DIM] = {
        "the mean x of its samples minus its pdf's at cos %.3g", "the mean y of its samples minus its pdf's at cos %.3g",
        "the mean z of its samples minus its pdf's at cos %.3g", "the mean |z| of its samples minus its pdf's at cos %.3g"};
    cf_mean_basis b;
    long nd = 0;
    int c, j, k, wj = 3;
    for (c = 0; c < l->ncell; ++c) {
        p += pdfc[c] > 0 ? pdfc[c] : 0;
        if (!counts[c]) continue;
        cf_mean_funcs(l, c, h);
        for (j = 0; j < CF_MEAN_DIM; ++j) so[j] += (double)counts[c] * h[j];
        nd += counts[c];
    }
    if (!(p > 0) || nd < 1 || !cf_mean_basis_of(l, pdfc, &b)) return; /* nothing to set against (chi2 says why) */
    for (j = 0; j < CF_MEAN_DIM; ++j) so[j] /= (double)nd;
    for (k = 0; k < b.rank; ++k) {
        double e = 0, sys = 0;
        for (j = 0; j < CF_MEAN_DIM; ++j) {
            e += b.a[k][j] * (so[j] - b.mu[j]);
            sys += fabs(b.a[k][j]) * (2 * cerr / p + x->allow);
        }
        e = fmax(0, fabs(e) - sys);
        t += (double)nd * e * e;
    }
    pv = cf_chi2_pvalue(t, b.rank);
    for (j = 0; j < CF_MEAN_DIM; ++j) {
        double dv = so[j] - b.mu[j];
        cf_measure_add(res, dv, sqrt(b.var[j] / (double)nd), 2 * cerr / p + x->allow, d->wo.z, mean_what[j]);
        if (b.var[j] > 0 && fabs(dv) / sqrt(b.var[j]) > worst) {
            worst = fabs(dv) / sqrt(b.var[j]);
            wj = j;
        }
    }
    if (pv < a->mean_p || a->mean_wo < 0) {
        char wod[200];
        a->mean_p = fmin(a->mean_p, pv);
        a->mean_wo = d->index;
        a->mean_dof = b.rank;
        snprintf(a->mean_what, sizeof a->mean_what, "%s %.6f vs %.6f at cos %.4g", fname[wj], so[wj], b.mu[wj], d->wo.z);
        cf_describe_wo(d->wo, wod, sizeof wod);
        snprintf(res->where, sizeof res->where, "%s: the means of its %ld samples in cells: x %.6f y %.6f z %.6f |z| %.6f; "
                 "its pdf's: x %.6f y %.6f z %.6f |z| %.6f (%d dof, chi2 %.3g)", wod, nd, so[0], so[1], so[2], so[3],
                 b.mu[0], b.mu[1], b.mu[2], b.mu[3], b.rank, t);
    }
}

/* The energy of the delta lobes in the implementation's transport. */
static void lobes_energy(const cf_ctx *x, const cf_wo_data *d, double *fwd, double *energy)
{
    int j, k;
    for (k = 0; k < 3; ++k) fwd[k] = energy[k] = 0;
    for (j = 0; j < d->nlobes; ++j) {
        const cf_lobe *b = d->lobes + j;
        double conv = 1;
        if (x->test->conv.transport == CF_RADIANCE && (b->flags & CF_TRANSMISSION)) {
            double r = b->ratio > 0 ? b->ratio : 0;
            /* eta_i / eta_o, from its own directions or the configuration's */
            if (r == 0 && x->eta > 0) r = cf_dot(d->wo, x->ns) > 0 ? x->eta : 1 / x->eta;
            conv = r > 0 ? r * r : 1;
        }
        for (k = 0; k < 3; ++k) {
            fwd[k] += b->c[k];
            energy[k] += b->c[k] * conv;
        }
    }
}

static int wo_cells(cf_ctx *x, acc *a, cf_wo_data *d, int slot)
{
    cf_result *res = x->out->res;
    cf_layout *l = &x->out->layout[slot];
    long *counts = NULL, n = d->n;
    double *pdfc = NULL, *pdfm = NULL, tot[7], err[7], oth[7], oerr[7], dfwd[3], den[3];
    double cerr, ferr, integral, succ, se, tol;
    cf_regions rg;
    /* no cells where nothing was seen, nor for checks that need none (agree
     * delta alone needs the probes, not the cubature) */
    int k, r = 0, cells = x->density && (x->stages & ST_CELLS);
    memset(&rg, 0, sizeof rg);
    lobes_energy(x, d, dfwd, den);
    if (!cells) {
        cf_layout_free(l);
        for (k = 0; k < 7; ++k) tot[k] = err[k] = 0;
    } else {
        /* the cells (wo_pilot) and the counts in them (wo_main) */
        counts = d->counts;
        pdfc = calloc((size_t)l->ncell, sizeof *pdfc);
        pdfm = calloc((size_t)l->ncell, sizeof *pdfm);
        if (!pdfc || !pdfm) {
            r = CF_NOMEM;
            goto out;
        }
        if ((r = cf_regions_build(&rg, l, d->pilot, d->npilot)) ||
            (r = cf_cells_integrate(x->test, l, &rg, d->wo, x->ns, x->ng, 0, n, pdfc, tot, err)))
            goto out;
    }
    integral = tot[0];
    cerr = err[0];
    ferr = fmax(err[1], fmax(err[2], err[3]));
    succ = (double)d->ndirs / n;
    if (cells) {
        cf_measure_hist(&res[CK_CHI2], counts, l->ncell, n - d->ndirs, d->wo.z);
        cf_measure_hist(&res[CK_CHI2_MATERIA], counts, l->ncell, n - d->ndirs, d->wo.z);
        /* chi2 and the pdf's integral */
        chi2_of(x, a, 0, d, l, counts, pdfc, integral);
        mean_of(x, a, d, l, counts, pdfc, cerr);
        se = sqrt(fmax(succ * (1 - succ), 1.0 / n) / n);
        tol = x->z * se + cerr + x->allow;
        cf_measure_add(&res[CK_INTEGRAL], integral - succ, se, cerr + x->allow, d->wo.z,
                       "the pdf's integral minus the success fraction at cos %.3g");
        if (fabs(integral - succ) / tol > a->worst_int || a->int_wo < 0) {
            char wod[200];
            a->worst_int = fmax(a->worst_int, fabs(integral - succ) / tol);
            a->int_wo = d->index;
            cf_describe_wo(d->wo, wod, sizeof wod);
            snprintf(a->int_what, sizeof a->int_what, "int %.6f vs %.6f at cos %.4g", integral, succ, d->wo.z);
            snprintf(res[CK_INTEGRAL].where, sizeof res[CK_INTEGRAL].where, "%s: the integral of its pdf %.6f, the "
                     "fraction of its %ld samples in cells %.6f (tolerance %.2g)", wod, integral, n, succ, tol);
        }
        /* materia's pdf over the same cells */
        if (x->ref && (x->stages & ST_REFCELLS)) {
            double im = 0;
            if ((r = cf_cells_ref_pdf(x->ref->bsdf, l, &rg, d->wo, n, pdfm))) goto out;
            for (k = 0; k < l->ncell; ++k) im += pdfm[k];
            chi2_of(x, a, 1, d, l, counts, pdfm, im);
        }
        /* the energy of light arriving from wo, in radiance transport */
        if (x->test->conv.transport == CF_RADIANCE) {
            if (d->across) {
                if ((r = cf_cells_integrate(x->test, l, &rg, d->wo, x->ns, x->ng, 1, n, NULL, oth, oerr))) goto out;
                a->other = 1;
                for (k = 0; k < 3; ++k) den[k] += oth[3 + k] - oth[k];
                ferr += fmax(oerr[0], fmax(oerr[1], oerr[2])) + fmax(oerr[3], fmax(oerr[4], oerr[5]));
            }
        }
    }
    /* furnace: Monte Carlo against quadrature, then the energy bound */
    for (k = 0; k < 3; ++k) {
        double fq = tot[1 + k], gap = tot[4 + k], q = fq - gap + dfwd[k], m = d->mc[k] / n;
        double se_mc = sqrt(fmax(d->mc2[k] / n - m * m, 0) / n);
        double sys = ferr + x->allow * fabs(q) + (double)n * DBL_EPSILON * fabs(q) + 1e-12, dev;
        double gap_tol = ferr + x->allow * fabs(fq) + QUAD_SLACK, rho, slack, excess = 0, v = x->c->expect_rho;
        if (cells) {
            if (gap > gap_tol && !(x->c->flags & CF_CASE_SHADING_GAP) && !a->gap_bad) {
                a->gap_bad = 1;
                snprintf(a->gap_what, sizeof a->gap_what, "f > 0 where pdf = 0: %.4g of rho unreachable at cos %.4g", gap,
                         d->wo.z);
                cf_describe_wo(d->wo, res[CK_FURNACE_MC].where, sizeof res[CK_FURNACE_MC].where);
                res[CK_FURNACE_MC].wo = d->index;
            }
            a->worst_gap = fmax(a->worst_gap, gap);
            cf_measure_add(&res[CK_FURNACE_MC], gap, 0, gap_tol, d->wo.z, "the albedo where the pdf is 0 at cos %.3g");
        }
        dev = fabs(m - q) / (x->z * se_mc + sys);
        cf_measure_add(&res[CK_FURNACE_MC], m - q, se_mc, sys, d->wo.z,
                       "the Monte Carlo albedo minus the quadrature at cos %.3g");
        if (dev > a->worst_mc || a->mc_wo < 0) {
            a->worst_mc = fmax(a->worst_mc, dev);
            a->mc_wo = d->index;
            snprintf(a->mc_what, sizeof a->mc_what, "quad %.6f MC %.6f +- %.1g at cos %.4g", q, m, se_mc, d->wo.z);
            if (!a->gap_bad) {
                char wod[200];
                cf_describe_wo(d->wo, wod, sizeof wod);
                snprintf(res[CK_FURNACE_MC].where, sizeof res[CK_FURNACE_MC].where,
                         "%s: channel %d: the mean of f |cos| / pdf over %ld samples %.6f +- %.2g, the cubature of f "
                         "|cos| %.6f and its delta lobes %.6f",
                         wod, k, n, m, se_mc, fq - gap, dfwd[k]);
            }
        }
        /* the energy */
        rho = tot[1 + k] + den[k];
        slack = x->allow * fmax(1, fabs(v)) + QUAD_SLACK + ferr;
        if (x->c->expect == CF_EXPECT_LE) excess = rho - (v + slack);
        if (x->c->expect == CF_EXPECT_EQ) excess = fabs(rho - v) - slack;
        a->rho_lo = fmin(a->rho_lo, rho);
        a->rho_hi = fmax(a->rho_hi, rho);
        if (excess > a->worst_excess || a->rho_wo < 0) {
            char wod[200];
            a->worst_excess = fmax(a->worst_excess, excess);
            a->rho_wo = d->index;
            snprintf(a->rho_what, sizeof a->rho_what, "rho %.6f at cos %.4g", rho, d->wo.z);
            cf_describe_wo(d->wo, wod, sizeof wod);
            snprintf(res[CK_FURNACE].where, sizeof res[CK_FURNACE].where, "%s: channel %d: the energy %.6f (cubature "
                     "%.6f, delta lobes %.6f)", wod, k, rho, rho - den[k], den[k]);
        }
        cf_measure_add(&res[CK_FURNACE], rho, 0, slack, d->wo.z, "the albedo at cos %.3g");
    }
    measure_fraction(&res[CK_IDENTITY], d->invalid, n, d->wo.z, "the fraction of invalid samples at cos %.3g");
    measure_fraction(&res[CK_IDENTITY], d->unlike, d->nid, d->wo.z, "the fraction of samples unlike eval at cos %.3g");
out:
    cf_regions_free(&rg);
    free(pdfc);
    free(pdfm);
    return r;
}

static void free_wo(cf_wo_data *d)
{
    free(d->counts);
    free(d->pilot);
    free(d->probe);
    free(d->probe_ref);
    memset(d, 0, sizeof *d);
}

static void finish(cf_ctx *x, acc *a)
{
    cf_result *res = x->out->res;
    const cf_run *run = x->run;
    char b[64];
    int w, k;
    long invalid = 0, unlike = 0, nid = 0, drawn = 0;
    double id_tol = fmax(x->test->eps < 1e-10 ? IDENTITY_REL_DOUBLE : IDENTITY_REL_FLOAT, x->allow_own);
    for (w = 0; w < x->nwo; ++w) {
        invalid += x->w[w].invalid;
        unlike += x->w[w].unlike;
        nid += x->w[w].nid;
        drawn += x->w[w].n;
    }
    snprintf(b, sizeof b, "rel <= %.2g", id_tol);
    cf_set(&res[CK_IDENTITY], invalid + unlike == 0, b, "%ld invalid of %ld samples, %ld of %ld unlike eval",
           invalid, drawn, unlike, nid);
    if (x->density) {
        snprintf(b, sizeof b, "p >= %.2g", run->cfg.alpha_test);
        for (k = 0; k < 2; ++k) {
            cf_result *r = &res[k ? CK_CHI2_MATERIA : CK_CHI2];
            if (k && !(x->ref && (x->stages & ST_REFCELLS))) continue;
            if (a->chi[k].hard)
                cf_set(r, 0, b, "hard failure: samples where %s pdf is 0", k ? "materia's" : "its own");
            else
                cf_set(r, a->chi[k].min_p >= run->cfg.alpha_test, b, "min p %.3g (%ld dof)", a->chi[k].min_p,
                       a->chi[k].dof);
            r->wo = a->chi[k].wo;
            snprintf(r->where, sizeof r->where, "%s", a->chi[k].where);
        }
        if (a->mean_wo >= 0) {
            cf_set(&res[CK_MEAN], a->mean_p >= run->cfg.alpha_test, b, "min p %.3g (%d dof; %s)", a->mean_p, a->mean_dof,
                   a->mean_what);
            res[CK_MEAN].wo = a->mean_wo;
        } else {
            cf_set(&res[CK_MEAN], 1, "p >= alpha", "not applicable: no sample in a cell (chi2 and pdf integral judge it)");
        }
        cf_set(&res[CK_INTEGRAL], a->worst_int <= 1, "dev/tol <= 1", "dev/tol %.2f (%s)", a->worst_int, a->int_what);
        res[CK_INTEGRAL].wo = a->int_wo;
    }
    if (a->gap_bad)
        cf_set(&res[CK_FURNACE_MC], 0, "pdf covers f", "%s", a->gap_what);
    else if (a->worst_gap > 0 && (x->c->flags & CF_CASE_SHADING_GAP))
        cf_set(&res[CK_FURNACE_MC], a->worst_mc <= 1, "dev/tol <= 1", "dev/tol %.2f (%s; unreachable %.3g)", a->worst_mc,
               a->mc_what, a->worst_gap);
    else
        cf_set(&res[CK_FURNACE_MC], a->worst_mc <= 1, "dev/tol <= 1", "dev/tol %.2f (%s)", a->worst_mc, a->mc_what);
    if (res[CK_FURNACE_MC].wo < 0) res[CK_FURNACE_MC].wo = a->mc_wo;
    {
        char bound[64] = "report";
        const char *how = x->test->conv.transport == CF_RADIANCE && (a->other || x->eta > 0) ? ", radiance: light from wo"
                                                                                             : "";
        if (x->c->expect == CF_EXPECT_EQ) snprintf(bound, sizeof bound, "rho = %g", x->c->expect_rho);
        if (x->c->expect == CF_EXPECT_LE) snprintf(bound, sizeof bound, "rho <= %g", x->c->expect_rho);
        cf_set(&res[CK_FURNACE], a->worst_excess <= 0, bound, "rho %.6f..%.6f (%s%s)", a->rho_lo, a->rho_hi, a->rho_what,
               how);
        res[CK_FURNACE].wo = a->rho_wo;
    }
}

static unsigned stages_of(const cf_run *run, const cf_impl *ref)
{
    unsigned s = 0;
    int k;
    for (k = 0; k < CK_NCHECK; ++k) {
        if (run->only_check >= 0 && k != run->only_check) continue;
        if (cf_checks[k].kind == CF_AGREEMENT && !ref) continue;
        s |= cf_checks[k].stages;
    }
    return s;
}

int cf_run_case(const cf_run *run, const cf_case *c, cf_impl *test, cf_impl *ref, const cf_outcome *fixed,
                cf_outcome *out)
{
    cf_ctx x;
    acc a;
    cf_v3 wo[CF_MAX_WO];
    int nwo, w, k, r = 0;
    memset(&x, 0, sizeof x);
    memset(&a, 0, sizeof a);
    for (k = 0; k < CK_NCHECK; ++k) {
        memset(&out->res[k], 0, sizeof out->res[k]);
        out->res[k].ok = -1;
        out->res[k].wo = -1;
    }
    a.chi[0].min_p = a.chi[1].min_p = 2;
    a.chi[0].wo = a.chi[1].wo = -1;
    a.rho_lo = 1e300;
    a.rho_hi = -1e300;
    a.int_wo = a.mc_wo = a.rho_wo = a.mean_wo = -1;
    a.mean_p = 2;
    x.run = run;
    x.c = c;
    x.test = test;
    x.ref = ref;
    x.out = out;
    x.fixed = fixed;
    x.stages = stages_of(run, ref);
    normals(c, &x.ns, &x.ng);
    /* a cubature's nodes are directions rounded to float, unit only to a
     * float epsilon: its integrals carry a float epsilon of rounding
     * whatever the precision of the values; one value set against another
     * at the same inputs (identity, reciprocity) carries the
     * implementation's own */
    x.allow = allowance(c, fmax(test->eps, FLT_EPSILON));
    x.allow_own = allowance(c, test->eps);
    x.z = cf_normal_two_sided_z(run->cfg.alpha_test);
    nwo = cf_case_wo(c, run->quick, wo);
    out->nwo = nwo;
    memcpy(out->wo, wo, sizeof wo);
    if (!(x.w = calloc((size_t)nwo, sizeof *x.w))) return CF_NOMEM;
    for (w = 0; w < nwo; ++w) {
        x.w[w].wo = wo[w];
        x.w[w].index = w;
    }
    x.nwo = nwo;
    /* the pilots and cells of every direction (the one asked alone, with
     * --wo), then their samples: as many as the run's, the configuration
     * that fixed the cells', or (--power) as many as its pilots say */
    for (w = 0; w < nwo && !r; ++w) {
        if (run->only_wo >= 0 && w != run->only_wo) continue;
        r = wo_pilot(&x, &x.w[w], w);
    }
    {
        long np = !r && run->power > 0 ? power_samples(&x) : run->cfg.samples;
        for (w = 0; w < nwo; ++w)
            if (run->only_wo < 0 || w == run->only_wo) x.w[w].n = fixed && fixed->pw_n[w] && run->power > 0 ? fixed->pw_n[w] : np;
    }
    for (w = 0; w < nwo && !r; ++w) {
        if (run->only_wo >= 0 && w != run->only_wo) continue;
        r = wo_main(&x, &x.w[w], w);
        if (x.w[w].ndirs || x.w[w].npilot) x.density = 1;
    }
    /* specular transmission there and back (the index its answers give),
     * pairs (which also tell a density the samples did not show), delta
     * lobes, extremes */
    if (!r) r = cf_helmholtz(&x);
    if (!r) r = cf_pairs(&x);
    if (!r && (x.stages & ST_PROBES) && ref) r = cf_delta_agree(&x);
    if (!r && (x.stages & ST_EXTREMES)) r = cf_extremes_check(&x);
    /* the cells of every direction */
    for (w = 0; w < nwo && !r; ++w) {
        if (run->only_wo >= 0 && w != run->only_wo) continue;
        if (x.stages & (ST_CELLS | ST_PROBES)) r = wo_cells(&x, &a, &x.w[w], w);
    }
    if (!r) {
        if (x.stages & (ST_CELLS | ST_PROBES | ST_IDENTITY)) finish(&x, &a);
        if (!(x.stages & (ST_CELLS | ST_PROBES))) {
            for (k = CK_CHI2; k <= CK_FURNACE; ++k) out->res[k].ok = -1;
        }
        if (!(x.stages & ST_IDENTITY)) out->res[CK_IDENTITY].ok = -1;
        if (!(x.stages & ST_CELLS))
            out->res[CK_CHI2].ok = out->res[CK_MEAN].ok = out->res[CK_INTEGRAL].ok = out->res[CK_CHI2_MATERIA].ok = -1;
    }
    out->eta = x.eta;
    for (w = 0; w < nwo; ++w) free_wo(&x.w[w]);
    free(x.w);
    /* a check run alone: the others not reported */
    if (run->only_check >= 0)
        for (k = 0; k < CK_NCHECK; ++k)
            if (k != run->only_check) out->res[k].ok = -1;
    if (!ref)
        for (k = 0; k < CK_NCHECK; ++k)
            if (cf_checks[k].kind == CF_AGREEMENT) out->res[k].ok = -1;
    return r;
}
