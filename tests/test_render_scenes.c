/*
 * Small scenes with known answers, rendered end to end: a Lambertian plane
 * under a constant sky (Kd L exactly, in expectation), a diffuse sphere under
 * a point light (the analytic irradiance, pixel by pixel), a mirror and a
 * glass sphere in a constant environment (all energy comes back: L), path
 * and directlighting where they must agree; the same image on 1, 2 and 3
 * threads; no heap allocation per sample; broken scenes rejected with their
 * file and line, and nothing written.
 *
 * Means are compared with 5 standard errors estimated from the renderer's
 * per-pixel variance (conservative for low-discrepancy samples) plus the
 * float rounding of the sums.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <dirent.h>
#include "materia/tools/alloc.h"
#include "support/check.h"
#include "support/tfiles.h"
#include "support/trender.h"

#define PI_D 3.14159265358979323846

static int render(const char *name, const char *text, int spp, mt_image *img, mt_image *var)
{
    mt_error err;
    mt_scene *s = t_scene_or_fail(name, text);
    mt_status st;
    if (!s) return 0;
    st = t_render(s, spp, 0, 1, img, var, &err);
    mt_scene_destroy(s);
    if (st != MT_OK) {
        char buf[1024];
        t_fail(name, "render: %s", mt_error_format(&err, buf, sizeof buf));
        return 0;
    }
    return 1;
}

/* The image's mean per channel against want, within 5 standard errors. */
static void check_mean(const char *name, const mt_image *img, const mt_image *var, const double want[3])
{
    double m[3], se[3], worst = 0;
    int c, ok = 1;
    for (c = 0; c < 3; ++c) {
        t_region_stats(img, var, 0, 0, img->width, img->height, c, &m[c], &se[c]);
        if (fabs(m[c] - want[c]) > 5 * se[c] + 1e-5 * want[c]) ok = 0;
        worst = fmax(worst, fabs(m[c] - want[c]) / fmax(se[c], 1e-30));
    }
    t_check(ok, name, "mean (%.6g %.6g %.6g), want (%.6g %.6g %.6g), standard errors (%.2g %.2g %.2g)",
            m[0], m[1], m[2], want[0], want[1], want[2], se[0], se[1], se[2]);
}

/* ---- a Lambertian plane under a constant sky: Kd L ----------------------------- */

static const char *plane_scene =
    "LookAt 0 0 5  0 0 0  0 1 0 Camera \"perspective\" \"float fov\" [30]\n"
    "Film \"image\" \"integer xresolution\" [24] \"integer yresolution\" [16]\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [16]\n"
    "SurfaceIntegrator \"%s\"\n"
    "WorldBegin\n"
    "LightSource \"infinite\" \"rgb L\" [0.8 1.0 1.25]\n"
    "Material \"matte\" \"rgb Kd\" [0.5 0.3 0.7]\n"
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
    "  \"point P\" [-100 -100 0  100 -100 0  100 100 0  -100 100 0]\n"
    "WorldEnd\n";

static void test_plane_furnace(void)
{
    static const char *integ[] = {"path", "directlighting"};
    const double want[3] = {0.5 * 0.8, 0.3 * 1.0, 0.7 * 1.25};
    int i;
    for (i = 0; i < 2; ++i) {
        char text[2048], name[128];
        mt_image img, var;
        snprintf(text, sizeof text, plane_scene, integ[i]);
        snprintf(name, sizeof name, "%s: a Lambertian plane under a constant sky is Kd L", integ[i]);
        if (!render(name, text, 0, &img, &var)) continue;
        check_mean(name, &img, &var, want);
        mt_image_destroy(&img);
        mt_image_destroy(&var);
    }
}

/* ---- a diffuse sphere under a point light ---------------------------------------- */

static const char *point_scene =
    "LookAt 0 0 10  0 0 0  0 1 0 Camera \"orthographic\" \"float screenwindow\" [-1.2 1.2 -1.2 1.2]\n"
    "Film \"image\" \"integer xresolution\" [24] \"integer yresolution\" [24]\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [16]\n"
    "SurfaceIntegrator \"%s\"\n"
    "WorldBegin\n"
    "LightSource \"point\" \"rgb I\" [50 40 30] \"point from\" [3 2 6]\n"
    "Material \"matte\" \"rgb Kd\" [0.6 0.6 0.6]\n"
    "Shape \"sphere\" \"float radius\" [1]\n"
    "WorldEnd\n";

