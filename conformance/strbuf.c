/* A growing text buffer (strbuf.h). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include "strbuf.h"

int cf_strbuf_vprintf(cf_strbuf *b, const char *fmt, va_list ap)
{
    va_list again;
    int need;
    if (b->failed) return -1; /* sticky: no text after a hole */
    /* measured first: a line longer than any fixed reserve (a long
       parameter list) is appended whole, never cut */
    va_copy(again, ap);
    need = vsnprintf(NULL, 0, fmt, ap);
    if (need < 0) {
        va_end(again);
        b->failed = 1;
        return -1;
    }
    if (b->n + (size_t)need + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 1 << 16;
        char *s;
        while (cap < b->n + (size_t)need + 1) cap *= 2;
        if (!(s = realloc(b->s, cap))) {
            va_end(again);
            b->failed = 1;
            return -1;
        }
        b->s = s;
        b->cap = cap;
    }
    vsnprintf(b->s + b->n, b->cap - b->n, fmt, again);
    va_end(again);
    b->n += (size_t)need;
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
