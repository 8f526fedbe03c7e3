/*
 * materia-query: answers queries about materials and textures, one line in,
 * one line out (protocol in include/materia/query.h and README.md). It never
 * stops on a bad line: it answers "error <message>" and goes on.
 *
 *   materia-query [--dir DIR] < queries > answers
 *
 * Warnings (parameters a statement did not use, redefinitions) go to standard
 * error as "warning FILE:LINE: MESSAGE"; standard output carries one answer
 * per query. Exit status 0, 1 on an error of the tool itself (out of memory,
 * output failed), 2 on a wrong command line.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/query.h"

static void warn(void *ctx, const char *file, int line, const char *msg)
{
    (void)ctx;
    fflush(stdout); /* keep the order when both streams go to one file */
    if (file && *file) fprintf(stderr, "warning %s:%d: %s\n", file, line, msg);
    else fprintf(stderr, "warning %s\n", msg);
}

int main(int argc, char **argv)
{
    const char *dir = NULL;
    mt_query *q;
    mt_error err;
    char *line = NULL, out[4096];
    size_t cap = 0;
    int i;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--dir") && i + 1 < argc)
            dir = argv[++i];
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: materia-query [--dir DIR] < queries\n"
                   "       materia-query --help | --version\n"
                   "Answers one line per query on standard output (see README.md, \"The query tool\");\n"
                   "relative file names resolve against DIR (default: the current directory).\n"
                   "Warnings go to standard error as \"warning FILE:LINE: MESSAGE\".\n");
            return 0;
        } else if (!strcmp(argv[i], "--version")) {
            printf("materia-query (materia) %s, %s\n", mt_version(), mt_precision());
            return 0;
        } else {
            fprintf(stderr, "%s: unknown argument \"%s\" (usage: %s [--dir DIR] < queries)\n", argv[0], argv[i], argv[0]);
            return 2;
        }
    }
    mt_error_clear(&err);
    if (!(q = mt_query_create(dir, &err))) {
        fprintf(stderr, "%s: %s\n", argv[0], err.message);
        return 1;
    }
    mt_query_set_warning(q, warn, NULL);
    for (;;) {
        /* getline-free line reading: C99 has only fgets */
        size_t len = 0;
        int got = 0;
        for (;;) {
            if (cap - len < 2) {
                char *n = realloc(line, cap ? 2 * cap : 4096);
                if (!n) {
                    fprintf(stderr, "%s: out of memory\n", argv[0]);
                    return 1;
                }
                line = n;
                cap = cap ? 2 * cap : 4096;
            }
            if (!fgets(line + len, (int)(cap - len), stdin)) break;
            got = 1;
            len += strlen(line + len);
            if (len && line[len - 1] == '\n') break;
        }
        if (!got) break;
        while (len && (line[len - 1] == '\n' || line[len - 1] == '\r')) line[--len] = 0;
        if (mt_query_line(q, line, out, sizeof out)) {
            puts(out);
            fflush(stdout);
        }
    }
    if (mt_query_finish(q, out, sizeof out)) puts(out);
    free(line);
    mt_query_destroy(q);
    return ferror(stdout) ? 1 : 0;
}
