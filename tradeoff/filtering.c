/*
 * filtering: error against time per lookup of the texture filters
 * (tradeoff/3-filtering.sh).
 *
 *   filtering --out DIR [--quick]
 *
 * A lookup is given a point (s, t) and its screen-space differentials d0 =
 * (ds/dx, dt/dx), d1 = (ds/dy, dt/dy), which pbrt-v2 scales to the spacing
 * of the samples (1/sqrt(spp) of a pixel's). The truth of a lookup is the
 * box average of the texture over the sample's own cell, the parallelogram
 * p + a d0 + b d1 with a, b in [-1/2, 1/2] -- what the average of many
 * unfiltered samples converges to, with a box pixel filter -- computed by
 * brute force in double (the midpoint rule on a fine grid, independent of
 * materia's filters). pbrt-v2's filters reach further (trilinear's square of
 * side 2 max|d|, the closed-form checkerboard's box of +-max|d|, EWA's
 * ellipse with the differentials as semi-axes): their error against the box
 * over a, b in [-1, 1] is reported beside it ("wide").
 *
 * Image map (DIR/3-filtering-imagemap.csv): a 512 x 512 periodic pattern
 * of eight plane waves, 2 to 205 cycles across the image (up to 0.4 cycles
 * a texel), amplitudes falling as 1/sqrt(frequency), values in [0, 1]. The continuous texture is the bilinear
 * interpolant of its texels (what a lookup without filtering reads). Modes
 * through the public MIP-map API (materia/mipmap.h), as pbrt-v2's imagemap
 * uses it: "none" (bilinear at level 0: mt_mipmap_lookup_width(m, s, t,
 * 0)), "trilinear" ("bool trilinear" "true": pbrt-v2 mode, width 2 max|d|),
 * "trilinear-corrected" (width max|d|, erratum trilinear-width fixed),
 * "ewa" at each "float maxanisotropy" from 1 to 64 (pbrt-v2's default
 * filter, maxanisotropy 8), and "supersampled" S x S (S = 2, 4, 8): the
 * bilinear level-0 value at the midpoints of an S x S grid over the cell,
 * what a caller gets by taking more samples instead.
 *
 * Checkerboard (DIR/3-filtering-checker.csv): pbrt-v2's float checkerboard
 * (tex1 1, tex2 0, checks of side 1 in (s, t)) through the public texture
 * API (mt_texture_create, mt_texture_eval_float): "none" and "closedform"
 * (its two aamodes; pbrt-v2 has no supersampling mode) and "supersampled"
 * S x S (S = 2, 4, 8, 16): aamode none at the midpoints of an S x S grid
 * over the cell.
 *
 * Footprints: for each footprint size (the major semi-axis |d0|: 0.25 to 64
 * texels; 0.01 to 3 checks) and anisotropy |d0| / |d1| (1 to 64), K
 * footprints at uniformly random points and orientations (d1 perpendicular
 * to d0). Error: the RMS over a group's footprints of lookup - truth (both
 * textures' values span [0, 1]). Time: ns per lookup on one thread, CPU time
 * (CLOCK_THREAD_CPUTIME_ID), the median of 3 runs of 8 passes over the
 * group's K lookups.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "materia.h"
#include "support/timing.h"
#include "materia/mipmap.h"

#define PI 3.14159265358979323846
#define TEX_N 512
#define PASSES 8
#define RUNS 3

typedef struct footprint {
    double s, t, d0s, d0t, d1s, d1t;
} footprint;

static void die(const char *what, const mt_error *err)
{
    char buf[512];
    if (err) mt_error_format(err, buf, sizeof buf);
    fprintf(stderr, "filtering: %s%s%s\n", what, err ? ": " : "", err ? buf : "");
    exit(1);
}

/* K footprints of major semi-axis len and the given anisotropy, (s, t) in
 * [0, 1)^2 scaled by `extent` (the image, or 8 checks). */
