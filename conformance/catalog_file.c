/*
 * --catalog FILE: an implementation's own configurations, for materials the
 * suite's catalog does not have (a GGX conductor, a coated diffuse, a
 * sheen) or settings it does not try. The format (docs/CONFORMANCE-SUITE.md,
 * "Your own configurations"), one item per line:
 *
 *   # a comment; blank lines are skipped
 *   configuration NAME                 starts one (NAME: the rest of the line)
 *     Material "roughconductor" ...    pbrt-v2 statements, one per line, sent
 *     at ng 0.6 0 0.8                  as they are, and "at" lines
 *     two-sided                        incoming directions from below too
 *     wo COS_THETA PHI_DEGREES         its own incoming directions (replace
 *                                      the suite's; up to 16)
 *     expect albedo <= 1               or "= X", "<= X": the furnace's bound
 *     lobe-exponent E                  as sharp as cos^E (2 / alpha^2 for a
 *                                      microfacet alpha): rounding allowances
 *     quick                            in the --quick set
 *   end
 *
 * A statement line starts with an upper-case letter; anything else that is
 * not one of these words is an error naming the file and line.
 */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "impl.h"

#define DEG_TO_RAD (3.14159265358979323846 / 180)

static int word_is(const char *s, const char *w)
{
    size_t n = strlen(w);
    return !strncmp(s, w, n) && (!s[n] || isspace((unsigned char)s[n]));
}

static char *trim(char *s)
{
    char *e;
    while (isspace((unsigned char)*s)) s++;
    e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1])) *--e = 0;
    return s;
}

int cf_catalog_read(const char *path, cf_case **cases, int *n, int *cap, char *msg, size_t nm)
{
    FILE *f = fopen(path, "r");
    char line[4096];
    int lineno = 0, open = 0, first = *n, i;
    cf_case *c = NULL;
    if (!f) {
        snprintf(msg, nm, "%s: %s", path, strerror(errno));
        return -1;
    }
#define BAD(...)                                                                       \
    do {                                                                               \
        int at_ = snprintf(msg, nm, "%s:%d: ", path, lineno);                          \
        snprintf(msg + (at_ > 0 && (size_t)at_ < nm ? at_ : 0), nm - (at_ > 0 && (size_t)at_ < nm ? (size_t)at_ : 0), \
                 __VA_ARGS__);                                                         \
        goto fail;                                                                     \
    } while (0)
    while (fgets(line, sizeof line, f)) {
        char *s;
        lineno++;
        if (!strchr(line, '\n') && !feof(f)) BAD("a line longer than %d bytes", (int)sizeof line - 2);
        s = trim(line);
        if (!*s || *s == '#') continue;
        if (word_is(s, "configuration")) {
            char *name = trim(s + 13);
            if (open) BAD("\"configuration\" inside \"%s\" (an \"end\" is missing)", c->name);
            if (!*name) BAD("a configuration needs a name");
            if (strlen(name) >= sizeof c->name) BAD("the name is longer than %d bytes", (int)sizeof c->name - 1);
            for (i = 0; i < *n; ++i)
                if (!strcmp((*cases)[i].name, name)) BAD("a second configuration called \"%s\"", name);
            if (*n == *cap) {
                cf_case *nc = realloc(*cases, (size_t)(*cap = *cap ? 2 * *cap : 64) * sizeof *nc);
                if (!nc) BAD("out of memory");
                *cases = nc;
            }
            c = &(*cases)[(*n)++];
            memset(c, 0, sizeof *c);
            snprintf(c->name, sizeof c->name, "%s", name);
            c->source = path;
            open = 1;
            continue;
        }
        if (!open) BAD("\"%.40s\" outside a configuration (begin one with \"configuration NAME\")", s);
        if (word_is(s, "end")) {
            if (!c->nlines) BAD("\"%s\" has no statement", c->name);
            open = 0;
        } else if (word_is(s, "two-sided")) {
            c->flags |= CF_CASE_TWO_SIDED;
        } else if (word_is(s, "quick")) {
            c->flags |= CF_CASE_QUICK;
        } else if (word_is(s, "wo")) {
            double ct, ph;
            char extra;
            if (sscanf(s + 2, "%lf %lf %c", &ct, &ph, &extra) != 2 || !(ct >= -1 && ct <= 1) || !isfinite(ph))
                BAD("wo needs cos theta (-1 to 1) and phi in degrees");
            if (c->nwo == CF_MAX_WO) BAD("more than %d incoming directions", CF_MAX_WO);
            c->wo[c->nwo++] = cf_v3_make(sqrt(1 - ct * ct) * cos(ph * DEG_TO_RAD), sqrt(1 - ct * ct) * sin(ph * DEG_TO_RAD), ct);
        } else if (word_is(s, "expect")) {
            char op[4], extra;
            double v;
            if (sscanf(s + 6, " albedo %3s %lf %c", op, &v, &extra) != 2 || (strcmp(op, "<=") && strcmp(op, "=")) ||
                !isfinite(v) || v < 0)
                BAD("expect needs \"albedo <= X\" or \"albedo = X\" (X >= 0)");
            c->expect = !strcmp(op, "=") ? CF_EXPECT_EQ : CF_EXPECT_LE;
            c->expect_rho = v;
        } else if (word_is(s, "lobe-exponent")) {
            char extra;
            if (sscanf(s + 13, "%lf %c", &c->lobe_exponent, &extra) != 1 || !(c->lobe_exponent >= 0) ||
                !isfinite(c->lobe_exponent))
                BAD("lobe-exponent needs a number >= 0");
        } else if (isupper((unsigned char)*s) || word_is(s, "at")) {
            if (c->nlines == CF_MAX_LINES) BAD("more than %d statements and at lines", CF_MAX_LINES);
            if (cf_case_add_line(c, s, NULL)) BAD("out of memory");
        } else {
            BAD("\"%.40s\" is neither a statement nor one of configuration, end, two-sided, wo, expect, "
                "lobe-exponent, quick",
                s);
        }
    }
    if (open) {
        lineno++;
        BAD("the file ends inside \"%s\" (an \"end\" is missing)", c->name);
    }
    if (*n == first) BAD("no configuration");
    fclose(f);
    return 0;
fail:
    fclose(f);
    return -1;
#undef BAD
}
