/*
 * Every texture class against its definition: constant, uv, bilerp and the
 * unfiltered checkerboard analytically; scale and mix compositions; dots and
 * the 3D checkerboard against pbrt-v2's definitions (including the mode
 * bits); the mappings; Perlin noise against its defining properties and
 * values worked out by hand; FBm's and Turbulence's weights and octave
 * clamp; marble at t = 1; the named-texture table; argument checks; and
 * bit-identical results across threads.
 */
#include <pthread.h>
#include "support/tex_util.h"

#define T_PI 3.14159265358979323846
#define PV2 MT_MODE_PBRT_V2
#define FIXED MT_MODE_CORRECTED

static mt_error err;

static void test_constant(void)
{
    mt_texture *f = mt_texture_constant_float((mt_real)0.37, &err);
    mt_texture *c = mt_texture_constant_rgb(mt_rgb_make(1, (mt_real)0.5, (mt_real)0.25), &err);
    mt_diffgeom dg = tu_dg((mt_real)0.3, (mt_real)-7, mt_v3(5, -2, 1e3f));
    mt_rgb v = mt_texture_eval_rgb(c, &dg);
    t_check(mt_texture_eval_float(f, &dg) == (mt_real)0.37 && mt_texture_is_float(f) &&
                !strcmp(mt_texture_class(f), "constant"),
            "constant: float value everywhere", "%g", (double)mt_texture_eval_float(f, &dg));
    t_check(v.c[0] == 1 && v.c[1] == (mt_real)0.5 && v.c[2] == (mt_real)0.25 &&
                !mt_texture_is_float(c),
            "constant: spectrum value everywhere", "%g %g %g", (double)v.c[0], (double)v.c[1],
            (double)v.c[2]);
    /* cross-type reads: gray, and pbrt-v2's luminance y() */
    v = mt_texture_eval_rgb(f, &dg);
    t_check(v.c[0] == (mt_real)0.37 && v.c[2] == (mt_real)0.37 &&
                mt_texture_eval_float(c, &dg) == mt_rgb_y(mt_rgb_make(1, (mt_real)0.5, (mt_real)0.25)),
            "constant: float read as gray, spectrum read as luminance", "%g", (double)v.c[0]);
    t_check(mt_texture_constant_float((mt_real)NAN, &err) == NULL && err.status == MT_ERR_INVALID,
            "constant: NaN rejected", "accepted");
    mt_texture_destroy(f);
    mt_texture_destroy(c);
}

/* uv: (su u + du - floor, sv v + dv - floor, 0), also for negative u. */
static void test_uv(void)
{
    mt_map2d m = mt__map2d_uv(3, (mt_real)0.5, (mt_real)0.25, -1);
    mt_texture *t = mt__tex_uv(&m, PV2, &err);
    double worst = 0;
    int i, j;
    for (i = -8; i <= 8; ++i)
        for (j = -8; j <= 8; ++j) {
            mt_real u = (mt_real)i * (mt_real)0.37, v = (mt_real)j * (mt_real)0.61;
            mt_diffgeom dg = tu_dg(u, v, mt_v3(0, 0, 0));
            mt_rgb r = mt_texture_eval_rgb(t, &dg);
            double s = 3.0 * u + 0.25, tt = 0.5 * v - 1;
            double ws = s - floor(s), wt = tt - floor(tt);
            /* the wrap may land on 1 - ulp instead of 0 near an integer */
            double ds = fmin(fabs(r.c[0] - ws), fabs(fabs(r.c[0] - ws) - 1));
            double dt = fmin(fabs(r.c[1] - wt), fabs(fabs(r.c[1] - wt) - 1));
            worst = fmax(worst, fmax(fmax(ds, dt), fabs(r.c[2])));
        }
    t_check(worst < 1e-5, "uv: fractional parts of the scaled, shifted (u, v)", "error %g", worst);
    t_check(!mt_texture_is_float(t) && !strcmp(mt_texture_class(t), "uv"),
            "uv: a spectrum texture", "-");
    mt_texture_destroy(t);
}

/* bilerp: the corners are v00 (0,0), v01 (0,1), v10 (1,0), v11 (1,1); inside
 * it is the bilinear interpolation, outside its extrapolation. */
static void test_bilerp(void)
{
    mt_rgb v[4] = {mt_rgb_make((mt_real)0.1, 0, 1), mt_rgb_make((mt_real)0.7, 1, 0),
                   mt_rgb_make((mt_real)-0.3, 2, 0), mt_rgb_make((mt_real)1.2, 3, 1)};
    mt_map2d m = mt__map2d_uv(1, 1, 0, 0);
    mt_texture *t = mt__tex_bilerp(0, &m, v, PV2, &err), *f = mt__tex_bilerp(1, &m, v, PV2, &err);
    double worst = 0;
    int i, k;
    for (i = 0; i < 200; ++i) {
        double s = -0.5 + 2.0 * (i % 20) / 19.0, tt = -0.5 + 2.0 * (i / 20) / 9.0;
        mt_diffgeom dg = tu_dg((mt_real)s, (mt_real)tt, mt_v3(0, 0, 0));
        mt_rgb r = mt_texture_eval_rgb(t, &dg);
        s = dg.u;
        tt = dg.v;
        for (k = 0; k < 3; ++k) {
            double want = (1 - s) * (1 - tt) * v[0].c[k] + (1 - s) * tt * v[1].c[k] +
                          s * (1 - tt) * v[2].c[k] + s * tt * v[3].c[k];
            worst = fmax(worst, fabs(r.c[k] - want));
        }
        worst = fmax(worst, fabs(mt_texture_eval_float(f, &dg) - r.c[0]));
    }
    t_check(worst < 4e-6, "bilerp: bilinear in (s, t), corners v00 v01 v10 v11", "error %g", worst);
    mt_texture_destroy(t);
    mt_texture_destroy(f);
}

