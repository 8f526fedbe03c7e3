/* Checks of MERL tables against the BSDF they were made from. */
#include <math.h>
#include <stdlib.h>
#include "support/check.h"
#include "support/merl_check.h"

#define TRIES 20000
#define T_PI 3.14159265358979323846

void t_merl_pair(double uh, double ud, double up, double phi_h, mt_vec3 *wo, mt_vec3 *wi)
{
    double c = cos(phi_h), sn = sin(phi_h);
    mt_vec3 o, i;
    mt_merl_directions(uh, ud, up, &o, &i);
    *wi = mt_v3((mt_real)(c * i.x - sn * i.y), (mt_real)(sn * i.x + c * i.y), i.z);
    *wo = mt_v3((mt_real)(c * o.x - sn * o.y), (mt_real)(sn * o.x + c * o.y), o.z);
}

static mt_rgb f_at(const mt_bsdf *b, double uh, double ud, double up, double phi_h)
{
    mt_vec3 wo, wi;
    t_merl_pair(uh, ud, up, phi_h, &wo, &wi);
    return mt_bsdf_f(b, wo, wi, MT_BSDF_ALL);
}

/* A random bin away from the degenerate regions: every corner's two
 * directions at least cos 0.05 above the horizon. */
static void pick_bin(mt_rng *r, int *ih, int *id, int *ip)
{
    for (;;) {
        int k, ok = 1;
        *ih = 8 + (int)mt_rng_bounded(r, MT_MERL_THETA_H - 8);
        *id = 2 + (int)mt_rng_bounded(r, MT_MERL_THETA_D - 2);
        *ip = (int)mt_rng_bounded(r, MT_MERL_PHI_D);
        for (k = 0; k < 8 && ok; ++k) {
            mt_vec3 wo, wi;
            t_merl_pair(*ih + (k & 1), *id + (k >> 1 & 1), *ip + (k >> 2 & 1), 0, &wo, &wi);
            ok = wo.z > 0.05 && wi.z > 0.05;
        }
        if (ok) return;
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void exact_in_bins(const char *prefix, const mt_bsdf *truth, const mt_bsdf *table, double off)
{
    mt_rng r;
    int n, c, bad = 0;
    double worst = 0;
    char name[160];
    mt_rng_seed(&r, 11, 1);
    for (n = 0; n < TRIES; ++n) {
        int ih, id, ip;
        mt_vec3 go, gi;
        mt_rgb want, got;
        pick_bin(&r, &ih, &id, &ip);
        mt_merl_directions(ih + off, id + off, ip + off, &go, &gi);
        want = mt_bsdf_f(truth, go, gi, MT_BSDF_ALL);
        got = f_at(table, ih + 0.1 + 0.8 * mt_rng_uniform_d(&r), id + 0.1 + 0.8 * mt_rng_uniform_d(&r),
                   ip + 0.1 + 0.8 * mt_rng_uniform_d(&r), 2 * T_PI * mt_rng_uniform_d(&r));
        for (c = 0; c < 3; ++c) {
            double e = t_reldiff(got.c[c], want.c[c], 1e-30);
            if (e > worst) worst = e;
            if (e > 4 * MT_REAL_EPSILON && bad++ < 3)
                printf("  bin (%d, %d, %d) channel %d: table %.9g, f at the sample point %.9g\n", ih,
                       id, ip, c, got.c[c], want.c[c]);
        }
    }
    snprintf(name, sizeof name, "%s: inside a bin the table gives f at its sample point", prefix);
    t_check(bad == 0, name, "%d of %d values differ beyond 4 ulps (worst %.3g relative)", bad,
            3 * TRIES, worst);
}

static void within_bin_variation(const char *prefix, const mt_bsdf *truth, const mt_bsdf *table, double off)
{
    mt_rng r;
    int n, c, k, bad = 0, m = 0;
    double worst = 0, sum = 0, *rel = malloc(3 * TRIES * sizeof *rel);
    char name[160];
    mt_rng_seed(&r, 12, 1);
    for (n = 0; n < TRIES && rel; ++n) {
        int ih, id, ip;
        double uh, ud, up;
        mt_rgb g, corner[8], t, f;
        pick_bin(&r, &ih, &id, &ip);
        uh = ih + 0.01 + 0.98 * mt_rng_uniform_d(&r);
        ud = id + 0.01 + 0.98 * mt_rng_uniform_d(&r);
        up = ip + 0.01 + 0.98 * mt_rng_uniform_d(&r);
        for (k = 0; k < 8; ++k) corner[k] = f_at(truth, ih + (k & 1), id + (k >> 1 & 1), ip + (k >> 2 & 1), 0);
        g = f_at(truth, ih + off, id + off, ip + off, 0);
        {
            double phi = 2 * T_PI * mt_rng_uniform_d(&r);
            t = f_at(table, uh, ud, up, phi);
            f = f_at(truth, uh, ud, up, phi);
        }
        for (c = 0; c < 3; ++c) {
            double v = 0, e = fabs(t.c[c] - f.c[c]);
            double tol = 8 * MT_REAL_EPSILON * fmax(fabs(g.c[c]), fabs(f.c[c]));
            for (k = 0; k < 8; ++k) v = fmax(v, fabs(corner[k].c[c] - g.c[c]));
            if (v > tol && e / v > worst) worst = e / v;
            if (e > v + tol && bad++ < 3)
                printf("  bin (%d, %d, %d) channel %d at (%.3f, %.3f, %.3f): error %.3g above the "
                       "corner variation %.3g\n", ih, id, ip, c, uh, ud, up, e, v);
            if (f.c[c] > 0) {
                rel[m++] = e / f.c[c];
                sum += e / f.c[c];
            }
        }
    }
    snprintf(name, sizeof name, "%s: |table - f| within the bin's corner variation", prefix);
    t_check(rel && bad == 0, name, "%d of %d values beyond it (worst error/variation %.3f)", bad,
            3 * TRIES, worst);
    if (rel && m > 0) {
        qsort(rel, (size_t)m, sizeof *rel, cmp_double);
        printf("  %s: relative error at random points of random bins (%d values): mean %.4g, "
               "median %.4g, 99%% %.4g, max %.4g; worst error/corner variation %.3f\n", prefix, m,
               sum / m, rel[m / 2], rel[(size_t)(0.99 * m)], rel[m - 1], worst);
    }
    free(rel);
}

/* Mean |table - f| at t times a random offset from the sample point to a
 * point of the bin. */
static double mean_error_at(const mt_bsdf *truth, const mt_bsdf *table, double off, double t)
{
    mt_rng r;
    int n, c;
    double sum = 0;
    mt_rng_seed(&r, 13, 1);
    for (n = 0; n < TRIES; ++n) {
        int ih, id, ip;
        double uh, ud, up, phi;
        mt_rgb a, b;
        pick_bin(&r, &ih, &id, &ip);
        /* corner: offsets in [0, 1), kept 1e-3 off the bin's edge */
        uh = ih + off + 1e-3 + t * (mt_rng_uniform_d(&r) - off);
        ud = id + off + 1e-3 + t * (mt_rng_uniform_d(&r) - off);
        up = ip + off + 1e-3 + t * (mt_rng_uniform_d(&r) - off);
        phi = 2 * T_PI * mt_rng_uniform_d(&r);
        a = f_at(table, uh, ud, up, phi);
        b = f_at(truth, uh, ud, up, phi);
        for (c = 0; c < 3; ++c) sum += fabs(a.c[c] - b.c[c]);
    }
    return sum / (3.0 * TRIES);
}

static void linear_in_offset(const char *prefix, const mt_bsdf *truth, const mt_bsdf *table, double off)
{
    double e2 = mean_error_at(truth, table, off, 0.2), e4 = mean_error_at(truth, table, off, 0.4);
    double e8 = mean_error_at(truth, table, off, 0.8), r2 = (e2 / 0.2) / (e8 / 0.8), r4 = (e4 / 0.4) / (e8 / 0.8);
    char name[160];
    printf("  %s: mean |table - f| at 0.2, 0.4, 0.8 of the way from the sample point: %.4g, %.4g, %.4g\n", prefix,
           e2, e4, e8);
    snprintf(name, sizeof name, "%s: the error is first order in the distance from the sample point", prefix);
    t_check(e8 > 0 && r2 > 0.8 && r2 < 1.05 && r4 > 0.8 && r4 < 1.05, name,
            "error per unit offset at 0.2 and 0.4 is %.3f and %.3f times that at 0.8 (want 0.8 to "
            "1.05)", r2, r4);
}

void t_merl_roundtrip_checks(const char *prefix, const mt_bsdf *truth, const mt_bsdf *table,
                             mt_merl_at at)
{
    double off = at == MT_MERL_AT_CENTRE ? 0.5 : 0;
    exact_in_bins(prefix, truth, table, off);
    within_bin_variation(prefix, truth, table, off);
    linear_in_offset(prefix, truth, table, off);
}