/* Kd / pi * I cos / d^2 at the sphere point under world (X, Y); 0 off it. */
static double point_radiance(double X, double Y, double I)
{
    double z2 = 1 - X * X - Y * Y, Z, lx, ly, lz, d2, c;
    if (z2 <= 0) return 0;
    Z = sqrt(z2);
    lx = 3 - X, ly = 2 - Y, lz = 6 - Z;
    d2 = lx * lx + ly * ly + lz * lz;
    c = (X * lx + Y * ly + Z * lz) / sqrt(d2);
    return c > 0 ? 0.6 / PI_D * I * c / d2 : 0;
}

static void test_point_light(void)
{
    static const char *integ[] = {"directlighting", "path"};
    const double I[3] = {50, 40, 30};
    int k;
    for (k = 0; k < 2; ++k) {
        char text[2048], name[160];
        mt_image img, var;
        double worst = 0;
        int x, y, c, n = 0, ok = 1;
        snprintf(text, sizeof text, point_scene, integ[k]);
        snprintf(name, sizeof name, "%s: a diffuse sphere under a point light, pixel by pixel", integ[k]);
        if (!render(name, text, 0, &img, &var)) continue;
        /* the camera's x runs along world -x (pbrt-v2's LookAt), its y along +y */
        for (y = 0; y < 24; ++y)
            for (x = 0; x < 24; ++x) {
                double sx0 = -1.2 + 0.1 * x, sy0 = 1.2 - 0.1 * y, want[3] = {0, 0, 0};
                int i, j, inside = 1, dark = 0;
                for (j = 0; j < 2; ++j)
                    for (i = 0; i < 2; ++i)
                        if ((sx0 + 0.1 * i) * (sx0 + 0.1 * i) + (sy0 - 0.1 * j) * (sy0 - 0.1 * j) > 0.97) inside = 0;
                if (!inside) continue;
                /* the pixel's mean by a 32x32 midpoint rule; pixels across the
                 * terminator are left out (16 samples on a kink: a few
                 * percent, and the sample variance can be 0 there) */
                for (j = 0; j < 32; ++j)
                    for (i = 0; i < 32; ++i)
                        for (c = 0; c < 3; ++c) {
                            double v = point_radiance(-(sx0 + 0.1 * (i + 0.5) / 32), sy0 - 0.1 * (j + 0.5) / 32, I[c]);
                            want[c] += v / 1024;
                            dark |= v == 0;
                        }
                if (dark) continue;
                for (c = 0; c < 3; ++c) {
                    double got = img.data[3 * (y * 24 + x) + c], sd = sqrt(var.data[3 * (y * 24 + x) + c]);
                    double tol = 5 * sd + 2e-3 * want[c] + 1e-6;
                    if (fabs(got - want[c]) > tol) ok = 0;
                    worst = fmax(worst, fabs(got - want[c]) / (want[c] + 1e-6));
                }
                n++;
            }
        t_check(ok && n > 200, name, "%d pixels, worst relative difference %.3g", n, worst);
        mt_image_destroy(&img);
        mt_image_destroy(&var);
    }
}

/* ---- mirror and glass spheres in a constant environment -------------------------- */

static const char *env_scene =
    "LookAt 0 -10 0  0 0 0  0 0 1 Camera \"orthographic\" \"float screenwindow\" [-0.9 0.9 -0.9 0.9]\n"
    "Film \"image\" \"integer xresolution\" [16] \"integer yresolution\" [16]\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [%d]\n"
    "SurfaceIntegrator \"path\" \"integer maxdepth\" [100]\n"
    "WorldBegin\n"
    "LightSource \"infinite\" \"rgb L\" [0.3 0.5 0.7]\n"
    "%s\n"
    "Shape \"sphere\" \"float radius\" [1]\n"
    "WorldEnd\n";