/* The point-sampled checkerboard: tex1 where floor(s) + floor(t) is even. */
static void test_checker_unfiltered(void)
{
    mt_map2d m = mt__map2d_uv(4, 3, (mt_real)0.5, 0);
    mt_texture *one = tu_const(1, 1, 1, 1), *zero = tu_const(1, 0, 0, 0);
    mt_texture *none = mt__tex_checker2d(1, &m, one, zero, 0, PV2, &err);
    mt_texture *cf = mt__tex_checker2d(1, &m, one, zero, 1, PV2, &err);
    int bad = 0, bad_cf = 0, i;
    mt_rng rng;
    mt_rng_seed(&rng, 1, 2);
    for (i = 0; i < 4000; ++i) {
        mt_real u = (mt_real)(mt_rng_uniform_d(&rng) * 20 - 10);
        mt_real v = (mt_real)(mt_rng_uniform_d(&rng) * 20 - 10);
        mt_diffgeom dg = tu_dg(u, v, mt_v3(0, 0, 0));
        mt_real s = 4 * u + (mt_real)0.5, t = 3 * v;
        long sum = (long)floor(s) + (long)floor(t);
        mt_real want = sum % 2 == 0 ? 1 : 0;
        if (mt_texture_eval_float(none, &dg) != want) bad++;
        /* closedform without differentials is the point sample */
        if (mt_texture_eval_float(cf, &dg) != want) bad_cf++;
        /* aamode none ignores any footprint */
        dg.dudx = dg.dvdy = (mt_real)0.3;
        if (mt_texture_eval_float(none, &dg) != want) bad++;
    }
    t_check(bad == 0, "checkerboard 2D none: tex1 on even floor(s) + floor(t)", "%d wrong", bad);
    t_check(bad_cf == 0, "checkerboard 2D closedform: point sample without differentials",
            "%d wrong", bad_cf);
    mt_texture_destroy(none);
    mt_texture_destroy(cf);
    mt_texture_destroy(one);
    mt_texture_destroy(zero);
}

/* scale and mix: the products and blends of their children, nested. */
static void test_compositions(void)
{
    mt_rgb v[4] = {mt_rgb_gray(0), mt_rgb_gray(1), mt_rgb_gray((mt_real)0.5),
                   mt_rgb_gray((mt_real)0.25)};
    mt_map2d m = mt__map2d_uv(1, 1, 0, 0), m4 = mt__map2d_uv(4, 4, 0, 0);
    mt_texture *amount = mt__tex_bilerp(1, &m, v, PV2, &err);
    mt_texture *a = tu_const(0, 1, (mt_real)0.5, (mt_real)0.25);
    mt_texture *b = tu_const(0, 0, (mt_real)0.2, (mt_real)0.4);
    mt_texture *two = tu_const(0, 2, 1, (mt_real)0.5);
    mt_texture *checker = mt__tex_checker2d(0, &m4, a, b, 0, PV2, &err);
    mt_texture *sc = mt__tex_scale(0, checker, two, PV2, &err);
    mt_texture *mx = mt__tex_mix(0, sc, a, amount, PV2, &err);
    mt_texture *fs = mt__tex_scale(1, amount, amount, PV2, &err);
    double worst = 0, worst_f = 0;
    int i, k;
    for (i = 0; i < 400; ++i) {
        mt_diffgeom dg = tu_dg((mt_real)(i % 20) / 19, (mt_real)(i / 20) / 19, mt_v3(0, 0, 0));
        mt_rgb c = mt_texture_eval_rgb(checker, &dg), s = mt_texture_eval_rgb(sc, &dg);
        mt_rgb x = mt_texture_eval_rgb(mx, &dg), av = mt_texture_eval_rgb(a, &dg);
        mt_real w = mt_texture_eval_float(amount, &dg);
        for (k = 0; k < 3; ++k) {
            double tw = k == 0 ? 2 : k == 1 ? 1 : 0.5;
            worst = fmax(worst, fabs(s.c[k] - c.c[k] * tw));
            worst = fmax(worst, fabs(x.c[k] - ((1 - w) * s.c[k] + w * av.c[k])));
        }
        worst_f = fmax(worst_f, fabs(mt_texture_eval_float(fs, &dg) - w * w));
    }
    t_check(worst < 1e-6, "scale and mix: products and blends of their children, nested",
            "error %g", worst);
    t_check(worst_f == 0, "scale: float variant multiplies", "error %g", worst_f);
    mt_texture_destroy(mx);
    mt_texture_destroy(sc);
    mt_texture_destroy(checker);
    mt_texture_destroy(fs);
    /* the children are still referenced by nothing but these: releasing the
     * composites first must not have freed them (ASan checks this) */
    t_check(mt_texture_eval_float(amount, &(mt_diffgeom){0}) == 0,
            "scale and mix: children outlive released parents", "-");
    mt_texture_destroy(amount);
    mt_texture_destroy(a);
    mt_texture_destroy(b);
    mt_texture_destroy(two);
}

/* The 3D checkerboard: tex1 where floor(x) + floor(y) + floor(z) is even in
 * texture space. pbrt-v2 maps world points by tex2world itself (Scale 2 2 2:
 * texture point 2p, a finer pattern); MT_FIX_MAPPING_3D by its inverse. */
