/*
 * The dipole integrator (src/tracer/dipole*.c, diffusion.c): the diffusion
 * profile against Jensen et al.'s closed form and its integral against the
 * total diffuse reflectance; Fdr in both modes; the Poisson point set
 * (minimum distance, the same bits on 1, 2 and 3 threads, areas); the
 * octree's Mo against the brute-force sum over every point (exact at
 * maxerror 0, converging as maxerror shrinks, within maxerror at 0.05);
 * more than 8 points at one position; the points file and its errors; the
 * progress of the preprocess; renders bit-identical across thread counts;
 * a scene without BSSRDF renders as directlighting does.
 */
#include <stdio.h>
#include <math.h>
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include <stdlib.h>
#include <string.h>
#include "materia/material.h"
#include "support/check.h"
#include "support/tfiles.h"
#include "support/trender.h"
#include "tracer/scene.h"

#define SCENE_HEAD                                                                                  \
    "LookAt 0 -6.5 2.6  0 0 0.85  0 0 1\nCamera \"perspective\" \"float fov\" [26]\n"             \
    "Film \"image\" \"integer xresolution\" [32] \"integer yresolution\" [24]\n"                  \
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [4]\n"
#define SCENE_WORLD(material)                                                                       \
    "WorldBegin\nAttributeBegin\nLightSource \"infinite\" \"rgb L\" [0.3 0.32 0.36]\nAttributeEnd\n" \
    "AttributeBegin\nMaterial \"matte\" \"rgb Kd\" [0 0 0]\nTranslate 3 -3 6\n"                    \
    "AreaLightSource \"area\" \"rgb L\" [9 9 9]\nShape \"sphere\" \"float radius\" [1]\nAttributeEnd\n" \
    "AttributeBegin\nMaterial \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\n"                               \
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point P\" [-8 -8 0 8 -8 0 8 8 0 -8 8 0]\n" \
    "AttributeEnd\nAttributeBegin\n" material "\nTranslate 0 0 1\nShape \"sphere\" \"float radius\" [1]\n" \
    "AttributeEnd\nWorldEnd\n"
#define SS_MATERIAL "Material \"subsurface\" \"rgb sigma_a\" [0.05 0.2 0.5] \"rgb sigma_prime_s\" [4 4 4] \"float index\" [1.33]"

static const char *scene_text(mt_real min_dist, const char *extra)
{
    static char buf[4096];
    snprintf(buf, sizeof buf,
             SCENE_HEAD "SurfaceIntegrator \"dipolesubsurface\" \"float minsampledistance\" [%g] %s\n" SCENE_WORLD(SS_MATERIAL),
             (double)min_dist, extra ? extra : "");
    return buf;
}

static mt_scene *load(const char *text, mt_mode mode, mt_error *err)
{
    mt_render_options o;
    mt_render_options_default(&o);
    o.mode = mode;
    return mt_scene_load_string(text, "<test>", NULL, &o, err);
}

/* ---- the diffusion profile ----------------------------------------------------------- */

static double poly_fdr(double eta)
{
    if (eta >= 1) return -1.4399 / (eta * eta) + 0.7099 / eta + 0.6681 + 0.0636 * eta;
    return -0.4399 + 0.7099 / eta - 0.3319 / (eta * eta) + 0.0636 / (eta * eta * eta);
}

/* Jensen, Marschner, Levoy, Hanrahan 2001, equation 4, with the real
 * source at zr = 1/sigma't and the virtual one at zv = zr + 4 A D. */
static double jensen_rd(double r, double sa, double sps, double eta)
{
    double st = sa + sps, ap = sps / st, D = 1 / (3 * st), F = poly_fdr(eta), A = (1 + F) / (1 - F);
    double str = sqrt(sa / D), zr = 1 / st, zv = zr + 4 * A * D;
    double dr = sqrt(r * r + zr * zr), dv = sqrt(r * r + zv * zv);
    return ap / (4 * M_PI) * (zr * (1 + str * dr) * exp(-str * dr) / (dr * dr * dr) + zv * (1 + str * dv) * exp(-str * dv) / (dv * dv * dv));
}

