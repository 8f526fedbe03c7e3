/*
 * The extremes grid: every BxDF at the edges of its parameters -- cos theta
 * in {1, 1-1e-7, 1e-2, 1e-4, 1e-7, 0} and their negatives, roughness in
 * {0, 1e-6, 1e-3, 0.5, 1, 10} (Blinn exponents up to 1e4 and beyond), index
 * of refraction {1, 1+1e-6, 1.5, 4, 100} and inverses, conductor k in
 * {0, 1e-6, 100}, Oren-Nayar sigma {0, 1e-4, 90}, colours with zeros and
 * above 1 -- and directions that are not unit, zero, infinite or NaN. Every
 * answer must be finite and non-negative, and no floating-point exception
 * other than inexact or underflow may be raised (fetestexcept).
 */
#include <fenv.h>
#include <stdio.h>
#include <string.h>
#include "conformance.h"

#if defined(__clang__)
#pragma STDC FENV_ACCESS ON
#endif

#define BAD_FE (FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW)

static const double cosines[] = {1, 1 - 1e-7, 1e-2, 1e-4, 1e-7, 0, -1, -(1 - 1e-7), -1e-2, -1e-4, -1e-7, -0.0};
static const double roughness[] = {0, 1e-6, 1e-3, 0.5, 1, 10};
static const double etas[] = {1, 1 + 1e-6, 1.5, 4, 100, 1 / (1 + 1e-6), 1 / 1.5, 0.25, 0.01};
static const double ks[] = {0, 1e-6, 100};
static const double sigmas[] = {0, 1e-4, 90};

#define NDIR (sizeof cosines / sizeof cosines[0] * 3)

static void directions(mt_vec3 *d)
{
    size_t i;
    for (i = 0; i < NDIR; ++i) {
        double c = cosines[i / 3], s = sqrt(fmax(0, 1 - c * c)), phi = 0.3 + 2.1 * (double)(i % 3);
        d[i] = mt_v3((mt_real)(s * cos(phi)), (mt_real)(s * sin(phi)), (mt_real)c);
    }
}

typedef struct tally {
    long evals, bad;
    char first[160];
} tally;

static void note(tally *t, const char *what, const char *cfg)
{
    if (!t->bad++) snprintf(t->first, sizeof t->first, "%.60s: %.90s", cfg, what);
}

static int good_rgb(mt_rgb f) { return mt_rgb_is_finite(f) && mt_rgb_min(f) >= 0; }

/* Evaluates b over the grid and odd directions, counting violations. */
int cf_extreme_directions(mt_vec3 *d, int max)
{
    mt_vec3 all[NDIR];
    int i;
    directions(all);
    for (i = 0; i < (int)NDIR && i < max; ++i) d[i] = all[i];
    return i;
}

static void exercise(const mt_bsdf *b, const char *cfg, tally *t)
{
    static const mt_real us[] = {0, 0.25f, 0.5f, 0.999999f, MT_ONE_MINUS_EPSILON};
    mt_vec3 dirs[NDIR + 6];
    size_t i, j, k, l, m, nd = NDIR;
    mt_real nan = (mt_real)NAN, inf = (mt_real)INFINITY;
    directions(dirs);
    dirs[nd++] = mt_v3(0, 0, 0);
    dirs[nd++] = mt_v3(nan, 0, 1);
    dirs[nd++] = mt_v3(inf, 0, 1);
    dirs[nd++] = mt_v3(0, 0, 3);          /* not unit */
    dirs[nd++] = mt_v3(1e-30f, 0, 1e-30f); /* tiny */
    dirs[nd++] = mt_v3(1e30f, 1e30f, 0);   /* huge, in the tangent plane */
    feclearexcept(FE_ALL_EXCEPT);
    for (i = 0; i < nd; ++i) {
        for (j = 0; j < nd; ++j) {
            mt_rgb f = mt_bsdf_f(b, dirs[i], dirs[j], MT_BSDF_ALL);
            mt_real p = mt_bsdf_pdf(b, dirs[i], dirs[j], MT_BSDF_ALL);
            t->evals += 2;
            if (!good_rgb(f)) note(t, "f not finite or negative", cfg);
            if (!(p >= 0) || !mt_is_finite(p)) note(t, "pdf not finite or negative", cfg);
        }
        for (k = 0; k < 5; ++k)
            for (l = 0; l < 5; ++l)
                for (m = 0; m < 5; ++m) {
                    mt_bsdf_sample s = mt_bsdf_sample_f(b, dirs[i], us[k], us[l], us[m], MT_BSDF_ALL);
                    t->evals++;
                    if (!good_rgb(s.f) || !(s.pdf >= 0) || !mt_is_finite(s.pdf) || !mt_v3_is_finite(s.wi))
                        note(t, "sample not finite or negative", cfg);
                    else if (s.pdf > 0 && fabs(mt_v3_len(s.wi) - 1) > 1e-4)
                        note(t, "sampled direction not unit", cfg);
                }
        {
            mt_rng rng;
            mt_rgb r;
            mt_rng_seed(&rng, 3, 3);
            r = mt_bsdf_rho_hd(b, dirs[i], &rng, MT_BSDF_ALL, 2);
            t->evals++;
            if (!good_rgb(r)) note(t, "rho not finite or negative", cfg);
        }
    }
    if (fetestexcept(BAD_FE)) {
        char what[64];
        snprintf(what, sizeof what, "floating-point exception%s%s%s",
                 fetestexcept(FE_INVALID) ? " invalid" : "", fetestexcept(FE_DIVBYZERO) ? " divbyzero" : "",
                 fetestexcept(FE_OVERFLOW) ? " overflow" : "");
        note(t, what, cfg);
    }
}