static void test_checker3d(void)
{
    mt_transform id = mt_transform_identity(), s2 = mt_scale(2, 2, 2);
    mt_map3d mid = mt__map3d(&id, PV2), mv2 = mt__map3d(&s2, PV2), mfix = mt__map3d(&s2, FIXED);
    mt_texture *one = tu_const(1, 1, 1, 1), *zero = tu_const(1, 0, 0, 0);
    mt_texture *t = mt__tex_checker3d(1, &mid, one, zero, PV2, &err);
    mt_texture *tv2 = mt__tex_checker3d(1, &mv2, one, zero, PV2, &err);
    mt_texture *tfix = mt__tex_checker3d(1, &mfix, one, zero, FIXED, &err);
    int bad = 0, bad_v2 = 0, bad_fix = 0, i;
    mt_rng rng;
    mt_rng_seed(&rng, 3, 4);
    for (i = 0; i < 4000; ++i) {
        double x = mt_rng_uniform_d(&rng) * 10 - 5, y = mt_rng_uniform_d(&rng) * 10 - 5,
               z = mt_rng_uniform_d(&rng) * 10 - 5;
        mt_diffgeom dg = tu_dg(0, 0, mt_v3((mt_real)x, (mt_real)y, (mt_real)z));
        double px = dg.p.x, py = dg.p.y, pz = dg.p.z;
        long n1 = (long)(floor(px) + floor(py) + floor(pz));
        long n2 = (long)(floor(2 * px) + floor(2 * py) + floor(2 * pz));
        long nh = (long)(floor(px / 2) + floor(py / 2) + floor(pz / 2));
        if (mt_texture_eval_float(t, &dg) != (n1 % 2 == 0 ? 1 : 0)) bad++;
        if (mt_texture_eval_float(tv2, &dg) != (n2 % 2 == 0 ? 1 : 0)) bad_v2++;
        if (mt_texture_eval_float(tfix, &dg) != (nh % 2 == 0 ? 1 : 0)) bad_fix++;
    }
    t_check(bad == 0, "checkerboard 3D: tex1 on even floor(x) + floor(y) + floor(z)", "%d wrong",
            bad);
    t_check(bad_v2 == 0, "checkerboard 3D, pbrt-v2 mode: Scale 2 2 2 doubles the frequency",
            "%d wrong", bad_v2);
    t_check(bad_fix == 0, "checkerboard 3D, corrected: Scale 2 2 2 doubles the checks' size",
            "%d wrong", bad_fix);
    mt_texture_destroy(t);
    mt_texture_destroy(tv2);
    mt_texture_destroy(tfix);
    mt_texture_destroy(one);
    mt_texture_destroy(zero);
}

/* pbrt-v2's dots, recomputed in double from its definition (dots.h): the
 * cell (floor(s + 1/2), floor(t + 1/2)) has a dot when Noise at its centre
 * (+1/2, +1/2, 1/2) is positive; the dot's centre is shifted by 0.15 times
 * Noise at (+1.5, +2.8) and (+4.5, +9.8); its radius is 0.35. */
static int dot_at(double s, double t, double *margin)
{
    double sc = floor(s + 0.5), tc = floor(t + 0.5), cs, ct, d;
    if (!(mt__noise((mt_real)(sc + 0.5), (mt_real)(tc + 0.5), (mt_real)0.5) > 0)) {
        *margin = 1;
        return 0;
    }
    cs = sc + 0.15 * mt__noise((mt_real)(sc + 1.5), (mt_real)(tc + 2.8), (mt_real)0.5);
    ct = tc + 0.15 * mt__noise((mt_real)(sc + 4.5), (mt_real)(tc + 9.8), (mt_real)0.5);
    d = sqrt((s - cs) * (s - cs) + (t - ct) * (t - ct));
    *margin = fabs(d - 0.35);
    return d < 0.35;
}

static void test_dots(void)
{
    mt_map2d m = mt__map2d_uv(4, 4, 0, 0);
    mt_texture *in = tu_const(1, 1, 1, 1), *out = tu_const(1, 0, 0, 0);
    mt_texture *fixed = mt__tex_dots(1, &m, in, out, FIXED, &err);
    mt_texture *v2 = mt__tex_dots(1, &m, in, out, PV2, &err);
    int bad = 0, swapped = 0, n = 0, dots = 0, i;
    mt_rng rng;
    mt_rng_seed(&rng, 5, 6);
    for (i = 0; i < 20000; ++i) {
        mt_diffgeom dg = tu_dg((mt_real)(mt_rng_uniform_d(&rng) * 6 - 3),
                               (mt_real)(mt_rng_uniform_d(&rng) * 6 - 3), mt_v3(0, 0, 0));
        double margin;
        int on = dot_at(4.0 * dg.u, 4.0 * dg.v, &margin);
        if (margin < 1e-5) continue; /* too close to a rim for float arithmetic */
        n++;
        dots += on;
        if (mt_texture_eval_float(fixed, &dg) != (on ? 1 : 0)) bad++;
        if (mt_texture_eval_float(v2, &dg) != (on ? 0 : 1)) swapped++;
    }
    t_check(bad == 0 && dots > n / 10 && dots < n / 3,
            "dots, corrected: inside on the dots of pbrt-v2's definition",
            "%d of %d wrong, %d on dots", bad, n, dots);
    t_check(swapped == 0, "dots, pbrt-v2 mode: \"inside\" drawn around the dots (dots-inside)",
            "%d of %d differ", swapped, n);
    mt_texture_destroy(fixed);
    mt_texture_destroy(v2);
    mt_texture_destroy(in);
    mt_texture_destroy(out);
}

static void map_at(const mt_map2d *m, mt_vec3 p, mt_st *st)
{
    mt_diffgeom dg = tu_dg(0, 0, p);
    dg.dpdx = mt_v3((mt_real)0.01, 0, 0);
    dg.dpdy = mt_v3(0, (mt_real)0.01, 0);
    mt__map2d_apply(m, &dg, st);
}