static void footprints(footprint *f, int k, double len, double aniso, double extent, mt_rng *rng)
{
    int i;
    for (i = 0; i < k; i++) {
        double th = 2 * PI * mt_rng_uniform_d(rng), minor = len / aniso;
        f[i].s = extent * mt_rng_uniform_d(rng);
        f[i].t = extent * mt_rng_uniform_d(rng);
        f[i].d0s = len * cos(th);
        f[i].d0t = len * sin(th);
        f[i].d1s = -minor * sin(th);
        f[i].d1t = minor * cos(th);
    }
}

/* The box average of fn over the parallelogram p + a d0 + b d1, a, b in
 * [-h, h], by the midpoint rule on an m0 x m1 grid. */
typedef double (*point_fn)(const void *ctx, double s, double t);

static double truth(point_fn fn, const void *ctx, const footprint *f, double h, int m0, int m1)
{
    double sum = 0;
    int i, j;
    for (i = 0; i < m0; i++) {
        double a = h * (2 * (i + 0.5) / m0 - 1);
        for (j = 0; j < m1; j++) {
            double b = h * (2 * (j + 0.5) / m1 - 1);
            sum += fn(ctx, f->s + a * f->d0s + b * f->d1s, f->t + a * f->d0t + b * f->d1t);
        }
    }
    return sum / ((double)m0 * m1);
}

/* The mean of lookup(ctx, s, t) at the midpoints of an n x n grid over the
 * sample's cell (a, b in [-1/2, 1/2]): supersampling by the caller. */
static double supersample(double (*lookup)(const void *ctx, double s, double t), const void *ctx,
                          const footprint *f, int n)
{
    double sum = 0;
    int i, j;
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            double a = (i + 0.5) / n - 0.5, b = (j + 0.5) / n - 0.5;
            sum += lookup(ctx, f->s + a * f->d0s + b * f->d1s, f->t + a * f->d0t + b * f->d1t);
        }
    return sum / ((double)n * n);
}

/* ---- the image map -------------------------------------------------------- */

typedef struct wave {
    int fx, fy;
    double a, phase;
} wave;

/* Eight waves; amplitudes 1/sqrt(|f|) (set in imagemap(), then scaled so
 * that values lie in [0, 1]): between a natural image's 1/|f| and the flat
 * spectrum of fine detail such as text or bricks. */
static wave waves[8] = {{2, 1, 0, 0.3},     {5, -3, 0, 1.1},    {11, 7, 0, 2.0},
                        {23, -17, 0, 0.7},  {47, 31, 0, 2.9},   {97, -61, 0, 1.6},
                        {151, 113, 0, 0.2}, {200, -45, 0, 2.4}};
static double wave_scale;

static double pattern(double x, double y)
{
    double v = 0;
    int k;
    for (k = 0; k < 8; k++)
        v += waves[k].a * cos(2 * PI * (waves[k].fx * x + waves[k].fy * y) + waves[k].phase);
    return 0.5 + wave_scale * v;
}

static int wrap(int i, int n)
{
    i %= n;
    return i < 0 ? i + n : i;
}

/* The bilinear interpolant of the level-0 texels, pbrt-v2's convention
 * (MIPMap::triangle: texel centres at (i + 1/2) / n, wrap repeat). */
static double bilinear(const void *ctx, double s, double t)
{
    const mt_image *img = ctx;
    double x = s * TEX_N - 0.5, y = t * TEX_N - 0.5, fx = floor(x), fy = floor(y), dx = x - fx,
           dy = y - fy;
    int x0 = wrap((int)fx, TEX_N), y0 = wrap((int)fy, TEX_N), x1 = wrap(x0 + 1, TEX_N),
        y1 = wrap(y0 + 1, TEX_N);
    const float *d = img->data;
    return (1 - dx) * (1 - dy) * d[y0 * TEX_N + x0] + dx * (1 - dy) * d[y0 * TEX_N + x1] +
           (1 - dx) * dy * d[y1 * TEX_N + x0] + dx * dy * d[y1 * TEX_N + x1];
}

enum { M_NONE, M_TRI, M_TRI_CORR, M_EWA, M_SS };

typedef struct imode {
    int kind, param;
    const char *name;
    mt_mipmap *m;
} imode;

static double level0(const void *m, double s, double t)
{
    return mt_mipmap_lookup_width(m, (mt_real)s, (mt_real)t, 0).c[0];
}