static void test_env_spheres(void)
{
    const double L[3] = {0.3, 0.5, 0.7};
    char text[2048];
    mt_image img, var;
    snprintf(text, sizeof text, env_scene, 4, "Material \"mirror\" \"rgb Kr\" [1 1 1]");
    if (render("mirror sphere", text, 0, &img, &var)) {
        double worst = 0;
        int i;
        for (i = 0; i < 16 * 16 * 3; ++i) worst = fmax(worst, fabs(img.data[i] - L[i % 3]) / L[i % 3]);
        t_check(worst < 1e-5, "path: a perfect mirror sphere in a constant sky reflects L exactly",
                "worst relative difference %.3g", worst);
        mt_image_destroy(&img);
        mt_image_destroy(&var);
    }
    snprintf(text, sizeof text, env_scene, 64, "Material \"glass\"");
    if (render("glass sphere", text, 0, &img, &var)) {
        double mv = 0;
        size_t i, n;
        check_mean("path: a glass sphere in a constant sky returns L (R + T = 1 at every event)",
                   &img, &var, L);
        /* The path's choice between reflection and transmission follows what
         * each brings (Fresnel), so every event's weight is R + T: the pixels'
         * variance is that of Russian roulette alone. Mean variance of a
         * pixel's value 6.9e-6 as measured; pbrt-v2's choice of one of the
         * two with probability 1/2 (weights 2R and 2T) gives 8.2e-3. */
        n = (size_t)var.width * (size_t)var.height * (size_t)var.channels;
        for (i = 0; i < n; ++i) mv += var.data[i];
        mv /= (double)n;
        t_check(mv < 2.4e-4, "path: through glass, reflection or transmission is chosen by its Fresnel weight",
                "mean variance of a pixel %.3g (bound 2.4e-4; a choice of 1/2 each gives 8.2e-3)", mv);
        mt_image_destroy(&img);
        mt_image_destroy(&var);
    }
}

/* ---- path and directlighting where they must agree ------------------------------- */

static const char *agree_scene =
    "LookAt 0 -6 1  0 0 0  0 0 1 Camera \"perspective\" \"float fov\" [25]\n"
    "Film \"image\" \"integer xresolution\" [24] \"integer yresolution\" [24]\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [32]\n"
    "SurfaceIntegrator \"%s\"\n"
    "WorldBegin\n"
    "AttributeBegin Material \"matte\" \"rgb Kd\" [0 0 0] Translate 2 -2 3\n"
    "  AreaLightSource \"area\" \"rgb L\" [8 8 8] \"integer nsamples\" [2]\n"
    "  Shape \"sphere\" \"float radius\" [0.7]\n"
    "AttributeEnd\n"
    "%s Shape \"sphere\" \"float radius\" [1]\n"
    "WorldEnd\n";

/* A single convex object and a black area light: nothing lights anything
 * twice, so the path integrator's estimate equals direct lighting. */
static void test_path_vs_direct(void)
{
    static const char *mats[] = {"Material \"plastic\" \"rgb Kd\" [0.3 0.4 0.5] \"float roughness\" [0.05]",
                                 "Material \"mirror\" \"rgb Kr\" [0.8 0.8 0.8]"};
    int k;
    for (k = 0; k < 2; ++k) {
        char text[2048], name[160];
        mt_image a, av, b, bv;
        int c, ok = 1;
        double ma[3], sa[3], mb[3], sb[3];
        snprintf(name, sizeof name, "path and directlighting agree on a %s sphere under an area light",
                 k ? "mirror" : "plastic");
        snprintf(text, sizeof text, agree_scene, "path", mats[k]);
        if (!render(name, text, 0, &a, &av)) continue;
        snprintf(text, sizeof text, agree_scene, "directlighting", mats[k]);
        if (!render(name, text, 0, &b, &bv)) {
            mt_image_destroy(&a);
            mt_image_destroy(&av);
            continue;
        }
        for (c = 0; c < 3; ++c) {
            t_region_stats(&a, &av, 0, 0, 24, 24, c, &ma[c], &sa[c]);
            t_region_stats(&b, &bv, 0, 0, 24, 24, c, &mb[c], &sb[c]);
            if (fabs(ma[c] - mb[c]) > 5 * sqrt(sa[c] * sa[c] + sb[c] * sb[c]) + 1e-5 * mb[c] || !(mb[c] > 0.01))
                ok = 0;
        }
        t_check(ok, name, "path (%.5g %.5g %.5g) +- (%.2g %.2g %.2g), directlighting (%.5g %.5g %.5g) +- (%.2g %.2g %.2g)",
                ma[0], ma[1], ma[2], sa[0], sa[1], sa[2], mb[0], mb[1], mb[2], sb[0], sb[1], sb[2]);
        mt_image_destroy(&a);
        mt_image_destroy(&av);
        mt_image_destroy(&b);
        mt_image_destroy(&bv);
    }
}

