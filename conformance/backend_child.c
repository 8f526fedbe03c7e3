/*
 * An implementation in a child process that speaks the query protocol
 * (docs/PROTOCOL.md), behind the core's batched operations. Each batch of
 * queries is written while the answers are read, so that the pipe stays
 * full, and ends with the mode line, whose "ok" shows that answers and
 * queries are still in step. Every answer is parsed strictly: the number
 * of values, numbers only, flags an integer; an answer that is not what the
 * query asks for names the query. An error answer that says "unsupported"
 * makes the configuration unsupported (CF_UNSUPPORTED), not a failure.
 *
 * An implementation that announces "batch N" in its conventions (protocol
 * 3) gets the queries of one wo that follow each other as "evals" and
 * "samples" lines of up to N triples (at most CF_LINE_TRIPLES): one line, one
 * answer, for what would be that many. An error answer to such a line
 * makes the suite ask the whole call again one query a line, so that the
 * query an error names, and what the suite does with it, are the plain
 * protocol's; an answer of the wrong shape is a failure naming the line.
 */
#include <ctype.h>
#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core.h"
#include "core/numtext.h"

/* The suite's longest batched line (whatever the implementation takes):
 * about 12 kB of query, up to 30 kB of answer. */
#define CF_LINE_TRIPLES 256

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

/* Appends " v" to line, at len: in C99 hexadecimal (exact whatever the
 * precision) to an implementation that reads it, else cf_format_num (the
 * same text as printf's %.9g for the suite's float inputs, without its
 * cost). */
static size_t put_value(char *line, size_t len, size_t size, double v, int hex)
{
    line[len++] = ' ';
    return len + (size_t)(hex ? mt__format_hex(line + len, size - len, v) : cf_format_num(line + len, size - len, v));
}

/* Appends the lines of n queries WORD wo[i] v[i] to im->text: one plain
 * line each, or (batch > 1) lines of up to batch triples for the queries
 * of one wo in a row. start[] gets each line's first query (start[lines]
 * = n); the number of lines. */
static int put_queries(cf_impl *im, const char *word, int n, const cf_v3 *wo, const double (*v)[3], int batch, int *start)
{
    char line[128];
    size_t wl = strlen(word);
    int i = 0, lines = 0;
    while (i < n) {
        int k = 1, j;
        size_t len = wl;
        while (batch > 1 && i + k < n && k < batch && !memcmp(&wo[i + k], &wo[i], sizeof *wo)) k++;
        start[lines++] = i;
        memcpy(line, word, wl);
        if (k > 1) line[len++] = 's'; /* evals, samples */
        len = put_value(line, len, sizeof line, wo[i].x, im->conv.hex);
        len = put_value(line, len, sizeof line, wo[i].y, im->conv.hex);
        len = put_value(line, len, sizeof line, wo[i].z, im->conv.hex);
        cf_strbuf_append(&im->text, line, len); /* a failure stays in text.failed: send() reports it */
        for (j = i; j < i + k; ++j) {
            len = put_value(line, 0, sizeof line, v[j][0], im->conv.hex);
            len = put_value(line, len, sizeof line, v[j][1], im->conv.hex);
            len = put_value(line, len, sizeof line, v[j][2], im->conv.hex);
            cf_strbuf_append(&im->text, line, len);
        }
        cf_strbuf_append(&im->text, "\n", 1);
        i += k;
    }
    start[lines] = n;
    return lines;
}

/* Sends the batch in im->text (n lines, q queries), then the mode line. */
static int send(cf_impl *im, int n, int q)
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
    im->queries += q;
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

/* The next number of an answer at *s (strtod's syntax: "nan" and "inf" are
 * numbers, judged by the checks), rounded to float when the implementation
 * computes in float: 1, 0 at the end of the answer, -1 when the next word
 * is not a number. */
static int next_number(const cf_impl *im, const char **s, double *v)
{
    const char *p = *s;
    char *end;
    double x;
    while (isspace((unsigned char)*p)) p++;
    if (!*p) return 0;
    x = mt__strtod(p, &end); /* strtod's value, faster (core/numtext.h) */
    if (end == p || (*end && !isspace((unsigned char)*end))) return -1;
    *v = im->eps < 1e-10 || !isfinite(x) ? x : as_float(x);
    *s = end;
    return 1;
}