static double image_lookup(const imode *md, const footprint *f)
{
    if (md->kind == M_NONE) return mt_mipmap_lookup_width(md->m, (mt_real)f->s, (mt_real)f->t, 0).c[0];
    if (md->kind == M_SS) return supersample(level0, md->m, f, md->param);
    return mt_mipmap_lookup(md->m, (mt_real)f->s, (mt_real)f->t, (mt_real)f->d0s, (mt_real)f->d0t,
                            (mt_real)f->d1s, (mt_real)f->d1t)
        .c[0];
}

static volatile double sink;

/* The group's error against both truths and its ns per lookup. */
typedef double (*lookup_fn)(const void *mode, const footprint *f);

static void measure(lookup_fn fn, const void *mode, const footprint *f, const double *tf, const double *tp,
                    int k, double *err_wide, double *err_cell, double *ns)
{
    double ef = 0, ep = 0, t[RUNS];
    int i, r, p;
    for (i = 0; i < k; i++) {
        double v = fn(mode, &f[i]);
        ef += (v - tf[i]) * (v - tf[i]);
        ep += (v - tp[i]) * (v - tp[i]);
    }
    *err_wide = sqrt(ef / k);
    *err_cell = sqrt(ep / k);
    for (r = 0; r < RUNS; r++) {
        double s = 0, t0 = t_cpu_now();
        for (p = 0; p < PASSES; p++)
            for (i = 0; i < k; i++) s += fn(mode, &f[i]);
        t[r] = (t_cpu_now() - t0) / ((double)PASSES * k) * 1e9;
        sink += s;
    }
    *ns = t_median(t, RUNS);
}

static double image_lookup_fn(const void *mode, const footprint *f)
{
    return image_lookup(mode, f);
}

static int grid_points(double len_units, double per_unit, int lo, int hi)
{
    int m = (int)ceil(len_units * per_unit);
    if (m < lo) m = lo;
    if (m > hi) m = hi;
    return m + (m & 1);
}

static FILE *open_tmp(const char *dir, const char *name, char *path, size_t size)
{
    FILE *f;
    snprintf(path, size, "%s/%s.tmp", dir, name);
    f = fopen(path, "w");
    if (!f) die("cannot write a CSV file in the output folder", NULL);
    return f;
}

static void close_tmp(FILE *f, const char *path)
{
    char final[1100];
    if (fclose(f) != 0) die("writing a CSV file", NULL);
    snprintf(final, sizeof final, "%.*s", (int)(strlen(path) - 4), path);
    if (rename(path, final) != 0) die("renaming a CSV file", NULL);
}

