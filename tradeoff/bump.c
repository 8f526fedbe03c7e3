/*
 * Bump mapping's finite-difference step against the error of the shading
 * normal (tradeoff/6-bump.sh). pbrt-v2's Material::Bump (core/material.cpp)
 * differentiates the displacement by a forward difference with step du =
 * (|dudx| + |dudy|) / 2, or 0.01 when the hit has no ray differentials; here
 * the differentials are set so that du = dv = h and h is swept.
 *
 * The surface is the unit sphere P(u, v) = (sin th cos ph, sin th sin ph,
 * cos th), ph = 2 pi u, th = pi v (N = P, so dN/du = dP/du), displaced by
 *   d(u, v) = A (u + v) (2 - u - v),  A = 0.05,
 * built from materia's own textures: "scale" of two "bilerp" textures (u + v
 * and A (2 - u - v)). Its exact normal is that of S = P + d N, whose tangents
 * are S_u = (1 + d) P_u + d_u N and S_v = (1 + d) P_v + d_v N. The forward
 * difference's truncation error is h/2 d_uu = -A h (the error grows as h);
 * below some step the rounding of d(u + h) - d(u) (eps |d| / h) takes over.
 *
 * Output, CSV on stdout: step, median and maximum angle (radians) between
 * the bumped and the exact normal over the points, and the same with
 * MT_BUMP_DROP_DNDU (without the d dN/du terms, what many renderers do);
 * then "# cost" lines: ns per mt_bump call and per evaluation of the
 * displacement texture (CPU time of the thread, median of repetitions).
 *
 * usage: bump [NPOINTS]
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/bump.h"
#include "materia/state.h"
#include "support/timing.h"

#define T_PI 3.14159265358979323846
#define AMP 0.05

static const char scene[] =
    "Texture \"s\" \"float\" \"bilerp\" \"float v00\" [0] \"float v10\" [1] \"float v01\" [1] \"float v11\" [2] "
    "Texture \"r\" \"float\" \"bilerp\" \"float v00\" [0.1] \"float v10\" [0.05] \"float v01\" [0.05] "
    "\"float v11\" [0] "
    "Texture \"d\" \"float\" \"scale\" \"texture tex1\" \"s\" \"texture tex2\" \"r\"";

static double disp(double u, double v) { return AMP * (u + v) * (2 - u - v); }
static double disp_u(double u, double v) { return AMP * (2 - 2 * (u + v)); }

typedef struct vec {
    double x, y, z;
} vec;

static vec vadd(vec a, vec b) { vec r = {a.x + b.x, a.y + b.y, a.z + b.z}; return r; }
static vec vmul(vec a, double s) { vec r = {a.x * s, a.y * s, a.z * s}; return r; }
static double vdot(vec a, vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static double vlen(vec a) { return sqrt(vdot(a, a)); }
static vec vcross(vec a, vec b)
{
    vec r = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return r;
}
static mt_vec3 to_mt(vec a) { return mt_v3((mt_real)a.x, (mt_real)a.y, (mt_real)a.z); }

/* the angle between a and b, accurate for small angles (atan2 of |a x b|) */
static double angle(vec a, mt_vec3 b)
{
    vec bb = {b.x, b.y, b.z};
    return atan2(vlen(vcross(a, bb)), vdot(a, bb));
}

typedef struct point {
    double u, v;
    vec p, pu, pv, n_exact;
} point;

static point at(double u, double v)
{
    point s;
    double ph = 2 * T_PI * u, th = T_PI * v, d = disp(u, v), du = disp_u(u, v), dv = disp_u(u, v);
    vec su, sv;
    s.u = u;
    s.v = v;
    s.p.x = sin(th) * cos(ph);
    s.p.y = sin(th) * sin(ph);
    s.p.z = cos(th);
    s.pu.x = -2 * T_PI * sin(th) * sin(ph);
    s.pu.y = 2 * T_PI * sin(th) * cos(ph);
    s.pu.z = 0;
    s.pv.x = T_PI * cos(th) * cos(ph);
    s.pv.y = T_PI * cos(th) * sin(ph);
    s.pv.z = -T_PI * sin(th);
    su = vadd(vmul(s.pu, 1 + d), vmul(s.p, du));
    sv = vadd(vmul(s.pv, 1 + d), vmul(s.p, dv));
    s.n_exact = vcross(su, sv);
    s.n_exact = vmul(s.n_exact, (vdot(s.n_exact, s.p) < 0 ? -1 : 1) / vlen(s.n_exact));
    return s;
}