static void test_profile(void)
{
    const double sa[3] = {0.05, 0.2, 0.5}, sps[3] = {4, 4, 4}, eta = 1.33;
    const double r[] = {0, 0.01, 0.1, 0.3, 1, 2, 5};
    mt__diffusion rd;
    double worst = 0, tot[3] = {0, 0, 0};
    size_t i;
    int c, k;
    mt__diffusion_init(&rd, mt_rgb_make((mt_real)sa[0], (mt_real)sa[1], (mt_real)sa[2]),
                       mt_rgb_make((mt_real)sps[0], (mt_real)sps[1], (mt_real)sps[2]), mt__fdr((mt_real)eta, MT_MODE_PBRT_V2));
    for (i = 0; i < sizeof r / sizeof r[0]; ++i) {
        mt_rgb v = mt__diffusion_eval(&rd, (mt_real)(r[i] * r[i]));
        for (c = 0; c < 3; ++c) {
            double want = jensen_rd(r[i], sa[c], sps[c], eta), e = fabs(v.c[c] - want) / want;
            if (e > worst) worst = e;
        }
    }
    t_check(worst < (sizeof(mt_real) == 4 ? 2e-5 : 1e-12), "diffusion profile: Jensen et al.'s closed form at r = 0 .. 5",
            "worst relative difference %.3g", worst);
    /* int Rd 2 pi r dr = the total diffuse reflectance (Jensen et al. eq. 5) */
    for (k = 0; k < 400000; ++k) {
        double rr = (k + 0.5) * 1e-4;
        mt_rgb v = mt__diffusion_eval(&rd, (mt_real)(rr * rr));
        for (c = 0; c < 3; ++c) tot[c] += v.c[c] * 2 * M_PI * rr * 1e-4;
    }
    worst = 0;
    for (c = 0; c < 3; ++c) {
        double ap = sps[c] / (sa[c] + sps[c]), F = poly_fdr(eta), A = (1 + F) / (1 - F), s = sqrt(3 * (1 - ap));
        double want = ap / 2 * (1 + exp(-4.0 / 3.0 * A * s)) * exp(-s);
        double e = fabs(tot[c] - want) / want;
        if (e > worst) worst = e;
    }
    t_check(worst < 2e-3, "diffusion profile: its integral over the plane is the total diffuse reflectance",
            "worst relative difference %.3g", worst);
}

static void test_fdr(void)
{
    const double etas[] = {0.5, 0.8, 1.1, 1.33, 1.5, 2, 3, 5, 10};
    double worst = 0;
    size_t i;
    int poly_bad = 0;
    for (i = 0; i < sizeof etas / sizeof etas[0]; ++i) {
        /* 2 int Fr(mu) mu dmu by a plain midpoint sum of 200000 steps */
        double e = etas[i], sum = 0, got;
        int k;
        for (k = 0; k < 200000; ++k) {
            double mu = (k + 0.5) / 200000, sint = e * sqrt(1 - mu * mu), fr = 1;
            if (sint < 1) {
                double ct = sqrt(1 - sint * sint), a = (mu - e * ct) / (mu + e * ct), b = (e * mu - ct) / (e * mu + ct);
                fr = (a * a + b * b) / 2;
            }
            sum += 2 * fr * mu / 200000;
        }
        got = mt__fdr((mt_real)e, MT_MODE_CORRECTED);
        if (fabs(got - sum) > worst) worst = fabs(got - sum);
        if (fabs(mt__fdr((mt_real)e, MT_MODE_PBRT_V2) - poly_fdr(e)) > 1e-6) poly_bad++;
    }
    t_check(poly_bad == 0, "Fdr pbrt-v2 mode: the polynomial fit at eta 0.5 .. 10", "%d of 9 differ", poly_bad);
    t_check(worst < 2e-5, "Fdr corrected: the hemispherical integral of the Fresnel reflectance", "worst %.3g", worst);
    printf("  fdr-range: eta 1.33 fit %.5f integral %.5f; eta 4 fit %.5f integral %.5f; eta 5 fit %.5f (1 - Fdr = %.3f) integral %.5f\n",
           poly_fdr(1.33), (double)mt__fdr((mt_real)1.33, MT_MODE_CORRECTED), poly_fdr(4),
           (double)mt__fdr(4, MT_MODE_CORRECTED), poly_fdr(5), 1 - poly_fdr(5), (double)mt__fdr(5, MT_MODE_CORRECTED));
    t_check(mt__fdr(5, MT_MODE_PBRT_V2) > 1 && mt__fdr(5, MT_MODE_CORRECTED) < 1,
            "fdr-range: pbrt-v2's fit exceeds 1 at eta 5, the integral does not", "%g %g",
            (double)mt__fdr(5, MT_MODE_PBRT_V2), (double)mt__fdr(5, MT_MODE_CORRECTED));
}