/* ---- direct lighting's two strategies with several lights -------------------------- */

static const char *lights_scene =
    "LookAt 0 -6 2.5  0 0 0.6  0 0 1 Camera \"perspective\" \"float fov\" [30]\n"
    "Film \"image\" \"integer xresolution\" [24] \"integer yresolution\" [24]\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [64]\n"
    "SurfaceIntegrator %s\n"
    "WorldBegin\n"
    "AttributeBegin LightSource \"infinite\" \"rgb L\" [0.3 0.35 0.4] AttributeEnd\n"
    "LightSource \"point\" \"point from\" [-2 -1 3] \"rgb I\" [2 2 2]\n"
    "AttributeBegin Material \"matte\" \"rgb Kd\" [0 0 0] Translate 2 -2 3\n"
    "  AreaLightSource \"area\" \"rgb L\" [8 8 8] Shape \"sphere\" \"float radius\" [0.4]\n"
    "AttributeEnd\n"
    "AttributeBegin Material \"matte\" \"rgb Kd\" [0 0 0] Translate -3 2 2\n"
    "  AreaLightSource \"area\" \"rgb L\" [2 1.5 1] Shape \"sphere\" \"float radius\" [1.2]\n"
    "AttributeEnd\n"
    "AttributeBegin Material \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\n"
    "  Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
    "  \"point P\" [-10 -10 0  10 -10 0  10 10 0  -10 10 0]\n"
    "AttributeEnd\n"
    "AttributeBegin Translate 0 0 1 %s Shape \"sphere\" \"float radius\" [1] AttributeEnd\n"
    "WorldEnd\n";

#define SEEDS 16

/* The image means per channel of SEEDS renders with seeds 1..SEEDS: their
 * mean and its standard error from their spread (the renders are
 * independent; low-discrepancy samples make a render's own variance image
 * claim several times the true error, too little power here). */
static int seed_means(const char *name, const char *text, double m[3], double se[3])
{
    mt_scene *sc = t_scene_or_fail(name, text);
    double x[SEEDS][3];
    int k, c;
    if (!sc) return 0;
    for (k = 0; k < SEEDS; ++k) {
        mt_image img;
        mt_error err;
        if (t_render(sc, 0, 0, (uint64_t)k + 1, &img, NULL, &err) != MT_OK) {
            char buf[1024];
            t_fail(name, "render: %s", mt_error_format(&err, buf, sizeof buf));
            mt_scene_destroy(sc);
            return 0;
        }
        for (c = 0; c < 3; ++c) {
            double unused;
            t_region_stats(&img, NULL, 0, 0, img.width, img.height, c, &x[k][c], &unused);
        }
        mt_image_destroy(&img);
    }
    mt_scene_destroy(sc);
    for (c = 0; c < 3; ++c) {
        double sum = 0, ss = 0;
        for (k = 0; k < SEEDS; ++k) sum += x[k][c];
        m[c] = sum / SEEDS;
        for (k = 0; k < SEEDS; ++k) ss += (x[k][c] - m[c]) * (x[k][c] - m[c]);
        se[c] = sqrt(ss / (SEEDS - 1) / SEEDS);
    }
    return 1;
}

