/*
 * An implementation in a child process that speaks the query protocol
 * (docs/PROTOCOL.md), behind the core's batched operations. Each batch of
 * queries is written while the answers are read, so that the pipe stays
 * full, and ends with the mode line, whose "ok" shows that answers and
 * queries are still in step. Every answer is parsed strictly: the number
 * of values, numbers only, flags an integer; an answer that is not what the
 * query asks for names the query. An error answer that says "unsupported"
 * makes the configuration unsupported (CF_UNSUPPORTED), not a failure.
 */
#include <ctype.h>
#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core.h"

static int fail(cf_impl *im, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static int fail(cf_impl *im, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(im->msg, sizeof im->msg, fmt, ap);
    va_end(ap);
    return im->failed = status;
}

/* Appends "WORD v0 ... v5\n" (cf_format_num: the same text as printf's
 * %.9g for the suite's float inputs, without its cost). */
static void put_query(cf_impl *im, const char *word, const double v[6])
{
    char line[256];
    size_t len = strlen(word);
    int i;
    memcpy(line, word, len);
    for (i = 0; i < 6; ++i) {
        line[len++] = ' ';
        len += (size_t)cf_format_num(line + len, sizeof line - len, v[i]);
    }
    line[len++] = '\n';
    cf_strbuf_append(&im->text, line, len); /* a failure stays in text.failed: send() reports it */
}

/* Sends the batch in im->text (n lines), then the mode line. */
static int send(cf_impl *im, int n)
{
    cf_strbuf_printf(&im->text, "%s\n", im->mode_line);
    if (im->text.failed) return fail(im, CF_NOMEM, "out of memory for a batch of %d queries", n);
    if (im->ans_cap < n + 1) {
        const char **a = realloc(im->ans, (size_t)(n + 1) * sizeof *a);
        if (!a) return fail(im, CF_NOMEM, "out of memory");
        im->ans = a;
        im->ans_cap = n + 1;
    }
    if (cf_child_batch(&im->child, im->text.s, im->text.n, n + 1, im->ans))
        return fail(im, CF_FAILED, "%s", im->child.msg);
    im->queries += n;
    if (strcmp(im->ans[n], "ok"))
        return fail(im, CF_FAILED,
                    "answers out of step: \"%.100s\" to \"%s\" at the end of a batch of %d queries (an extra or a "
                    "missing answer before it)",
                    im->ans[n], im->mode_line, n);
    return 0;
}

static void shorten(const char *s, char *out, size_t n)
{
    snprintf(out, n, "%s", s);
    if (strlen(s) >= n && n > 4) strcpy(out + n - 4, "...");
}

/* An answer of a float implementation is a float: its 9 digits name one,
 * which strtod alone does not give back (0.299458086 is not the float
 * 0.29945808649...). Rounded through a volatile float (docs/CONTRIBUTING.md). */
static double as_float(double x)
{
    volatile float f = (float)x;
    return f;
}

/* Exactly n numbers (strtod's syntax: "nan" and "inf" are numbers, judged by
 * the checks), rounded to float when the implementation computes in float.
 * 0, or -1 and why. */
static int numbers(const cf_impl *im, const char *s, double *v, int n, char *why, size_t wn)
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
        if (i < n) v[i] = im->eps < 1e-10 || !isfinite(x) ? x : as_float(x);
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

/* An answer that is not the n numbers asked for: unsupported, or a failure
 * naming the query. */
static int bad_answer(cf_impl *im, const char *query, const char *answer, const char *why)
{
    char a[200];
    const char *u = cf_unsupported(answer);
    if (u) return fail(im, CF_UNSUPPORTED, "%.300s (to \"%.300s\")", u, query);
    shorten(answer, a, sizeof a);
    return fail(im, CF_FAILED, "answered %s: \"%s\" to \"%s\"", why, a, query);
}

static int c_open(cf_impl *im, const cf_case *c)
{
    int i;
    if (cf_child_start(&im->child, im->command, im->timeout)) return fail(im, CF_FAILED, "%s", im->child.msg);
    cf_strbuf_printf(&im->text, "%s\n", im->mode_line);
    for (i = 0; i < c->nlines; ++i) cf_strbuf_printf(&im->text, "%s\n", c->lines[i]);
    if (send(im, c->nlines + 1)) return im->failed;
    for (i = 0; i <= c->nlines; ++i)
        if (strcmp(im->ans[i], "ok")) {
            char q[300];
            shorten(i ? c->lines[i - 1] : im->mode_line, q, sizeof q);
            return bad_answer(im, q, im->ans[i], "not \"ok\"");
        }
    cf_strbuf_clear(&im->text);
    return 0;
}

static int c_eval(cf_impl *im, int n, const cf_v3 *wo, const cf_v3 *wi, cf_eval *out)
{
    int i, k;
    if (im->failed) return im->failed;
    cf_strbuf_clear(&im->text);
    for (i = 0; i < n; ++i) {
        const double v[6] = {wo[i].x, wo[i].y, wo[i].z, wi[i].x, wi[i].y, wi[i].z};
        put_query(im, "eval", v);
    }
    if (send(im, n)) return im->failed;
    for (i = 0; i < n; ++i) {
        double v[4];
        char why[64];
        if (numbers(im, im->ans[i], v, 4, why, sizeof why)) {
            char q[200];
            cf_q_eval(q, sizeof q, wo[i], wi[i]);
            return bad_answer(im, q, im->ans[i], why);
        }
        for (k = 0; k < 3; ++k) out[i].f[k] = v[k];
        out[i].pdf = v[3];
    }
    return 0;
}

static int c_sample(cf_impl *im, int n, const cf_v3 *wo, const float (*u)[3], cf_samp *out)
{
    int i, k;
    if (im->failed) return im->failed;
    cf_strbuf_clear(&im->text);
    for (i = 0; i < n; ++i) {
        const double v[6] = {wo[i].x, wo[i].y, wo[i].z, u[i][0], u[i][1], u[i][2]};
        put_query(im, "sample", v);
    }
    if (send(im, n)) return im->failed;
    for (i = 0; i < n; ++i) {
        double v[8];
        char why[64];
        if (numbers(im, im->ans[i], v, 8, why, sizeof why) ||
            (!(v[7] >= 0 && v[7] < 32 && v[7] == (double)(int)v[7]) &&
             snprintf(why, sizeof why, "flags %g not an integer of 0..31", v[7]))) {
            char q[200];
            cf_q_sample(q, sizeof q, wo[i], u[i]);
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

static int c_close(cf_impl *im)
{
    int r = 0;
    if (!im->failed) {
        if (cf_child_finish(&im->child)) r = fail(im, CF_FAILED, "%s", im->child.msg);
    } else {
        cf_child_free(&im->child);
    }
    cf_strbuf_free(&im->text);
    free(im->ans);
    im->ans = NULL;
    return r;
}

static const cf_impl_ops child_ops = {"protocol", c_open, c_eval, c_sample, c_close};

void cf_impl_child(cf_impl *im, mt_mode mode, const char *command, double timeout)
{
    memset(im, 0, sizeof *im);
    im->ops = &child_ops;
    im->mode = mode;
    im->command = command;
    im->timeout = timeout;
    im->mode_line = mode == MT_MODE_PBRT_V2 ? "mode pbrt-v2" : "mode corrected";
    im->conv = cf_conventions_default();
    im->eps = FLT_EPSILON;
}

int cf_impl_probe(const char *command, double timeout, cf_conventions *conv, int *declared, double *eps,
                  char *name, size_t nn, char *msg, size_t nm)
{
    cf_child ch;
    const char *ans[2];
    static const char text[] = "version\nconventions\n";
    char why[200];
    *conv = cf_conventions_default();
    *declared = 0;
    *eps = FLT_EPSILON;
    snprintf(name, nn, "(no version)");
    if (cf_child_start(&ch, command, timeout) || cf_child_batch(&ch, text, sizeof text - 1, 2, ans)) {
        snprintf(msg, nm, "%s", ch.msg);
        cf_child_free(&ch);
        return -1;
    }
    /* "protocol N NAME VERSION precision P" */
    if (!strncmp(ans[0], "protocol ", 9)) {
        const char *p = strstr(ans[0], " precision ");
        snprintf(name, nn, "%.200s", ans[0] + 9 + strspn(ans[0] + 9, "0123456789 "));
        if (p && !strcmp(p + 11, "double")) *eps = DBL_EPSILON;
    }
    if (strncmp(ans[1], "error", 5)) { /* protocol 1: "error ..." gives pbrt-v2's */
        if (cf_conventions_parse(ans[1], conv, why, sizeof why)) {
            snprintf(msg, nm, "its answer to \"conventions\", \"%.200s\": %s", ans[1], why);
            cf_child_free(&ch);
            return -1;
        }
        *declared = 1;
    }
    if (cf_child_finish(&ch)) {
        snprintf(msg, nm, "after \"version\" and \"conventions\": %s", ch.msg);
        return -1;
    }
    return 0;
}
