/* Fast, exact "%.9g" of a float and strtod of a short decimal (numtext.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/numtext.h"

static int numtext_digit(char c) { return c >= '0' && c <= '9'; }

/* 5^n for n <= 17: m 5^n stays below 2^64 for a 24-bit float mantissa m. */
static const unsigned long long numtext_pow5[18] = {
    1ULL, 5ULL, 25ULL, 125ULL, 625ULL, 3125ULL, 15625ULL, 78125ULL, 390625ULL, 1953125ULL, 9765625ULL,
    48828125ULL, 244140625ULL, 1220703125ULL, 6103515625ULL, 30517578125ULL, 152587890625ULL, 762939453125ULL};

/* round(m 2^q 10^n) to nearest, ties to even (as glibc's printf rounds an
 * exact tie), exactly in integers; n in 0..17. */
static unsigned long long numtext_scaled(unsigned long long m, int q, int n)
{
    unsigned long long p = m * numtext_pow5[n], r, half, d;
    int s = q + n;
    if (s >= 0) return s < 40 ? p << s : ~0ULL;
    s = -s;
    if (s >= 64) return 0;
    d = p >> s;
    r = p & ((1ULL << s) - 1);
    half = 1ULL << (s - 1);
    if (r > half || (r == half && (d & 1))) d++;
    return d;
}

int mt__format_g9(char *out, size_t size, float f)
{
    double a = fabs((double)f);
    unsigned long long m, d = 0;
    unsigned bits;
    int q, k, n, i, len = 0;
    char dig[10];
    /* outside [1e-9, 1e9), and zero, NaN, infinity: the C library */
    if (!(a >= 1e-9 && a < 1e9) || size < 24) return snprintf(out, size, "%.9g", (double)f);
    /* a = m 2^q with the float's 24-bit mantissa (a normal float here) */
    memcpy(&bits, &f, sizeof bits);
    m = (bits & 0x7fffffu) | 0x800000u;
    q = (int)((bits >> 23) & 0xffu) - 150;
    /* floor(log10 a), estimated with log2(1 + x) ~ x (off by at most one
     * near a power of ten; corrected below) */
    k = (int)floor(((double)(q + 23) + (double)(m - 0x800000u) / 8388608.0) * 0.30102999566398120);
    for (i = 0; i < 4; ++i) {
        n = 8 - k;
        if (n < 0 || n > 17) return snprintf(out, size, "%.9g", (double)f);
        d = numtext_scaled(m, q, n);
        if (d >= 1000000000ULL)
            k++;
        else if (d < 100000000ULL)
            k--;
        else
            break;
    }
    if (i == 4) return snprintf(out, size, "%.9g", (double)f);
    for (i = 8; i >= 0; --i) {
        dig[i] = (char)('0' + d % 10);
        d /= 10;
    }
    n = 9;
    while (n > 1 && dig[n - 1] == '0') n--; /* %g drops trailing zeros */
    if (f < 0) out[len++] = '-';
    if (k >= -4 && k < 9) {
        if (k >= 0) {
            for (i = 0; i <= k; ++i) out[len++] = i < n ? dig[i] : '0';
            if (n > k + 1) {
                out[len++] = '.';
                for (; i < n; ++i) out[len++] = dig[i];
            }
        } else {
            out[len++] = '0';
            out[len++] = '.';
            for (i = 0; i < -k - 1; ++i) out[len++] = '0';
            for (i = 0; i < n; ++i) out[len++] = dig[i];
        }
    } else {
        int e = k < 0 ? -k : k;
        out[len++] = dig[0];
        if (n > 1) {
            out[len++] = '.';
            for (i = 1; i < n; ++i) out[len++] = dig[i];
        }
        out[len++] = 'e';
        out[len++] = k < 0 ? '-' : '+';
        out[len++] = (char)('0' + e / 10);
        out[len++] = (char)('0' + e % 10);
    }
    out[len] = 0;
    return len;
}

int mt__format_hex(char *out, size_t size, double v)
{
    static const char hex[] = "0123456789abcdef";
    unsigned long long bits, frac;
    int e, len = 0, i, ee;
    char d[24];
    memcpy(&bits, &v, sizeof bits);
    e = (int)((bits >> 52) & 0x7ff);
    frac = bits & 0xfffffffffffffULL;
    /* NaN, infinities, subnormals, a small buffer: the C library */
    if (e == 0x7ff || (e == 0 && frac) || size < 32) return snprintf(out, size, "%a", v);
    if (bits >> 63) out[len++] = '-';
    out[len++] = '0';
    out[len++] = 'x';
    out[len++] = e ? '1' : '0';
    if (frac) {
        out[len++] = '.';
        for (i = 0; i < 13 && frac; ++i) { /* 52 bits, the last zero digits left out */
            out[len++] = hex[(frac >> 48) & 0xf];
            frac = (frac << 4) & 0xfffffffffffffULL;
        }
    }
    out[len++] = 'p';
    ee = e ? e - 1023 : 0;
    out[len++] = ee < 0 ? '-' : '+';
    if (ee < 0) ee = -ee;
    i = 0;
    do {
        d[i++] = (char)('0' + ee % 10);
        ee /= 10;
    } while (ee);
    while (i) out[len++] = d[--i];
    out[len] = 0;
    return len;
}