typedef mt_bxdf *(*maker)(mt_arena *a, mt_mode m, int i, char *cfg, size_t n, mt_error *err);

static mt_rgb color_of(int i)
{
    static const float c[4][3] = {{1, 1, 1}, {0, 0.5f, 1}, {0, 0, 0}, {4, 1e-6f, 1e6f}};
    return mt_rgb_make(c[i % 4][0], c[i % 4][1], c[i % 4][2]);
}

static mt_bxdf *m_lambertian(mt_arena *a, mt_mode m, int i, char *cfg, size_t n, mt_error *err)
{
    if (i >= 4) return NULL;
    snprintf(cfg, n, "lambertian colour %d", i);
    return mt_lambertian_create(a, m, color_of(i), err);
}

static mt_bxdf *m_orennayar(mt_arena *a, mt_mode m, int i, char *cfg, size_t n, mt_error *err)
{
    if (i >= 3 * 4) return NULL;
    snprintf(cfg, n, "orennayar sigma %g colour %d", sigmas[i % 3], i / 3);
    return mt_orennayar_create(a, m, color_of(i / 3), (mt_real)sigmas[i % 3], err);
}

static mt_fresnel fresnel_of(int f)
{
    int nf = (int)(sizeof etas / sizeof etas[0]);
    if (f == 0) return mt_fresnel_noop();
    f--;
    if (f < nf) return mt_fresnel_dielectric(1, (mt_real)etas[f]);
    f -= nf;
    if (f < nf) return mt_fresnel_dielectric((mt_real)etas[f], 1);
    f -= nf;
    return mt_fresnel_conductor(mt_rgb_gray((mt_real)etas[f / 3 % nf]), mt_rgb_gray((mt_real)ks[f % 3]));
}

#define NFRESNEL (1 + 2 * 9 + 9 * 3)

static mt_bxdf *m_specular(mt_arena *a, mt_mode m, int i, char *cfg, size_t n, mt_error *err)
{
    int ne = (int)(sizeof etas / sizeof etas[0]);
    if (i < NFRESNEL) {
        snprintf(cfg, n, "specular reflection fresnel %d", i);
        return mt_specular_reflection_create(a, m, color_of(i), fresnel_of(i), err);
    }
    i -= NFRESNEL;
    if (i >= 2 * ne) return NULL;
    snprintf(cfg, n, "specular transmission %s eta %g", i < ne ? "1->" : "->1", etas[i % ne]);
    return i < ne ? mt_specular_transmission_create(a, m, color_of(i), 1, (mt_real)etas[i], err)
                  : mt_specular_transmission_create(a, m, color_of(i), (mt_real)etas[i - ne], 1, err);
}

static mt_distribution dist_of(int i, char *buf, size_t n)
{
    int nr = (int)(sizeof roughness / sizeof roughness[0]);
    mt_real r1 = (mt_real)roughness[i % nr], r2 = (mt_real)roughness[(i / nr) % nr];
    if (i < nr) {
        snprintf(buf, n, "blinn 1/%g", (double)r1);
        return mt_blinn(1 / r1);
    }
    if (i == nr) {
        snprintf(buf, n, "blinn 1e6");
        return mt_blinn(1e6f);
    }
    if (i == nr + 1) {
        snprintf(buf, n, "blinn NaN");
        return mt_blinn((mt_real)NAN);
    }
    snprintf(buf, n, "anisotropic 1/%g x 1/%g", (double)r1, (double)r2);
    return mt_anisotropic(1 / r1, 1 / r2);
}

