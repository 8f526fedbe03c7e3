/*
 * A growing text buffer: printf appends, the text stays NUL-terminated.
 * Used by --impl to build a batch of protocol lines and by the vectors'
 * test to build its CSV files. An allocation failure is never silent: the
 * append returns -1 and the buffer remembers it (failed), its text intact
 * up to the last append that fit; later appends fail too, so the
 * text never has a hole.
 */
#ifndef CF_STRBUF_H
#define CF_STRBUF_H

#include <stdarg.h>
#include <stddef.h>

typedef struct cf_strbuf {
    char *s;     /* the text (NULL until the first append) */
    size_t n;    /* its length */
    size_t cap;  /* bytes allocated */
    int failed;  /* an append ran out of memory */
} cf_strbuf;

/* Appends the formatted text: 0, or -1 (out of memory, or a format error). */
int cf_strbuf_printf(cf_strbuf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
int cf_strbuf_vprintf(cf_strbuf *b, const char *fmt, va_list ap);
/* Appends n bytes of text: 0, or -1 (out of memory). */
int cf_strbuf_append(cf_strbuf *b, const char *text, size_t n);
/* Empties the buffer (keeps its memory and clears failed). */
void cf_strbuf_clear(cf_strbuf *b);
void cf_strbuf_free(cf_strbuf *b);

/* printf's "%.9g" of (double)f, the same characters, written into out
 * (size >= 24 for the fast path); the length. Nine digits read back to f
 * exactly. glibc's printf takes multi-precision arithmetic for every
 * number; this takes two 64-bit integer operations for the numbers of a
 * query line (magnitudes 1e-9 to 1e9) and gives the rest to snprintf. The
 * query lines of --impl are most of the suite's own time otherwise. */
int cf_format_g9(char *out, size_t size, float f);

#endif
