/* The test vocabulary: one line per check, and a count for the exit status. */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "support/check.h"

static int failures;

void t_pass(const char *name) { printf("PASS %s\n", name); }

static void vline(const char *tag, const char *name, const char *fmt, va_list ap)
{
    printf("%s %s: ", tag, name);
    vprintf(fmt, ap);
    printf("\n");
}

void t_fail(const char *name, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vline("FAIL", name, fmt, ap);
    va_end(ap);
    failures++;
}

void t_xfail(const char *name, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vline("XFAIL", name, fmt, ap);
    va_end(ap);
}

void t_skip(const char *name, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vline("SKIP", name, fmt, ap);
    va_end(ap);
}

int t_check(int cond, const char *name, const char *fmt, ...)
{
    va_list ap;
    if (cond) {
        t_pass(name);
        return 1;
    }
    va_start(ap, fmt);
    vline("FAIL", name, fmt, ap);
    va_end(ap);
    failures++;
    return 0;
}

int t_near(double got, double want, double tol, const char *name)
{
    return t_check(fabs(got - want) <= tol, name, "got %.9g, want %.9g (tolerance %.3g)", got,
                   want, tol);
}

int t_rel(double got, double want, double rel, double floor, const char *name)
{
    double scale = fabs(want) > floor ? fabs(want) : floor;
    return t_check(fabs(got - want) <= rel * scale, name,
                   "got %.9g, want %.9g (relative tolerance %.3g)", got, want, rel);
}

int t_status(void) { return failures ? 1 : 0; }

double t_reldiff(double a, double b, double floor)
{
    double m = fabs(a) > fabs(b) ? fabs(a) : fabs(b);
    if (m < floor) m = floor;
    return fabs(a - b) / m;
}

double t_ulps(mt_real a, mt_real b)
{
#if MT_USE_DOUBLE
    int64_t ia, ib;
    memcpy(&ia, &a, 8);
    memcpy(&ib, &b, 8);
    if (ia < 0) ia = INT64_MIN - ia;
    if (ib < 0) ib = INT64_MIN - ib;
    return fabs((double)ia - (double)ib);
#else
    int32_t ia, ib;
    memcpy(&ia, &a, 4);
    memcpy(&ib, &b, 4);
    if (ia < 0) ia = INT32_MIN - ia;
    if (ib < 0) ib = INT32_MIN - ib;
    return fabs((double)ia - (double)ib);
#endif
}

const char *t_shared_dir(void)
{
    static const char *candidates[] = {"../shared", "../../shared", NULL};
    const char *env = getenv("MATERIA_SHARED");
    int i;
    if (env && *env) return access(env, R_OK) == 0 ? env : NULL;
    for (i = 0; candidates[i]; ++i)
        if (access(candidates[i], R_OK) == 0) return candidates[i];
    return NULL;
}

int t_has_format(const char *ext, const char *name)
{
    const char *list = mt_image_formats(), *p = list;
    size_t n = strlen(ext);
    for (; (p = strstr(p, ext)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == 0)) return 1;
    t_skip(name, "this build of materia has no .%s files (built with make NO_%s=1)", ext,
           !strcmp(ext, "exr") ? "EXR" : !strcmp(ext, "png") ? "PNG" : "?");
    return 0;
}
