/* Rows of pbrt-v2's BSDF values and their comparison with a materia BSDF. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/pbrt_values.h"

int t_bsdf_row_parse(const char *line, t_bsdf_row *row)
{
    char buf[1024], *f[16], *p = buf;
    int n = 0;
    snprintf(buf, sizeof buf, "%s", line);
    buf[strcspn(buf, "\r\n")] = 0;
    while (n < 16) {
        f[n++] = p;
        p = strchr(p, ',');
        if (!p) break;
        *p++ = 0;
    }
    if (n < 16) return 0;
    memset(row, 0, sizeof *row);
    snprintf(row->id, sizeof row->id, "%.*s", (int)sizeof row->id - 1, f[0]);
    row->eval = !strcmp(f[1], "eval");
    for (n = 2; n < 16; ++n) row->v[n] = *f[n] ? atof(f[n]) : 0;
    return 1;
}

/* x rounded to float. The volatile is not decoration: GCC 12.2's SLP
 * vectorizer drops the pair of conversions in (double)(float)v[i] when two
 * such lanes are vectorized together (-O2; -fno-tree-slp-vectorize or clang
 * give the right answer), which silently un-rounds the inputs. */
static mt_real to_float(double x)
{
    volatile float f = (float)x;
    return f;
}

static int close_rel(double got, double want)
{
    return fabs(got - want) <= 1e-4 * fmax(fabs(got), fabs(want)) + 1e-9;
}

static int rgb_close(mt_rgb f, const double *v)
{
    return close_rel(f.c[0], v[11]) && close_rel(f.c[1], v[12]) && close_rel(f.c[2], v[13]);
}

int t_bsdf_row_agrees(const mt_bsdf *b, const t_bsdf_row *row, int show, double *dw)
{
    const double *v = row->v;
    mt_real in[9];
    mt_vec3 wo;
    int i, ok;
    /* pbrt-v2's inputs were floats: round them so the double build sees them */
    for (i = 0; i < 6; ++i) in[i] = to_float(v[2 + i]);
    for (i = 0; i < 3; ++i) in[6 + i] = to_float(v[8 + i]);
    wo = mt_v3(in[0], in[1], in[2]);
    if (dw) *dw = 0;
    if (row->eval) {
        mt_vec3 wi = mt_v3(in[3], in[4], in[5]);
        mt_rgb f = mt_bsdf_f(b, wo, wi, MT_BSDF_ALL);
        mt_real pdf = mt_bsdf_pdf(b, wo, wi, MT_BSDF_ALL);
        ok = rgb_close(f, v) && close_rel(pdf, v[14]);
        if (!ok && show)
            printf("  %s eval: f %.9g %.9g %.9g pdf %.9g; pbrt-v2 f %.9g %.9g %.9g pdf %.9g\n",
                   row->id, f.c[0], f.c[1], f.c[2], pdf, v[11], v[12], v[13], v[14]);
    } else {
        mt_bsdf_sample s = mt_bsdf_sample_f(b, wo, in[6], in[7], in[8], MT_BSDF_ALL);
        double d = fmax(fabs(s.wi.x - v[5]), fmax(fabs(s.wi.y - v[6]), fabs(s.wi.z - v[7])));
        if (dw) *dw = d;
        ok = d <= 1e-5 && rgb_close(s.f, v) && close_rel(s.pdf, v[14]) && (int)s.type == (int)v[15];
        if (!ok && show)
            printf("  %s sample: wi %.9g %.9g %.9g f %.9g pdf %.9g type %u; pbrt-v2 %.9g %.9g %.9g "
                   "f %.9g pdf %.9g type %d\n", row->id, s.wi.x, s.wi.y, s.wi.z, s.f.c[0], s.pdf,
                   s.type, v[5], v[6], v[7], v[11], v[14], (int)v[15]);
    }
    return ok;
}

void t_check_pbrt_rows(const char *id, const char *name, t_bsdf_builder build, void *ctx)
{
    const char *shared = t_shared_dir();
    char path[512], line[1024];
    FILE *fp;
    mt_arena *a;
    int rows = 0, bad = 0;
    if (!shared) {
        t_skip(name, "../shared is absent");
        return;
    }
    snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/bsdf-values.csv", shared);
    if (!(fp = fopen(path, "r"))) {
        t_fail(name, "cannot open %s", path);
        return;
    }
    a = mt_arena_create(0);
    while (fgets(line, sizeof line, fp)) {
        t_bsdf_row row;
        mt_bsdf *b;
        mt_error err;
        if (!t_bsdf_row_parse(line, &row) || strcmp(row.id, id)) continue;
        mt_arena_reset(a);
        if (!(b = build(ctx, a, &err))) {
            t_fail(name, "no BSDF: %s", err.message);
            bad = -1;
            break;
        }
        rows++;
        if (!t_bsdf_row_agrees(b, &row, bad < 3, NULL)) bad++;
    }
    fclose(fp);
    mt_arena_destroy(a);
    if (bad < 0) return;
    if (!MT_USE_DOUBLE)
        t_check(rows == 400 && bad == 0, name, "%d of %d rows differ", bad, rows);
    else
        t_skip(name, "double build: %d of %d rows agree to the float tolerances (the rest are "
               "ill-conditioned at float precision); the verdict is the float build's",
               rows - bad, rows);
}