/* ---- points and the octree ----------------------------------------------------------------- */

static int build(const mt_scene *s, mt_mode mode, uint64_t seed, int threads, mt__dipole *d, const mt_render_options *po)
{
    mt_render_options o;
    mt_error err;
    if (po) o = *po;
    else mt_render_options_default(&o);
    o.seed = seed;
    (void)mode;
    if (mt__dipole_build(s, &o, threads, d, &err) != MT_OK) {
        t_fail("dipole preprocess", "%s", err.message);
        return 0;
    }
    return 1;
}

static void test_points(void)
{
    mt_error err;
    mt_scene *s = load(scene_text((mt_real)0.1, NULL), MT_MODE_PBRT_V2, &err);
    mt_scene *sc = load(scene_text((mt_real)0.1, NULL), MT_MODE_CORRECTED, &err);
    mt__dipole d1, d2, d3, dc;
    double min2 = 1e30, sum_area = 0, sum_c = 0;
    int i, j, same;
    if (!s || !sc) {
        t_fail("dipole scene", "%s", err.message);
        return;
    }
    if (!build(s, MT_MODE_PBRT_V2, 7, 1, &d1, NULL) || !build(s, MT_MODE_PBRT_V2, 7, 2, &d2, NULL) ||
        !build(s, MT_MODE_PBRT_V2, 7, 3, &d3, NULL) || !build(sc, MT_MODE_CORRECTED, 7, 2, &dc, NULL))
        return;
    same = d1.npts == d2.npts && d1.npts == d3.npts && d1.npts > 100;
    for (i = 0; same && i < d1.npts; ++i)
        same = !memcmp(&d1.pts[i].p, &d2.pts[i].p, sizeof(mt_vec3)) && !memcmp(&d1.pts[i].E, &d2.pts[i].E, sizeof(mt_rgb)) &&
               !memcmp(&d1.pts[i].p, &d3.pts[i].p, sizeof(mt_vec3)) && !memcmp(&d1.pts[i].E, &d3.pts[i].E, sizeof(mt_rgb));
    t_check(same, "irradiance points: the same points and irradiance on 1, 2 and 3 threads", "%d, %d, %d points", d1.npts,
            d2.npts, d3.npts);
    for (i = 0; i < d1.npts; ++i)
        for (j = i + 1; j < d1.npts; ++j) {
            double dd = mt_v3_len2(mt_v3_sub(d1.pts[i].p, d1.pts[j].p));
            if (dd < min2) min2 = dd;
        }
    t_check(min2 >= 0.1 * 0.1 * (1 - 1e-6), "irradiance points: no two closer than minsampledistance",
            "closest pair %.5f apart (%d points)", sqrt(min2), d1.npts);
    for (i = 0; i < d1.npts; ++i) {
        double r = mt_v3_len(mt_v3_sub(d1.pts[i].p, mt_v3(0, 0, 1)));
        sum_area += d1.pts[i].area;
        if (fabs(r - 1) > 1e-3) {
            t_fail("irradiance points: on the subsurface sphere only", "point %d at distance %g from its centre", i, r);
            break;
        }
    }
    for (i = 0; i < dc.npts; ++i) sum_c += dc.pts[i].area;
    printf("  %d points (min distance 0.1, %ld paths, %ld candidates): areas sum to %.3f (pbrt-v2: pi d^2/4 each), "
           "%.3f corrected; the sphere's is %.3f\n",
           d1.npts, d1.paths, d1.candidates, sum_area, sum_c, 4 * M_PI);
    t_check(fabs(sum_c / (4 * M_PI) - 1) < 0.05, "dipole-area corrected: the points' areas sum to the sphere's within 5%",
            "%.4f of it", sum_c / (4 * M_PI));
    t_check(sum_area / (4 * M_PI) < 0.7, "dipole-area pbrt-v2: pi (d/2)^2 per point covers well under the sphere",
            "%.4f of it", sum_area / (4 * M_PI));
    {
        /* another seed, another point set */
        mt__dipole d4;
        if (build(s, MT_MODE_PBRT_V2, 8, 2, &d4, NULL)) {
            t_check(d4.npts != d1.npts || memcmp(&d4.pts[0].p, &d1.pts[0].p, sizeof(mt_vec3)) != 0,
                    "irradiance points: another seed gives another set", "%d points", d4.npts);
            mt__dipole_free(&d4);
        }
    }
    mt__dipole_free(&d1);
    mt__dipole_free(&d2);
    mt__dipole_free(&d3);
    mt__dipole_free(&dc);
    mt_scene_destroy(s);
    mt_scene_destroy(sc);
}

