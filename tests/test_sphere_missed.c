/*
 * mt_shape_missed: the renderer's cheap rejection of rays that miss a sphere
 * (direct lighting's BSDF-sampled rays against a sphere light) must never
 * reject a ray that mt_shape_intersect would find a hit for, and must
 * reject the clear misses (else it saves nothing). Rays are aimed at the
 * silhouette, where the two tests are closest: relative offsets of the
 * aiming point from 1e-9 to 1e-1 of the radius on both sides, and rays
 * leaving the surface itself. A test without its margin, or one that took
 * the object radius for the world radius (a scaled sphere), rejects hits
 * here.
 */
#include <math.h>
#include <stdio.h>
#include "materia/rng.h"
#include "support/check.h"
#include "support/tgeom.h"

typedef struct case_ {
    const char *name, *text;
    double radius;
    double scale, zscale; /* uniform scale; z scale (an ellipsoid when != scale) */
    double tx, ty, tz;    /* translation */
    /* 1: clear misses must be rejected; 0: nothing may be (no ball); -1: no
     * requirement (float cannot certify a ball smaller than the rounding of
     * its centre) */
    int has_ball;
    double clear; /* a miss by this fraction of the radius is clear */
} case_;

static mt_vec3 v3d(double x, double y, double z) { return mt_v3((mt_real)x, (mt_real)y, (mt_real)z); }

static void run(const case_ *c)
{
    mt_transform t = mt_translate(v3d(c->tx, c->ty, c->tz)), r = mt_rotate(29, mt_v3(1, 2, 3));
    mt_transform s = mt_scale((mt_real)c->scale, (mt_real)c->scale, (mt_real)c->zscale), a, xf;
    mt_error err;
    mt_shape *sh;
    mt_rng rng;
    char name[160];
    long n = 0, wrong = 0, clear = 0, rejected_clear = 0, rejected = 0;
    int i, k;
    a = mt_transform_compose(&t, &r);
    xf = mt_transform_compose(&a, &s);
    sh = t_shape(c->text, &xf, 0, NULL, &err);
    if (!sh) {
        t_fail(c->name, "creation failed: %s", err.message);
        return;
    }
    mt_rng_seed(&rng, 7, 0);
    for (i = 0; i < 40000; ++i) {
        /* a point of the (whole) sphere in object space, its world image, and
         * a tangent direction there; the aiming point is moved off the
         * surface along the normal by a relative offset */
        double z = 1 - 2 * mt_rng_uniform_d(&rng), ph = 6.283185307179586 * mt_rng_uniform_d(&rng);
        double sr = sqrt(fmax(0, 1 - z * z)), po[3] = {sr * cos(ph), sr * sin(ph), z}, tg[3], len;
        double off = pow(10, -9 + 8 * mt_rng_uniform_d(&rng)) * (mt_rng_uniform_d(&rng) < 0.5 ? -1 : 1);
        double dist = 0.5 + 30 * mt_rng_uniform_d(&rng);
        double pw[3], tw[3], o[3], d[3];
        double(*m)[4] = xf.m.m;
        mt_hit hit;
        mt_ray ray;
        int hits, missed;
        /* tangent: po x random axis */
        tg[0] = po[1] * 0.3 - po[2] * 0.8;
        tg[1] = po[2] * 0.5 - po[0] * 0.3;
        tg[2] = po[0] * 0.8 - po[1] * 0.5;
        len = sqrt(tg[0] * tg[0] + tg[1] * tg[1] + tg[2] * tg[2]);
        if (!(len > 1e-3)) continue;
        for (k = 0; k < 3; ++k) tg[k] /= len;
        for (k = 0; k < 3; ++k) {
            double q[3] = {c->radius * po[0] * (1 + off), c->radius * po[1] * (1 + off),
                           c->radius * po[2] * (1 + off)};
            pw[k] = m[k][0] * q[0] + m[k][1] * q[1] + m[k][2] * q[2] + m[k][3];
            tw[k] = m[k][0] * tg[0] + m[k][1] * tg[1] + m[k][2] * tg[2];
        }
        if (i % 4 == 3) {
            /* a ray leaving the surface (off the point by its offset), outwards
             * or inwards */
            double nrm[3];
            for (k = 0; k < 3; ++k) nrm[k] = m[k][0] * po[0] + m[k][1] * po[1] + m[k][2] * po[2];
            for (k = 0; k < 3; ++k) {
                o[k] = pw[k];
                d[k] = tw[k] + (off > 0 ? 0.3 : -0.3) * nrm[k];
            }
        } else {
            /* from afar along the tangent, through the aiming point */
            double len_d = 0.5 + mt_rng_uniform_d(&rng);
            for (k = 0; k < 3; ++k) {
                o[k] = pw[k] - dist * c->radius * tw[k];
                d[k] = tw[k] * len_d;
            }
        }
        ray = mt_ray_make(v3d(o[0], o[1], o[2]), v3d(d[0], d[1], d[2]), 0, MT_RAY_TMAX);
        hits = mt_shape_intersect(sh, 0, &ray, &hit);
        missed = mt_shape_missed(sh, 0, &ray);
        ++n;
        rejected += missed;
        if (missed && hits) {
            if (wrong++ < 3)
                t_fail(c->name, "ray %d (offset %.3g) rejected but mt_shape_intersect hits at t %g", i, off,
                       (double)hit.t);
        }
        if (i % 4 != 3 && off > c->clear) {
            ++clear;
            rejected_clear += missed;
        }
    }
    snprintf(name, sizeof name, "%s: no ray that hits is rejected (%ld rays, %ld rejected)", c->name, n, rejected);
    t_check(wrong == 0, name, "%ld rays rejected that hit", wrong);
    snprintf(name, sizeof name, "%s: %s", c->name,
             c->has_ball > 0   ? "clear misses are rejected"
             : c->has_ball < 0 ? "no rejection asked for (a ball the size of its centre's rounding)"
                               : "no rejection without a ball (not a similarity)");
    if (c->has_ball < 0)
        t_pass(name);
    else if (c->has_ball)
        t_check(rejected_clear >= clear * 99 / 100 && clear > 1000, name, "%ld of %ld misses by %g of the radius or more rejected",
                rejected_clear, clear, c->clear);
    else
        t_check(rejected == 0, name, "%ld rejected", rejected);
    mt_shape_destroy(sh);
}

int main(void)
{
    static const case_ cases[] = {
        {"unit sphere, translated", "Shape \"sphere\"", 1, 1, 1, 3, -3, 6, 1, 1e-3},
        {"radius 2, scale 2", "Shape \"sphere\" \"float radius\" [2]", 2, 2, 2, 0.5, 0.25, -1, 1, 1e-3},
        {"far from the origin", "Shape \"sphere\"", 1, 1, 1, 1e3, -2e3, 5e2, 1, 3e-2},
        {"small, far from the origin", "Shape \"sphere\" \"float radius\" [0.01]", 0.01, 1e-2, 1e-2, 1e3, -2e3, 5e2, -1, 1e-3},
        {"large", "Shape \"sphere\" \"float radius\" [3]", 3, 1e3, 1e3, 0, 0, 0, 1, 1e-3},
        {"partial", "Shape \"sphere\" \"float zmin\" [-0.5] \"float zmax\" [0.7] \"float phimax\" [250]", 1, 1.5, 1.5,
         -2, 1, 0.5, 1, 1e-3},
        {"ellipsoid", "Shape \"sphere\"", 1, 1, 0.6, 1, 1, 1, 0, 1e-3},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) run(&cases[i]);
    return t_status();
}
