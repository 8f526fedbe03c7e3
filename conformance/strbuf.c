/* A growing text buffer, and a fast %.9g of a float (strbuf.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "strbuf.h"

/* Room for n more bytes and the NUL: 0, or -1 (failed is then set). */
static int reserve(cf_strbuf *b, size_t n)
{
    size_t cap = b->cap ? b->cap : 1 << 16;
    char *s;
    if (b->failed) return -1; /* sticky: no text after a hole */
    if (b->n + n + 1 <= b->cap) return 0;
    while (cap < b->n + n + 1) cap *= 2;
    if (!(s = realloc(b->s, cap))) {
        b->failed = 1;
        return -1;
    }
    b->s = s;
    b->cap = cap;
    return 0;
}

int cf_strbuf_vprintf(cf_strbuf *b, const char *fmt, va_list ap)
{
    va_list again;
    int need;
    /* measured first: a line longer than any fixed reserve (a long
       parameter list) is appended whole, never cut */
    va_copy(again, ap);
    need = vsnprintf(NULL, 0, fmt, ap);
    if (need < 0) b->failed = 1;
    if (need < 0 || reserve(b, (size_t)need)) {
        va_end(again);
        return -1;
    }
    vsnprintf(b->s + b->n, b->cap - b->n, fmt, again);
    va_end(again);
    b->n += (size_t)need;
    return 0;
}

int cf_strbuf_append(cf_strbuf *b, const char *text, size_t n)
{
    if (reserve(b, n)) return -1;
    memcpy(b->s + b->n, text, n);
    b->n += n;
    b->s[b->n] = 0;
    return 0;
}

int cf_strbuf_printf(cf_strbuf *b, const char *fmt, ...)
{
    va_list ap;
    int r;
    va_start(ap, fmt);
    r = cf_strbuf_vprintf(b, fmt, ap);
    va_end(ap);
    return r;
}

void cf_strbuf_clear(cf_strbuf *b)
{
    b->n = 0;
    b->failed = 0;
    if (b->s) b->s[0] = 0;
}

void cf_strbuf_free(cf_strbuf *b)
{
    free(b->s);
    b->s = NULL;
    b->n = b->cap = 0;
    b->failed = 0;
}

/* 5^n for n <= 17: m 5^n stays below 2^64 for a 24-bit float mantissa m. */
static const unsigned long long pow5[18] = {
    1ULL, 5ULL, 25ULL, 125ULL, 625ULL, 3125ULL, 15625ULL, 78125ULL, 390625ULL, 1953125ULL, 9765625ULL,
    48828125ULL, 244140625ULL, 1220703125ULL, 6103515625ULL, 30517578125ULL, 152587890625ULL, 762939453125ULL};

/* round(m 2^q 10^n) to nearest, ties to even (as glibc's printf rounds an
 * exact tie), exactly in integers; n in 0..17. */
static unsigned long long scaled(unsigned long long m, int q, int n)
{
    unsigned long long p = m * pow5[n], r, half, d;
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

int cf_format_g9(char *out, size_t size, float f)
{
    double a = fabs((double)f), fr;
    unsigned long long m, d = 0;
    int ex, q, k, n, i, len = 0;
    char dig[10];
    /* outside [1e-9, 1e9), and zero, NaN, infinity: the C library */
    if (!(a >= 1e-9 && a < 1e9) || size < 24) return snprintf(out, size, "%.9g", (double)f);
    fr = frexp(a, &ex); /* a = fr 2^ex, fr in [0.5, 1): 24 bits */
    m = (unsigned long long)ldexp(fr, 24);
    q = ex - 24;
    k = (int)floor(log10(a)); /* an estimate, corrected below */
    for (i = 0; i < 4; ++i) {
        n = 8 - k;
        if (n < 0 || n > 17) return snprintf(out, size, "%.9g", (double)f);
        d = scaled(m, q, n);
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