#define NDIST (6 + 2 + 36)

static mt_bxdf *m_microfacet(mt_arena *a, mt_mode m, int i, char *cfg, size_t n, mt_error *err)
{
    char d[64];
    mt_distribution dist;
    if (i >= NDIST * NFRESNEL) return NULL;
    dist = dist_of(i % NDIST, d, sizeof d);
    snprintf(cfg, n, "microfacet %s fresnel %d", d, i / NDIST);
    return mt_microfacet_create(a, m, color_of(i), fresnel_of(i / NDIST), dist, err);
}

static mt_bxdf *m_fresnelblend(mt_arena *a, mt_mode m, int i, char *cfg, size_t n, mt_error *err)
{
    char d[64];
    mt_distribution dist;
    if (i >= NDIST * 4) return NULL;
    dist = dist_of(i % NDIST, d, sizeof d);
    snprintf(cfg, n, "fresnelblend %s colours %d", d, i / NDIST);
    return mt_fresnelblend_create(a, m, color_of(i / NDIST), color_of(i / NDIST + 1), dist, err);
}

static mt_bxdf *m_wrappers(mt_arena *a, mt_mode m, int i, char *cfg, size_t n, mt_error *err)
{
    char d[64];
    mt_distribution dist;
    if (i >= 2 * NDIST) return NULL;
    dist = dist_of(i % NDIST, d, sizeof d);
    if (i < NDIST) {
        snprintf(cfg, n, "scaled microfacet %s", d);
        return mt_scaled_bxdf_create(a, m, mt_microfacet_create(a, m, mt_rgb_gray(1), fresnel_of(3), dist, err),
                                     mt_rgb_make(0, 2, 0.5f), err);
    }
    snprintf(cfg, n, "brdf_to_btdf microfacet %s", d);
    return mt_brdf_to_btdf_create(a, m, mt_microfacet_create(a, m, mt_rgb_gray(1), fresnel_of(2), dist, err), err);
}

void cf_extreme_grid(cf_rows *rows)
{
    static const struct {
        const char *family;
        maker make;
    } families[] = {{"lambertian", m_lambertian}, {"orennayar", m_orennayar},
                    {"specular", m_specular},     {"microfacet", m_microfacet},
                    {"fresnelblend", m_fresnelblend}, {"scaled / brdf_to_btdf", m_wrappers}};
    size_t fi;
    int mi;
    for (mi = 0; mi < 2; ++mi) {
        mt_mode mode = mi ? MT_MODE_CORRECTED : MT_MODE_PBRT_V2;
        for (fi = 0; fi < sizeof families / sizeof families[0]; ++fi) {
            mt_arena *a = mt_arena_create(0);
            tally t;
            int i, configs = 0;
            cf_row r;
            memset(&t, 0, sizeof t);
            for (i = 0;; ++i) {
                char cfg[96];
                mt_error err;
                mt_diffgeom dg = mt_diffgeom_default();
                mt_bsdf *b;
                mt_bxdf *x;
                mt_arena_reset(a);
                mt_error_clear(&err);
                x = families[fi].make(a, mode, i, cfg, sizeof cfg, &err);
                if (!x && err.status == MT_OK) break; /* the family's grid is done */
                if (!x) {
                    note(&t, err.message, cfg);
                    continue;
                }
                configs++;
                /* in a BSDF twice: with ng = n, and with a tilted ng */
                b = mt_bsdf_create(a, mode, &dg, dg.n, 1.5f, &err);
                mt_bsdf_add(b, x, &err);
                exercise(b, cfg, &t);
                b = mt_bsdf_create(a, mode, &dg, mt_v3_normalize(mt_v3(0.6f, 0, 0.8f)), 1.5f, &err);
                mt_bsdf_add(b, x, &err);
                exercise(b, cfg, &t);
            }
            mt_arena_destroy(a);
            memset(&r, 0, sizeof r);
            snprintf(r.subject, sizeof r.subject, "extremes %s", families[fi].family);
            snprintf(r.mode, sizeof r.mode, "%s", mt_mode_name(mode));
            snprintf(r.check, sizeof r.check, "extremes");
            snprintf(r.statistic, sizeof r.statistic, "%ld violations in %ld calls, %d configurations",
                     t.bad, t.evals, configs);
            if (t.bad) snprintf(r.note, sizeof r.note, "first: %s", t.first);
            snprintf(r.bound, sizeof r.bound, "0 violations");
            r.verdict = t.bad ? CF_FAIL : CF_PASS;
            cf_rows_add(rows, &r);
        }
    }
}