static void imagemap(const char *out, int quick)
{
    static const double sizes_full[] = {0.25, 0.5, 1, 2, 4, 8, 16, 32, 64};
    static const double sizes_quick[] = {0.5, 2, 8, 32};
    static const double anisos_full[] = {1, 2, 4, 8, 16, 32, 64};
    static const double anisos_quick[] = {1, 4, 16, 64};
    const double *sizes = quick ? sizes_quick : sizes_full, *anisos = quick ? anisos_quick : anisos_full;
    int ns = quick ? 4 : 9, na = quick ? 4 : 7, k = quick ? 40 : 200;
    imode modes[16];
    int nm = 0, i, x, y, si, ai, mi;
    mt_image img;
    mt_error err;
    double amp = 0;
    footprint *fp = malloc(sizeof *fp * (size_t)k);
    double *tf = malloc(sizeof *tf * (size_t)k), *tp = malloc(sizeof *tp * (size_t)k);
    char path[1100];
    FILE *f;
    mt_rng rng;
    if (!fp || !tf || !tp) die("out of memory", NULL);
    for (i = 0; i < 8; i++) {
        waves[i].a = 1 / sqrt(sqrt((double)waves[i].fx * waves[i].fx + (double)waves[i].fy * waves[i].fy));
        amp += waves[i].a;
    }
    wave_scale = 0.5 / amp;
    if (mt_image_create(&img, TEX_N, TEX_N, 1, &err) != MT_OK) die("image", &err);
    for (y = 0; y < TEX_N; y++)
        for (x = 0; x < TEX_N; x++)
            img.data[y * TEX_N + x] = (float)pattern((x + 0.5) / TEX_N, (y + 0.5) / TEX_N);
    modes[nm++] = (imode){M_NONE, 0, "none", mt_mipmap_create(&img, 1, 8, MT_WRAP_REPEAT, MT_MODE_PBRT_V2, &err)};
    modes[nm++] = (imode){M_TRI, 0, "trilinear", mt_mipmap_create(&img, 1, 8, MT_WRAP_REPEAT, MT_MODE_PBRT_V2, &err)};
    modes[nm++] = (imode){M_TRI_CORR, 0, "trilinear-corrected",
                          mt_mipmap_create(&img, 1, 8, MT_WRAP_REPEAT, MT_MODE_CORRECTED, &err)};
    for (i = 1; i <= 64; i *= 2)
        modes[nm++] = (imode){M_EWA, i, "ewa", mt_mipmap_create(&img, 0, (mt_real)i, MT_WRAP_REPEAT, MT_MODE_PBRT_V2, &err)};
    for (i = 2; i <= 8; i *= 2) modes[nm++] = (imode){M_SS, i, "supersampled", modes[0].m};
    for (mi = 0; mi < nm; mi++)
        if (!modes[mi].m) die("MIP-map", &err);
    f = open_tmp(out, "3-filtering-imagemap.csv", path, sizeof path);
    fprintf(f, "mode,param,size_texels,aniso,rms_err,rms_err_wide,ns_per_lookup\n");
    mt_rng_seed(&rng, 31, 1);
    for (si = 0; si < ns; si++)
        for (ai = 0; ai < na; ai++) {
            double len = sizes[si] / TEX_N;
            int m0 = grid_points(sizes[si], 8, 16, 512), m1 = grid_points(sizes[si] / anisos[ai], 8, 16, 512);
            footprints(fp, k, len, anisos[ai], 1, &rng);
            for (i = 0; i < k; i++) {
                tp[i] = truth(bilinear, &img, &fp[i], 0.5, m0, m1);
                tf[i] = truth(bilinear, &img, &fp[i], 1, m0, m1);
            }
            for (mi = 0; mi < nm; mi++) {
                double ef, ep, t;
                measure(image_lookup_fn, &modes[mi], fp, tf, tp, k, &ef, &ep, &t);
                fprintf(f, "%s,%d,%g,%g,%.5g,%.5g,%.2f\n", modes[mi].name, modes[mi].param, sizes[si], anisos[ai], ep,
                        ef, t);
            }
        }
    fprintf(stderr, "filtering: image map done\n");
    close_tmp(f, path);
    for (mi = 0; mi < nm; mi++)
        if (modes[mi].kind != M_SS) mt_mipmap_destroy(modes[mi].m);
    mt_image_destroy(&img);
    free(fp);
    free(tf);
    free(tp);
}

/* ---- the checkerboard ----------------------------------------------------- */

static double check_point(const void *ctx, double s, double t)
{
    (void)ctx;
    return ((long)floor(s) + (long)floor(t)) % 2 == 0 ? 1.0 : 0.0;
}

typedef struct cmode {
    int kind, param; /* M_NONE (aamode none), M_TRI standing for closedform, M_SS */
    const char *name;
    const mt_texture *tex;
} cmode;

/* aamode none at one point (no differentials). */
static double check_none(const void *tex, double s, double t)
{
    mt_diffgeom dg = mt_diffgeom_default();
    dg.u = (mt_real)s;
    dg.v = (mt_real)t;
    return mt_texture_eval_float(tex, &dg);
}

static double check_lookup_fn(const void *mode, const footprint *f)
{
    const cmode *md = mode;
    mt_diffgeom dg = mt_diffgeom_default();
    if (md->kind == M_SS) return supersample(check_none, md->tex, f, md->param);
    dg.u = (mt_real)f->s;
    dg.v = (mt_real)f->t;
    dg.dudx = (mt_real)f->d0s;
    dg.dvdx = (mt_real)f->d0t;
    dg.dudy = (mt_real)f->d1s;
    dg.dvdy = (mt_real)f->d1t;
    return mt_texture_eval_float(md->tex, &dg);
}

