/*
 * materia's own plugin with one smooth error of relative size EPS planted
 * (--impl-arg "KIND EPS"), the three classes the suite's power is measured
 * on (docs/TRADEOFF.md, "Power"):
 *
 *   none   materia itself (the false-rejection rate)
 *   warp   the sampler draws u1 + EPS u1 (1 - u1) in place of u1; f and pdf
 *          are honest for the direction returned
 *   pdf    eval's and sample's pdf times 1 + EPS (|cos theta_i| - m), m the
 *          mean of |cos theta_i| under the pdf at that wo (so it still
 *          integrates to 1); the samples untouched
 *   f      f times 1 + EPS |cos theta_i|, in eval and sample alike
 *
 * None of them breaks the identity of a sample with eval: only the
 * statistics and the physics can see them.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia/real.h"
#include "materia/rng.h"
#include "../plugins/materia_plugin.h"

enum { NONE, WARP, PDF, FSHAPE };

typedef struct planted {
    int kind;
    double eps;
} planted;

/* the means of |cos theta_i| at the directions seen (the suite's are few) */
#define MAX_MEANS 4096
typedef struct pconfig {
    const planted *p;
    void *inner;
    int nmean;
    mt_impl_v3 wo[MAX_MEANS];
    double mean[MAX_MEANS];
} pconfig;

static const mt_impl_plugin *inner(void) { return mt_materia_plugin(); }

static void *p_create(const char *arg, char *msg, size_t n)
{
    planted *p = calloc(1, sizeof *p);
    char kind[16] = "";
    if (!p) return NULL;
    if (!arg || sscanf(arg, "%15s %lf", kind, &p->eps) != 2 || !(p->eps >= 0 && p->eps < 0.5) ||
        ((p->kind = !strcmp(kind, "none") ? NONE : !strcmp(kind, "warp") ? WARP : !strcmp(kind, "pdf") ? PDF
                                                                              : !strcmp(kind, "f") ? FSHAPE : -1) < 0)) {
        snprintf(msg, n, "--impl-arg \"%s\": wants \"none|warp|pdf|f EPS\", EPS in [0, 0.5)", arg ? arg : "");
        free(p);
        return NULL;
    }
    return p;
}

static void p_destroy(void *state) { free(state); }

static int p_open(void *state, const char *mode, const char *const *lines, int nlines, void **config, char *msg,
                  size_t n)
{
    pconfig *c = calloc(1, sizeof *c);
    int r;
    *config = NULL;
    if (!c) return MT_IMPL_ERROR;
    c->p = state;
    if ((r = inner()->open(NULL, mode, lines, nlines, &c->inner, msg, n)) != MT_IMPL_OK) {
        free(c);
        return r;
    }
    *config = c;
    return MT_IMPL_OK;
}

static void p_close(void *config)
{
    pconfig *c = config;
    inner()->close(c->inner);
    free(c);
}

/* The mean of |cos theta_i| under materia's pdf at wo (its non-delta
 * samples). The first PRECISE directions the suite asks about are its
 * own incoming directions (the samples' identity comes before the pairs),
 * whose pdf the suite integrates: 2^20 samples there, so that the planted
 * pdf stays normalized far below the pdf integral's tolerance (eps times
 * the mean's error, 2e-4, is 2e-6 at eps 0.01). Others (the pairs' random
 * directions, whose pdf no integral reads): 4096 samples, cached while
 * there is room. */