static double mo_error(const mt__dipole *d, const mt__diffusion *rd, mt_real maxerror, double *mean)
{
    double worst = 0, sum = 0;
    int i, n = 0, c;
    for (i = 0; i < d->npts; i += 7) {
        /* on the surface, and a little inside it */
        int k;
        for (k = 0; k < 2; ++k) {
            mt_vec3 p = k == 0 ? d->pts[i].p : mt_v3_sub(d->pts[i].p, mt_v3_scale(d->pts[i].n, (mt_real)0.02));
            mt_rgb a = mt__dipole_mo(d, p, rd, maxerror), b = mt__dipole_mo_brute(d, p, rd);
            for (c = 0; c < 3; ++c) {
                double e = b.c[c] > 0 ? fabs(a.c[c] - b.c[c]) / b.c[c] : fabs(a.c[c]);
                if (e > worst) worst = e;
                sum += e;
                n++;
            }
        }
    }
    *mean = n ? sum / n : 0;
    return worst;
}

static void test_octree(void)
{
    mt_error err;
    mt_scene *s = load(scene_text((mt_real)0.06, NULL), MT_MODE_PBRT_V2, &err);
    mt__dipole d;
    mt__diffusion rd;
    double e0, e05, e01, e001, m0, m05, m01, m001, ec05, mc05;
    if (!s) {
        t_fail("dipole scene", "%s", err.message);
        return;
    }
    if (!build(s, MT_MODE_PBRT_V2, 1, 2, &d, NULL)) return;
    mt__diffusion_init(&rd, mt_rgb_make((mt_real)0.05, (mt_real)0.2, (mt_real)0.5), mt_rgb_gray(4),
                       mt__fdr((mt_real)1.33, MT_MODE_PBRT_V2));
    e0 = mo_error(&d, &rd, 0, &m0);
    e05 = mo_error(&d, &rd, (mt_real)0.05, &m05);
    e01 = mo_error(&d, &rd, (mt_real)0.01, &m01);
    e001 = mo_error(&d, &rd, (mt_real)0.001, &m001);
    printf("  octree Mo against the sum over %d points: worst (mean) relative error %.2e (%.2e) at maxerror 0.05, "
           "%.2e (%.2e) at 0.01, %.2e (%.2e) at 0.001, %.2e at 0\n",
           d.npts, e05, m05, e01, m01, e001, m001, e0);
    t_check(e0 < (sizeof(mt_real) == 4 ? 1e-4 : 1e-10), "octree Mo at maxerror 0: the sum over every point", "%.3g", e0);
    t_check(e05 < 0.05, "octree Mo at maxerror 0.05: within 5% of the sum over every point", "worst %.3g", e05);
    t_check(e001 < e01 && e01 < e05 && m001 < m01 && m01 < m05, "octree Mo converges to the sum as maxerror goes to 0",
            "worst %.3g %.3g %.3g, mean %.3g %.3g %.3g", e05, e01, e001, m05, m01, m001);
    /* the cluster erratum: the same points, the octree of corrected mode */
    d.mode = MT_MODE_CORRECTED;
    if (mt__dipole_octree(&d, &err) != MT_OK) {
        t_fail("octree", "%s", err.message);
    } else {
        ec05 = mo_error(&d, &rd, (mt_real)0.05, &mc05);
        printf("  octree-cluster: at maxerror 0.05 the area-weighted clusters err by %.2e (mean %.2e), pbrt-v2's mean of "
               "children by %.2e (mean %.2e)\n",
               ec05, mc05, e05, m05);
        t_check(mc05 < m05, "octree-cluster corrected: area-weighted clusters are closer to the sum", "%.3g vs %.3g", mc05, m05);
    }
    /* more than 8 points at one position (a points file may hold them) */
    {
        int i;
        for (i = 0; i < 20 && i < d.npts; ++i) d.pts[i].p = d.pts[0].p;
        if (mt__dipole_octree(&d, &err) != MT_OK) {
            t_fail("octree with 20 coincident points", "%s", err.message);
        } else {
            e0 = mo_error(&d, &rd, 0, &m0);
            t_check(e0 < (sizeof(mt_real) == 4 ? 1e-4 : 1e-10), "octree with 20 coincident points: built, Mo exact at maxerror 0",
                    "%.3g", e0);
        }
    }
    mt__dipole_free(&d);
    mt_scene_destroy(s);
}

