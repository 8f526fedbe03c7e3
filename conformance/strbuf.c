/* A growing text buffer, and a fast %.9g of a float (strbuf.h; the library's
 * src/core/numtext.c, which materia-query writes its answers with). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "strbuf.h"
#include "core/numtext.h"

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

int cf_format_g9(char *out, size_t size, float f)
{
    return mt__format_g9(out, size, f);
}