static void test_mappings(void)
{
    mt_transform id = mt_transform_identity(), tr = mt_translate(mt_v3(1, 0, 0));
    mt_map2d sph = mt__map2d_spherical(&id, PV2), sph_t = mt__map2d_spherical(&tr, PV2);
    mt_map2d cyl = mt__map2d_cylindrical(&id, PV2), cyl_fix = mt__map2d_cylindrical(&id, FIXED);
    mt_map2d pl = mt__map2d_planar(mt_v3(1, 1, 0), mt_v3(0, 0, 2), (mt_real)0.5, -1);
    mt_st a, b, c, d;
    double sx, tx;
    /* spherical: s = theta / pi, t = phi / 2pi, in texture space (the inverse
     * of tex2world, as pbrt-v2's creators pass) */
    map_at(&sph, mt_v3(0, 2, 0), &a);
    map_at(&sph, mt_v3(0, 0, 3), &b);
    map_at(&sph_t, mt_v3(1, 0, 3), &c);
    t_check(fabs(a.s - 0.5) < 1e-6 && fabs(a.t - 0.25) < 1e-6 && fabs(b.s) < 1e-6 &&
                fabs(c.s) < 1e-6,
            "spherical mapping: theta/pi and phi/2pi in texture space", "%g %g %g %g",
            (double)a.s, (double)a.t, (double)b.s, (double)c.s);
    /* its derivatives: forward differences over 0.1 dpdx */
    map_at(&sph, mt_v3((mt_real)0.6, (mt_real)0.3, (mt_real)0.7), &a);
    {
        mt_vec3 q = mt_v3((mt_real)0.601, (mt_real)0.3, (mt_real)0.7);
        double len = sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
        sx = acos(q.z / len) / T_PI;
        tx = atan2(q.y, q.x) / (2 * T_PI);
    }
    t_check(fabs(a.dsdx - (sx - a.s) / 0.1) < 2e-4 && fabs(a.dtdx - (tx - a.t) / 0.1) < 2e-4,
            "spherical mapping: derivatives by forward differences of 0.1 dpdx", "%g %g",
            (double)a.dsdx, (double)a.dtdx);
    /* cylindrical: s = (pi + phi) / 2pi, t = z of the normalized position */
    map_at(&cyl, mt_v3(3, 0, 0), &a);
    map_at(&cyl, mt_v3(0, 1, 1), &b);
    t_check(fabs(a.s - 0.5) < 1e-6 && fabs(a.t) < 1e-6 && fabs(b.s - 0.75) < 1e-6 &&
                fabs(b.t - sqrt(0.5)) < 1e-6,
            "cylindrical mapping: (pi + phi)/2pi and the normalized z", "%g %g %g %g",
            (double)a.s, (double)a.t, (double)b.s, (double)b.t);
    /* the origin (pbrt-v2: 0/0) is defined in both modes; on the axis the
     * sign of a zero decides pbrt-v2's u, corrected mode takes phi = 0 */
    map_at(&cyl, mt_v3(0, 0, 0), &a);
    map_at(&sph, mt_v3(0, 0, 0), &d);
    t_check(a.s == (mt_real)0.5 && a.t == 0 && d.s == (mt_real)0.5 && d.t == 0 &&
                mt_is_finite(a.dsdx) && mt_is_finite(d.dtdy),
            "cylindrical and spherical mappings: the origin maps to (0.5, 0) in both modes",
            "(%g, %g) (%g, %g)", (double)a.s, (double)a.t, (double)d.s, (double)d.t);
    map_at(&cyl, mt_v3(-0.0f, 0, 2), &b);
    map_at(&cyl_fix, mt_v3(-0.0f, 0, 2), &c);
    t_check(b.s == 1 && c.s == (mt_real)0.5 && b.t == 1 && c.t == 1,
            "cylindrical mapping on the axis: pbrt-v2 u = 1 for x = -0, corrected u = 0.5",
            "%g %g", (double)b.s, (double)c.s);
    /* planar: s = ds + p.v1, t = dt + p.v2, derivatives dpdx.v1 ... */
    map_at(&pl, mt_v3(2, 3, 4), &a);
    t_check(a.s == (mt_real)5.5 && a.t == 7 && fabs(a.dsdx - 0.01) < 1e-9 &&
                fabs(a.dtdx) < 1e-9 && fabs(a.dsdy - 0.01) < 1e-9,
            "planar mapping: offsets plus projections on v1 and v2", "%g %g", (double)a.s,
            (double)a.t);
}

/* Noise at points worked out by hand from pbrt-v2's definition (texture.cpp):
 * corner hashes h = NoisePerm[NoisePerm[NoisePerm[x] + y] + z] & 15 read from
 * the permutation table, gradient terms +-u +-v with u = dx (h < 8 or h = 12,
 * 13) else dy, v = dy (h < 4 or 12, 13) else dz.
 *  Noise(.5, .5, .5): all weights 1/2, so the mean of the eight corners. The
 *    hashes are 4, 6, 12, 0, 7, 4, 14, 3 for corners 000, 100, 010, 110, 001,
 *    101, 011, 111, giving dx+dz = 1, dx-dz at (-.5, ., .5) = -1, dy+dx at
 *    (., -.5, .) = 0, dx+dy at (-.5, -.5) = -1, -dx+dz... = 0, -1, 0, 1:
 *    sum -1, mean -1/8.
 *  Noise(.25, 0, 0): dy = dz = 0 so only corners 000 (h = 4: dx + dz = .25)
 *    and 100 (h = 6: dx - dz = -.75) count, blended by the quintic
 *    w(.25) = 6/1024 - 15/256 + 10/64 = 0.103515625: .25 - w = 0.146484375.
 *  Noise(-3.7, 12.25, .5): the cell (-4, 12, 0) wraps to (252, 12, 0); the
 *    same steps (hashes 1, 11, 2, 10, 6, 3, 4, 5) give 0.28738427 in float
 *    arithmetic (checked with a float32 calculator). */
static void test_noise_values(void)
{
    t_check(mt__noise((mt_real)0.5, (mt_real)0.5, (mt_real)0.5) == (mt_real)-0.125,
            "noise: Noise(.5, .5, .5) = -1/8 (by hand)", "%.9g",
            (double)mt__noise((mt_real)0.5, (mt_real)0.5, (mt_real)0.5));
    t_check(mt__noise((mt_real)0.25, 0, 0) == (mt_real)0.146484375,
            "noise: Noise(.25, 0, 0) = .25 - w(.25) = 0.146484375 (by hand)", "%.9g",
            (double)mt__noise((mt_real)0.25, 0, 0));
    t_near(mt__noise((mt_real)-3.7, (mt_real)12.25, (mt_real)0.5), 0.28738427, 2e-6,
           "noise: Noise(-3.7, 12.25, .5) with a negative cell (by hand)");
}

