/*
 * materia-query: answers queries about materials and textures, one line in,
 * one line out (protocol in include/materia/tools/query.h and README.md). It never
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
#include "materia/tools/query.h"
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

/* --list materials|textures: the registered kinds, one a line, each
 * followed by what a script may need to tell them apart. */
static int list(const char *what)
{
    int i;
    if (!strcmp(what, "materials")) {
        for (i = 0; i < mt_material_kind_count(); ++i) {
            const mt_material_kind *k = mt_material_kind_at(i);
            printf("%s%s\n", mt_material_kind_name(k), mt_material_kind_has_bssrdf(k) ? " bssrdf" : "");
        }
    } else if (!strcmp(what, "textures")) {
        for (i = 0; i < mt_texture_kind_count(); ++i) {
            const mt_texture_kind *k = mt_texture_kind_at(i);
            printf("%s%s\n", mt_texture_kind_name(k), mt_texture_kind_has_float(k) ? " float" : "");
        }
    } else {
        fprintf(stderr, "materia-query: --list takes materials or textures, not \"%s\"\n", what);
        return 2;
    }
    return fflush(stdout) == 0 ? 0 : 1;
}

int main(int argc, char **argv)
{
    const char *dir = NULL;
    int radiance = 0;
    mt_query *q;
    mt_error err;
    static char out[MT_QUERY_ANSWER_SIZE];
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
        } else if (!strcmp(argv[i], "--list")) {
            if (i + 1 == argc) return tool_no_value("materia-query", argv[i]);
            return list(argv[i + 1]);
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: materia-query [--dir DIR] [--transport importance|radiance] < queries\n"
                   "       materia-query --list materials|textures\n"
                   "       materia-query --help | --version\n"
                   "Answers one line per query on standard output (docs/PROTOCOL.md; README.md, \"The\n"
                   "query tool\"); a bad line is answered \"error MESSAGE\" and the session goes on.\n"
                   "Warnings go to standard error as \"warning FILE:LINE: MESSAGE\". The mode is pbrt-v2\n"
                   "until a \"mode corrected\" line.\n"
                   "  --dir DIR     relative file names resolve against DIR (default: the current directory)\n"
                   "  --transport T importance (default: pbrt-v2's) or radiance: radiance scales specular\n"
                   "                transmission by (eta_t/eta_i)^2, as pbrt-v3 does\n"
                   "  --list WHAT   instead of a session: the registered material kinds (\"bssrdf\" after\n"
                   "                those with one) or texture classes (\"float\" after those with a float\n"
                   "                variant), one a line\n"
                   "  --help, -h    this text;  --version  materia's version, precision and image formats\n"
                   "Exit status: 0 at the end of the input, 1 error of the tool itself (out of memory,\n"
                   "output failed), 2 wrong command line.\n");
            return 0;
        } else if (!strcmp(argv[i], "--version")) {
            /* (mt_image_formats also links every format into the tool: imagemap
             * textures of a session read them) */
            printf("materia-query (materia) %s, %s, image formats %s\n", mt_version(), mt_precision(),
                   mt_image_formats());
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
    mt_query_announce_fast(q, 1); /* batched lines, hexadecimal numbers (docs/PROTOCOL.md) */
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
