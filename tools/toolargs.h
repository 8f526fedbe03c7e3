/*
 * Shared by the command-line tools (included, not compiled on its own):
 * reading a number given to an option, an option given without its value,
 * a directory given to an option.
 */
#ifndef MT_TOOLS_TOOLARGS_H
#define MT_TOOLS_TOOLARGS_H

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The value s of option opt: the whole string must be a number in [lo, hi]
 * (and a whole number when whole is set). Prints "prog: opt needs ..." and
 * returns 0 otherwise. */
static inline int tool_number(const char *prog, const char *opt, const char *s, double lo, double hi,
                       int whole, double *out)
{
    char *end;
    double v = s ? strtod(s, &end) : 0;
    if (!s || end == s || *end || !(v >= lo && v <= hi) || (whole && v != (double)(long)v)) {
        fprintf(stderr, "%s: %s needs a %s between %g and %g, not \"%s\"\n", prog, opt,
                whole ? "whole number" : "number", lo, hi, s ? s : "");
        return 0;
    }
    *out = v;
    return 1;
}

/* An option that takes a value came last: prints "prog: opt needs a value"
 * and returns 2 (a wrong command line). */
static inline int tool_no_value(const char *prog, const char *opt)
{
    fprintf(stderr, "%s: %s needs a value\n", prog, opt);
    return 2;
}

/* 1 when path (the value of option opt) is a directory; else prints why,
 * naming the option and the path, and returns 0. */
static inline int tool_directory(const char *prog, const char *opt, const char *path)
{
    struct stat sb;
    if (stat(path, &sb) != 0) {
        fprintf(stderr, "%s: %s \"%s\": %s\n", prog, opt, path, strerror(errno));
        return 0;
    }
    if (!S_ISDIR(sb.st_mode)) {
        fprintf(stderr, "%s: %s \"%s\": not a directory\n", prog, opt, path);
        return 0;
    }
    return 1;
}

#endif
