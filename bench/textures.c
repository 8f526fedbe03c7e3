/*
 * Nanoseconds per evaluation of every texture class, float and spectrum
 * variants, over 4096 shading points with screen-space differentials (the
 * filtered paths are taken). Composites have constant children, so their
 * figure is their own cost plus two or three constant lookups. The image
 * map is measured with the MIP-map engineer's benchmarks.
 */
#include <time.h>
#include "support/tex_util.h"

#define NPTS 4096

static mt_diffgeom pts[NPTS];

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* The best of 5 runs of enough passes to take about 50 ms each. */
static void bench(const char *name, const mt_texture *t)
{
    volatile mt_real sink = 0;
    double best = 1e30;
    int run, pass, i, passes = 1;
    double t0 = now();
    for (i = 0; i < NPTS; ++i) sink += mt_texture_eval_rgb(t, &pts[i]).c[1];
    passes = (int)(0.05 / fmax(now() - t0, 1e-7)) + 1;
    for (run = 0; run < 5; ++run) {
        mt_real acc = 0;
        t0 = now();
        for (pass = 0; pass < passes; ++pass)
            for (i = 0; i < NPTS; ++i)
                acc += mt_texture_is_float(t) ? mt_texture_eval_float(t, &pts[i])
                                              : mt_texture_eval_rgb(t, &pts[i]).c[1];
        best = fmin(best, (now() - t0) / ((double)passes * NPTS));
        sink += acc;
    }
    printf("BENCH texture/%s/%s %.2f ns/eval\n", name, mt_texture_is_float(t) ? "float" : "spectrum",
           best * 1e9);
    (void)sink;
}

int main(void)
{
    mt_error err;
    mt_transform id = mt_transform_identity(), rot = mt_rotate(30, mt_v3(1, 1, 0));
    mt_map2d uv = mt__map2d_uv(4, 4, 0, 0), sph = mt__map2d_spherical(&rot, MT_MODE_PBRT_V2);
    mt_map3d m3 = mt__map3d(&id, MT_MODE_PBRT_V2);
    mt_rgb v[4] = {mt_rgb_gray(0), mt_rgb_make(1, 0, 0), mt_rgb_make(0, 1, 0), mt_rgb_gray(1)};
    mt_rng rng;
    int i, k;
    mt_rng_seed(&rng, 2024, 1);
    for (i = 0; i < NPTS; ++i) {
        mt_real u = mt_rng_uniform(&rng), w = mt_rng_uniform(&rng);
        pts[i] = tu_dg(u, w, mt_v3(4 * u - 2, 4 * w - 2, mt_rng_uniform(&rng)));
        pts[i].dudx = (mt_real)0.004 * mt_rng_uniform(&rng);
        pts[i].dvdy = (mt_real)0.004 * mt_rng_uniform(&rng);
        pts[i].dpdx = mt_v3((mt_real)0.01 * mt_rng_uniform(&rng), 0, 0);
        pts[i].dpdy = mt_v3(0, (mt_real)0.01 * mt_rng_uniform(&rng), 0);
    }
    for (k = 0; k <= 1; ++k) {
        mt_texture *a = tu_const(k, (mt_real)0.2, (mt_real)0.4, (mt_real)0.6);
        mt_texture *b = tu_const(k, (mt_real)0.9, (mt_real)0.5, (mt_real)0.1);
        mt_texture *amount = tu_const(1, (mt_real)0.3, 0, 0);
        struct {
            const char *name;
            mt_texture *t;
        } all[] = {
            {"constant", mt__tex_constant(k, v[1], 0, &err)},
            {"scale", mt__tex_scale(k, a, b, 0, &err)},
            {"mix", mt__tex_mix(k, a, b, amount, 0, &err)},
            {"bilerp", mt__tex_bilerp(k, &uv, v, 0, &err)},
            {"bilerp-spherical", mt__tex_bilerp(k, &sph, v, 0, &err)},
            {"uv", k ? NULL : mt__tex_uv(&uv, 0, &err)},
            {"checkerboard-none", mt__tex_checker2d(k, &uv, a, b, 0, 0, &err)},
            {"checkerboard-closedform", mt__tex_checker2d(k, &uv, a, b, 1, 0, &err)},
            {"checkerboard-3d", mt__tex_checker3d(k, &m3, a, b, 0, &err)},
            {"dots", mt__tex_dots(k, &uv, a, b, 0, &err)},
            {"fbm", mt__tex_fbm(k, &m3, 8, (mt_real)0.5, 0, &err)},
            {"wrinkled", mt__tex_wrinkled(k, &m3, 8, (mt_real)0.5, 0, &err)},
            {"windy", mt__tex_windy(k, &m3, 0, &err)},
            {"marble", k ? NULL : mt__tex_marble(&m3, 8, (mt_real)0.5, 1, (mt_real)0.2, 0, &err)},
        };
        for (i = 0; i < (int)(sizeof all / sizeof all[0]); ++i) {
            if (!all[i].t) continue;
            bench(all[i].name, all[i].t);
            mt_texture_destroy(all[i].t);
        }
        mt_texture_destroy(a);
        mt_texture_destroy(b);
        mt_texture_destroy(amount);
    }
    /* Perlin's noise itself, the unit of the noise textures' cost */
    {
        volatile mt_real sink = 0;
        double best = 1e30, t0;
        int run, pass;
        for (run = 0; run < 5; ++run) {
            mt_real acc = 0;
            t0 = now();
            for (pass = 0; pass < 50; ++pass)
                for (i = 0; i < NPTS; ++i) acc += mt__noise(pts[i].p.x, pts[i].p.y, pts[i].p.z);
            best = fmin(best, (now() - t0) / (50.0 * NPTS));
            sink += acc;
        }
        printf("BENCH texture/noise %.2f ns/eval\n", best * 1e9);
        (void)sink;
    }
    return 0;
}