static void test_noise_properties(void)
{
    static const double big[] = {0, 1, -1, 7, -255, 256, 1e6, -3e9, 4294967296.0, 1e20};
    double maxabs = 0, maxslope = 0, jump = 0, sum = 0;
    int zeros = 1, finite = 1, i, j;
    mt_rng rng;
    /* zero at every lattice point, however far (pbrt-v2's Floor2Int
     * overflows beyond 2^31; materia's cell index does not) */
    for (i = 0; i < 10; ++i)
        for (j = 0; j < 10; ++j)
            if (mt__noise((mt_real)big[i], (mt_real)big[j], (mt_real)big[(i + j) % 10]) != 0)
                zeros = 0;
    t_check(zeros, "noise: zero at integer lattice points (up to 1e20)", "non-zero");
    t_check(mt__noise((mt_real)INFINITY, 0, 0) == 0 && mt__noise(0, (mt_real)NAN, 0) == 0,
            "noise: non-finite input gives 0", "-");
    /* beyond 2^31 the cell index is floor(x) mod 256, exactly: 3e9 + 256 k
     * (k up to 2^14, still exact in float) are the same lattice cell */
    t_check(mt__noise((mt_real)3e9, (mt_real)0.5, (mt_real)0.25) ==
                mt__noise((mt_real)(3e9 + 256.0 * 4096), (mt_real)0.5, (mt_real)0.25),
            "noise: cells mod 256 beyond the int range", "-");
    /* range: every gradient term is +-a +-b with offsets in [-1, 1], so
     * |Noise| <= 2 (a convex combination); Perlin's noise stays near 1 */
    mt_rng_seed(&rng, 7, 8);
    for (i = 0; i < 200000; ++i) {
        mt_real x = (mt_real)(mt_rng_uniform_d(&rng) * 64 - 32);
        mt_real y = (mt_real)(mt_rng_uniform_d(&rng) * 64 - 32);
        mt_real z = (mt_real)(mt_rng_uniform_d(&rng) * 64 - 32);
        mt_real n = mt__noise(x, y, z);
        if (!mt_is_finite(n)) finite = 0;
        maxabs = fmax(maxabs, fabs(n));
        sum += n;
    }
    t_check(finite && maxabs <= 2 && maxabs > 0.7,
            "noise: range within the bound 2 (and not trivially small)",
            "max |Noise| %.6f", maxabs);
    t_check(fabs(sum / 200000) < 0.01, "noise: mean near 0", "mean %g", sum / 200000);
    printf("  noise: max |Noise| over 2e5 points %.6f\n", maxabs);
    /* continuity: |dN/dx| <= |w'| max 1.875 times |g1 - g0| <= 4, plus the
     * gradient's own slope 1, so 8.5; checked across lattice planes too */
    mt_rng_seed(&rng, 9, 10);
    for (i = 0; i < 20000; ++i) {
        double h = 1e-3;
        mt_real x = (mt_real)(mt_rng_uniform_d(&rng) * 16 - 8), y = (mt_real)(i % 7) - (mt_real)0.0005;
        mt_real z = (mt_real)(mt_rng_uniform_d(&rng) * 16 - 8);
        mt_real n0 = mt__noise(x, y, z);
        double s1 = fabs(mt__noise(x + (mt_real)h, y, z) - n0) / h;
        double s2 = fabs(mt__noise(x, y + (mt_real)h, z) - n0) / h;
        double s3 = fabs(mt__noise(x, y, z + (mt_real)h) - n0) / h;
        maxslope = fmax(maxslope, fmax(s1, fmax(s2, s3)));
        if (i % 7 == 3) jump = fmax(jump, s2);
    }
    t_check(maxslope <= 8.5 + 0.01 && maxslope > 1,
            "noise: Lipschitz within the derived bound 8.5, across lattice planes",
            "max slope %.4f (across planes %.4f)", maxslope, jump);
}

/* FBm and Turbulence: weights omega^i at frequencies 1.99^i, the octave
 * count min(maxOctaves, -1 - log2(max(|dpdx|^2, |dpdy|^2)) / 2), the last
 * octave faded in by SmoothStep(.3, .7, fraction), and Turbulence's 0.2 per
 * octave left out. */
static mt_real octave(mt_vec3 p, int i)
{
    mt_real lambda = 1;
    int k;
    for (k = 0; k < i; ++k) lambda *= (mt_real)1.99;
    return mt__noise(lambda * p.x, lambda * p.y, lambda * p.z);
}