#define PRECISE 16
static double mean_cos(pconfig *c, mt_impl_v3 wo)
{
    enum { N = 4096 };
    mt_impl_v3 *wos;
    mt_impl_sample *s;
    float(*uu)[3];
    mt_rng rng;
    double sum = 0;
    long cnt = 0;
    int i, j, k, rounds = c->nmean < PRECISE ? 256 : 1;
    for (i = 0; i < c->nmean; ++i)
        if (c->wo[i].x == wo.x && c->wo[i].y == wo.y && c->wo[i].z == wo.z) return c->mean[i];
    wos = malloc(N * sizeof *wos);
    s = malloc(N * sizeof *s);
    uu = malloc(N * sizeof *uu);
    if (!wos || !s || !uu) {
        free(wos);
        free(s);
        free(uu);
        return 0;
    }
    mt_rng_seed(&rng, 12345, 7);
    for (i = 0; i < N; ++i) wos[i] = wo;
    for (j = 0; j < rounds; ++j) {
        for (i = 0; i < N; ++i)
            for (k = 0; k < 3; ++k) {
                float x = (float)mt_rng_uniform(&rng);
                uu[i][k] = x < 1 ? x : 0x1.fffffep-1f;
            }
        inner()->sample(c->inner, N, wos, (const float(*)[3])uu, s, NULL, 0);
        for (i = 0; i < N; ++i)
            if (s[i].pdf > 0 && !(s[i].flags & MT_IMPL_SPECULAR)) {
                sum += fabs(s[i].wi[2]);
                cnt++;
            }
    }
    free(wos);
    free(s);
    free(uu);
    if (c->nmean < MAX_MEANS) {
        c->wo[c->nmean] = wo;
        c->mean[c->nmean++] = cnt ? sum / cnt : 0;
    }
    return cnt ? sum / cnt : 0;
}

static int p_eval(void *config, int n, const mt_impl_v3 *wo, const mt_impl_v3 *wi, mt_impl_eval *out, char *msg,
                  size_t msz)
{
    pconfig *c = config;
    int i, k, r = inner()->eval(c->inner, n, wo, wi, out, msg, msz);
    if (r != MT_IMPL_OK || c->p->kind == NONE || c->p->kind == WARP) return r;
    for (i = 0; i < n; ++i) {
        double ci = fabs(wi[i].z);
        if (c->p->kind == PDF)
            out[i].pdf *= 1 + c->p->eps * (ci - mean_cos(c, wo[i]));
        else
            for (k = 0; k < 3; ++k) out[i].f[k] *= 1 + c->p->eps * ci;
    }
    return MT_IMPL_OK;
}

static int p_sample(void *config, int n, const mt_impl_v3 *wo, const float (*u)[3], mt_impl_sample *out, char *msg,
                    size_t msz)
{
    pconfig *c = config;
    int i, k, r;
    if (c->p->kind == WARP) {
        float(*w)[3] = malloc((size_t)(n > 0 ? n : 1) * sizeof *w);
        if (!w) return MT_IMPL_ERROR;
        for (i = 0; i < n; ++i) {
            double u1 = u[i][1];
            w[i][0] = u[i][0];
            w[i][1] = (float)(u1 + c->p->eps * u1 * (1 - u1));
            if (!(w[i][1] < 1)) w[i][1] = 0x1.fffffep-1f;
            w[i][2] = u[i][2];
        }
        r = inner()->sample(c->inner, n, wo, (const float(*)[3])w, out, msg, msz);
        free(w);
        return r;
    }
    if ((r = inner()->sample(c->inner, n, wo, u, out, msg, msz)) != MT_IMPL_OK || c->p->kind == NONE) return r;
    for (i = 0; i < n; ++i) {
        double ci = fabs(out[i].wi[2]);
        if (!(out[i].pdf > 0) || (out[i].flags & MT_IMPL_SPECULAR)) continue;
        if (c->p->kind == PDF)
            out[i].pdf *= 1 + c->p->eps * (ci - mean_cos(c, wo[i]));
        else
            for (k = 0; k < 3; ++k) out[i].f[k] *= 1 + c->p->eps * ci;
    }
    return MT_IMPL_OK;
}

static mt_impl_plugin table;

MT_API const mt_impl_plugin *mt_impl_plugin_v1(void);
const mt_impl_plugin *mt_impl_plugin_v1(void)
{
    table = *inner();
    table.name = "materia-planted";
    table.create = p_create;
    table.destroy = p_destroy;
    table.open = p_open;
    table.eval = p_eval;
    table.sample = p_sample;
    table.close = p_close;
    return &table;
}