/* The path integrator with maxdepth 0 is direct lighting with one light
 * chosen per vertex; directlighting with maxdepth 1 follows no specular
 * bounce. Both must give the expectation of directlighting "all" (every
 * light's EstimateDirect) with the light sample drawn for one light and the
 * BSDF sample counting for whichever light it finds: on a plastic sphere, a
 * shinymetal one (a specular lobe: the path's continuation serves direct
 * lighting only when it samples the glossy one) and a mix of plastic and
 * mirror (pbrt-v2's ScaledBxDF, whose pdf is not its sampling density:
 * erratum scaled-pdf), under two sphere lights, a point light and a sky. Welch's t over 16 seeds each, |t| below 5 (a false alarm
 * about once in 10^4 runs of the 12 tests): MIS weights of the BSDF sample
 * taken against 1.5 times the pdf of the light it finds give |t| of 5 to 10. */
static void test_light_strategies(void)
{
    static const char *mats[] = {"Material \"plastic\" \"rgb Kd\" [0.3 0.4 0.5] \"float roughness\" [0.05]",
                                 "Material \"shinymetal\" \"float roughness\" [0.05]",
                                 "MakeNamedMaterial \"p\" \"string type\" \"plastic\" \"float roughness\" [0.2]\n"
                                 "MakeNamedMaterial \"m\" \"string type\" \"mirror\"\n"
                                 "Material \"mix\" \"string namedmaterial1\" \"p\" \"string namedmaterial2\" \"m\" "
                                 "\"rgb amount\" [0.4 0.5 0.6]"};
    static const char *names[] = {"plastic", "shinymetal", "mix (plastic, mirror)"};
    static const char *integ[] = {"\"path\" \"integer maxdepth\" [0]",
                                  "\"directlighting\" \"integer maxdepth\" [1] \"string strategy\" \"one\""};
    int k, i;
    for (k = 0; k < 3; ++k) {
        char text[4096], name[200];
        double mb[3], sb[3];
        snprintf(text, sizeof text, lights_scene, "\"directlighting\" \"integer maxdepth\" [1]", mats[k]);
        if (!seed_means("light strategies", text, mb, sb)) continue;
        for (i = 0; i < 2; ++i) {
            double ma[3], sa[3], t[3];
            int c, ok = 1;
            snprintf(name, sizeof name, "%s and directlighting \"all\" agree on a %s sphere under four lights",
                     i ? "directlighting \"one\"" : "path (maxdepth 0)", names[k]);
            snprintf(text, sizeof text, lights_scene, integ[i], mats[k]);
            if (!seed_means(name, text, ma, sa)) continue;
            for (c = 0; c < 3; ++c) {
                t[c] = (ma[c] - mb[c]) / sqrt(sa[c] * sa[c] + sb[c] * sb[c] + 1e-14);
                if (!(fabs(t[c]) < 5) || !(mb[c] > 0.01)) ok = 0;
            }
            t_check(ok, name, "(%.6g %.6g %.6g) against (%.6g %.6g %.6g): t %.2f %.2f %.2f", ma[0], ma[1], ma[2],
                    mb[0], mb[1], mb[2], t[0], t[1], t[2]);
        }
    }
}

/* ---- a mesh light tested primitive by primitive or through the scene ---------------- */

static const char *mesh_light_scene =
    "LookAt 0 0 6  0 0 0  0 1 0 Camera \"perspective\" \"float fov\" [40]\n"
    "Film \"image\" \"integer xresolution\" [16] \"integer yresolution\" [16]\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [64]\n"
    "SurfaceIntegrator \"path\"\n"
    "WorldBegin\n"
    "AttributeBegin Material \"matte\" \"rgb Kd\" [0 0 0] AreaLightSource \"area\" \"rgb L\" [3 3 3]\n"
    "  Translate 0.7 0.4 2.5 Shape \"trianglemesh\" %s\n"
    "AttributeEnd\n"
    "Material \"matte\" \"rgb Kd\" [0.5 0.5 0.5]\n"
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
    "  \"point P\" [-20 -20 0  20 -20 0  20 20 0  -20 20 0]\n"
    "WorldEnd\n";