static void test_fbm(void)
{
    mt_vec3 p = mt_v3((mt_real)1.3, (mt_real)-0.7, (mt_real)2.1), zero = mt_v3(0, 0, 0);
    mt_real omega = (mt_real)0.6, sum = 0, tsum = 0, o = 1, got;
    mt_vec3 d45, small;
    int i, whole;
    double foct;
    /* no footprint: every one of the 5 octaves, nothing faded */
    for (i = 0; i < 5; ++i) {
        sum += o * octave(p, i);
        tsum += o * mt_fabs(octave(p, i));
        o *= omega;
    }
    t_near(mt__fbm(p, zero, zero, omega, 5), sum, 1e-6, "fbm: sum of omega^i Noise(1.99^i P)");
    t_near(mt__turbulence(p, zero, zero, omega, 5), tsum, 1e-6,
           "turbulence: sum of omega^i |Noise(1.99^i P)|, nothing left out");
    t_check(mt__fbm(p, zero, zero, 0, 5) == octave(p, 0), "fbm: omega 0 is Noise(P)", "-");
    /* footprint 2^-5.5: -1 - log2(2^-11)/2 = 4.5 octaves: 4 whole, the fifth
     * at SmoothStep(.3, .7, .5) = 1/2; the octave count uses the longer vector */
    d45 = mt_v3(0, (mt_real)pow(2, -5.5), 0);
    small = mt_v3((mt_real)1e-4, 0, 0);
    foct = mt__noise_octaves(small, d45, 8, &whole);
    t_check(fabs(foct - 4.5) < 1e-5 && whole == 4, "fbm: octaves -1 - log2(max |d|^2)/2",
            "%.7f (%d whole)", foct, whole);
    sum = tsum = 0;
    o = 1;
    for (i = 0; i < 4; ++i) {
        sum += o * octave(p, i);
        tsum += o * mt_fabs(octave(p, i));
        o *= omega;
    }
    got = mt__fbm(p, small, d45, omega, 8);
    t_near(got, sum + o * 0.5 * octave(p, 4), 2e-5, "fbm: fifth octave half faded in");
    got = mt__turbulence(p, d45, small, omega, 8);
    t_near(got, tsum + o * 0.5 * mt_fabs(octave(p, 4)) + (8 - 4.5) * 0.2, 2e-5,
           "turbulence: plus 0.2 for each of the 3.5 octaves left out");
    /* the clamp to maxOctaves, and a footprint so large no octave is whole */
    foct = mt__noise_octaves(mt_v3((mt_real)1e-9, 0, 0), zero, 6, &whole);
    t_check(foct == 6 && whole == 6, "fbm: octaves clamped to maxOctaves", "%g", foct);
    /* a footprint of 0.7: -1 - log2(0.49)/2 = -0.49, clamped to 0 octaves:
     * FBm exactly 0 and Turbulence 0.2 maxOctaves, as pbrt-v2's binary
     * renders them (unclamped, half an octave of noise would fade in) */
    foct = mt__noise_octaves(mt_v3((mt_real)0.7, 0, 0), zero, 6, &whole);
    t_check(foct == 0 && whole == 0, "fbm: a wide footprint gives 0 octaves, not -0.49", "%g", foct);
    got = mt__fbm(p, mt_v3((mt_real)0.7, 0, 0), zero, omega, 6);
    t_check(got == 0, "fbm: exactly 0 for a footprint of 0.7", "%g", (double)got);
    got = mt__turbulence(p, zero, mt_v3(16, 0, 0), omega, 6);
    t_check(got == (mt_real)6 * (mt_real)0.2, "turbulence: 0.2 maxOctaves for a footprint of 16", "%.9g",
            (double)got);
    /* an overflowing footprint (pbrt-v2: -inf octaves, Turbulence +inf) */
    got = mt__turbulence(p, mt_v3((mt_real)1e30, (mt_real)1e30, 0), zero, omega, 8);
    t_check(mt_is_finite(got), "turbulence: finite for a footprint whose square overflows",
            "%g", (double)got);
}

/* marble at t = 1: pbrt-v2 reads one past its colour table with weight 0
 * (1.5 c[6]); corrected clamps (1.5 c[8]); c[6] = c[8] = (.58, .58, .6). */
static void test_marble(void)
{
    mt_transform id = mt_transform_identity();
    mt_map3d m = mt__map3d(&id, PV2);
    mt_texture *v2 = mt__tex_marble(&m, 8, (mt_real)0.5, 1, 0, PV2, &err);
    mt_texture *fix = mt__tex_marble(&m, 8, (mt_real)0.5, 1, 0, FIXED, &err);
    /* variation 0: t = 1/2 + sin(y)/2 = 1 at y = pi/2 */
    mt_diffgeom dg = tu_dg(0, 0, mt_v3(0, (mt_real)(T_PI / 2), 0));
    mt_rgb a = mt_texture_eval_rgb(v2, &dg), b = mt_texture_eval_rgb(fix, &dg);
    mt_real want0 = (mt_real)1.5 * 0.58f, want2 = (mt_real)1.5 * 0.6f;
    int i, finite = 1;
    t_check(fabs(a.c[0] - want0) < 1e-6 && fabs(a.c[2] - want2) < 1e-6 &&
                fabs(b.c[0] - want0) < 1e-6 && fabs(b.c[2] - want2) < 1e-6,
            "marble at t = 1: 1.5 (.58, .58, .6) in both modes (marble-index)",
            "%g %g / %g %g", (double)a.c[0], (double)a.c[2], (double)b.c[0], (double)b.c[2]);
    /* just below t = 1 the spline approaches the same colour */
    dg.p.y = (mt_real)(T_PI / 2 - 0.01);
    b = mt_texture_eval_rgb(fix, &dg);
    t_check(fabs(b.c[0] - want0) < 1e-3, "marble: continuous into t = 1", "%g", (double)b.c[0]);
    for (i = 0; i < 1000; ++i) {
        dg.p = mt_v3((mt_real)i * (mt_real)0.37, (mt_real)i * (mt_real)-1.3, (mt_real)i);
        a = mt_texture_eval_rgb(v2, &dg);
        if (!mt_rgb_is_finite(a) || mt_rgb_min(a) < 0) finite = 0;
    }
    t_check(finite, "marble: finite and non-negative", "-");
    mt_texture_destroy(v2);
    mt_texture_destroy(fix);
}

