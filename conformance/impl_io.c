/*
 * The two implementations --impl compares: a child process reached through
 * the query protocol's text, and materia in-process (the same mt_query
 * session that materia-query runs, whose BSDF is called directly so that
 * the reference costs no text). Every answer of the child is parsed
 * strictly: the number of values, numbers only, flags an integer; an answer
 * that is not what the query asks for names the query.
 */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "impl.h"

static int fail(cf_impl *im, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static int fail(cf_impl *im, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(im->msg, sizeof im->msg, fmt, ap);
    va_end(ap);
    im->failed = 1;
    return -1;
}

/* Appends to the batch; out of memory fails the implementation (its
 * queries would otherwise go missing from the batch unnoticed). */
static void put(cf_impl *im, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void put(cf_impl *im, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    cf_strbuf_vprintf(&im->text, fmt, ap); /* a failure stays in text.failed: send() reports it */
    va_end(ap);
}

/* Appends "WORD v0 ... v5\n", each value as %.9g of a float (cf_format_g9:
 * the same text as printf's, without its cost). */
static void put_query(cf_impl *im, const char *word, const float v[6])
{
    char line[256];
    size_t len = strlen(word);
    int i;
    memcpy(line, word, len);
    for (i = 0; i < 6; ++i) {
        line[len++] = ' ';
        len += (size_t)cf_format_g9(line + len, sizeof line - len, v[i]);
    }
    line[len++] = '\n';
    cf_strbuf_append(&im->text, line, len); /* a failure stays in text.failed: send() reports it */
}

/* Sends the batch in im->text (n query lines, then the mode line). */
static int send(cf_impl *im, int n)
{
    put(im, "%s\n", im->mode_line);
    if (im->text.failed) return fail(im, "out of memory for a batch of %d queries", n);
    if (im->ans_cap < n + 1) {
        const char **a = realloc(im->ans, (size_t)(n + 1) * sizeof *a);
        if (!a) return fail(im, "out of memory");
        im->ans = a;
        im->ans_cap = n + 1;
    }
    if (cf_child_batch(&im->child, im->text.s, im->text.n, n + 1, im->ans)) return fail(im, "%s", im->child.msg);
    im->queries += n;
    if (strcmp(im->ans[n], "ok"))
        return fail(im, "answers out of step: \"%.100s\" to \"%s\" at the end of a batch of %d queries (an extra or a "
                        "missing answer before it)", im->ans[n], im->mode_line, n);
    return 0;
}

static void shorten(const char *s, char *out, size_t n)
{
    snprintf(out, n, "%s", s);
    if (strlen(s) >= n && n > 4) strcpy(out + n - 4, "...");
}

/* Exactly n numbers (strtod's syntax: "nan" and "inf" are numbers, judged by
 * the checks). 0, or -1 and why. */
static int numbers(const char *s, double *v, int n, char *why, size_t wn)
{
    int i;
    if (!strncmp(s, "error", 5)) {
        snprintf(why, wn, "an error answer");
        return -1;
    }
    for (i = 0;; ++i) {
        char *end;
        double x;
        while (isspace((unsigned char)*s)) s++;
        if (!*s) break;
        x = strtod(s, &end);
        if (end == s || (*end && !isspace((unsigned char)*end))) {
            snprintf(why, wn, "garbage (value %d is not a number)", i + 1);
            return -1;
        }
        if (i < n) v[i] = x;
        s = end;
    }
    if (i < n) {
        snprintf(why, wn, "too few values (%d of %d)", i, n);
        return -1;
    }
    if (i > n) {
        snprintf(why, wn, "too many values (%d for %d)", i, n);
        return -1;
    }
    return 0;
}

static int bad_answer(cf_impl *im, const char *query, const char *answer, const char *why)
{
    char a[200];
    shorten(answer, a, sizeof a);
    return fail(im, "answered %s: \"%s\" to \"%s\"", why, a, query);
}

int cf_impl_open(cf_impl *im, const char *command, double timeout, mt_mode mode, const char *const *lines,
                 int nlines)
{
    int i;
    mt_error err;
    memset(im, 0, sizeof *im);
    im->mode_line = mode == MT_MODE_PBRT_V2 ? "mode pbrt-v2" : "mode corrected";
    if (!command) {
        char out[1024];
        im->inproc = 1;
        mt_error_clear(&err);
        if (!(im->q = mt_query_create(NULL, &err)) || !(im->arena = mt_arena_create(0)))
            return fail(im, "materia: %s", err.message);
        mt_query_line(im->q, im->mode_line, out, sizeof out);
        for (i = 0; i < nlines; ++i)
            if (mt_query_line(im->q, lines[i], out, sizeof out) && strcmp(out, "ok"))
                return fail(im, "materia answered \"%.300s\" to \"%.300s\"", out, lines[i]);
        if (!(im->bsdf = mt_query_bsdf(im->q, im->arena, &err))) return fail(im, "materia: %s", err.message);
        return 0;
    }
    if (cf_child_start(&im->child, command, timeout)) return fail(im, "%s", im->child.msg);
    put(im, "%s\n", im->mode_line);
    for (i = 0; i < nlines; ++i) put(im, "%s\n", lines[i]);
    if (send(im, nlines + 1)) return -1;
    for (i = 0; i <= nlines; ++i)
        if (strcmp(im->ans[i], "ok")) {
            char q[300];
            shorten(i ? lines[i - 1] : im->mode_line, q, sizeof q);
            return bad_answer(im, q, im->ans[i], "not \"ok\"");
        }
    cf_strbuf_clear(&im->text);
    return 0;
}

int cf_impl_eval(cf_impl *im, int n, const mt_vec3 *wo, const mt_vec3 *wi, cf_eval *out)
{
    int i, k;
    if (im->failed) return -1;
    if (im->inproc) {
        for (i = 0; i < n; ++i) {
            mt_rgb f = mt_bsdf_f(im->bsdf, wo[i], wi[i], MT_BSDF_ALL);
            for (k = 0; k < 3; ++k) out[i].f[k] = f.c[k];
            out[i].pdf = mt_bsdf_pdf(im->bsdf, wo[i], wi[i], MT_BSDF_ALL);
        }
        return 0;
    }
    cf_strbuf_clear(&im->text);
    for (i = 0; i < n; ++i) {
        const float v[6] = {(float)wo[i].x, (float)wo[i].y, (float)wo[i].z, (float)wi[i].x, (float)wi[i].y, (float)wi[i].z};
        put_query(im, "eval", v);
    }
    if (send(im, n)) return -1;
    for (i = 0; i < n; ++i) {
        double v[4];
        char why[64];
        if (numbers(im->ans[i], v, 4, why, sizeof why)) {
            char q[160];
            snprintf(q, sizeof q, "eval %.9g %.9g %.9g %.9g %.9g %.9g", (double)(float)wo[i].x, (double)(float)wo[i].y,
                     (double)(float)wo[i].z, (double)(float)wi[i].x, (double)(float)wi[i].y, (double)(float)wi[i].z);
            return bad_answer(im, q, im->ans[i], why);
        }
        for (k = 0; k < 3; ++k) out[i].f[k] = v[k];
        out[i].pdf = v[3];
    }
    return 0;
}

int cf_impl_sample(cf_impl *im, int n, const mt_vec3 *wo, const float (*u)[3], cf_samp *out)
{
    int i, k;
    if (im->failed) return -1;
    if (im->inproc) {
        for (i = 0; i < n; ++i) {
            mt_bsdf_sample s = mt_bsdf_sample_f(im->bsdf, wo[i], u[i][0], u[i][1], u[i][2], MT_BSDF_ALL);
            out[i].wi[0] = s.wi.x;
            out[i].wi[1] = s.wi.y;
            out[i].wi[2] = s.wi.z;
            for (k = 0; k < 3; ++k) out[i].f[k] = s.f.c[k];
            out[i].pdf = s.pdf;
            out[i].flags = s.type;
        }
        return 0;
    }
    cf_strbuf_clear(&im->text);
    for (i = 0; i < n; ++i) {
        const float v[6] = {(float)wo[i].x, (float)wo[i].y, (float)wo[i].z, u[i][0], u[i][1], u[i][2]};
        put_query(im, "sample", v);
    }
    if (send(im, n)) return -1;
    for (i = 0; i < n; ++i) {
        double v[8];
        char why[64];
        if (numbers(im->ans[i], v, 8, why, sizeof why) ||
            (!(v[7] >= 0 && v[7] < 32 && v[7] == (double)(int)v[7]) &&
             snprintf(why, sizeof why, "flags %g not an integer of 0..31", v[7]))) {
            char q[160];
            snprintf(q, sizeof q, "sample %.9g %.9g %.9g %.9g %.9g %.9g", (double)(float)wo[i].x,
                     (double)(float)wo[i].y, (double)(float)wo[i].z, (double)u[i][0], (double)u[i][1],
                     (double)u[i][2]);
            return bad_answer(im, q, im->ans[i], why);
        }
        for (k = 0; k < 3; ++k) {
            out[i].wi[k] = v[k];
            out[i].f[k] = v[3 + k];
        }
        out[i].pdf = v[6];
        out[i].flags = (unsigned)v[7];
    }
    return 0;
}

int cf_impl_close(cf_impl *im)
{
    int r = 0;
    if (im->inproc) {
        mt_query_destroy(im->q);
        mt_arena_destroy(im->arena);
    } else if (!im->failed) {
        if (cf_child_finish(&im->child)) r = fail(im, "%s", im->child.msg);
    } else {
        cf_child_free(&im->child);
        r = -1;
    }
    cf_strbuf_free(&im->text);
    free(im->ans);
    im->ans = NULL;
    return r;
}