/* The same 1x1 square light facing down (-z) as 2 triangles and as 32
 * (a 4x4 grid): BSDF-sampled rays test the first's primitives one by one
 * and find the second's through the scene; the images must agree. */
static void test_mesh_light(void)
{
    char mesh[4096], text[8192];
    mt_image a, av, b, bv;
    double ma, sa, mb, sb;
    int i, j, n = 0, len;
    len = snprintf(mesh, sizeof mesh, "\"integer indices\" [0 2 1 0 3 2] "
                   "\"point P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]");
    snprintf(text, sizeof text, mesh_light_scene, mesh);
    if (!render("mesh light", text, 0, &a, &av)) return;
    len = snprintf(mesh, sizeof mesh, "\"integer indices\" [");
    for (j = 0; j < 4; ++j)
        for (i = 0; i < 4; ++i) {
            int v = j * 5 + i;
            len += snprintf(mesh + len, sizeof mesh - (size_t)len, " %d %d %d %d %d %d", v, v + 6, v + 1,
                            v, v + 5, v + 6);
            n += 2;
        }
    len += snprintf(mesh + len, sizeof mesh - (size_t)len, "] \"point P\" [");
    for (j = 0; j < 5; ++j)
        for (i = 0; i < 5; ++i)
            len += snprintf(mesh + len, sizeof mesh - (size_t)len, " %g %g 0", -0.5 + 0.25 * i, -0.5 + 0.25 * j);
    snprintf(mesh + len, sizeof mesh - (size_t)len, "]");
    snprintf(text, sizeof text, mesh_light_scene, mesh);
    if (render("mesh light", text, 0, &b, &bv)) {
        t_region_stats(&a, &av, 0, 0, 16, 16, 1, &ma, &sa);
        t_region_stats(&b, &bv, 0, 0, 16, 16, 1, &mb, &sb);
        t_check(n == 32 && ma > 0.01 && fabs(ma - mb) <= 5 * sqrt(sa * sa + sb * sb) + 1e-5 * mb,
                "an area light of 2 and of 32 triangles (direct tests and scene queries) agree",
                "%d triangles: %.6g +- %.2g against %.6g +- %.2g", n, mb, sb, ma, sa);
        mt_image_destroy(&b);
        mt_image_destroy(&bv);
    }
    mt_image_destroy(&a);
    mt_image_destroy(&av);
}

/* ---- determinism and allocation --------------------------------------------------- */

static const char *busy_scene =
    "LookAt 0 -5 2  0 0 0.6  0 0 1 Camera \"perspective\" \"float fov\" [35]\n"
    "Film \"image\" \"integer xresolution\" [37] \"integer yresolution\" [29]\n"
    "PixelFilter \"gaussian\"\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [4]\n"
    "SurfaceIntegrator \"path\"\n"
    "WorldBegin\n"
    "LightSource \"infinite\" \"rgb L\" [0.4 0.45 0.5]\n"
    "AttributeBegin Translate 2 -2 3 AreaLightSource \"area\" \"rgb L\" [5 5 5]\n"
    "  Shape \"sphere\" \"float radius\" [0.5] AttributeEnd\n"
    "Texture \"c\" \"color\" \"checkerboard\" \"float uscale\" [8] \"float vscale\" [8]\n"
    "Material \"matte\" \"texture Kd\" \"c\"\n"
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"float uv\" [0 0 1 0 1 1 0 1]\n"
    "  \"point P\" [-4 -4 0  4 -4 0  4 4 0  -4 4 0]\n"
    "Material \"plastic\" Translate 0 0 0.7 Shape \"sphere\" \"float radius\" [0.7]\n"
    "WorldEnd\n";

static mt_status render_opts(const mt_scene *s, int spp, int threads, int tile, mt_image *img)
{
    mt_render_options o;
    mt_error err;
    mt_render_options_default(&o);
    o.spp = spp;
    o.threads = threads;
    o.tile_size = tile;
    o.seed = 5;
    return mt_scene_render(s, &o, img, NULL, NULL, &err);
}

