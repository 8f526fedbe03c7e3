/*
 * MIP-map filters: cost and error. For each filter -- point (bilinear at
 * level 0, no filtering), trilinear in corrected and pbrt-v2 mode, EWA --
 * the time per lookup on a 1024 x 1024 RGB texture over random footprints
 * (0.5 to 64 texels, anisotropy up to 16), and the error against the
 * reference filters of tests/support/mipref.c (the box of the footprint for
 * the isotropic filters, the Gaussian ellipse for EWA) on a smooth pattern
 * and on a 7-texel wave. Prints "BENCH name value unit".
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "materia/mipmap.h"
#include "support/mipref.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct lookup_args {
    mt_real s, t, w, d[4];
} lookup_args;

/* The best of five runs over the same lookups, in ns per lookup. */
static double time_filter(const mt_mipmap *m, int filter, const lookup_args *a, int n,
                          double *sink)
{
    double best = 1e30;
    int run, i;
    for (run = 0; run < 5; run++) {
        double t0 = now(), acc = 0;
        for (i = 0; i < n; i++) {
            mt_rgb r;
            if (filter == T_F_POINT)
                r = mt_mipmap_lookup_width(m, a[i].s, a[i].t, 0);
            else
                r = mt_mipmap_lookup(m, a[i].s, a[i].t, a[i].d[0], a[i].d[1], a[i].d[2], a[i].d[3]);
            acc += r.c[0] + r.c[1] + r.c[2];
        }
        t0 = now() - t0;
        *sink += acc;
        if (t0 < best) best = t0;
    }
    return 1e9 * best / n;
}

static const char *const keys[T_NFILTERS] = {"point", "trilinear", "trilinear_pbrt", "ewa"};

static void timings(void)
{
    enum { N = 1024, COUNT = 100000 };
    mt_image img;
    mt_mipmap *tri, *tri_pbrt, *ewa;
    lookup_args *a = malloc(sizeof *a * COUNT);
    t_pattern sm = t_pattern_smooth(), hf = t_pattern_high();
    mt_rng rng;
    double sink = 0;
    int i, x, y;
    mt_image_create(&img, N, N, 3, NULL);
    for (y = 0; y < N; y++)
        for (x = 0; x < N; x++) {
            double u = (x + 0.5) / N, v = (y + 0.5) / N;
            float *p = img.data + 3 * ((size_t)y * N + (size_t)x);
            p[0] = (float)t_pattern_value(&sm, u, v);
            p[1] = (float)t_pattern_value(&hf, u, v);
            p[2] = 0.5f * (p[0] + p[1]);
        }
    tri = mt_mipmap_create(&img, 1, 8, MT_WRAP_REPEAT, MT_MODE_CORRECTED, NULL);
    tri_pbrt = mt_mipmap_create(&img, 1, 8, MT_WRAP_REPEAT, MT_MODE_PBRT_V2, NULL);
    ewa = mt_mipmap_create(&img, 0, 8, MT_WRAP_REPEAT, MT_MODE_PBRT_V2, NULL);
    mt_rng_seed(&rng, 1, 1);
    for (i = 0; i < COUNT; i++) {
        double len = pow(2, 7 * mt_rng_uniform_d(&rng) - 1) / N,
               ratio = pow(2, -4 * mt_rng_uniform_d(&rng)),
               th = 6.283185307179586 * mt_rng_uniform_d(&rng);
        a[i].s = (mt_real)mt_rng_uniform_d(&rng);
        a[i].t = (mt_real)mt_rng_uniform_d(&rng);
        a[i].d[0] = (mt_real)(len * cos(th));
        a[i].d[1] = (mt_real)(len * sin(th));
        a[i].d[2] = (mt_real)(-len * ratio * sin(th));
        a[i].d[3] = (mt_real)(len * ratio * cos(th));
    }
    printf("BENCH mipmap_point_ns %.1f ns/lookup\n", time_filter(tri, T_F_POINT, a, COUNT, &sink));
    printf("BENCH mipmap_trilinear_ns %.1f ns/lookup\n", time_filter(tri, T_F_TRI, a, COUNT, &sink));
    printf("BENCH mipmap_trilinear_pbrt_ns %.1f ns/lookup\n",
           time_filter(tri_pbrt, T_F_TRI, a, COUNT, &sink));
    printf("BENCH mipmap_ewa_ns %.1f ns/lookup\n", time_filter(ewa, T_F_EWA, a, COUNT, &sink));
    {
        double t0 = now();
        mt_mipmap *m = mt_mipmap_create(&img, 0, 8, MT_WRAP_REPEAT, MT_MODE_PBRT_V2, NULL);
        printf("BENCH mipmap_build_1024_ms %.2f ms\n", 1e3 * (now() - t0));
        mt_mipmap_destroy(m);
    }
    if (sink == 42) printf("#\n"); /* keep the lookups */
    mt_mipmap_destroy(tri);
    mt_mipmap_destroy(tri_pbrt);
    mt_mipmap_destroy(ewa);
    mt_image_destroy(&img);
    free(a);
}

/* RMS and maximum error against the reference filters. */
static void errors(const char *name, t_pattern pat)
{
    enum { N = 256, NC = 16, PER = 25 };
    static t_footprint fp[NC * PER];
    mt_image img;
    mt_mipmap *m;
    int f, k;
    t_pattern_image(&pat, N, &img);
    m = mt_mipmap_create(&img, 0, 8, MT_WRAP_CLAMP, MT_MODE_PBRT_V2, NULL);
    t_footprints(fp, NC, PER, N, 8, 77);
    for (f = 0; f < T_NFILTERS; f++) {
        double sum2 = 0, mx = 0;
        for (k = 0; k < NC * PER; k++) {
            double e = fabs(t_filter_lookup(m, f, &fp[k]) - t_filter_reference(&img, f, &fp[k]).value);
            sum2 += e * e;
            if (e > mx) mx = e;
        }
        printf("BENCH mipmap_err_%s_%s_rms %.3e abs\n", name, keys[f], sqrt(sum2 / (NC * PER)));
        printf("BENCH mipmap_err_%s_%s_max %.3e abs\n", name, keys[f], mx);
    }
    mt_mipmap_destroy(m);
    mt_image_destroy(&img);
}

int main(void)
{
    timings();
    errors("smooth", t_pattern_smooth());
    errors("wave7", t_pattern_high());
    return 0;
}
