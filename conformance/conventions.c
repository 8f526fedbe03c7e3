/*
 * The conventions an implementation declares in answer to the protocol's
 * "conventions" query (docs/PROTOCOL.md): "key value" pairs separated by
 * single spaces. The suite knows two keys; any other is ignored, so that
 * later keys do not break an older suite.
 *
 *   transport importance|radiance
 *       importance: pbrt-v2's BTDF values, without the (eta_i/eta_t)^2 of
 *       radiance; radiance: pbrt-v3's, pbrt-v4's and Mitsuba's radiance mode.
 *   sample-numbers 3|2
 *       3: pbrt-v2's, uc chooses the component, u1 and u2 its direction;
 *       2: uc chooses and is rescaled to drive the component (pbrt-v3's
 *       Sample_f(wo, &wi, u)), u1 the second number, u2 unused.
 *   batch N
 *       protocol 3: it answers "evals" and "samples" lines of up to N
 *       triples (N >= 1; not a convention of its values: formatted apart).
 *   numbers hex|decimal
 *       protocol 3: hex, it reads C99 hexadecimal floats in queries and
 *       writes them after the line "numbers hex" (formatted apart too).
 *
 * And "unsupported": an error answer whose message (after any
 * "FILE:LINE:COL:" position) starts with the word unsupported.
 */
#include <ctype.h>
#include <stdio.h>
#include <string.h>
#include "core.h"

cf_conventions cf_conventions_default(void)
{
    cf_conventions c;
    c.transport = CF_IMPORTANCE;
    c.sample_numbers = 3;
    c.batch = 1;
    c.hex = 0;
    return c;
}

void cf_conventions_format(const cf_conventions *c, char *out, size_t n)
{
    snprintf(out, n, "transport %s sample-numbers %d", c->transport == CF_RADIANCE ? "radiance" : "importance",
             c->sample_numbers);
}

/* The next word of s (up to a space or the end): its length. */
static size_t word(const char *s) { return strcspn(s, " "); }

int cf_conventions_parse(const char *answer, cf_conventions *c, char *why, size_t n)
{
    const char *s = answer;
    cf_conventions out = cf_conventions_default();
    while (*s) {
        size_t kl = word(s), vl;
        const char *v;
        if (!kl || s[kl] != ' ') {
            snprintf(why, n, "\"%.60s\" is not a key followed by a value", s);
            return -1;
        }
        v = s + kl + 1;
        vl = word(v);
        if (!vl) {
            snprintf(why, n, "the key \"%.*s\" has no value (one space between words)", (int)kl, s);
            return -1;
        }
        if (kl == 9 && !strncmp(s, "transport", 9)) {
            if (vl == 10 && !strncmp(v, "importance", 10))
                out.transport = CF_IMPORTANCE;
            else if (vl == 8 && !strncmp(v, "radiance", 8))
                out.transport = CF_RADIANCE;
            else {
                snprintf(why, n, "transport \"%.*s\" is neither importance nor radiance", (int)vl, v);
                return -1;
            }
        } else if (kl == 5 && !strncmp(s, "batch", 5)) {
            long b = 0;
            size_t i;
            for (i = 0; i < vl && isdigit((unsigned char)v[i]) && b <= 100000000; ++i) b = 10 * b + (v[i] - '0');
            if (i < vl || b < 1 || b > 100000000) {
                snprintf(why, n, "batch \"%.*s\" is not a whole number from 1 to 100000000", (int)(vl > 20 ? 20 : vl), v);
                return -1;
            }
            out.batch = (int)b;
        } else if (kl == 7 && !strncmp(s, "numbers", 7)) {
            if (vl == 3 && !strncmp(v, "hex", 3))
                out.hex = 1;
            else if (vl == 7 && !strncmp(v, "decimal", 7))
                out.hex = 0;
            else {
                snprintf(why, n, "numbers \"%.*s\" is neither hex nor decimal", (int)(vl > 20 ? 20 : vl), v);
                return -1;
            }
        } else if (kl == 14 && !strncmp(s, "sample-numbers", 14)) {
            if (vl == 1 && (*v == '3' || *v == '2'))
                out.sample_numbers = *v - '0';
            else {
                snprintf(why, n, "sample-numbers \"%.*s\" is neither 3 nor 2", (int)vl, v);
                return -1;
            }
        }
        s = v + vl;
        if (*s == ' ') {
            if (!s[1]) {
                snprintf(why, n, "a space at the end");
                return -1;
            }
            s++;
        }
    }
    *c = out;
    return 0;
}

const char *cf_unsupported(const char *answer)
{
    const char *s = answer, *p;
    if (strncmp(s, "error ", 6)) return NULL;
    s += 6;
    /* a position "NAME:LINE:COL:" first (no space in it) */
    p = s + strcspn(s, " ");
    if (p > s && p[-1] == ':') {
        const char *q = p - 1, *d;
        int colons = 0;
        for (d = s; d < q; ++d) colons += *d == ':';
        if (colons >= 2 && isdigit((unsigned char)q[-1])) s = *p ? p + 1 : p;
    }
    if (strncmp(s, "unsupported", 11) || isalnum((unsigned char)s[11]) || s[11] == '-' || s[11] == '_') return NULL;
    return s;
}