static void test_threads_identical(void)
{
    mt_scene *s = t_scene_or_fail("threads", busy_scene);
    mt_image one, two, three;
    if (!s) return;
    if (render_opts(s, 0, 1, 8, &one) == MT_OK && render_opts(s, 0, 2, 8, &two) == MT_OK &&
        render_opts(s, 0, 3, 8, &three) == MT_OK) {
        double sum = 0;
        int i;
        for (i = 0; i < 37 * 29 * 3; ++i) sum += one.data[i];
        t_check(t_images_identical(&one, &two) && t_images_identical(&one, &three) && sum > 0,
                "bit-identical images on 1, 2 and 3 threads (gaussian filter across 8x8 tiles)",
                "images differ");
        mt_image_destroy(&one);
        mt_image_destroy(&two);
        mt_image_destroy(&three);
    } else {
        t_fail("bit-identical images on 1, 2 and 3 threads", "render failed");
    }
    mt_scene_destroy(s);
}

static void test_no_allocation_per_sample(void)
{
    mt_scene *s = t_scene_or_fail("allocation", busy_scene);
    mt_image img;
    unsigned long c0, c1, c2;
    int threads;
    if (!s) return;
    for (threads = 1; threads <= 2; ++threads) {
        char name[160];
        render_opts(s, 1, threads, 0, &img); /* warm-up: texture and image caches */
        mt_image_destroy(&img);
        c0 = mt_alloc_count();
        render_opts(s, 2, threads, 0, &img);
        mt_image_destroy(&img);
        c1 = mt_alloc_count();
        render_opts(s, 16, threads, 0, &img);
        mt_image_destroy(&img);
        c2 = mt_alloc_count();
        snprintf(name, sizeof name,
                 "no heap allocation per sample (%d thread%s: allocations of a render at 2 and 16 spp)",
                 threads, threads > 1 ? "s" : "");
        t_check(c2 - c1 == c1 - c0, name, "%lu allocations at 2 spp, %lu at 16 spp", c1 - c0, c2 - c1);
    }
    mt_scene_destroy(s);
}

/* ---- broken scenes ------------------------------------------------------------------ */

typedef struct broken {
    const char *text;
    int line;
    const char *what; /* a substring of the message */
} broken;

#define OPT "Film \"image\" \"integer xresolution\" [8] \"integer yresolution\" [8]\n"

static void test_broken_scenes(void)
{
    static const broken cases[] = {
        {OPT "WorldBegin\nVolume \"homogeneous\"\nWorldEnd\n", 3, "Volume"},
        {OPT "SurfaceIntegrator \"dipolesubsurface\" \"float maxerror\" [-1]\nWorldBegin\nWorldEnd\n", 2, "maxerror"},
        {OPT "SurfaceIntegrator \"dipolesubsurface\" \"string pointsfile\" \"no-such-points.txt\"\nWorldBegin\nWorldEnd\n", 2, "no-such-points"},
        {OPT "SurfaceIntegrator \"photonmap\"\nWorldBegin\nWorldEnd\n", 2, "photonmap"},
        {OPT "WorldBegin\nObjectBegin \"a\"\nObjectEnd\nWorldEnd\n", 3, "ObjectBegin"},
        {OPT "Shape \"sphere\"\nWorldBegin\nWorldEnd\n", 2, "WorldBegin"},
        {OPT "WorldBegin\nCamera \"perspective\"\nWorldEnd\n", 3, "world block"},
        {OPT "Camera \"environment\"\nWorldBegin\nWorldEnd\n", 2, "environment"},
        {OPT "Camera \"perspective\" \"float fov\" [200]\nWorldBegin\nWorldEnd\n", 2, "fov"},
        {OPT "PixelFilter \"lanczos\"\nWorldBegin\nWorldEnd\n", 2, "lanczos"},
        {OPT "Sampler \"metropolis\"\nWorldBegin\nWorldEnd\n", 2, "metropolis"},
        {OPT "WorldBegin\nLightSource \"goniometric\"\nWorldEnd\n", 3, "goniometric"},
        {OPT "WorldBegin\nAreaLightSource \"spot\"\nShape \"sphere\"\nWorldEnd\n", 4, "spot"},
        {OPT "WorldBegin\nLightSource \"infinite\" \"string mapname\" \"no-such-map.exr\"\nWorldEnd\n", 3, "no-such-map"},
        {OPT "WorldBegin\nShape \"cone\"\nWorldEnd\n", 3, "cone"},
        {OPT "WorldBegin\nMaterial \"velvet\"\nShape \"sphere\"\nWorldEnd\n", 4, "velvet"},
        {OPT "WorldBegin\nShape \"sphere\" \"float radius\" \"big\"\nWorldEnd\n", 3, "radius"},
        {OPT "WorldBegin\nShape \"sphere\"\n", 3, "WorldEnd"},
        {OPT "WorldBegin\nWorldEnd\nWorldBegin\nWorldEnd\n", 4, "one WorldBegin"},
        {OPT "SurfaceIntegrator \"directlighting\" \"string strategy\" \"some\"\nWorldBegin\nWorldEnd\n", 2, "strategy"},
        {OPT "WorldBegin\nFrobnicate 1\nWorldEnd\n", 3, "Frobnicate"},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        mt_error err;
        mt_scene *s = t_scene(cases[i].text, NULL, NULL, &err);
        char buf[1024], name[160];
        snprintf(name, sizeof name, "broken scene %d (%s) is an error at <test>:%d", (int)i, cases[i].what, cases[i].line);
        mt_error_format(&err, buf, sizeof buf);
        t_check(!s && strcmp(err.file, "<test>") == 0 && err.line == cases[i].line &&
                    strstr(buf, cases[i].what) != NULL,
                name, "got %s", s ? "a scene" : buf);
        mt_scene_destroy(s);
    }
}

