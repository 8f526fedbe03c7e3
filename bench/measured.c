/*
 * Measured BRDFs: ns per f of pbrt-v2's IrregIsotropicBRDF (mystique.brdf
 * from ../shared when present, else 1439 synthetic samples of the same kind)
 * and RegularHalfangleBRDF (a MERL table of the default plastic), for both
 * directions in the upper hemisphere and, for the irregular BRDF, over the
 * whole sphere (where the search radius grows further); and the time to
 * read each format and to tabulate a BSDF at the MERL grid. One thread, the
 * median of several repetitions of the thread's CPU time (reading and
 * tabulating: wall time).
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include "materia.h"
#include "materia/tools/merl.h"
#include "support/check.h"
#include "support/tfiles.h"
#include "support/timing.h"

#define N 4096
#define REPS 7

static mt_vec3 wo_[N], wi_[N];
static volatile double sink;

static void directions(int upper)
{
    mt_rng rng;
    int i;
    mt_rng_seed(&rng, 7, 3);
    for (i = 0; i < N; ++i) {
        mt_real u[4];
        int k;
        for (k = 0; k < 4; ++k) u[k] = mt_rng_uniform(&rng);
        wo_[i] = upper ? mt_uniform_sample_hemisphere(u[0], u[1]) : mt_uniform_sample_sphere(u[0], u[1]);
        wi_[i] = upper ? mt_uniform_sample_hemisphere(u[2], u[3]) : mt_uniform_sample_sphere(u[2], u[3]);
    }
}

/* ns per mt_bxdf_f over the prepared pairs, median of REPS */
static double time_f(const mt_bxdf *b, int loops)
{
    double t[REPS];
    int r, i, l;
    for (r = 0; r < REPS; ++r) {
        double s = 0, t0 = t_cpu_now();
        for (l = 0; l < loops; ++l)
            for (i = 0; i < N; ++i) s += mt_bxdf_f(b, wo_[i], wi_[i]).c[1];
        t[r] = (t_cpu_now() - t0) / ((double)loops * N) * 1e9;
        sink += s;
    }
    return t_median(t, REPS);
}

/* 1439 samples spread as the Cornell files spread theirs. */
static mt_measured *synthetic(mt_error *err)
{
    enum { S = 1439 };
    static mt_vec3 wo[S], wi[S];
    static mt_rgb v[S];
    mt_rng rng;
    int i;
    mt_rng_seed(&rng, 9, 1);
    for (i = 0; i < S; ++i) {
        mt_real theta = 0.17f + 1.2f * mt_rng_uniform(&rng);
        wi[i] = mt_spherical_direction(mt_sin(theta), mt_cos(theta), 0);
        wo[i] = mt_uniform_sample_hemisphere(mt_rng_uniform(&rng), 0.97f * mt_rng_uniform(&rng));
        v[i] = mt_rgb_gray(mt_rng_uniform(&rng));
    }
    return mt_measured_irregular_create(wo, wi, v, S, err);
}

static mt_bsdf *plastic(mt_arena *a, mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *b = mt_bsdf_create(a, MT_MODE_PBRT_V2, &dg, dg.n, 1, err);
    if (!b || mt_bsdf_add(b, mt_lambertian_create(a, MT_MODE_PBRT_V2, mt_rgb_gray(0.25f), err), err) ||
        mt_bsdf_add(b, mt_microfacet_create(a, MT_MODE_PBRT_V2, mt_rgb_gray(0.25f), mt_fresnel_dielectric(1.5f, 1),
                                            mt_blinn(10), err), err))
        return NULL;
    return b;
}

int main(void)
{
    mt_arena *a = mt_arena_create(0);
    mt_error err;
    mt_measured *irr, *merl = NULL;
    mt_bsdf *pl = plastic(a, &err);
    double *values = malloc(3 * (size_t)MT_MERL_SAMPLES * sizeof *values), t0, t_tab = 0, t_read = 0, t_brdf = 0;
    const char *shared = t_shared_dir(), *dir = t_tmpdir_create("bench-measured");
    char path[1024];
    if (!pl || !values || !dir) {
        fprintf(stderr, "bench: setup failed\n");
        return 1;
    }
    if (shared) {
        snprintf(path, sizeof path, "%s/reference/scenes/brdfs/mystique.brdf", shared);
        t0 = t_now();
        irr = mt_measured_load(path, &err);
        t_brdf = t_now() - t0;
    } else {
        irr = synthetic(&err);
    }
    snprintf(path, sizeof path, "%s/plastic.binary", dir);
    t0 = t_now();
    if (irr && mt_merl_tabulate(pl, MT_MERL_AT_CORNER, values, &err) == MT_OK) {
        t_tab = t_now() - t0;
        if (mt_merl_write(path, values, &err) == MT_OK) {
            t0 = t_now();
            merl = mt_measured_load(path, &err);
            t_read = t_now() - t0;
        }
    }
    remove(path);
    t_tmpdir_remove();
    if (!irr || !merl) {
        fprintf(stderr, "bench: %s\n", err.message);
        return 1;
    }
    printf("Measured BRDFs, one thread, %s build (ns per f; irregular data: %s)\n", mt_precision(),
           shared ? "mystique.brdf" : "1439 synthetic samples");
    directions(1);
    printf("BENCH irregular_isotropic.f %.1f ns/call\n",
           time_f(mt_irregular_isotropic_brdf_create(a, MT_MODE_PBRT_V2, irr, &err), 4));
    printf("BENCH regular_halfangle.f %.1f ns/call\n",
           time_f(mt_regular_halfangle_brdf_create(a, MT_MODE_PBRT_V2, merl, &err), 32));
    directions(0);
    printf("BENCH irregular_isotropic.f_sphere %.1f ns/call\n",
           time_f(mt_irregular_isotropic_brdf_create(a, MT_MODE_PBRT_V2, irr, &err), 2));
    if (shared) printf("BENCH brdf_file_read %.1f ms\n", 1e3 * t_brdf);
    printf("BENCH merl_file_read %.1f ms\n", 1e3 * t_read);
    printf("BENCH merl_tabulate_plastic %.1f ms\n", 1e3 * t_tab);
    mt_measured_destroy(irr);
    mt_measured_destroy(merl);
    mt_measured_cache_clear();
    free(values);
    mt_arena_destroy(a);
    return 0;
}
