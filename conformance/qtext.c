/*
 * Query lines and answers as the protocol writes them, for the batches a
 * child receives, the worst queries of a failed check and --repro files:
 * one format everywhere, so that a query quoted in a report is the line the
 * implementation received.
 */
#include <stdio.h>
#include <string.h>
#include "core.h"

int cf_format_num(char *out, size_t n, double v)
{
    /* the suite's own inputs are floats (9 digits read back exactly); a
     * direction a double implementation returned is passed on as it is */
    if ((double)(float)v == v) return cf_format_g9(out, n, (float)v);
    return snprintf(out, n, "%.17g", v);
}

static size_t put(char *q, size_t at, size_t n, double v)
{
    if (at + 1 < n) {
        q[at++] = ' ';
        at += (size_t)cf_format_num(q + at, n - at, v);
    }
    return at < n ? at : n - 1;
}

void cf_q_eval(char *q, size_t n, cf_v3 wo, cf_v3 wi)
{
    size_t at = (size_t)snprintf(q, n, "eval");
    at = put(q, at, n, wo.x);
    at = put(q, at, n, wo.y);
    at = put(q, at, n, wo.z);
    at = put(q, at, n, wi.x);
    at = put(q, at, n, wi.y);
    put(q, at, n, wi.z);
}

void cf_q_sample(char *q, size_t n, cf_v3 wo, const float *u)
{
    size_t at = (size_t)snprintf(q, n, "sample");
    at = put(q, at, n, wo.x);
    at = put(q, at, n, wo.y);
    at = put(q, at, n, wo.z);
    at = put(q, at, n, u[0]);
    at = put(q, at, n, u[1]);
    put(q, at, n, u[2]);
}

void cf_a_eval(char *a, size_t n, const cf_eval *e)
{
    snprintf(a, n, "%.9g %.9g %.9g %.9g", e->f[0], e->f[1], e->f[2], e->pdf);
}

void cf_a_sample(char *a, size_t n, const cf_samp *s)
{
    snprintf(a, n, "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %u", s->wi[0], s->wi[1], s->wi[2], s->f[0], s->f[1], s->f[2],
             s->pdf, s->flags);
}

void cf_worst_add(cf_worst *list, double score, const char *query, const char *expected, const char *got,
                  const char *query2)
{
    int i, j;
    for (i = 0; i < CF_WORST; ++i)
        if (!list[i].query[0] || score > list[i].score) break;
    if (i == CF_WORST) return;
    for (j = CF_WORST - 1; j > i; --j) list[j] = list[j - 1];
    list[i].score = score;
    snprintf(list[i].query, sizeof list[i].query, "%s", query);
    snprintf(list[i].expected, sizeof list[i].expected, "%s", expected);
    snprintf(list[i].got, sizeof list[i].got, "%s", got);
    snprintf(list[i].query2, sizeof list[i].query2, "%s", query2 ? query2 : "");
}