static void test_table(void)
{
    mt_texture_table *t = mt_texture_table_create(), *c;
    mt_texture *f = tu_const(1, 1, 1, 1), *s = tu_const(0, 1, 2, 3), *f2 = tu_const(1, 2, 2, 2);
    mt_diffgeom dg = mt_diffgeom_default();
    mt_texture_table_set(t, "x", f, &err);
    mt_texture_table_set(t, "x", s, &err);
    t_check(mt_texture_table_get(t, "x", 1) == f && mt_texture_table_get(t, "x", 0) == s &&
                mt_texture_table_get(t, "y", 1) == NULL,
            "texture table: float and spectrum namespaces", "-");
    c = mt_texture_table_clone(t);
    mt_texture_table_set(t, "x", f2, &err);
    t_check(mt_texture_table_get(t, "x", 1) == f2 && mt_texture_table_get(c, "x", 1) == f,
            "texture table: a clone keeps its bindings when the original changes", "-");
    mt_texture_destroy(f);
    mt_texture_destroy(s);
    mt_texture_destroy(f2);
    mt_texture_table_destroy(t);
    /* the clone's references keep f and s alive (ASan would catch a use after free) */
    t_check(mt_texture_eval_float(mt_texture_table_get(c, "x", 1), &dg) == 1 &&
                mt_texture_eval_rgb(mt_texture_table_get(c, "x", 0), &dg).c[2] == 3,
            "texture table: bindings hold references", "-");
    mt_texture_table_destroy(c);
}

/* Every failing allocation is reported and leaks nothing (ASan checks). */
static void test_alloc_failures(void)
{
    int i, ok = 1;
    for (i = 0; i < 8; ++i) {
        mt_texture_table *t = mt_texture_table_create(), *c = NULL;
        mt_texture *f = tu_const(1, 1, 1, 1);
        mt_status st;
        if (!t || !f) {
            mt_texture_table_destroy(t);
            mt_texture_destroy(f);
            continue;
        }
        mt_texture_table_set(t, "a", f, &err);
        mt_alloc_fail_after(i % 4);
        st = mt_texture_table_set(t, i < 4 ? "b" : "a", f, &err);
        c = mt_texture_table_clone(t);
        mt_alloc_fail_after(-1);
        if (st != MT_OK && st != MT_ERR_NOMEM) ok = 0;
        mt_texture_table_destroy(c);
        mt_texture_table_destroy(t);
        mt_texture_destroy(f);
    }
    mt_alloc_fail_after(0);
    ok = ok && tu_const(1, 1, 1, 1) == NULL;
    mt_alloc_fail_after(-1);
    t_check(ok, "textures: allocation failures reported cleanly", "-");
}

static void test_rejections(void)
{
    mt_transform id = mt_transform_identity();
    mt_map3d m3 = mt__map3d(&id, PV2);
    mt_map2d bad = mt__map2d_uv((mt_real)INFINITY, 1, 0, 0);
    mt_texture *f = tu_const(1, 1, 1, 1), *s = tu_const(0, 1, 1, 1);
    mt_rgb v[4] = {mt_rgb_gray(0), mt_rgb_gray((mt_real)NAN), mt_rgb_gray(0), mt_rgb_gray(0)};
    mt_map2d uv = mt__map2d_uv(1, 1, 0, 0);
    t_check(mt__tex_fbm(1, &m3, -1, (mt_real)0.5, PV2, &err) == NULL &&
                !strcmp(err.param, "octaves"),
            "fbm: negative octaves rejected, naming the parameter", "%s", err.message);
    t_check(mt__tex_wrinkled(1, &m3, 200, (mt_real)0.5, PV2, &err) == NULL,
            "wrinkled: octaves beyond 128 rejected", "accepted");
    t_check(mt__tex_fbm(1, &m3, 128, (mt_real)1e10, PV2, &err) == NULL && !strcmp(err.param, "roughness"),
            "fbm: roughness whose powers overflow rejected", "%s", err.message);
    t_check(mt__tex_marble(&m3, 8, (mt_real)0.5, (mt_real)NAN, 0, PV2, &err) == NULL &&
                !strcmp(err.param, "scale"),
            "marble: NaN scale rejected", "%s", err.message);
    t_check(mt__tex_checker2d(1, &bad, f, f, 1, PV2, &err) == NULL &&
                !strcmp(err.param, "uscale"),
            "checkerboard: infinite uscale rejected", "%s", err.message);
    t_check(mt__tex_bilerp(1, &uv, v, PV2, &err) == NULL && !strcmp(err.param, "v01"),
            "bilerp: NaN v01 rejected", "%s", err.message);
    t_check(mt__tex_scale(0, f, s, PV2, &err) == NULL && !strcmp(err.param, "tex1"),
            "scale: a float child where a spectrum one is needed is rejected", "%s",
            err.message);
    t_check(mt__tex_mix(1, f, f, s, PV2, &err) == NULL && !strcmp(err.param, "amount"),
            "mix: a spectrum amount is rejected", "%s", err.message);
    mt_texture_destroy(f);
    mt_texture_destroy(s);
}

/* --- the same bits from every thread --- */

#define NPTS 1500
#define NTEX 16

static mt_texture *all[NTEX];

static void eval_all(mt_rgb *out)
{
    int i, k;
    for (k = 0; k < NTEX; ++k)
        for (i = 0; i < NPTS; ++i) {
            mt_diffgeom dg = tu_dg((mt_real)(i % 37) * (mt_real)0.071,
                                   (mt_real)(i / 37) * (mt_real)0.053,
                                   mt_v3((mt_real)i * (mt_real)0.013, (mt_real)(i % 11) * (mt_real)0.3,
                                         (mt_real)-0.2 * (mt_real)(i % 5)));
            dg.dudx = dg.dvdy = (mt_real)(i % 3) * (mt_real)0.01;
            dg.dpdx = mt_v3((mt_real)(i % 4) * (mt_real)0.02, 0, 0);
            out[k * NPTS + i] = mt_texture_eval_rgb(all[k], &dg);
        }
}

/* Awkward but valid shading points: exact lattice values and check edges,
 * signed zeros, the origin and axes of the projections, large coordinates
 * (beyond 2^31 for the noise lattice), zero, one-sided and wide footprints:
 * every class in both modes stays finite. */
