/*
 * materia-query: answers queries about materials and textures, one line in,
 * one line out (protocol in include/materia/query.h and README.md). It never
 * stops on a bad line: it answers "error <message>" and goes on.
 *
 *   materia-query [--dir DIR] [--transport importance|radiance] < queries > answers
 *
 * --transport radiance turns on materia's radiance-transmission option
 * (MT_OPT_RADIANCE_TRANSMISSION: specular transmission scaled by
 * (eta_t/eta_i)^2, pbrt-v3's radiance mode) in both modes; the
 * "conventions" query says which.
 *
 * Warnings (parameters a statement did not use, redefinitions) go to standard
 * error as "warning FILE:LINE: MESSAGE"; standard output carries one answer
 * per query. Exit status 0, 1 on an error of the tool itself (out of memory,
 * output failed), 2 on a wrong command line.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "materia.h"
#include "materia/query.h"
#include "toolargs.h"

static void warn(void *ctx, const char *file, int line, const char *msg)
{
    (void)ctx;
    fflush(stdout); /* keep the order when both streams go to one file */
    if (file && *file) fprintf(stderr, "warning %s:%d: %s\n", file, line, msg);
    else fprintf(stderr, "warning %s\n", msg);
}

/* Standard input, read with read(2) into a buffer of our own so that the
 * tool knows when it has answered every line it has: it writes its answers
 * out then, before it waits for more input. A client that sends one line
 * and waits gets its answer at once; one that keeps the pipe full (a batch
 * of queries) gets the answers in large writes instead of one system call,
 * and one wake-up of the client, per answer. */
typedef struct reader {
    char *buf;
    size_t start, len, cap;
    int eof;
} reader;

/* The next line without its newline (NUL-terminated in the buffer, valid
 * until the next call), or NULL at the end of input; *oom on out of memory. */
static char *next_line(reader *r, int *oom)
{
    for (;;) {
        char *nl = r->len > r->start ? memchr(r->buf + r->start, '\n', r->len - r->start) : NULL;
        ssize_t got;
        if (nl) {
            char *l = r->buf + r->start;
            *nl = 0;
            r->start = (size_t)(nl - r->buf) + 1;
            return l;
        }
        if (r->eof) {
            char *l = r->buf + r->start;
            if (r->len == r->start) return NULL;
            r->buf[r->len] = 0; /* a last line without a newline (room kept below) */
            r->start = r->len;
            return l;
        }
        fflush(stdout); /* every line read is answered: out before waiting */
        if (r->start > 0) /* (before the first read there is no buffer yet) */
            memmove(r->buf, r->buf + r->start, r->len - r->start);
        r->len -= r->start;
        r->start = 0;
        if (r->cap - r->len < 4097) {
            size_t nc = r->cap ? 2 * r->cap : 1 << 16;
            char *n = realloc(r->buf, nc);
            if (!n) {
                *oom = 1;
                return NULL;
            }
            r->buf = n;
            r->cap = nc;
        }
        got = read(0, r->buf + r->len, r->cap - r->len - 1);
        if (got > 0)
            r->len += (size_t)got;
        else if (got == 0 || errno != EINTR)
            r->eof = 1; /* the end, or an input that cannot be read: the same */
    }
}

int main(int argc, char **argv)
{
    const char *dir = NULL;
    int radiance = 0;
    mt_query *q;
    mt_error err;
    char out[4096];
    reader in = {NULL, 0, 0, 0, 0};
    int i;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--dir")) {
            if (i + 1 == argc) return tool_no_value("materia-query", argv[i]);
            dir = argv[++i];
            if (!tool_directory("materia-query", "--dir", dir)) return 1;
        } else if (!strcmp(argv[i], "--transport")) {
            if (i + 1 == argc) return tool_no_value("materia-query", argv[i]);
            ++i;
            if (strcmp(argv[i], "importance") && strcmp(argv[i], "radiance")) {
                fprintf(stderr, "materia-query: --transport: \"%s\" is neither importance nor radiance\n", argv[i]);
                return 2;
            }
            radiance = !strcmp(argv[i], "radiance");
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: materia-query [--dir DIR] [--transport importance|radiance] < queries\n"
                   "       materia-query --help | --version\n"
                   "Answers one line per query on standard output (see README.md, \"The query tool\");\n"
                   "relative file names resolve against DIR (default: the current directory).\n"
                   "--transport radiance scales specular transmission by (eta_t/eta_i)^2 (radiance\n"
                   "transport, as pbrt-v3); the default is pbrt-v2's importance.\n"
                   "Warnings go to standard error as \"warning FILE:LINE: MESSAGE\".\n");
            return 0;
        } else if (!strcmp(argv[i], "--version")) {
            printf("materia-query (materia) %s, %s\n", mt_version(), mt_precision());
            return 0;
        } else {
            fprintf(stderr, "materia-query: unknown argument \"%s\" (usage: materia-query [--dir DIR] < queries)\n",
                    argv[i]);
            return 2;
        }
    }
    mt_error_clear(&err);
    if (!(q = mt_query_create(dir, &err))) {
        fprintf(stderr, "materia-query: %s\n", err.message);
        return 1;
    }
    mt_query_set_warning(q, warn, NULL);
    if (radiance) mt_query_set_options(q, MT_OPT_RADIANCE_TRANSMISSION);
    setvbuf(stdout, NULL, _IOFBF, 1 << 16);
    for (;;) {
        int oom = 0;
        char *line = next_line(&in, &oom);
        size_t len;
        if (oom) {
            fprintf(stderr, "materia-query: out of memory\n");
            return 1;
        }
        if (!line) break;
        len = strlen(line);
        while (len && line[len - 1] == '\r') line[--len] = 0;
        if (mt_query_line(q, line, out, sizeof out)) puts(out);
    }
    if (mt_query_finish(q, out, sizeof out)) puts(out);
    free(in.buf);
    mt_query_destroy(q);
    return fflush(stdout) || ferror(stdout) ? 1 : 0;
}