/* ---- renders, progress, the points file ------------------------------------------------- */

typedef struct stages {
    int deposit, irradiance, last_ok;
    long count;
} stages;

static void on_stage(void *ctx, const char *name, double f, long count, double el, double rem)
{
    stages *st = ctx;
    (void)el;
    (void)rem;
    if (!strcmp(name, "depositing points")) st->deposit++;
    if (!strcmp(name, "computing irradiance")) {
        st->irradiance++;
        st->last_ok = f == 1;
        st->count = count;
    }
}

static void test_renders(void)
{
    mt_error err;
    mt_scene *s = load(scene_text((mt_real)0.1, NULL), MT_MODE_PBRT_V2, &err);
    mt_render_options o;
    mt_render_stats st;
    mt_image a, b;
    stages sg;
    size_t i, bad = 0;
    if (!s) {
        t_fail("dipole scene", "%s", err.message);
        return;
    }
    mt_render_options_default(&o);
    o.spp = 4;
    o.threads = 1;
    o.seed = 5;
    memset(&sg, 0, sizeof sg);
    o.stage = on_stage;
    o.progress_ctx = &sg;
    if (mt_scene_render(s, &o, &a, NULL, &st, &err) != MT_OK) {
        t_fail("dipole render", "%s", err.message);
        mt_scene_destroy(s);
        return;
    }
    o.threads = 2;
    o.stage = NULL;
    if (mt_scene_render(s, &o, &b, NULL, NULL, &err) != MT_OK) {
        t_fail("dipole render", "%s", err.message);
    } else {
        t_check(t_images_identical(&a, &b), "dipolesubsurface render: bit-identical on 1 and 2 threads", "images differ");
        mt_image_free(&b);
    }
    t_check(sg.deposit > 0 && sg.irradiance > 0 && sg.last_ok && sg.count == st.points && st.points > 100,
            "dipolesubsurface progress: the deposition and the irradiance pass, with the point count",
            "%d deposition and %d irradiance calls, count %ld of %ld points", sg.deposit, sg.irradiance, sg.count, st.points);
    for (i = 0; i < (size_t)a.width * a.height * 3; ++i)
        if (!isfinite(a.data[i]) || a.data[i] < 0) bad++;
    t_check(bad == 0, "dipolesubsurface render: finite, non-negative", "%zu bad values", bad);
    mt_image_free(&a);
    mt_scene_destroy(s);

    /* eta 5: pbrt-v2's Fdr > 1 makes the subsurface term negative; never a NaN */
    {
        char text[4096];
        snprintf(text, sizeof text,
                 SCENE_HEAD "SurfaceIntegrator \"dipolesubsurface\" \"float minsampledistance\" [0.2]\n" SCENE_WORLD(
                     "Material \"subsurface\" \"rgb sigma_a\" [0.05 0.2 0.5] \"rgb sigma_prime_s\" [4 4 4] \"float index\" [5]"));
        s = load(text, MT_MODE_PBRT_V2, &err);
        if (s && mt_scene_render(s, &o, &a, NULL, NULL, &err) == MT_OK) {
            bad = 0;
            for (i = 0; i < (size_t)a.width * a.height * 3; ++i)
                if (!isfinite(a.data[i])) bad++;
            t_check(bad == 0, "fdr-range pbrt-v2 mode, index 5: no NaN or infinity", "%zu bad values", bad);
            mt_image_free(&a);
        } else {
            t_fail("fdr-range render", "%s", err.message);
        }
        mt_scene_destroy(s);
    }

    /* no BSSRDF anywhere: pbrt-v2 gives up on the points and renders as
     * directlighting (no specular surfaces: the depth rules do not differ) */
    {
        char t1[4096], t2[4096];
        int nwarn = 0;
        snprintf(t1, sizeof t1, SCENE_HEAD "SurfaceIntegrator \"dipolesubsurface\"\n" SCENE_WORLD("Material \"matte\""));
        snprintf(t2, sizeof t2, SCENE_HEAD "SurfaceIntegrator \"directlighting\"\n" SCENE_WORLD("Material \"matte\""));
        {
            mt_scene *s1 = t_scene(t1, NULL, &nwarn, &err), *s2 = t_scene(t2, NULL, NULL, &err);
            if (s1 && s2 && t_render(s1, 4, 2, 1, &a, NULL, &err) == MT_OK && t_render(s2, 4, 2, 1, &b, NULL, &err) == MT_OK) {
                t_check(t_images_identical(&a, &b), "dipolesubsurface without BSSRDF: the directlighting image", "images differ");
                mt_image_free(&a);
                mt_image_free(&b);
            } else {
                t_fail("dipolesubsurface without BSSRDF", "%s", err.message);
            }
            mt_scene_destroy(s1);
            mt_scene_destroy(s2);
        }
    }
}

