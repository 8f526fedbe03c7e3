/*
 * impl-wrong BUG: a deliberately wrong implementation of the query protocol,
 * for proving that materia-conformance --impl catches each kind of error
 * (tests/test_impl.c). It answers as materia-query does (the same mt_query
 * session) and then spoils the answers one way:
 *
 *   pdf-high      eval and sample report the pdf 5% high
 *   energy-gain   f 8% high everywhere (eval and sample agree)
 *   nonreciprocal f scaled by 1 + 0.3 (cos wo - cos wi): f(wo, wi) != f(wi, wo)
 *   other-dir     a sample's f and pdf are those of another sampled direction
 *   nan-grazing   f is NaN when wo or wi is within 1e-3 of the horizon
 *   colour        red 3% low everywhere (the physics intact)
 *   skewed        samples a distorted distribution (u2 squared), reporting
 *                 eval's f and pdf where they land: only the distribution is wrong
 *   glossy-below  pbrt-v2's erratum glossy-sample-pdf made worse: a glossy
 *                 sample with u2 < 0.25 is sent below the horizon with f 0
 *                 and its pdf kept, which pbrt-v2 does only for the few
 *                 whose half vector reflects wo below it: the same failure,
 *                 more often (eval is materia's)
 *   exit          exits with status 3 at query 500
 *   crash         aborts at query 500
 *   hang          stops answering at query 500 (and never exits by itself)
 *   garbage       answers "#?%" to query 500
 *   few           eval answers three values from query 500 on
 *   extra         prints one line too many after the answer to query 500
 *   none          no bug (materia-query's answers)
 */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "support/answer_out.h"
#include "materia.h"
#include "materia/tools/query.h"

static double scale_f(const char *bug, const double *wo, const double *wi)
{
    if (!strcmp(bug, "energy-gain")) return 1.08;
    if (!strcmp(bug, "nonreciprocal")) return 1 + 0.3 * (wo[2] - wi[2]);
    return 1;
}

/* materia's sample from wo = v[0..2] with uc = v[3] and (u1, u2): 1 and
 * its eight values in b when it succeeded. */
static int resample(mt_query *q, const double *v, double u1, double u2, double *b)
{
    char line[256], ans[4096];
    snprintf(line, sizeof line, "sample %.9g %.9g %.9g %.9g %.9g %.9g", v[0], v[1], v[2], v[3], u1, u2);
    return mt_query_line(q, line, ans, sizeof ans) &&
           sscanf(ans, "%lf %lf %lf %lf %lf %lf %lf %lf", &b[0], &b[1], &b[2], &b[3], &b[4], &b[5], &b[6], &b[7]) ==
               8 &&
           b[6] > 0;
}

int main(int argc, char **argv)
{
    const char *bug = argc > 1 ? argv[1] : "none";
    char line[65536], ans[4096], fixed[4096];
    mt_error err;
    mt_query *q;
    long n = 0;
    mt_error_clear(&err);
    if (!(q = mt_query_create(NULL, &err))) return 1;
    while (fgets(line, sizeof line, stdin)) {
        double v[8], a[8];
        size_t len = strlen(line);
        while (len && (line[len - 1] == '\n' || line[len - 1] == '\r')) line[--len] = 0;
        if (!mt_query_line(q, line, ans, sizeof ans)) continue;
        n++;
        if (n == 500) {
            if (!strcmp(bug, "exit")) { mt_query_destroy(q); return 3; }
            if (!strcmp(bug, "crash")) abort();
            if (!strcmp(bug, "hang")) {
                fflush(stdout);
                for (;;) pause();
            }
            if (!strcmp(bug, "garbage")) {
                t_answer_out("#?%");
                continue;
            }
        }
        if (sscanf(line, "eval %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]) == 6 &&
            sscanf(ans, "%lf %lf %lf %lf", &a[0], &a[1], &a[2], &a[3]) == 4) {
            double s = scale_f(bug, v, v + 3);
            if (!strcmp(bug, "pdf-high")) a[3] *= 1.05;
            if (!strcmp(bug, "colour")) a[0] *= 0.97;
            if (!strcmp(bug, "nan-grazing") && (fabs(v[2]) < 1e-3 || fabs(v[5]) < 1e-3)) a[0] = NAN;
            if (!strcmp(bug, "few") && n >= 500)
                snprintf(fixed, sizeof fixed, "%.9g %.9g %.9g", a[0] * s, a[1] * s, a[2] * s);
            else
                snprintf(fixed, sizeof fixed, "%.9g %.9g %.9g %.9g", a[0] * s, a[1] * s, a[2] * s, a[3]);
            t_answer_out(fixed);
        } else if (sscanf(line, "sample %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]) == 6 &&
                   sscanf(ans, "%lf %lf %lf %lf %lf %lf %lf %lf", &a[0], &a[1], &a[2], &a[3], &a[4], &a[5], &a[6],
                          &a[7]) == 8) {
            double s = scale_f(bug, v, a);
            double b[8];
            if (!strcmp(bug, "other-dir") && !((unsigned)a[7] & 16) && resample(q, v, v[5], v[4], b)) {
                /* f and pdf of the sample that swapped u1 and u2 */
                a[3] = b[3];
                a[4] = b[4];
                a[5] = b[5];
                a[6] = b[6];
            }
            if (!strcmp(bug, "skewed") && !((unsigned)a[7] & 16)) {
                char l2[256], a2[4096];
                if (resample(q, v, v[4], v[5] * v[5], b)) {
                    snprintf(l2, sizeof l2, "eval %.9g %.9g %.9g %.9g %.9g %.9g", v[0], v[1], v[2], b[0], b[1], b[2]);
                    if (mt_query_line(q, l2, a2, sizeof a2) && sscanf(a2, "%lf %lf %lf %lf", &a[3], &a[4], &a[5], &a[6]) == 4) {
                        a[0] = b[0];
                        a[1] = b[1];
                        a[2] = b[2];
                    }
                }
            }
            if (!strcmp(bug, "glossy-below") && ((unsigned)a[7] & 24) == 8 && v[5] < 0.25) {
                a[2] = -a[2];
                a[3] = a[4] = a[5] = 0;
            }
            if (!strcmp(bug, "pdf-high")) a[6] *= 1.05;
            if (!strcmp(bug, "colour")) a[3] *= 0.97;
            if (!strcmp(bug, "nan-grazing") && fabs(v[2]) < 1e-3) a[3] = NAN;
            snprintf(fixed, sizeof fixed, "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %u", a[0], a[1], a[2], a[3] * s, a[4] * s,
                     a[5] * s, a[6], (unsigned)a[7]);
            t_answer_out(fixed);
        } else {
            t_answer_out(ans);
        }
        if (n == 500 && !strcmp(bug, "extra")) t_answer_out("0 0 0 0");
    }
    mt_query_destroy(q);
    return 0;
}