/* A character's hexadecimal value, or -1 (a table: each digit of a number
 * is read with one load; ASCII). */
static const signed char numtext_hexval[256] = {
    -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
    -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, -1, -1, -1, -1, -1, -1,
    -1, 10, 11, 12, 13, 14, 15, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
    -1, 10, 11, 12, 13, 14, 15, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
    -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
    -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
    -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
    -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};

static int numtext_hexdigit(char c) { return numtext_hexval[(unsigned char)c]; }

/* m 2^e for an integer m < 2^53 when the result is a normal double: exact,
 * with the power of two made from its bits (no libm call). */
static double numtext_pow2(double m, int e)
{
    unsigned long long b;
    double p;
    if (e < -1022 || e > 1023) return ldexp(m, e);
    b = (unsigned long long)(e + 1023) << 52;
    memcpy(&p, &b, sizeof p);
    return m * p;
}

/* A hexadecimal float "[-]0xH[.H...]p[+-]D..." of at most 53 significant
 * bits and a normal (or zero) result: 1 and *x, *end; else 0 (strtod's). */
static int numtext_hex(const char *s, double *x, const char **end)
{
    const char *p = s;
    unsigned long long m = 0;
    int neg = 0, digits = 0, shift = 0, h, ev = 0, eneg = 0;
    if (*p == '-') {
        neg = 1;
        p++;
    }
    p += 2; /* "0x" */
    for (; (h = numtext_hexdigit(*p)) >= 0; ++p) {
        if (!digits && !h) continue; /* leading zeros */
        if (++digits > 14) return 0;
        m = 16 * m + (unsigned)h;
    }
    if (*p == '.')
        for (++p; (h = numtext_hexdigit(*p)) >= 0; ++p) {
            shift += 4;
            if (!digits && !h) continue;
            if (++digits > 14) return 0;
            m = 16 * m + (unsigned)h;
        }
    if (p == s + neg + 2 || (p == s + neg + 3 && s[neg + 2] == '.')) return 0; /* no digit */
    if ((*p != 'p' && *p != 'P') || !(numtext_digit(p[1]) || ((p[1] == '-' || p[1] == '+') && numtext_digit(p[2]))))
        return 0; /* no exponent: strtod's (rare; the end differs) */
    p++;
    if (*p == '-' || *p == '+') eneg = *p++ == '-';
    for (; numtext_digit(*p); ++p)
        if (ev < 100000) ev = 10 * ev + (*p - '0');
    if (m >> 53) return 0;
    ev = (eneg ? -ev : ev) - shift;
    /* m 2^ev exact when it is a normal double: m < 2^53, exponent in range */
    if (m && (ev < -1022 - 52 + 53 || ev > 1023 - 53)) return 0;
    *x = numtext_pow2((double)m, ev);
    if (neg) *x = -*x;
    *end = p;
    return 1;
}

/* 10^k for k <= 22: each exact in a double (5^22 < 2^53). */
static const double numtext_pow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                         1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};


double mt__strtod(const char *s, char **end)
{
    const char *p = s;
    unsigned long long m = 0;
    int neg = 0, digits = 0, any = 0, e10 = 0;
    double x;
    if (*p == '-') {
        neg = 1;
        p++;
    }
    /* a hexadecimal number ("0x"): read here when it is exact, else strtod's */
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) {
        const char *e;
        if (!numtext_hex(s, &x, &e)) return strtod(s, end);
        if (end) *end = (char *)e;
        return x;
    }
    while (*p == '0') { /* leading zeros are no significant digits */
        p++;
        any = 1;
    }
    for (; numtext_digit(*p); ++p, any = 1) {
        if (digits < 19) m = 10 * m + (unsigned)(*p - '0');
        digits++;
    }
    if (digits > 19) e10 += digits - 19;
    if (*p == '.') {
        p++;
        if (!digits)
            while (*p == '0') {
                p++;
                e10--;
                any = 1;
            }
        for (; numtext_digit(*p); ++p, any = 1) {
            if (digits < 19) {
                m = 10 * m + (unsigned)(*p - '0');
                e10--;
            }
            digits++;
        }
    }
    /* no digit at all ("", "-", ".", "inf", "nan", " 1", "+1"): strtod's */
    if (!any) return strtod(s, end);
    if (*p == 'e' || *p == 'E') {
        const char *q = p + 1;
        int eneg = 0, ev = 0;
        if (*q == '-' || *q == '+') eneg = *q++ == '-';
        if (numtext_digit(*q)) { /* else the 'e' is not part of the number */
            for (; numtext_digit(*q); ++q)
                if (ev < 10000) ev = 10 * ev + (*q - '0');
            e10 += eneg ? -ev : ev;
            p = q;
        }
    }
    /* exact only when m is (m < 2^53, at most 15 digits taken) and so is
     * the power of ten: then one rounding, strtod's */
    if (digits > 15 || e10 < -22 || e10 > 22) return strtod(s, end);
    x = (double)m;
    x = e10 < 0 ? x / numtext_pow10[-e10] : x * numtext_pow10[e10];
    if (end) *end = (char *)p;
    return neg ? -x : x;
}