/* An error inside an included file names that file and line; a failed
 * write leaves nothing behind. */
static void test_broken_files(void)
{
    const char *dir = t_tmpdir_create("render-scenes");
    char scene[600], out[600];
    mt_render_options o;
    mt_error err;
    mt_scene *s;
    mt_image img;
    DIR *d;
    struct dirent *e;
    int n = 0;
    if (!dir) {
        t_fail("broken files", "no temporary directory");
        return;
    }
    t_write_file("inc/part.pbrt", "Material \"matte\"\n\nShape \"sphere\" \"float radius\" [-1]\n", (size_t)-1);
    snprintf(scene, sizeof scene, "%s", t_write_file("main.pbrt", OPT "WorldBegin\nInclude \"inc/part.pbrt\"\nWorldEnd\n", (size_t)-1));
    mt_render_options_default(&o);
    s = mt_scene_load(scene, &o, &err);
    t_check(!s && strstr(err.file, "inc/part.pbrt") != NULL && err.line == 3,
            "an error in an included file names that file and line", "%s:%d", err.file, err.line);
    mt_scene_destroy(s);
    /* a good scene rendered to a path that cannot be replaced (a directory) */
    snprintf(scene, sizeof scene, "%s", t_write_file("good.pbrt", OPT "WorldBegin\nWorldEnd\n", (size_t)-1));
    s = mt_scene_load(scene, &o, &err);
    snprintf(out, sizeof out, "%s/out.exr", dir);
    mkdir(out, 0700);
    if (s && mt_scene_render(s, &o, &img, NULL, NULL, &err) == MT_OK) {
        mt_status st = mt_render_write(out, &img, s, &o, &err);
        d = opendir(dir);
        while (d && (e = readdir(d)) != NULL)
            if (e->d_name[0] != '.') n++;
        if (d) closedir(d);
        /* main.pbrt, good.pbrt, inc, out.exr: no temporary file left */
        t_check(st != MT_OK && n == 4, "a failed write leaves no temporary file", "status %d, %d entries", st, n);
        mt_image_destroy(&img);
    } else {
        t_fail("a failed write leaves no temporary file", "render failed");
    }
    mt_scene_destroy(s);
    t_tmpdir_remove();
}

int main(void)
{
    test_plane_furnace();
    test_point_light();
    test_env_spheres();
    test_path_vs_direct();
    test_light_strategies();
    test_mesh_light();
    test_threads_identical();
    test_no_allocation_per_sample();
    test_broken_scenes();
    test_broken_files();
    return t_status();
}