static void test_points_file(void)
{
    const char *dir = t_tmpdir_create("dipole");
    const char *good = "# position normal area epsilon\n0 0 2  0 0 1  0.01 0.001\n0.1 0 1.995 0.1 0 1 0.01 0.001\n"
                       "0 1 1 0 1 0 0.02 0.001 # a third\n";
    char text[4096], path[512];
    mt_error err;
    mt_scene *s;
    mt_render_options o;
    mt_render_stats st;
    mt_image img;
    if (!dir) {
        t_fail("points file", "no temporary directory");
        return;
    }
    snprintf(path, sizeof path, "%s", t_write_file("pts.txt", good, strlen(good)));
    snprintf(text, sizeof text, "%s", scene_text((mt_real)0.1, ""));
    {
        char *at = strstr(text, "[0.1] ");
        char tail[4096];
        snprintf(tail, sizeof tail, "%s", at + 6);
        snprintf(at + 6, sizeof text - (size_t)(at + 6 - text), "\"string pointsfile\" \"%s\"%s", path, tail);
    }
    s = load(text, MT_MODE_PBRT_V2, &err);
    mt_render_options_default(&o);
    o.spp = 1;
    if (!s || mt_scene_render(s, &o, &img, NULL, &st, &err) != MT_OK) {
        t_fail("points file: read and rendered", "%s", err.message);
    } else {
        t_check(st.points == 3, "points file: its 3 points are the irradiance points", "%ld points", st.points);
        mt_image_free(&img);
    }
    mt_scene_destroy(s);
    {
        /* a relative name is the scene file's neighbour, whatever the
         * current directory (pbrt-v2 as released reads it with
         * FindOneFilename, d9f2b75; the 2012 source from the current
         * directory) */
        char rel[4096], scene_path[512];
        snprintf(rel, sizeof rel, "%s", scene_text((mt_real)0.1, "\"string pointsfile\" \"pts.txt\""));
        snprintf(scene_path, sizeof scene_path, "%s", t_write_file("scene.pbrt", rel, strlen(rel)));
        mt_render_options_default(&o);
        o.spp = 1;
        s = mt_scene_load(scene_path, &o, &err);
        if (!s || mt_scene_render(s, &o, &img, NULL, &st, &err) != MT_OK) {
            t_fail("points file: a relative name is found beside the scene file (d9f2b75)", "%s", err.message);
        } else {
            t_check(st.points == 3, "points file: a relative name is found beside the scene file (d9f2b75)",
                    "%ld points", st.points);
            mt_image_free(&img);
        }
        mt_scene_destroy(s);
    }
    {
        static const struct {
            const char *content;
            int line;
            const char *what;
        } bad[] = {{"0 0 2 0 0 1 0.01 0.001\n0 0 x 0 0 1 0.01 0.001\n", 2, "not a finite number"},
                   {"0 0 2 0 0 1 0.01 0.001\n1 2 3\n", 0, "not a multiple of 8"},
                   {"0 0 2 0 0 0 0.01 0.001\n", 0, "zero normal"}};
        size_t k;
        for (k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
            char name[64], msg[128];
            const char *p;
            snprintf(name, sizeof name, "bad%zu.txt", k);
            p = t_write_file(name, bad[k].content, strlen(bad[k].content));
            {
                char t2[4096], *at;
                snprintf(t2, sizeof t2, "%s", text);
                at = strstr(t2, path);
                memmove(at + strlen(p), at + strlen(path), strlen(at + strlen(path)) + 1);
                memcpy(at, p, strlen(p));
                s = load(t2, MT_MODE_PBRT_V2, &err);
            }
            snprintf(msg, sizeof msg, "points file error located: %s", bad[k].what);
            t_check(!s && strstr(err.message, bad[k].what) && strcmp(err.file, p) == 0 &&
                        (bad[k].line == 0 || err.line == bad[k].line) && strcmp(err.param, "pointsfile") == 0,
                    msg, "%s:%d: %s [%s]", err.file, err.line, err.message, err.param);
            mt_scene_destroy(s);
        }
        {
            char t2[4096], *at;
            snprintf(t2, sizeof t2, "%s", text);
            at = strstr(t2, "pts.txt");
            memcpy(at, "nox.txt", 7);
            s = load(t2, MT_MODE_PBRT_V2, &err);
            t_check(!s && strstr(err.message, "nox.txt"), "points file missing: an error naming it", "%s", s ? "loaded" : err.message);
            mt_scene_destroy(s);
        }
    }
    t_tmpdir_remove();
}

