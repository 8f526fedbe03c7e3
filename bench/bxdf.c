/*
 * BSDF throughput: ns per f, sample_f and pdf call for each BxDF
 * configuration, and for the default plastic, glass and substrate BSDFs that
 * ../shared/reference/README.md gives pbrt-v2's single-thread rates for
 * (both directions in the upper hemisphere). One thread, the median of
 * several repetitions of the thread's CPU time; make bench runs the float
 * and double builds in turn and prints the ratio.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include "materia.h"
#include "support/timing.h"

#define N 4096
#define REPS 7

typedef mt_status (*build_fn)(mt_arena *a, mt_bsdf **out, mt_error *err);

static mt_bsdf *new_bsdf(mt_arena *a, mt_real eta, mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    return mt_bsdf_create(a, MT_MODE_PBRT_V2, &dg, dg.n, eta, err);
}

#define M MT_MODE_PBRT_V2
#define ONE(expr)                                      \
    mt_bsdf *b = *out = new_bsdf(a, 1, err);           \
    if (!b) return err->status;                        \
    return mt_bsdf_add(b, (expr), err)

static mt_status lambertian(mt_arena *a, mt_bsdf **out, mt_error *err) { ONE(mt_lambertian_create(a, M, mt_rgb_gray(0.5f), err)); }
static mt_status orennayar(mt_arena *a, mt_bsdf **out, mt_error *err) { ONE(mt_orennayar_create(a, M, mt_rgb_gray(0.5f), 20, err)); }
static mt_status blinn(mt_arena *a, mt_bsdf **out, mt_error *err)
{
    ONE(mt_microfacet_create(a, M, mt_rgb_gray(1), mt_fresnel_dielectric(1, 1.5f), mt_blinn(10), err));
}
static mt_status aniso(mt_arena *a, mt_bsdf **out, mt_error *err)
{
    ONE(mt_microfacet_create(a, M, mt_rgb_gray(1), mt_fresnel_conductor(mt_rgb_make(0.2f, 0.9f, 1.1f), mt_rgb_make(3.9f, 2.4f, 2.2f)),
                             mt_anisotropic(10, 100), err));
}
static mt_status mirror(mt_arena *a, mt_bsdf **out, mt_error *err) { ONE(mt_specular_reflection_create(a, M, mt_rgb_gray(0.9f), mt_fresnel_noop(), err)); }
static mt_status btdf(mt_arena *a, mt_bsdf **out, mt_error *err)
{
    ONE(mt_brdf_to_btdf_create(a, M, mt_lambertian_create(a, M, mt_rgb_gray(0.5f), err), err));
}

/* The defaults of pbrt-v2's plastic, glass and substrate materials. */
static mt_status plastic(mt_arena *a, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, 1, err);
    mt_status st;
    if (!b) return err->status;
    if ((st = mt_bsdf_add(b, mt_lambertian_create(a, M, mt_rgb_gray(0.25f), err), err))) return st;
    return mt_bsdf_add(b, mt_microfacet_create(a, M, mt_rgb_gray(0.25f), mt_fresnel_dielectric(1.5f, 1), mt_blinn(10), err), err);
}
static mt_status glass(mt_arena *a, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, 1.5f, err);
    mt_status st;
    if (!b) return err->status;
    if ((st = mt_bsdf_add(b, mt_specular_reflection_create(a, M, mt_rgb_gray(1), mt_fresnel_dielectric(1, 1.5f), err), err)))
        return st;
    return mt_bsdf_add(b, mt_specular_transmission_create(a, M, mt_rgb_gray(1), 1, 1.5f, err), err);
}
static mt_status substrate(mt_arena *a, mt_bsdf **out, mt_error *err)
{
    ONE(mt_fresnelblend_create(a, M, mt_rgb_gray(0.5f), mt_rgb_gray(0.5f), mt_anisotropic(10, 10), err));
}

static mt_vec3 wo_[N], wi_[N];
static mt_real u_[N][3];
static volatile double sink;

/* ns per call of one operation over the N prepared queries, median of REPS */
static double time_op(const mt_bsdf *b, int op)
{
    double t[REPS];
    int r, i, loops = 32;
    for (r = 0; r < REPS; ++r) {
        double s = 0, t0 = t_cpu_now();
        int l;
        for (l = 0; l < loops; ++l)
            for (i = 0; i < N; ++i) {
                if (op == 0) {
                    s += mt_bsdf_f(b, wo_[i], wi_[i], MT_BSDF_ALL).c[1];
                } else if (op == 1) {
                    mt_bsdf_sample smp = mt_bsdf_sample_f(b, wo_[i], u_[i][0], u_[i][1], u_[i][2], MT_BSDF_ALL);
                    s += smp.pdf + smp.f.c[1];
                } else {
                    s += mt_bsdf_pdf(b, wo_[i], wi_[i], MT_BSDF_ALL);
                }
            }
        t[r] = (t_cpu_now() - t0) / ((double)loops * N) * 1e9;
        sink += s;
    }
    return t_median(t, REPS);
}

int main(void)
{
    static const struct {
        const char *name;
        build_fn build;
        double pbrt_f, pbrt_sample; /* pbrt-v2 calls per second (reference README) */
    } cases[] = {
        {"lambertian", lambertian, 0, 0},         {"orennayar", orennayar, 0, 0},
        {"microfacet_blinn", blinn, 0, 0},        {"microfacet_anisotropic", aniso, 0, 0},
        {"specular_reflection", mirror, 0, 0},    {"brdf_to_btdf", btdf, 0, 0},
        {"plastic_default", plastic, 1.25e7, 5.7e6}, {"glass_default", glass, 0, 1.85e7},
        {"substrate_default", substrate, 1.09e7, 4.2e6},
    };
    mt_arena *a = mt_arena_create(0);
    mt_rng rng;
    size_t c;
    int i;
    mt_rng_seed(&rng, 1, 2);
    for (i = 0; i < N; ++i) {
        wo_[i] = mt_uniform_sample_hemisphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng));
        wi_[i] = mt_uniform_sample_hemisphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng));
        u_[i][0] = mt_rng_uniform(&rng);
        u_[i][1] = mt_rng_uniform(&rng);
        u_[i][2] = mt_rng_uniform(&rng);
    }
    printf("BSDF calls, one thread, %s build (ns per call; pbrt-v2 rates from ../shared/reference/README.md)\n",
           mt_precision());
    for (c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        mt_bsdf *b;
        mt_error err;
        double tf, ts, tp;
        mt_arena_reset(a);
        if (cases[c].build(a, &b, &err)) {
            fprintf(stderr, "bench: %s: %s\n", cases[c].name, err.message);
            return 1;
        }
        tf = time_op(b, 0);
        ts = time_op(b, 1);
        tp = time_op(b, 2);
        printf("BENCH %s.f %.2f ns/call\n", cases[c].name, tf);
        printf("BENCH %s.sample_f %.2f ns/call\n", cases[c].name, ts);
        printf("BENCH %s.pdf %.2f ns/call\n", cases[c].name, tp);
        if (cases[c].pbrt_f > 0)
            printf("  %s f: %.3g calls/s = %.2fx pbrt-v2's %.3g\n", cases[c].name, 1e9 / tf, 1e9 / tf / cases[c].pbrt_f,
                   cases[c].pbrt_f);
        if (cases[c].pbrt_sample > 0)
            printf("  %s sample_f: %.3g calls/s = %.2fx pbrt-v2's %.3g\n", cases[c].name, 1e9 / ts,
                   1e9 / ts / cases[c].pbrt_sample, cases[c].pbrt_sample);
    }
    mt_arena_destroy(a);
    return 0;
}