/* Exactly n numbers into v: 0, or -1 and why. */
static int numbers(const cf_impl *im, const char *s, double *v, int n, char *why, size_t wn)
{
    int i, r = 1;
    double extra;
    if (!strncmp(s, "error", 5)) {
        snprintf(why, wn, "an error answer");
        return -1;
    }
    for (i = 0; i < n && (r = next_number(im, &s, v + i)) == 1; ++i) continue;
    if (r == 1)
        while ((r = next_number(im, &s, &extra)) == 1) i++;
    if (r < 0) {
        snprintf(why, wn, "garbage (value %d is not a number)", i + 1);
        return -1;
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
    /* the mode, "numbers hex" when it takes it, the statements */
    cf_strbuf_printf(&im->text, "%s\n%s", im->mode_line, im->conv.hex ? "numbers hex\n" : "");
    for (i = 0; i < c->nlines; ++i) cf_strbuf_printf(&im->text, "%s\n", c->lines[i]);
    if (send(im, c->nlines + 1 + im->conv.hex, c->nlines + 1 + im->conv.hex)) return im->failed;
    for (i = 0; i <= c->nlines + im->conv.hex; ++i)
        if (strcmp(im->ans[i], "ok")) {
            char q[300];
            shorten(!i ? im->mode_line : i == 1 && im->conv.hex ? "numbers hex" : c->lines[i - 1 - im->conv.hex], q, sizeof q);
            return bad_answer(im, q, im->ans[i], "not \"ok\"");
        }
    cf_strbuf_clear(&im->text);
    return 0;
}

/* The k answers of a batched line, in per values each, into v (k per
 * values): 0, or a failure naming the line. An error answer is 1: the
 * caller asks again one query a line. */
static int batched_answer(cf_impl *im, const char *answer, int line, int lines, int k, int per, double *v)
{
    char why[64], a[200], q[200];
    const char *text = im->text.s;
    int i;
    if (!strncmp(answer, "error", 5)) return 1;
    if (!numbers(im, answer, v, k * per, why, sizeof why)) return 0;
    for (i = 0; i < line && text; ++i) text = strchr(text, '\n') + 1; /* the line, quoted */
    snprintf(q, sizeof q, "%.*s", (int)strcspn(text, "\n"), text);
    if (strlen(q) >= sizeof q - 1) strcpy(q + sizeof q - 5, "...");
    shorten(answer, a, sizeof a);
    return fail(im, CF_FAILED, "answered %s: \"%s\" to the batched line %d of %d, \"%s\" (%d triples, %d values each)",
                why, a, line + 1, lines, q, k, per);
}

/* Lines of at most batch triples: the implementation's and the suite's. */
static int batch_of(const cf_impl *im)
{
    return im->conv.batch < CF_LINE_TRIPLES ? im->conv.batch : CF_LINE_TRIPLES;
}

/* Writes and sends n queries WORD wo[i] (wi[i] or u[i]) in lines of up to
 * batch triples: the number of lines and *start (each line's first query,
 * the caller frees it), or the failure (negative). */
static int ask(cf_impl *im, const char *word, int n, const cf_v3 *wo, const cf_v3 *wi, const float (*u)[3], int batch,
               int **start)
{
    int i, lines;
    double (*v)[3];
    if (im->failed) return im->failed;
    v = malloc((size_t)(n ? n : 1) * sizeof *v);
    if (!v || !(*start = malloc(((size_t)n + 1) * sizeof **start))) {
        free(v);
        return fail(im, CF_NOMEM, "out of memory for a batch of %d queries", n);
    }
    for (i = 0; i < n; ++i) {
        v[i][0] = wi ? wi[i].x : u[i][0];
        v[i][1] = wi ? wi[i].y : u[i][1];
        v[i][2] = wi ? wi[i].z : u[i][2];
    }
    cf_strbuf_clear(&im->text);
    lines = put_queries(im, word, n, wo, (const double(*)[3])v, batch, *start);
    free(v);
    if (send(im, lines, n)) {
        free(*start);
        *start = NULL;
        return im->failed;
    }
    return lines;
}

static int c_eval_lines(cf_impl *im, int n, const cf_v3 *wo, const cf_v3 *wi, cf_eval *out, int batch)
{
    int i, k, l, lines, *start = NULL;
    double x[4 * CF_LINE_TRIPLES];
    if ((lines = ask(im, "eval", n, wo, wi, NULL, batch, &start)) < 0) return lines;
    for (l = 0; l < lines; ++l) {
        int a = start[l], m = start[l + 1] - a;
        if (m > 1) { /* a batched line */
            int r = batched_answer(im, im->ans[l], l, lines, m, 4, x);
            if (r) {
                free(start);
                return r < 0 ? r : c_eval_lines(im, n, wo, wi, out, 1);
            }
            for (i = 0; i < m; ++i) {
                for (k = 0; k < 3; ++k) out[a + i].f[k] = x[4 * i + k];
                out[a + i].pdf = x[4 * i + 3];
            }
            continue;
        }
        {
            char why[64];
            if (numbers(im, im->ans[l], x, 4, why, sizeof why)) {
                char q[200];
                free(start);
                cf_q_eval(q, sizeof q, wo[a], wi[a]);
                return bad_answer(im, q, im->ans[l], why);
            }
            for (k = 0; k < 3; ++k) out[a].f[k] = x[k];
            out[a].pdf = x[3];
        }
    }
    free(start);
    return 0;
}

static int c_eval(cf_impl *im, int n, const cf_v3 *wo, const cf_v3 *wi, cf_eval *out)
{
    return c_eval_lines(im, n, wo, wi, out, batch_of(im));
}

/* One sample's 8 values into out: 0, or -1 and why. */
static int sample_values(const double *v, cf_samp *out, char *why, size_t wn)
{
    int k;
    if (!(v[7] >= 0 && v[7] < 32 && v[7] == (double)(int)v[7])) {
        snprintf(why, wn, "flags %g not an integer of 0..31", v[7]);
        return -1;
    }
    for (k = 0; k < 3; ++k) {
        out->wi[k] = v[k];
        out->f[k] = v[3 + k];
    }
    out->pdf = v[6];
    out->flags = (unsigned)v[7];
    return 0;
}

static int c_sample_lines(cf_impl *im, int n, const cf_v3 *wo, const float (*u)[3], cf_samp *out, int batch)
{
    int i, l, lines, *start = NULL;
    double x[8 * CF_LINE_TRIPLES];
    if ((lines = ask(im, "sample", n, wo, NULL, u, batch, &start)) < 0) return lines;
    for (l = 0; l < lines; ++l) {
        int a = start[l], m = start[l + 1] - a;
        char why[64];
        if (m > 1) { /* a batched line */
            int r = batched_answer(im, im->ans[l], l, lines, m, 8, x);
            if (r) {
                free(start);
                return r < 0 ? r : c_sample_lines(im, n, wo, u, out, 1);
            }
            for (i = 0; i < m; ++i)
                if (sample_values(x + 8 * i, out + a + i, why, sizeof why)) {
                    char q[200], a8[200];
                    free(start);
                    cf_q_sample(q, sizeof q, wo[a + i], u[a + i]);
                    snprintf(a8, sizeof a8, "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g", x[8 * i], x[8 * i + 1],
                             x[8 * i + 2], x[8 * i + 3], x[8 * i + 4], x[8 * i + 5], x[8 * i + 6], x[8 * i + 7]);
                    return fail(im, CF_FAILED, "answered %s: \"%s\" (triple %d of the batched line %d) to \"%s\"", why,
                                a8, i + 1, l + 1, q);
                }
            continue;
        }
        if (numbers(im, im->ans[l], x, 8, why, sizeof why) || sample_values(x, out + a, why, sizeof why)) {
            char q[200];
            free(start);
            cf_q_sample(q, sizeof q, wo[a], u[a]);
            return bad_answer(im, q, im->ans[l], why);
        }
    }
    free(start);
    return 0;
}

static int c_sample(cf_impl *im, int n, const cf_v3 *wo, const float (*u)[3], cf_samp *out)
{
    return c_sample_lines(im, n, wo, u, out, batch_of(im));
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