static void extremes(void)
{
    static const double coord[] = {0, -0.0, 1, -1, 0.5, 1e-30, 3e9, -7e6, 1e4};
    static const double width[] = {0, 1e-30, 0.25, 3, 1e3};
    int k, i, j, w, bad = 0, n = 0;
    for (k = 0; k < NTEX; ++k)
        for (i = 0; i < 9; ++i)
            for (j = 0; j < 9; ++j)
                for (w = 0; w < 5; ++w) {
                    mt_diffgeom dg = tu_dg((mt_real)coord[i], (mt_real)coord[j],
                                           mt_v3((mt_real)coord[j], (mt_real)coord[i],
                                                 (mt_real)coord[(i + j) % 9]));
                    mt_rgb r;
                    dg.dudx = (mt_real)width[w];
                    dg.dvdy = (mt_real)width[(w + i) % 5];
                    dg.dpdx = mt_v3((mt_real)width[w], 0, 0);
                    dg.dpdy = mt_v3(0, 0, (mt_real)width[(w + j) % 5]);
                    r = mt_texture_eval_rgb(all[k], &dg);
                    n++;
                    if (!mt_rgb_is_finite(r) || !mt_is_finite(mt_texture_eval_float(all[k], &dg)))
                        if (bad++ < 3)
                            printf("  texture %d (%s) not finite at u %g v %g width %g\n", k,
                                   mt_texture_class(all[k]), coord[i], coord[j], width[w]);
                }
    t_check(bad == 0, "textures: finite at lattice points, edges, axes, large coordinates and "
            "degenerate or wide footprints", "%d of %d evaluations", bad, n);
}

static void *thread_main(void *arg)
{
    eval_all(arg);
    return NULL;
}

static void test_threads(void)
{
    mt_transform rot = mt_rotate(30, mt_v3(1, 1, 0));
    mt_map3d m3 = mt__map3d(&rot, PV2), m3f = mt__map3d(&rot, FIXED);
    mt_map2d uv = mt__map2d_uv(4, 3, 0, 0), sph = mt__map2d_spherical(&rot, PV2);
    mt_map2d cyl = mt__map2d_cylindrical(&rot, FIXED), pl = mt__map2d_planar(mt_v3(1, 0, 1), mt_v3(0, 2, 0), 0, 0);
    mt_rgb v[4] = {mt_rgb_gray(0), mt_rgb_make(1, 0, 0), mt_rgb_make(0, 1, 0), mt_rgb_gray(1)};
    mt_texture *a = tu_const(0, 1, (mt_real)0.5, 0), *b = tu_const(0, 0, (mt_real)0.5, 1);
    mt_texture *fa = tu_const(1, (mt_real)0.2, 0, 0);
    mt_rgb *r0 = malloc(sizeof(mt_rgb) * NPTS * NTEX), *r1 = malloc(sizeof(mt_rgb) * NPTS * NTEX),
           *r2 = malloc(sizeof(mt_rgb) * NPTS * NTEX);
    pthread_t t1, t2;
    int k, same;
    all[0] = mt__tex_checker2d(0, &uv, a, b, 1, PV2, &err);
    all[1] = mt__tex_checker2d(0, &sph, a, b, 1, FIXED, &err);
    all[2] = mt__tex_checker3d(0, &m3, a, b, PV2, &err);
    all[3] = mt__tex_dots(0, &cyl, a, b, PV2, &err);
    all[4] = mt__tex_fbm(1, &m3, 8, (mt_real)0.5, PV2, &err);
    all[5] = mt__tex_wrinkled(0, &m3f, 6, (mt_real)0.7, FIXED, &err);
    all[6] = mt__tex_windy(1, &m3, PV2, &err);
    all[7] = mt__tex_marble(&m3, 8, (mt_real)0.5, 2, (mt_real)0.3, PV2, &err);
    all[8] = mt__tex_bilerp(0, &pl, v, PV2, &err);
    all[9] = mt__tex_uv(&sph, PV2, &err);
    all[10] = mt__tex_scale(0, all[0], all[8], PV2, &err);
    all[11] = mt__tex_mix(0, all[7], all[3], all[4], PV2, &err);
    all[12] = mt__tex_mix(1, all[4], all[6], fa, PV2, &err);
    all[13] = mt__tex_scale(1, all[4], all[12], PV2, &err);
    all[14] = mt__tex_dots(1, &uv, all[4], fa, FIXED, &err);
    all[15] = mt__tex_checker2d(1, &cyl, all[14], all[13], 1, PV2, &err);
    for (k = 0; k < NTEX; ++k)
        if (!all[k]) {
            t_fail("textures: determinism", "texture %d not created: %s", k, err.message);
            return;
        }
    extremes();
    eval_all(r0);
    pthread_create(&t1, NULL, thread_main, r1);
    pthread_create(&t2, NULL, thread_main, r2);
    pthread_join(t1, NULL);
    pthread_join(t2, NULL);
    same = !memcmp(r0, r1, sizeof(mt_rgb) * NPTS * NTEX) &&
           !memcmp(r0, r2, sizeof(mt_rgb) * NPTS * NTEX);
    t_check(same, "textures: bit-identical in two threads and the main thread", "differ");
    for (k = 0; k < NPTS * NTEX; ++k)
        if (!mt_rgb_is_finite(r0[k])) break;
    t_check(k == NPTS * NTEX, "textures: no NaN or Inf over every class and mapping", "at %d", k);
    for (k = NTEX - 1; k >= 0; --k) mt_texture_destroy(all[k]);
    mt_texture_destroy(a);
    mt_texture_destroy(b);
    mt_texture_destroy(fa);
    free(r0);
    free(r1);
    free(r2);
}

int main(void)
{
    test_constant();
    test_uv();
    test_bilerp();
    test_checker_unfiltered();
    test_compositions();
    test_checker3d();
    test_dots();
    test_mappings();
    test_noise_values();
    test_noise_properties();
    test_fbm();
    test_marble();
    test_table();
    test_alloc_failures();
    test_rejections();
    test_threads();
    return t_status();
}