/* The shading point of s with differentials giving du = dv = h. */
static mt_diffgeom shading(const point *s, double h)
{
    mt_diffgeom dg = mt_diffgeom_default();
    dg.u = (mt_real)s->u;
    dg.v = (mt_real)s->v;
    dg.p = to_mt(s->p);
    dg.n = to_mt(s->p);
    dg.dpdu = to_mt(s->pu);
    dg.dpdv = to_mt(s->pv);
    dg.dndu = to_mt(s->pu);
    dg.dndv = to_mt(s->pv);
    dg.dudx = (mt_real)h;
    dg.dudy = (mt_real)-h;
    dg.dvdx = (mt_real)h;
    dg.dvdy = (mt_real)h;
    return dg;
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : a > b;
}

static volatile double sink;

static mt_status apply(void *ctx, const mt_statement *st, mt_error *err)
{
    int handled = 0;
    mt_status s = mt_state_apply(ctx, st, &handled, err);
    if (!s && !handled) s = mt_error_set(err, MT_ERR_UNSUPPORTED, "%s: not a texture statement", st->directive);
    return s;
}

int main(int argc, char **argv)
{
    int npts = argc > 1 ? atoi(argv[1]) : 1024, i, k, r;
    mt_state *state = mt_state_create(MT_MODE_PBRT_V2);
    const mt_texture *d;
    mt_error err;
    point *pts;
    double *e, *ed, tb[7], tt[7];
    mt_rng rng;
    if (npts < 8 || npts > 1 << 20) {
        fprintf(stderr, "bump: NPOINTS %s: not in 8..1048576\n", argv[1]);
        return 2;
    }
    mt_error_clear(&err);
    if (!state) return 1;
    if (mt_parse_string(scene, "displacement", ".", 1, NULL, apply, state, &err)) {
        char msg[512];
        mt_error_format(&err, msg, sizeof msg);
        fprintf(stderr, "bump: %s\n", msg);
        return 1;
    }
    d = mt_texture_table_get(mt_state_textures(state), "d", 1);
    pts = malloc(sizeof *pts * (size_t)npts);
    e = malloc(sizeof *e * (size_t)npts);
    ed = malloc(sizeof *ed * (size_t)npts);
    if (!d || !pts || !e || !ed) return 1;
    /* points away from the poles (where dP/du vanishes) and the u seam */
    mt_rng_seed(&rng, 6, 1);
    for (i = 0; i < npts; ++i) pts[i] = at(0.05 + 0.9 * mt_rng_uniform_d(&rng), 0.15 + 0.7 * mt_rng_uniform_d(&rng));

    printf("step,median_rad,max_rad,median_drop_dndu_rad,max_drop_dndu_rad\n");
    /* 4 steps per decade, 1e-9 to 10^-0.5 */
    for (k = -36; k <= -2; ++k) {
        double h = pow(10, k / 4.0);
        for (i = 0; i < npts; ++i) {
            mt_diffgeom dg = shading(&pts[i], h), out;
            mt_bump(d, &dg, &dg, &out, 0);
            e[i] = angle(pts[i].n_exact, out.n);
            mt_bump(d, &dg, &dg, &out, MT_BUMP_DROP_DNDU);
            ed[i] = angle(pts[i].n_exact, out.n);
        }
        qsort(e, (size_t)npts, sizeof *e, cmp_double);
        qsort(ed, (size_t)npts, sizeof *ed, cmp_double);
        printf("%.6g,%.6g,%.6g,%.6g,%.6g\n", h, e[npts / 2], e[npts - 1], ed[npts / 2], ed[npts - 1]);
    }

    /* cost: a bump (three evaluations of d and the frame) against one
     * evaluation, at pbrt-v2's default step */
    for (r = 0; r < 7; ++r) {
        double t0, s = 0;
        int loops = 64;
        t0 = t_cpu_now();
        for (k = 0; k < loops; ++k)
            for (i = 0; i < npts; ++i) {
                mt_diffgeom dg = shading(&pts[i], 0), out;
                mt_bump(d, &dg, &dg, &out, 0);
                s += out.n.x;
            }
        tb[r] = (t_cpu_now() - t0) * 1e9 / ((double)loops * npts);
        t0 = t_cpu_now();
        for (k = 0; k < loops; ++k)
            for (i = 0; i < npts; ++i) {
                mt_diffgeom dg = shading(&pts[i], 0);
                s += mt_texture_eval_float(d, &dg);
            }
        tt[r] = (t_cpu_now() - t0) * 1e9 / ((double)loops * npts);
        sink = s;
    }
    printf("# cost ns_per_bump %.4g\n", t_median(tb, 7));
    printf("# cost ns_per_texture_eval %.4g\n", t_median(tt, 7));
    printf("# points %d\n", npts);
    free(pts);
    free(e);
    free(ed);
    mt_state_destroy(state);
    return 0;
}
