/*
 * The shared text buffer of the conformance suite (conformance/strbuf.c):
 * appends grow it and keep it NUL-terminated, a long line goes in whole,
 * and cf_format_g9 writes exactly what printf("%.9g") writes for every
 * float it is given (the query lines --impl sends are written with it, so
 * a difference would change the inputs an implementation reads), and the
 * library's mt__strtod (materia-query and the suite read every number of
 * the protocol with it) gives strtod's value and end for every text.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../conformance/strbuf.h"
#include "core/numtext.h"
#include "support/check.h"

static uint32_t rng(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

/* 0 when cf_format_g9 and snprintf agree on f; else prints both. */
static int differs(float f, char *first, size_t n)
{
    char a[64], b[64];
    int la = cf_format_g9(a, sizeof a, f), lb = snprintf(b, sizeof b, "%.9g", (double)f);
    if (la == lb && !strcmp(a, b)) return 0;
    if (!first[0]) snprintf(first, n, "%a: \"%s\", printf \"%s\"", (double)f, a, b);
    return 1;
}

/* 0 when mt__strtod and strtod agree on text (value bit for bit, end); else
 * prints both. */
static int reads_differently(const char *text, char *first, size_t n)
{
    char *ea, *eb;
    double a = mt__strtod(text, &ea), b = strtod(text, &eb);
    if (ea == eb && (memcmp(&a, &b, sizeof a) == 0 || (a != a && b != b))) return 0;
    if (!first[0]) snprintf(first, n, "\"%s\": %a end %d, strtod %a end %d", text, a, (int)(ea - text), b, (int)(eb - text));
    return 1;
}

