/*
 * extremes: eval over every pair of the extremes grid's directions (cos
 * theta 1, 1 - 1e-7, 1e-2, 1e-4, 1e-7, 0 and their negatives, at three
 * azimuths: extremes.c) and sample from each with u in {0, 0.25, 0.5,
 * 0.999999, 1 - 2^-24}^3: every answer finite and non-negative, a sampled
 * wi of unit length. Where a renderer's formulas divide by cos theta or
 * take the root of 1 - cos^2, this is where they fail.
 */
#include <stdio.h>
#include <stdlib.h>
#include "pass.h"

/* |wi| - 1 of a sample at a degenerate direction: a direction built from a
 * grazing or normal wo may lose a few digits more than an ordinary one */
#define EXTREME_UNIT_TOL 1e-4

static int finite_nonneg(double x) { return isfinite(x) && x >= 0; }

int cf_extremes_check(cf_ctx *x)
{
    static const float us[5] = {0, 0.25f, 0.5f, 0.999999f, 0.99999994f};
    cf_impl *t = x->test;
    cf_result *res = &x->out->res[CK_EXTREMES];
    mt_vec3 md[64];
    cf_v3 d[64], *a, *b;
    int nd = cf_extreme_directions(md, 64), i, j, k, n = 0, ns = 0, r = 0;
    long bad = 0;
    cf_eval *e;
    cf_samp *s;
    float (*u)[3];
    char q[200], got[240];
    for (i = 0; i < nd; ++i) d[i] = cf_v3_float(cf_v3_make(md[i].x, md[i].y, md[i].z));
    a = malloc((size_t)nd * (nd > 125 ? nd : 125) * sizeof *a);
    b = malloc((size_t)nd * nd * sizeof *b);
    e = malloc((size_t)nd * nd * sizeof *e);
    s = malloc((size_t)nd * 125 * sizeof *s);
    u = malloc((size_t)nd * 125 * sizeof *u);
    if (!a || !b || !e || !s || !u) {
        r = CF_NOMEM;
        goto out;
    }
    for (i = 0; i < nd; ++i)
        for (j = 0; j < nd; ++j) {
            a[n] = d[i];
            b[n++] = d[j];
        }
    if ((r = t->ops->eval(t, n, a, b, e))) goto out;
    for (i = 0; i < n; ++i) {
        int ok = finite_nonneg(e[i].pdf);
        for (k = 0; k < 3; ++k) ok &= finite_nonneg(e[i].f[k]);
        if (!ok) {
            bad++;
            cf_q_eval(q, sizeof q, a[i], b[i]);
            cf_a_eval(got, sizeof got, e + i);
            cf_worst_add(res->worst, 1, q, "finite, >= 0", got, NULL);
        }
    }
    for (i = 0; i < nd; ++i)
        for (j = 0; j < 125; ++j) {
            a[ns] = d[i];
            u[ns][0] = us[j / 25];
            u[ns][1] = us[(j / 5) % 5];
            u[ns++][2] = us[j % 5];
        }
    if ((r = t->ops->sample(t, ns, a, (const float(*)[3])u, s))) goto out;
    for (i = 0; i < ns; ++i) {
        double len = sqrt(s[i].wi[0] * s[i].wi[0] + s[i].wi[1] * s[i].wi[1] + s[i].wi[2] * s[i].wi[2]);
        int ok = finite_nonneg(s[i].pdf);
        for (k = 0; k < 3; ++k) ok &= finite_nonneg(s[i].f[k]) && isfinite(s[i].wi[k]);
        if (!ok || (s[i].pdf > 0 && !(fabs(len - 1) <= EXTREME_UNIT_TOL))) {
            bad++;
            cf_q_sample(q, sizeof q, a[i], u[i]);
            cf_a_sample(got, sizeof got, s + i);
            cf_worst_add(res->worst, 1, q, "finite, >= 0, |wi| = 1", got, NULL);
        }
    }
    cf_set(res, bad == 0, "0 violations", "%ld violations in %d evals and %d samples", bad, n, ns);
out:
    free(a);
    free(b);
    free(e);
    free(s);
    free(u);
    return r;
}