static void test_params(void)
{
    mt_error err;
    mt_scene *s = load(SCENE_HEAD "SurfaceIntegrator \"dipolesubsurface\"\n" SCENE_WORLD(SS_MATERIAL), MT_MODE_PBRT_V2, &err);
    if (!s) {
        t_fail("dipolesubsurface defaults", "%s", err.message);
        return;
    }
    t_check(s->integrator == MT__INTEGRATOR_DIPOLE && s->maxdepth == 5 && s->dipole.maxerror == (mt_real)0.05 &&
                s->dipole.min_dist == (mt_real)0.25 && s->dipole.nfile_pts == 0,
            "dipolesubsurface: pbrt-v2's defaults (maxdepth 5, maxerror 0.05, minsampledistance 0.25, no points file)",
            "%d %g %g", s->maxdepth, (double)s->dipole.maxerror, (double)s->dipole.min_dist);
    mt_scene_destroy(s);
    s = load(SCENE_HEAD "SurfaceIntegrator \"dipolesubsurface\" \"float minsampledistance\" [0]\n" SCENE_WORLD(SS_MATERIAL),
             MT_MODE_PBRT_V2, &err);
    t_check(!s && !strcmp(err.param, "minsampledistance") && err.line == 5, "dipolesubsurface: minsampledistance 0 rejected at its line",
            "%s:%d %s", err.file, err.line, err.message);
    mt_scene_destroy(s);
}

int main(void)
{
    test_profile();
    test_fdr();
    test_params();
    test_points();
    test_octree();
    test_renders();
    test_points_file();
    return t_status();
}