static mt_texture *checkerboard(const char *aamode, mt_texture_table *table)
{
    mt_paramset *ps = mt_paramset_create();
    mt_param p = mt_param_string("aamode", aamode);
    mt_texparams tp;
    mt_error err;
    mt_texture *t;
    if (!ps) die("out of memory", NULL);
    if (mt_paramset_add(ps, &p, &err) != MT_OK) die("parameters", &err);
    tp.geom = ps;
    tp.material = NULL;
    tp.textures = table;
    tp.mode = MT_MODE_PBRT_V2;
    t = mt_texture_create("checkerboard", 1, NULL, &tp, &err);
    if (!t) die("checkerboard", &err);
    mt_paramset_destroy(ps);
    return t;
}

static void checker(const char *out, int quick)
{
    static const double sizes_full[] = {0.01, 0.03, 0.1, 0.3, 1, 3};
    static const double sizes_quick[] = {0.03, 0.3, 1};
    static const double anisos_full[] = {1, 2, 4, 8, 16, 32, 64};
    static const double anisos_quick[] = {1, 4, 16, 64};
    const double *sizes = quick ? sizes_quick : sizes_full, *anisos = quick ? anisos_quick : anisos_full;
    int ns = quick ? 3 : 6, na = quick ? 4 : 7, k = quick ? 30 : 150, nm = 0, i, si, ai, mi;
    int mgrid = quick ? 256 : 512;
    mt_texture_table *table = mt_texture_table_create();
    mt_texture *none, *closed;
    cmode modes[8];
    footprint *fp = malloc(sizeof *fp * (size_t)k);
    double *tf = malloc(sizeof *tf * (size_t)k), *tp = malloc(sizeof *tp * (size_t)k);
    char path[1100];
    FILE *f;
    mt_rng rng;
    if (!table || !fp || !tf || !tp) die("out of memory", NULL);
    none = checkerboard("none", table);
    closed = checkerboard("closedform", table);
    modes[nm++] = (cmode){M_NONE, 0, "none", none};
    modes[nm++] = (cmode){M_TRI, 0, "closedform", closed};
    for (i = 2; i <= 16; i *= 2) modes[nm++] = (cmode){M_SS, i, "supersampled", none};
    f = open_tmp(out, "3-filtering-checker.csv", path, sizeof path);
    fprintf(f, "mode,param,size_checks,aniso,rms_err,rms_err_wide,ns_per_lookup\n");
    mt_rng_seed(&rng, 32, 1);
    for (si = 0; si < ns; si++)
        for (ai = 0; ai < na; ai++) {
            footprints(fp, k, sizes[si], anisos[ai], 8, &rng);
            for (i = 0; i < k; i++) {
                tp[i] = truth(check_point, NULL, &fp[i], 0.5, mgrid, mgrid);
                tf[i] = truth(check_point, NULL, &fp[i], 1, mgrid, mgrid);
            }
            for (mi = 0; mi < nm; mi++) {
                double ef, ep, t;
                measure(check_lookup_fn, &modes[mi], fp, tf, tp, k, &ef, &ep, &t);
                fprintf(f, "%s,%d,%g,%g,%.5g,%.5g,%.2f\n", modes[mi].name, modes[mi].param, sizes[si], anisos[ai], ep,
                        ef, t);
            }
        }
    fprintf(stderr, "filtering: checkerboard done\n");
    close_tmp(f, path);
    mt_texture_destroy(none);
    mt_texture_destroy(closed);
    mt_texture_table_destroy(table);
    free(fp);
    free(tf);
    free(tp);
}

int main(int argc, char **argv)
{
    const char *out = NULL;
    int quick = 0, i;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "--quick")) quick = 1;
        else out = NULL, i = argc;
    }
    if (!out) {
        fprintf(stderr, "usage: filtering --out DIR [--quick]\n");
        return 2;
    }
    imagemap(out, quick);
    checker(out, quick);
    return 0;
}
