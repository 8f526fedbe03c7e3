/*
 * Helpers shared by the texture tests and the texture benchmark: shading
 * points, constant children, and the reference files' rows (header only;
 * includes the library's internal texture header).
 */
#ifndef MT_TEST_TEX_UTIL_H
#define MT_TEST_TEX_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "textures/noise.h"
#include "textures/tex.h"

/* The query protocol's shading point moved to (u, v) and p. */
static inline mt_diffgeom tu_dg(mt_real u, mt_real v, mt_vec3 p)
{
    mt_diffgeom dg = mt_diffgeom_default();
    dg.u = u;
    dg.v = v;
    dg.p = p;
    return dg;
}

static inline mt_texture *tu_const(int is_float, mt_real r, mt_real g, mt_real b)
{
    mt_error err;
    return mt__tex_constant(is_float, mt_rgb_make(r, g, b), MT_MODE_PBRT_V2, &err);
}

/* A value read from a reference file was a float in pbrt-v2: round it so
 * that the double build sees the same input. The volatile defeats GCC 12's
 * SLP vectorizer, which drops paired (double)(float) conversions. */
static inline mt_real tu_float(double x)
{
    volatile float f = (float)x;
    return f;
}

/* The screen-space differentials as the reference files order them:
 * dudx, dudy, dvdx, dvdy, dpdx (3), dpdy (3). */
static inline void tu_differentials(mt_diffgeom *dg, const mt_real *x)
{
    dg->dudx = x[0];
    dg->dudy = x[1];
    dg->dvdx = x[2];
    dg->dvdy = x[3];
    dg->dpdx = mt_v3(x[4], x[5], x[6]);
    dg->dpdy = mt_v3(x[7], x[8], x[9]);
}

/* Splits a CSV line in place; returns the number of fields (at most max). */
static inline int tu_split(char *line, char **field, int max)
{
    int n = 0;
    char *p = line;
    line[strcspn(line, "\r\n")] = 0;
    while (n < max) {
        field[n++] = p;
        p = strchr(p, ',');
        if (!p) break;
        *p++ = 0;
    }
    return n;
}

#endif