int main(void)
{
    cf_strbuf b = {0, 0, 0, 0};
    char big[100000], first[200] = "";
    static const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 1e-9f, 9.99999e-10f, 1e-5f, 9.9999999e-5f, 1e-4f,
                                    0.1f, 0.3f, 0.7f, 0.03f, 123456789.0f, 999999999.0f, 1e9f, 5e8f, 1e-45f, 1e-38f,
                                    3.4e38f, 16777216.0f, 0.999999940f, 1.00000012f};
    long i, bad = 0, tried = 0;
    uint32_t s = 2463534242u;
    /* appends */
    cf_strbuf_printf(&b, "%s %d", "eval", 3);
    cf_strbuf_append(&b, " x", 2);
    t_check(b.s && !strcmp(b.s, "eval 3 x") && b.n == 8 && !b.failed, "strbuf: printf and append", "got \"%s\"",
            b.s ? b.s : "(null)");
    memset(big, 'a', sizeof big - 1);
    big[sizeof big - 1] = 0;
    cf_strbuf_printf(&b, "%s\n", big);
    t_check(b.n == 8 + sizeof big && b.s[b.n - 1] == '\n' && b.s[b.n] == 0 && b.cap > b.n,
            "strbuf: a line longer than the first allocation goes in whole", "length %zu", b.n);
    b.failed = 1; /* as after an allocation failure */
    t_check(cf_strbuf_printf(&b, "more") == -1 && cf_strbuf_append(&b, "more", 4) == -1 && b.n == 8 + sizeof big,
            "strbuf: after a failure, appends fail too (no hole in the text)", "length %zu", b.n);
    cf_strbuf_clear(&b);
    t_check(b.n == 0 && !b.failed && b.s[0] == 0 && !cf_strbuf_printf(&b, "ok"), "strbuf: clear", "n %zu", b.n);
    cf_strbuf_free(&b);
    /* %.9g: the special values, random bit patterns (every magnitude, NaN,
     * infinities, subnormals) and values in [-1, 1] as directions have,
     * and a float on each side of every power of ten */
    for (i = 0; i < (long)(sizeof special / sizeof special[0]); ++i, ++tried) bad += differs(special[i], first, sizeof first);
    for (i = 0; i < 1000000; ++i, ++tried) {
        uint32_t bits = rng(&s);
        float f;
        if (i & 1) {
            memcpy(&f, &bits, sizeof f);
        } else {
            f = (float)((double)(bits >> 8) / 16777216.0);
            if (bits & 1) f = -f;
            if (i % 6 == 2) f = f * f * f * f;
        }
        bad += differs(f, first, sizeof first);
    }
    for (i = -46; i <= 38; ++i, tried += 3) {
        float p = (float)pow(10, (double)i);
        bad += differs(p, first, sizeof first) + differs(nextafterf(p, 0), first, sizeof first) +
               differs(nextafterf(p, INFINITY), first, sizeof first);
    }
    t_check(bad == 0, "cf_format_g9 writes what printf(\"%.9g\") writes", "%ld of %ld differ, first %s", bad, tried,
            first);
    /* strtod: texts of every shape the protocol and its errors have, the
     * suite's %.9g of random floats, %.17g and %.15g of random doubles,
     * and random digit strings with a point and an exponent */
    {
        static const char *const texts[] = {"0", "-0", "0.5", ".5", "5.", ".", "-", "", " 1", "+1", "1e", "1e+",
                                            "1e-3x", "1.5e308", "1e309", "4.9e-324", "1e-400", "0x1p-3", "-0X1.8P1",
                                            "inf", "-nan", "nan(1)", "00012.50", "0.000000000000000000000012345",
                                            "123456789012345678901234567890", "9007199254740993", "1e22", "1e23",
                                            "3 4", "2e22", "0.1\n", "7e-23", "12345678901234567e-5", "0x1.8p-3",
                                            "0x1.8p", "0x1.8p+", "0x", "0x.", "0x.8p1", "0x1.fffffffffffffp+1023",
                                            "0x1p-1074", "0x1.0000000000000801p0", "0x0p+0", "-0x0.000p-5", "0X1P3",
                                            "0x123456789abcdefp-60", "0x1.8p-1022", "0x1p-1021"};
        char txt[64];
        first[0] = 0;
        bad = tried = 0;
        for (i = 0; i < (long)(sizeof texts / sizeof texts[0]); ++i, ++tried) bad += reads_differently(texts[i], first, sizeof first);
        for (i = 0; i < 600000; ++i, ++tried) {
            uint32_t a = rng(&s), c = rng(&s);
            float f;
            double d;
            memcpy(&f, &a, sizeof f);
            d = ((double)a * 4294967296.0 + c) / 18446744073709551616.0 * pow(10, (int)(c % 60) - 30);
            switch (i % 6) {
            case 4: mt__format_hex(txt, sizeof txt, (c & 1) ? (double)f : d); break;
            case 5: snprintf(txt, sizeof txt, "%a", (c & 1) ? (double)f : -d); break;
            case 0: cf_format_g9(txt, sizeof txt, f); break;
            case 1: snprintf(txt, sizeof txt, "%.17g", (c & 1) ? -d : d); break;
            case 2: snprintf(txt, sizeof txt, "%.15g", d); break;
            default:
                snprintf(txt, sizeof txt, "%s%u.%ue%d", (c & 2) ? "-" : "", a % 100000u, c % 1000000u, (int)(a % 61) - 30);
            }
            bad += reads_differently(txt, first, sizeof first);
        }
        t_check(bad == 0, "mt__strtod reads what strtod reads (value and end)", "%ld of %ld differ, first %s", bad, tried,
                first);
        /* hexadecimal: every double and float reads back bit for bit */
        first[0] = 0;
        bad = tried = 0;
        for (i = 0; i < 300000; ++i, ++tried) {
            uint32_t a = rng(&s), c = rng(&s);
            uint64_t bits = ((uint64_t)a << 32) | c;
            double d, back;
            float f;
            memcpy(&d, &bits, sizeof d);
            memcpy(&f, &a, sizeof f);
            if (i & 1) d = f;
            if (d != d) continue;
            mt__format_hex(txt, sizeof txt, d);
            back = strtod(txt, NULL);
            if (memcmp(&back, &d, sizeof d)) {
                bad++;
                if (!first[0]) snprintf(first, sizeof first, "%a written \"%s\"", d, txt);
            }
        }
        t_check(bad == 0, "mt__format_hex reads back to the same double", "%ld of %ld differ, first %s", bad, tried, first);
    }
    return t_status();
}
