/*
 * Shared by the command-line tools (included, not compiled on its own):
 * reading a number given to an option.
 */
#ifndef MT_TOOLS_TOOLARGS_H
#define MT_TOOLS_TOOLARGS_H

#include <stdio.h>
#include <stdlib.h>

/* The value s of option opt: the whole string must be a number in [lo, hi]
 * (and a whole number when whole is set). Prints "prog: opt needs ..." and
 * returns 0 otherwise. */
static int tool_number(const char *prog, const char *opt, const char *s, double lo, double hi,
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

#endif
