/* Fast, exact "%.9g" of a float and strtod of a short decimal (numtext.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/numtext.h"

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

/* 10^k for k <= 22: each exact in a double (5^22 < 2^53). */
static const double numtext_pow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                         1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

static int numtext_digit(char c) { return c >= '0' && c <= '9'; }

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
    /* a hexadecimal number ("0x"): strtod's */
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) return strtod(s, end);
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
