/*
 * The renderer's parts against their definitions: camera rays (pbrt-v2's
 * LookAt, fov on the shorter axis, screen window, Scale -1 1 1 mirroring,
 * differentials, orthographic, thin lens), each pixel filter's values and
 * integral against its formula, the film's normalization and crop window,
 * the sampler's stratification and determinism, and the lights: Sample_L
 * against Pdf, solid angles by Monte Carlo, the infinite map's importance
 * sampling against the map.
 *
 * Tolerances: directions computed in mt_real from double transforms agree
 * with the double formula within 1e-5 (float); quadratures use midpoint
 * rules whose error is below the stated tolerance; Monte Carlo checks allow
 * 5 standard errors estimated from the samples.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "materia/rng.h"
#include "materia/sampling.h"
#include "support/check.h"
#include "support/tfiles.h"
#include "support/tgeom.h"
#include "support/trender.h"
#include "tracer/scene.h"
#include "tracer/shading.h"

#define PI_D 3.14159265358979323846
#define DIR_TOL 2e-5

typedef struct d3 {
    double x, y, z;
} d3;

static d3 D3(double x, double y, double z)
{
    d3 r;
    r.x = x, r.y = y, r.z = z;
    return r;
}
static d3 d3_norm(d3 a)
{
    double l = sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return D3(a.x / l, a.y / l, a.z / l);
}
static d3 d3_cross(d3 a, d3 b)
{
    return D3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static double vdist(mt_vec3 a, d3 b)
{
    return fmax(fabs(a.x - b.x), fmax(fabs(a.y - b.y), fabs(a.z - b.z)));
}
static mt_vec3 unit(mt_vec3 v) { return mt_v3_normalize(v); }

/* ---- cameras ------------------------------------------------------------------ */

static mt_raydiff ray_at(const mt_scene *s, double x, double y)
{
    mt__camera_sample cs;
    mt_raydiff rd;
    cs.image_x = (mt_real)x;
    cs.image_y = (mt_real)y;
    cs.lens_u = cs.lens_v = (mt_real)0.5;
    mt__camera_ray(&s->camera, &cs, &rd);
    return rd;
}

/* pbrt-v2's LookAt frame: left = up x dir, newUp = dir x left (camera x, y, z). */
typedef struct frame3 {
    d3 pos, x, y, z;
} frame3;

static frame3 look_at(d3 pos, d3 look, d3 up)
{
    frame3 f;
    f.pos = pos;
    f.z = d3_norm(D3(look.x - pos.x, look.y - pos.y, look.z - pos.z));
    f.x = d3_norm(d3_cross(d3_norm(up), f.z));
    f.y = d3_cross(f.z, f.x);
    return f;
}

/* The expected world direction through raster (x, y): screen coordinates
 * scaled by tan(fov / 2), in the camera frame (mirror: camera x negated). */
static d3 expected_dir(const frame3 *f, const double sw[4], int xres, int yres, double fov,
                       double x, double y, int mirror)
{
    double sx = sw[0] + (sw[1] - sw[0]) * x / xres, sy = sw[3] - (sw[3] - sw[2]) * y / yres;
    double t = tan(fov * PI_D / 360), cx = sx * t * (mirror ? -1 : 1), cy = sy * t;
    return d3_norm(D3(cx * f->x.x + cy * f->y.x + f->z.x, cx * f->x.y + cy * f->y.y + f->z.y,
                      cx * f->x.z + cy * f->y.z + f->z.z));
}

static void check_camera(const char *name, const char *text, frame3 f, const double sw[4], int xres,
                         int yres, double fov, int mirror)
{
    static const double pts[][2] = {{0, 0}, {0.5, 0.5}, {1, 0.25}, {0.3, 1}, {0.77, 0.61}};
    mt_scene *s = t_scene_or_fail(name, text);
    double worst = 0, worst_dx = 0, worst_o = 0;
    size_t i;
    if (!s) return;
    for (i = 0; i < sizeof pts / sizeof pts[0]; ++i) {
        double x = pts[i][0] * xres, y = pts[i][1] * yres;
        mt_raydiff rd = ray_at(s, x, y);
        worst = fmax(worst, vdist(unit(rd.ray.d), expected_dir(&f, sw, xres, yres, fov, x, y, mirror)));
        worst_dx = fmax(worst_dx, vdist(unit(rd.rx_d), expected_dir(&f, sw, xres, yres, fov, x + 1, y, mirror)));
        worst_dx = fmax(worst_dx, vdist(unit(rd.ry_d), expected_dir(&f, sw, xres, yres, fov, x, y + 1, mirror)));
        worst_o = fmax(worst_o, vdist(rd.ray.o, f.pos));
    }
    t_check(worst < DIR_TOL && worst_dx < DIR_TOL && worst_o < 1e-5, name,
            "max direction error %.3g, differentials %.3g, origin %.3g", worst, worst_dx, worst_o);
    mt_scene_destroy(s);
}

static void test_cameras(void)
{
    frame3 f0 = look_at(D3(0, 0, 0), D3(0, 0, 1), D3(0, 1, 0));
    frame3 f1 = look_at(D3(1, 2, 3), D3(4, -1, 5), D3(0, 0, 1));
    double land[4] = {-2, 2, -1, 1}, port[4] = {-1, 1, -2, 2}, custom[4] = {-0.5, 1.5, -1, 0.25};
    double square[4] = {-1, 1, -1, 1};
    mt_scene *s;
    mt_raydiff a, b;
    check_camera("camera landscape: fov 90 spans y (the shorter axis), x right is world +x",
                 "LookAt 0 0 0  0 0 1  0 1 0 Camera \"perspective\" \"float fov\" [90]\n"
                 "Film \"image\" \"integer xresolution\" [200] \"integer yresolution\" [100]\n"
                 "WorldBegin WorldEnd\n",
                 f0, land, 200, 100, 90, 0);
    check_camera("camera portrait: fov 60 spans x (the shorter axis)",
                 "LookAt 1 2 3  4 -1 5  0 0 1 Camera \"perspective\" \"float fov\" [60]\n"
                 "Film \"image\" \"integer xresolution\" [100] \"integer yresolution\" [200]\n"
                 "WorldBegin WorldEnd\n",
                 f1, port, 100, 200, 60, 0);
    check_camera("camera screenwindow",
                 "LookAt 1 2 3  4 -1 5  0 0 1\n"
                 "Camera \"perspective\" \"float fov\" [45] \"float screenwindow\" [-0.5 1.5 -1 0.25]\n"
                 "Film \"image\" \"integer xresolution\" [64] \"integer yresolution\" [48]\n"
                 "WorldBegin WorldEnd\n",
                 f1, custom, 64, 48, 45, 0);
    check_camera("camera frameaspectratio 1 on a 64x32 film",
                 "LookAt 1 2 3  4 -1 5  0 0 1\n"
                 "Camera \"perspective\" \"float fov\" [50] \"float frameaspectratio\" [1]\n"
                 "Film \"image\" \"integer xresolution\" [64] \"integer yresolution\" [32]\n"
                 "WorldBegin WorldEnd\n",
                 f1, square, 64, 32, 50, 0);
    check_camera("camera Scale -1 1 1 mirrors the image horizontally",
                 "Scale -1 1 1 LookAt 1 2 3  4 -1 5  0 0 1 Camera \"perspective\" \"float fov\" [70]\n"
                 "Film \"image\" \"integer xresolution\" [80] \"integer yresolution\" [60]\n"
                 "WorldBegin WorldEnd\n",
                 f1, (double[4]){-80.0 / 60, 80.0 / 60, -1, 1}, 80, 60, 70, 1);

    /* orthographic: origins on the screen window in the camera plane, one direction */
    s = t_scene_or_fail("camera orthographic",
                      "LookAt 1 2 3  4 -1 5  0 0 1 Camera \"orthographic\" \"float screenwindow\" [-2 2 -1 1]\n"
                      "Film \"image\" \"integer xresolution\" [40] \"integer yresolution\" [20]\n"
                      "WorldBegin WorldEnd\n");
    if (s) {
        double worst = 0;
        int i;
        for (i = 0; i < 5; ++i) {
            double x = 40 * (0.1 + 0.2 * i), y = 20 * (0.9 - 0.17 * i);
            double sx = -2 + 4 * x / 40, sy = 1 - 2 * y / 20;
            d3 o = D3(f1.pos.x + sx * f1.x.x + sy * f1.y.x, f1.pos.y + sx * f1.x.y + sy * f1.y.y,
                      f1.pos.z + sx * f1.x.z + sy * f1.y.z);
            mt_raydiff rd = ray_at(s, x, y);
            worst = fmax(worst, fmax(vdist(rd.ray.o, o), vdist(unit(rd.ray.d), f1.z)));
            worst = fmax(worst, vdist(mt_v3_sub(rd.rx_o, rd.ray.o), D3(0.1 * f1.x.x, 0.1 * f1.x.y, 0.1 * f1.x.z)));
        }
        t_check(worst < 1e-5, "camera orthographic", "max error %.3g", worst);
        mt_scene_destroy(s);
    }

    /* thin lens: rays through different lens points meet on the plane of focus */
    s = t_scene_or_fail("camera thin lens",
                      "LookAt 1 2 3  4 -1 5  0 0 1\n"
                      "Camera \"perspective\" \"float fov\" [40] \"float lensradius\" [0.2] \"float focaldistance\" [3]\n"
                      "Film \"image\" \"integer xresolution\" [50] \"integer yresolution\" [50]\n"
                      "WorldBegin WorldEnd\n");
    if (s) {
        mt__camera_sample cs;
        mt_vec3 pa, pb;
        double ta, tb, la;
        cs.image_x = 13.3f, cs.image_y = 31.7f, cs.lens_u = 0.1f, cs.lens_v = 0.8f;
        mt__camera_ray(&s->camera, &cs, &a);
        cs.lens_u = 0.9f, cs.lens_v = 0.3f;
        mt__camera_ray(&s->camera, &cs, &b);
        /* camera z of a point = (p - pos) . f1.z; reach z = 3 */
        ta = (3 - ((a.ray.o.x - 1) * f1.z.x + (a.ray.o.y - 2) * f1.z.y + (a.ray.o.z - 3) * f1.z.z)) /
             (a.ray.d.x * f1.z.x + a.ray.d.y * f1.z.y + a.ray.d.z * f1.z.z);
        tb = (3 - ((b.ray.o.x - 1) * f1.z.x + (b.ray.o.y - 2) * f1.z.y + (b.ray.o.z - 3) * f1.z.z)) /
             (b.ray.d.x * f1.z.x + b.ray.d.y * f1.z.y + b.ray.d.z * f1.z.z);
        pa = mt_ray_at(&a.ray, (mt_real)ta);
        pb = mt_ray_at(&b.ray, (mt_real)tb);
        la = sqrt(pow(a.ray.o.x - 1, 2) + pow(a.ray.o.y - 2, 2) + pow(a.ray.o.z - 3, 2));
        t_check(vdist(pa, D3(pb.x, pb.y, pb.z)) < 1e-4 && la > 0.01 && la <= 0.2 + 1e-6,
                "camera thin lens: rays meet on the plane of focus, origins on the lens",
                "focus points differ by %.3g, lens offset %.3g", vdist(pa, D3(pb.x, pb.y, pb.z)), la);
        mt_scene_destroy(s);
    }
}

/* ---- lens differentials (88cdb51) and erratum ortho-lens ------------------------------ */

static mt_scene *scene_in_mode(const char *check, const char *text, mt_mode mode)
{
    mt_render_options o;
    mt_error err;
    mt_scene *s;
    mt_render_options_default(&o);
    o.mode = mode;
    s = mt_scene_load_string(text, "<test>", NULL, &o, &err);
    if (!s) {
        char buf[1024];
        t_fail(check, "scene: %s", mt_error_format(&err, buf, sizeof buf));
    }
    return s;
}

/* The point of r at camera depth z (the camera is the world's frame). */
static d3 at_depth(mt_vec3 o, mt_vec3 d, double z)
{
    double t = (z - o.z) / d.z;
    return D3(o.x + t * d.x, o.y + t * d.y, o.z + t * d.z);
}
static double d3_dist(d3 a, d3 b) { return sqrt(pow(a.x - b.x, 2) + pow(a.y - b.y, 2) + pow(a.z - b.z, 2)); }

/* Over 200 camera samples of a lens camera (lensradius 0.2, focaldistance 3,
 * 50 x 50 pixels) and the depths z = 1.5, 3 and 6: the footprint of the x
 * differential, |rx(z) - r(z)|, against the finite difference, the ray of
 * pixel x + 1 through the same lens point. *worst: the largest relative
 * error of the footprint vector; *lo, *hi: the range of the ratio of the
 * footprint's length to the finite difference's. */
static void lens_footprints(const mt_scene *s, double *worst, double *lo, double *hi)
{
    static const double depth[] = {1.5, 3, 6};
    mt_rng r;
    int i, k;
    *worst = 0, *lo = 1e30, *hi = 0;
    mt_rng_seed(&r, 7, 8);
    for (i = 0; i < 200; ++i) {
        mt__camera_sample cs;
        mt_raydiff a, b;
        cs.image_x = (mt_real)(48 * mt_rng_uniform(&r));
        cs.image_y = (mt_real)(50 * mt_rng_uniform(&r));
        cs.lens_u = mt_rng_uniform(&r);
        cs.lens_v = mt_rng_uniform(&r);
        mt__camera_ray(&s->camera, &cs, &a);
        cs.image_x += 1;
        mt__camera_ray(&s->camera, &cs, &b);
        for (k = 0; k < 3; ++k) {
            d3 p = at_depth(a.ray.o, a.ray.d, depth[k]), px = at_depth(a.rx_o, a.rx_d, depth[k]);
            d3 pf = at_depth(b.ray.o, b.ray.d, depth[k]);
            double fd = d3_dist(pf, p), ratio = d3_dist(px, p) / fd;
            *worst = fmax(*worst, d3_dist(px, pf) / fd);
            *lo = fmin(*lo, ratio);
            *hi = fmax(*hi, ratio);
        }
    }
}

/* The orthographic lens camera of pbrt-v2 (50 x 50 pixels, screen [-1, 1]^2,
 * lensradius 0.2, focaldistance 3, camera = world): over 200 samples, *dev
 * receives the largest distance of the x differential from pbrt-v2's
 * construction -- from the main ray's origin towards Pcamera + dxCamera at
 * depth focalDistance / d.z, with Pcamera read off the main ray at the plane
 * of focus -- and *shift the largest |mean lateral position at depth 2
 * focalDistance - 2 Pcamera| over 64 lens points of one pixel (pbrt-v2's
 * projection from the origin draws depth z at Pcamera z / focalDistance). */
static void ortho_lens_rays(const mt_scene *s, double *dev, double *shift_pbrt, double *shift_ortho)
{
    mt_rng r;
    int i, j;
    *dev = 0, *shift_pbrt = 0, *shift_ortho = 0;
    mt_rng_seed(&r, 9, 4);
    for (i = 0; i < 200; ++i) {
        mt__camera_sample cs;
        mt_raydiff a;
        d3 pf, q;
        double ft, t;
        cs.image_x = (mt_real)(50 * mt_rng_uniform(&r));
        cs.image_y = (mt_real)(50 * mt_rng_uniform(&r));
        cs.lens_u = mt_rng_uniform(&r);
        cs.lens_v = mt_rng_uniform(&r);
        mt__camera_ray(&s->camera, &cs, &a);
        pf = at_depth(a.ray.o, a.ray.d, 3);
        ft = 3 / ((double)a.ray.d.z / sqrt((double)mt_v3_len2(a.ray.d)));
        q = D3(pf.x + 0.04, pf.y, ft);
        /* the distance of q from the line of the x differential */
        t = ((q.x - a.rx_o.x) * a.rx_d.x + (q.y - a.rx_o.y) * a.rx_d.y + (q.z - a.rx_o.z) * a.rx_d.z) /
            mt_v3_len2(a.rx_d);
        *dev = fmax(*dev, d3_dist(q, D3(a.rx_o.x + t * a.rx_d.x, a.rx_o.y + t * a.rx_d.y,
                                        a.rx_o.z + t * a.rx_d.z)) +
                              vdist(a.rx_o, D3(a.ray.o.x, a.ray.o.y, a.ray.o.z)));
    }
    for (i = 0; i < 20; ++i) {
        mt__camera_sample cs;
        double mx = 0, my = 0, px = 0, py = 0;
        cs.image_x = (mt_real)(50 * mt_rng_uniform(&r));
        cs.image_y = (mt_real)(50 * mt_rng_uniform(&r));
        for (j = 0; j < 64; ++j) {
            mt_raydiff a;
            d3 p6, p3;
            /* a stratified lens: the mean offset is 0 to within the strata */
            cs.lens_u = (mt_real)((j % 8 + 0.5) / 8);
            cs.lens_v = (mt_real)((j / 8 + 0.5) / 8);
            mt__camera_ray(&s->camera, &cs, &a);
            p6 = at_depth(a.ray.o, a.ray.d, 6);
            p3 = at_depth(a.ray.o, a.ray.d, 3);
            mx += p6.x / 64, my += p6.y / 64, px = p3.x, py = p3.y;
        }
        *shift_pbrt = fmax(*shift_pbrt, fmax(fabs(mx - 2 * px), fabs(my - 2 * py)));
        *shift_ortho = fmax(*shift_ortho, fmax(fabs(mx - px), fabs(my - py)));
    }
}

static void test_lens_differentials(void)
{
    static const char *const cam[2] = {"perspective\" \"float fov\" [40]", "orthographic\""};
    int c, m;
    for (c = 0; c < 2; ++c)
        for (m = 0; m < 3; ++m) {
            /* m: pbrt-v2 mode, the erratum's bit alone, corrected mode */
            mt_mode mode = m == 0 ? MT_MODE_PBRT_V2 : m == 1 ? MT_FIX_ORTHO_LENS : MT_MODE_CORRECTED;
            const char *mname = m == 0 ? "pbrt-v2 mode" : m == 1 ? "ortho-lens fixed" : "corrected mode";
            char text[512], name[256];
            double worst, lo, hi;
            mt_scene *s;
            snprintf(text, sizeof text,
                     "Camera \"%s \"float lensradius\" [0.2] \"float focaldistance\" [3]\n"
                     "Film \"image\" \"integer xresolution\" [50] \"integer yresolution\" [50]\n"
                     "WorldBegin WorldEnd\n", cam[c]);
            snprintf(name, sizeof name, "camera %s thin lens (%s): x differential = the next pixel's ray "
                     "through the same lens point, at depths 0.5, 1 and 2 times focaldistance",
                     c ? "orthographic" : "perspective", mname);
            if (!(s = scene_in_mode(name, text, mode))) continue;
            lens_footprints(s, &worst, &lo, &hi);
            /* the two rays differ only by the rounding of pc + dx against
             * p00 + (x + 1) dx: about 1e-7 of |pc| (about 1) against a
             * footprint of at least 0.02. pbrt-v2's 2012 snapshot (the
             * lensless camera's differentials) gave 0.16 to 5.4 times the
             * footprint here. */
            if (c == 1 && m == 0 && worst > 1e-3)
                t_xfail(name, "erratum ortho-lens: the footprint is %.3g to %.3g times the "
                        "finite difference's (its vector off by up to %.3g of it)", lo, hi, worst);
            else
                t_check(worst < 1e-3, name, "footprint vector off by up to %.3g of the finite "
                        "difference's; length ratio %.3g to %.3g", worst, lo, hi);
            if (c == 1) {
                double dev, sp, so;
                ortho_lens_rays(s, &dev, &sp, &so);
                if (m == 0) {
                    t_check(dev < 1e-5, "camera orthographic thin lens (pbrt-v2 mode): the x "
                            "differential leaves the lens point towards Pcamera + dxCamera at depth "
                            "focaldistance / d.z (88cdb51)", "off by %.3g", dev);
                    t_check(sp < 1e-3 && so > 0.1, "camera orthographic thin lens (pbrt-v2 mode): "
                            "depth 2 focaldistance is drawn at twice its orthographic position",
                            "mean position off by %.3g (%.3g from the orthographic one)", sp, so);
                    t_xfail("camera orthographic thin lens: depth 2 focaldistance drawn at its "
                            "orthographic position", "erratum ortho-lens: off by up to %.3g "
                            "(screen half-width 1)", so);
                } else {
                    snprintf(name, sizeof name, "camera orthographic thin lens (%s): depth 2 "
                             "focaldistance drawn at its orthographic position", mname);
                    t_check(so < 1e-3, name, "mean position off by %.3g", so);
                }
            }
            mt_scene_destroy(s);
        }
}

/* A checkerboard (closed-form filtering) on a plane at the plane of focus,
 * seen through a lens of radius 0.3: every lens ray meets the pinhole's at
 * the plane, so the image is the pinhole camera's, in both modes since the
 * release's 88cdb51 (the 2012 snapshot's differentials, the lensless
 * camera's, gave a footprint of the lens offset and blurred the checks). */
static const char *const focus_scene =
    "Camera \"perspective\" \"float fov\" [40] \"float lensradius\" [%g] \"float focaldistance\" [3]\n"
    "Film \"image\" \"integer xresolution\" [32] \"integer yresolution\" [32]\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [4]\n"
    "SurfaceIntegrator \"directlighting\"\n"
    "WorldBegin\n"
    "LightSource \"distant\" \"point from\" [0 0 0] \"point to\" [0 0 1] \"rgb L\" [3 3 3]\n"
    "Texture \"c\" \"color\" \"checkerboard\" \"float uscale\" [16] \"float vscale\" [16]\n"
    "  \"rgb tex1\" [1 1 1] \"rgb tex2\" [0 0 0]\n"
    "Material \"matte\" \"texture Kd\" \"c\"\n"
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
    "  \"point P\" [-1.5 -1.5 3 1.5 -1.5 3 1.5 1.5 3 -1.5 1.5 3] \"float uv\" [0 0 1 0 1 1 0 1]\n"
    "WorldEnd\n";

static double image_rms(const mt_image *a, const mt_image *b)
{
    double sum = 0;
    size_t i, n = (size_t)a->width * (size_t)a->height * (size_t)a->channels;
    for (i = 0; i < n; ++i) sum += pow(a->data[i] - b->data[i], 2);
    return sqrt(sum / (double)n);
}

static void test_lens_texture_filtering(void)
{
    mt_image img[4];
    double sd = 0, mean = 0, rms[2];
    int k, ok = 1;
    size_t i, n;
    for (k = 0; k < 4; ++k) {
        /* in pbrt-v2 mode, then in corrected mode: the pinhole, then the lens */
        char text[2048];
        mt_error err;
        mt_scene *s;
        snprintf(text, sizeof text, focus_scene, k % 2 ? 0.3 : 0.0);
        s = scene_in_mode("camera thin lens texture filtering", text, k < 2 ? MT_MODE_PBRT_V2 : MT_MODE_CORRECTED);
        ok = ok && s && t_render(s, 0, 1, 5, &img[k], NULL, &err) == MT_OK;
        mt_scene_destroy(s);
        if (!ok) {
            t_fail("camera thin lens texture filtering", "scene or render failed");
            while (k-- > 0) mt_image_free(&img[k]);
            return;
        }
    }
    n = (size_t)img[0].width * (size_t)img[0].height * 3;
    for (i = 0; i < n; ++i) mean += img[0].data[i] / (double)n;
    for (i = 0; i < n; ++i) sd += pow(img[0].data[i] - mean, 2) / (double)n;
    sd = sqrt(sd);
    rms[0] = image_rms(&img[1], &img[0]);
    rms[1] = image_rms(&img[3], &img[2]);
    /* the lens rays and their differentials meet the pinhole's on the plane,
     * so the same texture lookups; but the renderer scales the
     * differentials by 1/sqrt(spp) as directions (d + (rx_d - d) / 2), which
     * meet the plane at slightly different points from a lens point than
     * from the pinhole: footprints differ by about 1e-4 of theirs (measured:
     * RMS 5.1e-5, 1.6e-4 of the standard deviation, in float). pbrt-v2's
     * 2012 snapshot, with the lensless camera's differentials, blurred the
     * checks: RMS 0.175, 53% of the standard deviation. */
    for (k = 0; k < 2; ++k)
        t_check(rms[k] < 1e-3 * sd, k ? "camera thin lens, plane in focus (corrected mode): the pinhole's image"
                                      : "camera thin lens, plane in focus (pbrt-v2 mode): the pinhole's image",
                "RMS difference %.3g (image standard deviation %.3g)", rms[k], sd);
    for (k = 0; k < 4; ++k) mt_image_free(&img[k]);
}

/* ---- specular ray differentials (core/integrator.cpp) ---------------------------- */

static d3 dv3(mt_vec3 v) { return D3(v.x, v.y, v.z); }
static mt_vec3 rv(d3 a) { return mt_v3((mt_real)a.x, (mt_real)a.y, (mt_real)a.z); }
static double d3_dot(d3 a, d3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static d3 d3_lin(d3 a, double s, d3 b) { return D3(a.x + s * b.x, a.y + s * b.y, a.z + s * b.z); }

/* The specular direction of the unit incident direction w at unit normal n
 * (double): the mirror direction, or Snell's refraction into glass of index
 * 1.5 (entering against n); 0 with total internal reflection. */
static int specular_dir(d3 w, d3 n, int transmit, d3 *out)
{
    double c, e, s2;
    if (!transmit) {
        *out = d3_lin(w, -2 * d3_dot(w, n), n);
        return 1;
    }
    if (d3_dot(w, n) > 0) n = D3(-n.x, -n.y, -n.z), e = 1.5;
    else e = 1 / 1.5;
    c = -d3_dot(w, n);
    s2 = e * e * (1 - c * c);
    if (s2 >= 1) return 0;
    *out = d3_lin(D3(e * w.x, e * w.y, e * w.z), e * c - sqrt(1 - s2), n);
    return 1;
}

/* A ray with differentials (the neighbours 1e-3 away in origin and
 * direction) meets a unit glass sphere; the differentials of its reflected
 * and refracted rays (mt__specular_differentials, pbrt-v2's formulas) against
 * the neighbours' own reflected and refracted directions at their own hits:
 * first order, so within a few 1e-3 of the difference. pbrt-v2's 2012
 * SpecularTransmit (before e6f6334) took wo's signs and the inverted eta. */
static void test_specular_differentials(void)
{
    static const double rays[2][6] = {
        {0.3, 0.2, 5, -0.05, 0.02, -1}, /* from outside, entering */
        {0.1, -0.2, 0.1, 0.2, 0.1, 1},  /* from inside, leaving */
    };
    mt_error err;
    mt_shape *s = t_shape("Shape \"sphere\"", NULL, 0, NULL, &err);
    int c, k;
    if (!s) {
        t_fail("specular differentials", "%s", err.message);
        return;
    }
    for (c = 0; c < 2; ++c)
        for (k = 0; k < 2; ++k) {
            const double eps = 1e-3;
            d3 o = D3(rays[c][0], rays[c][1], rays[c][2]);
            d3 d = d3_norm(D3(rays[c][3], rays[c][4], rays[c][5]));
            d3 ox = d3_lin(o, eps, D3(1, 0, 0)), dx = d3_norm(d3_lin(d, eps, D3(0, 1, 0.5)));
            d3 oy = d3_lin(o, eps, D3(0, 0.6, 0.8)), dy = d3_norm(d3_lin(d, -eps, D3(1, 0, 0)));
            d3 wi, wix, wiy;
            mt_raydiff rd, next;
            mt_ray r;
            mt_hit h;
            mt_surface sf, sx, sy;
            char name[160];
            double ex, ey, lx, ly;
            int ok;
            rd.ray = mt_ray_make(rv(o), rv(d), 0, MT_RAY_TMAX);
            rd.has_differentials = 1;
            rd.rx_o = rv(ox), rd.rx_d = rv(dx), rd.ry_o = rv(oy), rd.ry_d = rv(dy);
            ok = mt_shape_intersect(s, 0, &rd.ray, &h);
            if (ok) mt_hit_surface(&h, &rd.ray, &sf);
            r = mt_ray_make(rv(ox), rv(dx), 0, MT_RAY_TMAX);
            ok = ok && mt_shape_intersect(s, 0, &r, &h);
            if (ok) mt_hit_surface(&h, &r, &sx);
            r = mt_ray_make(rv(oy), rv(dy), 0, MT_RAY_TMAX);
            ok = ok && mt_shape_intersect(s, 0, &r, &h);
            if (ok) mt_hit_surface(&h, &r, &sy);
            ok = ok && specular_dir(d, dv3(sf.dg.n), k, &wi) && specular_dir(dx, dv3(sx.dg.n), k, &wix) &&
                 specular_dir(dy, dv3(sy.dg.n), k, &wiy);
            snprintf(name, sizeof name, "specular differentials: %s ray %s the sphere, x and y "
                     "neighbours' %s directions", k ? "refracted (SpecularTransmit, e6f6334)" : "reflected",
                     c ? "leaving" : "entering", k ? "refracted" : "reflected");
            if (!ok) {
                t_fail(name, "a ray missed or was totally reflected");
                continue;
            }
            mt_surface_differentials(&sf, &rd);
            next = mt_raydiff_from_ray(&rd.ray);
            mt__specular_differentials(&rd, &sf.dg, &sf.dg, sf.dg.p, sf.dg.n, rv(D3(-d.x, -d.y, -d.z)),
                                       rv(wi), k, (mt_real)1.5, &next);
            lx = d3_dist(wix, wi);
            ly = d3_dist(wiy, wi);
            ex = d3_dist(d3_lin(dv3(next.rx_d), -1, wi), d3_lin(wix, -1, wi)) / lx;
            ey = d3_dist(d3_lin(dv3(next.ry_d), -1, wi), d3_lin(wiy, -1, wi)) / ly;
            t_check(next.has_differentials && ex < 1e-2 && ey < 1e-2 && lx > 0.1 * eps && ly > 0.1 * eps, name,
                    "off by %.3g and %.3g of the neighbours' change (%.3g, %.3g)", ex, ey, lx, ly);
        }
    mt_shape_destroy(s);
}

/* ---- filters and film ---------------------------------------------------------- */

static void add_float(mt_paramset *ps, const char *name, double v)
{
    mt_param p;
    memset(&p, 0, sizeof p);
    p.name = name;
    p.type = MT_PARAM_FLOAT;
    p.type_name = "float";
    p.count = 1;
    p.reals = &v;
    mt_paramset_add(ps, &p, NULL);
}

/* The 2D integral of the filter over its support by the midpoint rule. */
static double filter_integral(const mt__filter *f, int n)
{
    double sum = 0, hx = 2 * f->xwidth / n, hy = 2 * f->ywidth / n;
    int i, j;
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i)
            sum += mt__filter_eval(f, (mt_real)(-f->xwidth + (i + 0.5) * hx),
                                   (mt_real)(-f->ywidth + (j + 0.5) * hy));
    return sum * hx * hy;
}

static double gauss1d_integral(double a, double w)
{
    return sqrt(PI_D / a) * erf(w * sqrt(a)) - 2 * w * exp(-a * w * w);
}

static void test_filters(void)
{
    mt__filter f;
    mt_error err;
    mt_paramset *ps = mt_paramset_create();
    double v, want;
    /* box */
    mt__filter_create(&f, "box", ps, &err);
    t_check(f.xwidth == 0.5f && f.ywidth == 0.5f && mt__filter_eval(&f, 0.3f, -0.4f) == 1,
            "filter box: default width 0.5, value 1", "width %g", (double)f.xwidth);
    t_rel(filter_integral(&f, 200), 1.0, 1e-6, 0, "filter box: integral (2 xw)(2 yw)");
    /* gaussian, defaults and custom */
    mt__filter_create(&f, "gaussian", ps, &err);
    v = mt__filter_eval(&f, 0.3f, -0.7f);
    want = (exp(-2 * 0.09) - exp(-8.0)) * (exp(-2 * 0.49) - exp(-8.0));
    t_rel(v, want, 1e-5, 1e-6, "filter gaussian: value (alpha 2, width 2)");
    t_rel(filter_integral(&f, 400), gauss1d_integral(2, 2) * gauss1d_integral(2, 2), 1e-4, 0,
          "filter gaussian: integral against the closed form");
    mt_paramset_destroy(ps);
    ps = mt_paramset_create();
    add_float(ps, "alpha", 1);
    add_float(ps, "xwidth", 1.5);
    mt__filter_create(&f, "gaussian", ps, &err);
    t_rel(filter_integral(&f, 400), gauss1d_integral(1, 1.5) * gauss1d_integral(1, 2), 1e-4, 0,
          "filter gaussian: alpha 1, xwidth 1.5");
    mt_paramset_destroy(ps);
    /* mitchell: the kernel integrates to one for any B, C; argument 2x/w */
    ps = mt_paramset_create();
    mt__filter_create(&f, "mitchell", ps, &err);
    t_rel(filter_integral(&f, 400), 1.0, 1e-4, 0, "filter mitchell: integral (w/2)^2 = 1");
    v = mt__filter_eval(&f, 0, 0);
    t_rel(v, pow((6 - 2.0 / 3) / 6, 2), 1e-5, 0, "filter mitchell: value at 0 ((6 - 2B) / 6)^2");
    v = mt__filter_eval(&f, 1.5f, 0);
    want = ((-1.0 / 3 - 2) * 3.375 + (2 + 10) * 2.25 + (-4 - 16) * 1.5 + (8.0 / 3 + 8)) / 6 * (6 - 2.0 / 3) / 6;
    t_rel(v, want, 1e-4, 1e-6, "filter mitchell: value on the outer lobe (|2x/w| = 1.5)");
    mt_paramset_destroy(ps);
    ps = mt_paramset_create();
    add_float(ps, "B", 0);
    add_float(ps, "C", 0.5);
    add_float(ps, "ywidth", 3);
    mt__filter_create(&f, "mitchell", ps, &err);
    t_rel(filter_integral(&f, 400), 1.0 * 1.5, 1e-4, 0, "filter mitchell: Catmull-Rom, ywidth 3");
    mt_paramset_destroy(ps);
    /* triangle */
    ps = mt_paramset_create();
    mt__filter_create(&f, "triangle", ps, &err);
    t_rel(mt__filter_eval(&f, 0.5f, -1.5f), 1.5 * 0.5, 1e-6, 0, "filter triangle: value");
    t_rel(filter_integral(&f, 400), 16.0, 1e-4, 0, "filter triangle: integral w^2 h^2");
    /* sinc: pbrt-v2's argument |x| / width */
    mt__filter_create(&f, "sinc", ps, &err);
    t_rel(mt__filter_eval(&f, 2, 0), -4 / (3 * PI_D * PI_D), 1e-5, 0,
          "filter sinc: value at x = width / 2 (sinc(pi/2) sinc(3 pi/2))");
    t_check(mt__filter_eval(&f, 0, 0) == 1 && mt__filter_eval(&f, 3.99f, 0) != 0, "filter sinc: shape",
            "f(0) = %g", (double)mt__filter_eval(&f, 0, 0));
    t_check(mt__filter_create(&f, "lanczos", ps, &err) == MT_ERR_UNSUPPORTED, "filter unknown name",
            "status %d", err.status);
    add_float(ps, "xwidth", 0);
    t_check(mt__filter_create(&f, "box", ps, &err) == MT_ERR_INVALID && strcmp(err.param, "xwidth") == 0,
            "filter zero width rejected", "status %d param %s", err.status, err.param);
    mt_paramset_destroy(ps);
}

/* A constant radiance gives that constant through any filter (the weights
 * are normalized), negative lobes included. */
static void test_film_normalization(void)
{
    static const char *names[] = {"box", "gaussian", "mitchell", "triangle", "sinc"};
    mt_paramset *ps = mt_paramset_create();
    mt_real crop[4] = {0, 1, 0, 1};
    size_t k;
    for (k = 0; k < 5; ++k) {
        mt__filter f;
        mt__film film;
        mt__film_buf b;
        mt_image img;
        mt_rng rng;
        mt_error err;
        double worst = 0;
        int i;
        char name[96];
        mt__filter_create(&f, names[k], ps, &err);
        mt__film_init(&film, 12, 9, crop, &f);
        mt__film_buf_alloc(&b, 12 * 9, &err);
        b.x0 = 0, b.y0 = 0, b.w = 12, b.h = 9;
        mt_rng_seed(&rng, 7, k);
        for (i = 0; i < 20000; ++i) {
            mt_real x = (mt_real)(film.sx0 + (film.sx1 - film.sx0) * mt_rng_uniform_d(&rng));
            mt_real y = (mt_real)(film.sy0 + (film.sy1 - film.sy0) * mt_rng_uniform_d(&rng));
            mt__film_add(&film, &b, x, y, mt_rgb_make(0.25f, 1.5f, 3));
        }
        mt__film_develop(&film, &b, &img, NULL, &err);
        for (i = 0; i < 12 * 9; ++i)
            worst = fmax(worst, fmax(fabs(img.data[3 * i] - 0.25), fmax(fabs(img.data[3 * i + 1] - 1.5),
                                                                         fabs(img.data[3 * i + 2] - 3))));
        snprintf(name, sizeof name, "film %s: a constant radiance develops to that constant", names[k]);
        t_check(worst < 1e-5, name, "max error %.3g", worst);
        mt_image_free(&img);
        mt__film_buf_free(&b);
    }
    mt_paramset_destroy(ps);
}

static const char *crop_scene =
    "LookAt 0 -4 2  0 0 0.5  0 0 1 Camera \"perspective\" \"float fov\" [35]\n"
    "Film \"image\" \"integer xresolution\" [32] \"integer yresolution\" [24] %s\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [4] SurfaceIntegrator \"path\"\n"
    "WorldBegin LightSource \"infinite\" \"rgb L\" [0.5 0.6 0.7]\n"
    "Material \"plastic\" Shape \"sphere\" \"float radius\" [0.8]\n"
    "Material \"matte\" Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
    "  \"point P\" [-5 -5 0 5 -5 0 5 5 0 -5 5 0]\n"
    "WorldEnd\n";

static void test_crop_window(void)
{
    char text[2048];
    mt_image full, crop;
    mt_error err;
    mt_scene *s;
    int x0, y0, w, h, x, y, same = 1;
    snprintf(text, sizeof text, crop_scene, "");
    s = t_scene_or_fail("film crop window", text);
    if (!s || t_render(s, 0, 2, 3, &full, NULL, &err) != MT_OK) {
        mt_scene_destroy(s);
        t_fail("film crop window", "render failed");
        return;
    }
    mt_scene_destroy(s);
    /* pbrt-v2: x0 = ceil(32 * .25) = 8, width = ceil(32 * .75) - 8 = 16; the
     * pairs are put in order; y0 = ceil(24 * .1) = 3, height = ceil(24 * .6) - 3 = 12 */
    snprintf(text, sizeof text, crop_scene, "\"float cropwindow\" [0.75 0.25 0.1 0.6]");
    s = t_scene_or_fail("film crop window", text);
    if (!s) return;
    x0 = s->film.x0, y0 = s->film.y0, w = s->film.width, h = s->film.height;
    t_check(x0 == 8 && w == 16 && y0 == 3 && h == 12, "film crop window in pixels (pbrt-v2's rounding)",
            "x0 %d w %d y0 %d h %d", x0, w, y0, h);
    if (t_render(s, 0, 1, 3, &crop, NULL, &err) == MT_OK) {
        /* box filter and per-pixel sampling: a crop renders the same pixels */
        for (y = 0; y < h && same; ++y)
            for (x = 0; x < w && same; ++x)
                same = memcmp(&crop.data[3 * (y * w + x)], &full.data[3 * ((y + y0) * 32 + x + x0)],
                              3 * sizeof(float)) == 0;
        t_check(crop.width == 16 && crop.height == 12 && same,
                "film crop window renders the same pixels as the full image", "size %dx%d, same %d",
                crop.width, crop.height, same);
        mt_image_free(&crop);
    }
    mt_image_free(&full);
    mt_scene_destroy(s);
    {
        /* the sample extent: pbrt-v2's GetSampleExtent as released (77bcd78,
         * 3f43c45), floor(x0 + 0.5 - w) to ceil(x0 + width - 0.5 + w)
         * exclusive -- the 2012 source's floor(x0 + 0.5 + width + w) added a
         * column of samples that reach no pixel; and no pixel of the window
         * misses a sample position that reaches it (sample positions on a
         * grid of 1/64 pixel) */
        static const double widths[] = {0.5, 1, 1.25, 1.5, 2, 4};
        static const mt_real crops[2][4] = {{0, 1, 0, 1}, {0.25, 0.75, 0.1, 0.6}};
        int bad = 0, k, c;
        for (k = 0; k < 6; ++k)
            for (c = 0; c < 2; ++c) {
                mt__film f;
                mt__filter flt;
                double xw = widths[k];
                int lo, hi, i;
                memset(&flt, 0, sizeof flt);
                flt.kind = MT__FILTER_TRIANGLE;
                flt.xwidth = flt.ywidth = (mt_real)xw;
                mt__film_init(&f, 32, 24, crops[c], &flt);
                if (f.sx0 != (int)floor(f.x0 + 0.5 - xw) || f.sx1 != (int)ceil(f.x0 + f.width - 0.5 + xw) ||
                    f.sy0 != (int)floor(f.y0 + 0.5 - xw) || f.sy1 != (int)ceil(f.y0 + f.height - 0.5 + xw))
                    bad++;
                /* the samples that reach pixels x0 .. x0 + width - 1 along x */
                lo = 1 << 30, hi = -(1 << 30);
                for (i = -64 * 8; i < 64 * 48; ++i) {
                    double ix = (i + 0.5) / 64.0; /* never on a pixel edge: those reach at single points */
                    if (ceil(ix - 0.5 - xw) <= f.x0 + f.width - 1 && floor(ix - 0.5 + xw) >= f.x0) {
                        lo = (int)fmin(lo, floor(ix));
                        hi = (int)fmax(hi, floor(ix) + 1);
                    }
                }
                if (lo < f.sx0 || hi > f.sx1 || f.sx1 - hi > 0) bad++;
            }
        t_check(bad == 0, "film sample extent: pbrt-v2's GetSampleExtent as released (3f43c45), "
                "exactly the pixels whose samples reach the window", "%d bad", bad);
    }
}

/* ---- sampler --------------------------------------------------------------------- */

/* 1 when the n = 2^m points form a (0,m,2)-net: every elementary interval of
 * area 2^-m holds exactly one. */
static int is_net(const uint32_t (*p)[2], int m)
{
    int n = 1 << m, a, i;
    int *count = calloc((size_t)n, sizeof *count);
    int ok = count != NULL;
    for (a = 0; a <= m && ok; ++a) {
        memset(count, 0, (size_t)n * sizeof *count);
        for (i = 0; i < n; ++i) {
            uint32_t cx = a ? p[i][0] >> (32 - a) : 0, cy = m - a ? p[i][1] >> (32 - (m - a)) : 0;
            count[(cx << (m - a)) | cy]++;
        }
        for (i = 0; i < n; ++i)
            if (count[i] != 1) ok = 0;
    }
    free(count);
    return ok;
}

static void test_sampler(void)
{
    mt__sobol_tables tab;
    mt__pixel_sampler ps, ps2;
    uint32_t pts[256][2];
    int i, nets = 1, blocks = 1, dim, px;
    double sx = 0, sxy = 0, sx2 = 0;
    uint32_t a[2], b[2];
    mt__sobol_tables_init(&tab);
    /* every dimension pair of several pixels: the first 2^m samples form a net */
    for (px = 0; px < 4; ++px)
        for (dim = 0; dim < 12; ++dim) {
            mt__pixel_sampler_init(&ps, &tab, 42, px * 7, px * 3 + 1);
            for (i = 0; i < 256; ++i) mt__sample_2d_bits(&ps, (uint32_t)dim, (uint32_t)i, pts[i]);
            nets &= is_net((const uint32_t(*)[2])pts, 8) && is_net((const uint32_t(*)[2])pts, 4) &&
                    is_net((const uint32_t(*)[2])(pts + 16), 4);
            /* arrays of 4 per camera sample: each sample's block is a (0,2,2)-net */
            for (i = 0; i < 64; ++i) blocks &= is_net((const uint32_t(*)[2])(pts + 4 * i), 2);
        }
    t_check(nets, "sampler: 16 and 256 samples of each pixel and pair form (0,m,2)-nets", "not a net");
    t_check(blocks, "sampler: array blocks of 4 per camera sample are (0,2,2)-nets", "not a net");
    /* determinism and seeds */
    mt__pixel_sampler_init(&ps, &tab, 42, 5, 9);
    mt__pixel_sampler_init(&ps2, &tab, 42, 5, 9);
    mt__sample_2d_bits(&ps, 3, 17, a);
    mt__sample_2d_bits(&ps2, 3, 17, b);
    t_check(a[0] == b[0] && a[1] == b[1], "sampler: deterministic", "differs");
    mt__pixel_sampler_init(&ps2, &tab, 43, 5, 9);
    mt__sample_2d_bits(&ps2, 3, 17, b);
    t_check(a[0] != b[0] && a[1] != b[1], "sampler: the seed changes the pattern", "same values");
    /* different pairs decorrelated: correlation of x in pairs 2 and 3 over
     * many pixels and samples (|r| < 5 / sqrt(n)) */
    for (px = 0; px < 64; ++px) {
        mt_real u[2], v[2];
        mt__pixel_sampler_init(&ps, &tab, 1, px, 0);
        for (i = 0; i < 64; ++i) {
            mt__sample_2d(&ps, 2, (uint32_t)i, u);
            mt__sample_2d(&ps, 3, (uint32_t)i, v);
            sx += u[0] - 0.5;
            sx2 += (u[0] - 0.5) * (u[0] - 0.5);
            sxy += (u[0] - 0.5) * (v[0] - 0.5);
        }
    }
    t_check(fabs(sxy / sx2) < 5 / sqrt(4096.0) && fabs(sx / 4096) < 1e-3,
            "sampler: pairs decorrelated, values centred", "r = %.4f, mean offset %.4g", sxy / sx2,
            sx / 4096);
}

/* ---- lights ----------------------------------------------------------------------- */

/* Mean and standard error of n values. */
typedef struct acc {
    double s, s2;
    long n;
} acc;
static void acc_add(acc *a, double v)
{
    a->s += v, a->s2 += v * v, a->n++;
}
static double acc_mean(const acc *a) { return a->s / (double)a->n; }
static double acc_se(const acc *a)
{
    double m = acc_mean(a);
    return sqrt(fmax(a->s2 / (double)a->n - m * m, 0) / (double)a->n);
}

/* Sample_L from p: pdf equals Pdf(p, wi); E[1/pdf] over samples with
 * radiance equals the solid angle `omega`; and Pdf integrates to one over
 * the directions that see the light (uniform directions). */
static void check_area_light(const char *name, const mt__light *l, mt_vec3 p, double omega)
{
    mt_rng rng;
    acc inv = {0, 0, 0}, integ = {0, 0, 0};
    double worst = 0;
    int i;
    char nm[160];
    mt_rng_seed(&rng, 11, 5);
    for (i = 0; i < 40000; ++i) {
        mt__light_sample ls;
        mt_real u0 = mt_rng_uniform(&rng), u1 = mt_rng_uniform(&rng), u2 = mt_rng_uniform(&rng);
        mt__light_sample_l(l, NULL, p, u0, u1, u2, &ls);
        if (ls.pdf > 0 && !mt_rgb_is_black(ls.Li)) {
            double q = mt__light_pdf(l, p, ls.wi);
            worst = fmax(worst, fabs(q - ls.pdf) / ls.pdf);
            acc_add(&inv, 1 / ls.pdf);
        } else {
            acc_add(&inv, 0);
        }
    }
    for (i = 0; i < 200000; ++i) {
        mt_vec3 w = mt_uniform_sample_sphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng));
        mt_ray r = mt_ray_make(p, w, (mt_real)1e-3, MT_RAY_TMAX);
        mt_hit h;
        uint32_t k;
        int hit = 0;
        for (k = 0; k < mt_shape_prim_count(l->shape) && !hit; ++k) hit = mt_shape_intersect(l->shape, k, &r, &h);
        acc_add(&integ, hit ? 4 * PI_D * mt__light_pdf(l, p, w) : 0);
    }
    snprintf(nm, sizeof nm, "light %s: Sample_L's pdf equals Pdf", name);
    t_check(worst < 1e-3, nm, "max relative difference %.3g", worst);
    snprintf(nm, sizeof nm, "light %s: E[1/pdf] is the solid angle", name);
    t_check(fabs(acc_mean(&inv) - omega) <= 5 * acc_se(&inv) + 1e-4 * omega, nm,
            "%.6g +- %.2g, want %.6g", acc_mean(&inv), acc_se(&inv), omega);
    snprintf(nm, sizeof nm, "light %s: Pdf integrates to 1 over the light", name);
    t_check(fabs(acc_mean(&integ) - 1) <= 5 * acc_se(&integ) + 1e-3, nm, "%.5g +- %.2g",
            acc_mean(&integ), acc_se(&integ));
}

static void test_area_lights(void)
{
    mt_paramset *ps = mt_paramset_create();
    mt_transform t = mt_translate(mt_v3(0, 0, 3));
    mt_error err;
    mt__light l;
    mt_shape *s;
    double h = 3, r = 0.7, a = 1.2, b = 0.8, d = 2;
    /* a sphere of radius 1 at distance 3: the cone 2 pi (1 - cos theta_max) */
    s = t_shape("Shape \"sphere\" \"float radius\" [1]", &t, 0, NULL, &err);
    if (s && mt__area_light_create(&l, "area", ps, s, &err) == MT_OK)
        check_area_light("sphere", &l, mt_v3(0, 0, 0), 2 * PI_D * (1 - sqrt(1 - 1.0 / 9)));
    mt_shape_destroy(s);
    /* a disk seen on its axis, facing the point (ReverseOrientation: the
     * disk's normal is +z; from below it needs -z) */
    s = t_shape("Shape \"disk\" \"float radius\" [0.7]", &t, 1, NULL, &err);
    if (s && mt__area_light_create(&l, "diffuse", ps, s, &err) == MT_OK)
        check_area_light("disk", &l, mt_v3(0, 0, 0), 2 * PI_D * (1 - h / sqrt(h * h + r * r)));
    mt_shape_destroy(s);
    /* a rectangle of two triangles facing the point: 4 asin(ab / sqrt((a^2 + 4d^2)(b^2 + 4d^2))) */
    t = mt_translate(mt_v3(0, 0, 2));
    s = t_shape("Shape \"trianglemesh\" \"integer indices\" [0 2 1 0 3 2]"
                " \"point P\" [-0.6 -0.4 0  0.6 -0.4 0  0.6 0.4 0  -0.6 0.4 0]",
                &t, 0, NULL, &err);
    if (s && mt__area_light_create(&l, "area", ps, s, &err) == MT_OK)
        check_area_light("triangle mesh", &l, mt_v3(0, 0, 0),
                         4 * asin(a * b / sqrt((a * a + 4 * d * d) * (b * b + 4 * d * d))));
    mt_shape_destroy(s);
    mt_paramset_destroy(ps);
}

/* ---- geometry errata seen through an area light ---------------------------------- */

/* Light sampling of an area light of radiance 1 seen from p, as direct
 * lighting does it but without BSDF and cosine: E[V Li / pdf], where V is
 * the shadow ray against the light's own primitives (a sample hidden
 * behind the light itself counts 0). Unbiased, it equals the solid angle
 * in which p sees the light emitting towards it: *ref, from uniform
 * directions and the normal of their first hit. *pdf_diff: the largest
 * relative difference between Sample_L's pdf and Pdf of the same direction
 * over the visible samples. */
static void light_estimate(const mt__light *l, mt_vec3 p, acc *est, acc *ref, double *pdf_diff)
{
    const mt_shape *s = l->shape;
    uint32_t n = mt_shape_prim_count(s), k;
    mt_rng rng;
    mt_vec3 cone_x, cone_y, cone_z;
    mt_real cone_ct;
    double omega;
    int i;
    mt_rng_seed(&rng, 17, 3);
    *pdf_diff = 0;
    for (i = 0; i < 30000; ++i) {
        mt__light_sample ls;
        mt_real u0 = mt_rng_uniform(&rng), u1 = mt_rng_uniform(&rng), u2 = mt_rng_uniform(&rng);
        int hidden = 0;
        mt__light_sample_l(l, NULL, p, u0, u1, u2, &ls);
        if (!(ls.pdf > 0) || mt_rgb_is_black(ls.Li)) {
            acc_add(est, 0);
            continue;
        }
        for (k = 0; k < n && !hidden; ++k) hidden = mt_shape_occluded(s, k, &ls.shadow);
        acc_add(est, hidden ? 0 : ls.Li.c[0] / ls.pdf);
        if (!hidden)
            *pdf_diff = fmax(*pdf_diff, fabs(mt__light_pdf(l, p, ls.wi) - ls.pdf) / ls.pdf);
    }
    /* the reference: uniform directions in a cone about the shape's
     * bounding sphere when p is outside it, else over the whole sphere */
    {
        mt_vec3 lo, hi, blo, bhi, c, ax;
        double R, d, ct = -1;
        mt_shape_prim_bounds(s, 0, &lo, &hi);
        for (k = 1; k < n; ++k) {
            mt_shape_prim_bounds(s, k, &blo, &bhi);
            lo = mt_v3(mt_min(lo.x, blo.x), mt_min(lo.y, blo.y), mt_min(lo.z, blo.z));
            hi = mt_v3(mt_max(hi.x, bhi.x), mt_max(hi.y, bhi.y), mt_max(hi.z, bhi.z));
        }
        c = mt_v3_scale(mt_v3_add(lo, hi), (mt_real)0.5);
        R = 0.5 * mt_v3_len(mt_v3_sub(hi, lo)) * 1.01;
        d = mt_v3_len(mt_v3_sub(c, p));
        if (d > R) ct = sqrt(1 - R * R / (d * d));
        ax = d > 0 ? mt_v3_normalize(mt_v3_sub(c, p)) : mt_v3(0, 0, 1);
        mt_coordinate_system(ax, &lo, &hi);
        omega = 2 * PI_D * (1 - ct);
        cone_ct = (mt_real)ct;
        cone_x = lo, cone_y = hi, cone_z = ax;
    }
    for (i = 0; i < 60000; ++i) {
        mt_vec3 w = mt_uniform_sample_cone_frame(mt_rng_uniform(&rng), mt_rng_uniform(&rng),
                                                 cone_ct, cone_x, cone_y, cone_z);
        mt_ray r = mt_ray_make(p, w, (mt_real)1e-3, MT_RAY_TMAX);
        mt_hit h, best;
        mt_surface sf;
        int hit = 0;
        for (k = 0; k < n; ++k)
            if (mt_shape_intersect(s, k, &r, &h)) {
                best = h;
                r.tmax = h.t;
                hit = 1;
            }
        if (hit) mt_hit_surface(&best, &r, &sf);
        acc_add(ref, hit && mt_v3_dot(sf.dg.n, mt_v3_neg(w)) > 0 ? omega : 0);
    }
}

static int estimate_agrees(const acc *est, const acc *ref)
{
    double se = sqrt(acc_se(est) * acc_se(est) + acc_se(ref) * acc_se(ref));
    return fabs(acc_mean(est) - acc_mean(ref)) <= 5 * se + 1e-4 * acc_mean(ref);
}

typedef struct light_case {
    const char *erratum, *what, *shape;
    double place[6]; /* Translate x y z, then Scale x y z */
    int ro;
    mt_real p[3];
    mt_mode bit;
    int hidden;
    /* bits set in all three runs: disk-partials for disks, whose hits in
     * pbrt-v2 mode face the other way than their samples (measured by a
     * case of its own), so that the reference (the side rays see) is the
     * side the samples emit to */
    mt_mode base;
    /* when hi > 0: the range pbrt-v2 mode's ratio must fall in (the
     * release's size of the erratum, not another version's) */
    double lo, hi;
} light_case;

static mt_transform placed(const double a[6])
{
    mt_transform t = mt_translate(mt_v3((mt_real)a[0], (mt_real)a[1], (mt_real)a[2]));
    mt_transform sc = mt_scale((mt_real)a[3], (mt_real)a[4], (mt_real)a[5]);
    return mt_transform_compose(&t, &sc);
}

/* One erratum seen through a light: in pbrt-v2 mode the estimate is biased
 * (reproduced: an expected failure with its measured size); with the
 * erratum's bit alone and in corrected mode it is unbiased and Sample_L's
 * pdf is Pdf's. A case marked `hidden` is an erratum the light does not
 * show: unbiased in pbrt-v2 mode too. */
static void check_light_erratum(const light_case *c)
{
    mt_mode modes[3];
    mt_paramset *ps = mt_paramset_create();
    mt_transform xf = placed(c->place);
    mt_vec3 p = mt_v3(c->p[0], c->p[1], c->p[2]);
    char nm[200];
    int m;
    modes[0] = MT_MODE_PBRT_V2 | c->base;
    modes[1] = c->bit | c->base;
    modes[2] = MT_MODE_CORRECTED;
    for (m = 0; m < 3; ++m) {
        mt_error err;
        mt__light l;
        acc est = {0, 0, 0}, ref = {0, 0, 0};
        double pdf_diff = 0;
        mt_shape *s = t_shape_mode(c->shape, &xf, c->ro, modes[m], NULL, &err);
        if (!s || mt__area_light_create(&l, "area", ps, s, &err) != MT_OK) {
            t_fail(c->what, "%s", err.message);
            mt_shape_destroy(s);
            continue;
        }
        light_estimate(&l, p, &est, &ref, &pdf_diff);
        if (m == 0 && c->hidden) {
            snprintf(nm, sizeof nm, "light %s: unbiased in pbrt-v2 mode (erratum %s hidden)",
                     c->what, c->erratum);
            t_check(estimate_agrees(&est, &ref), nm, "%.5g +- %.2g against %.5g +- %.2g",
                    acc_mean(&est), acc_se(&est), acc_mean(&ref), acc_se(&ref));
        } else if (m == 0) {
            double ratio = acc_mean(&est) / acc_mean(&ref);
            snprintf(nm, sizeof nm, "light %s: pbrt-v2's bias reproduced", c->what);
            t_check(!estimate_agrees(&est, &ref) && (c->hi == 0 || (ratio > c->lo && ratio < c->hi)), nm,
                    "%.5g +- %.2g against %.5g +- %.2g", acc_mean(&est), acc_se(&est), acc_mean(&ref),
                    acc_se(&ref));
            snprintf(nm, sizeof nm, "light %s", c->what);
            t_xfail(nm, "erratum %s: light sampling gives %.3f times the light seen (%.4g sr of %.4g)",
                    c->erratum, acc_mean(&est) / acc_mean(&ref), acc_mean(&est), acc_mean(&ref));
        } else {
            snprintf(nm, sizeof nm, "light %s: unbiased %s", c->what,
                     m == 1 ? "with its bit" : "in corrected mode");
            t_check(estimate_agrees(&est, &ref) && pdf_diff < 1e-3, nm,
                    "%.5g +- %.2g against %.5g +- %.2g, pdf differs by %.3g", acc_mean(&est),
                    acc_se(&est), acc_mean(&ref), acc_se(&ref), pdf_diff);
        }
        mt_shape_destroy(s);
    }
    mt_paramset_destroy(ps);
}

#define OCTAHEDRON                                                                     \
    "Shape \"trianglemesh\" \"point P\" [1 0 0 -1 0 0 0 1 0 0 -1 0 0 0 1 0 0 -1] "   \
    "\"integer indices\" [0 2 4 2 1 4 1 3 4 3 0 4 2 0 5 1 2 5 3 1 5 0 3 5]"

static void test_light_errata(void)
{
    static const light_case cases[] = {
        {"partial-sampling", "hemisphere dome (ReverseOrientation) seen from inside",
         "Shape \"sphere\" \"float radius\" 2 \"float zmin\" 0", {0, 0, 0, 1, 1, 1}, 1,
         {0.3f, -0.2f, 0.4f}, MT_FIX_PARTIAL_SAMPLING, 0, 0, 0, 0},
        {"partial-sampling", "annulus sector (innerradius 0.5 of 1, phimax 270)",
         "Shape \"disk\" \"float radius\" 1 \"float innerradius\" 0.5 \"float phimax\" 270",
         {0, 0, 2, 1, 1, 1}, 1, {0.1f, 0.2f, 0}, MT_FIX_PARTIAL_SAMPLING, 0, MT_FIX_DISK_PARTIALS, 0, 0},
        {"partial-sampling", "half sphere (phimax 180) seen from outside",
         "Shape \"sphere\" \"float phimax\" 180", {0.2, 0.1, 3, 1, 1, 1}, 0, {0, 0, 0},
         MT_FIX_PARTIAL_SAMPLING, 0, 0, 0, 0},
        {"quadric-scale", "sphere under Scale 2 seen from outside", "Shape \"sphere\"",
         {0, 0, 5, 2, 2, 2}, 0, {0, 0, 0}, MT_FIX_QUADRIC_SCALE, 0, 0, 0, 0},
        {"quadric-scale", "disk under Scale 2", "Shape \"disk\" \"float radius\" 0.7",
         {0, 0, 3, 2, 2, 2}, 1, {0, 0, 0}, MT_FIX_QUADRIC_SCALE, 0, MT_FIX_DISK_PARTIALS, 0, 0},
        {"quadric-scale", "ellipsoid (Scale 2 2 1) seen from outside", "Shape \"sphere\"",
         {0, 0, 4, 2, 2, 1}, 0, {0, 0, 0}, MT_FIX_QUADRIC_SCALE, 0, 0, 0, 0},
        /* mirrored: with quadric-scale fixed an ellipsoid's samples move to
         * the front, which the pdf must count */
        {"quadric-scale", "mirrored ellipsoid (Scale -2 2 1) seen from outside", "Shape \"sphere\"",
         {0, 0, 4, -2, 2, 1}, 0, {0, 0, 0}, MT_FIX_QUADRIC_SCALE, 0, 0, 0, 0},
        {"quadric-scale", "cylinder under Scale 2 seen from its axis (ReverseOrientation)",
         "Shape \"cylinder\"", {0, 0, 0, 2, 2, 2}, 1, {0, 0.1f, 0.3f}, MT_FIX_QUADRIC_SCALE, 0, 0, 0, 0},
        /* the release: about p_front / (p_front + p_back); the 2012 source's
         * re-intersection gave 0 from this side */
        {"shapeset-hit", "closed mesh (octahedron) seen from above", OCTAHEDRON,
         {0.3, 0.2, -3, 1, 1, 1}, 0, {0, 0, 0}, MT_FIX_SHAPESET_HIT, 0, 0, 0.4, 0.6},
        /* a sample on the far side is blocked by the near side, and
         * Shape::Pdf counts the near point alone: unbiased since df276f5
         * (the 2012 snapshot's re-intersection brought both to the near
         * point: 2.861 times the light) */
        {"shapeset-hit", "cylinder seen from outside", "Shape \"cylinder\"", {0, 3, 0, 1, 1, 1}, 0,
         {0, 0, 0}, MT_FIX_SHAPESET_HIT, 1, 0, 0, 0},
        /* Sample() ignores the mirror; the 2012 snapshot's re-intersection
         * replaced its normal with the hit's, the release leaves it */
        {"triangle-facing", "mirrored quad (Scale -1 1 1) seen from the side it faces",
         "Shape \"trianglemesh\" \"integer indices\" [0 2 1 0 3 2]"
         " \"point P\" [-0.6 -0.4 0  0.6 -0.4 0  0.6 0.4 0  -0.6 0.4 0]",
         {0.3, 0.2, 2, -1, 1, 1}, 0, {0, 0, 0}, MT_FIX_TRIANGLE_FACING, 0, 0, 0, 0},
        /* hits face -z, samples +z: seen from below, rays find the light
         * and light sampling finds none */
        {"disk-partials", "disk (its hits facing -z) seen from below", "Shape \"disk\" \"float radius\" 0.7",
         {0, 0, 3, 1, 1, 1}, 0, {0, 0, 0}, MT_FIX_DISK_PARTIALS, 0, 0, 0, 0},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) check_light_erratum(&cases[i]);
}

/* The infinite light: E[1/pdf] = 4 pi; Sample_L's pdf equals Pdf; Pdf
 * integrates to one; importance sampling estimates the map's integral
 * (against a dense quadrature of Le) with far less variance than uniform
 * sampling. */
static void check_infinite(const char *name, const mt__light *l, int peaked)
{
    mt_rng rng;
    acc inv = {0, 0, 0}, integ = {0, 0, 0}, imp = {0, 0, 0}, uni = {0, 0, 0};
    double quad = 0, dt = PI_D / 1024, dp = 2 * PI_D / 2048;
    long bad = 0;
    int i, j;
    char nm[160];
    mt_rng_seed(&rng, 3, 9);
    for (i = 0; i < 65536; ++i) {
        mt__light_sample ls;
        mt__light_sample_l(l, NULL, mt_v3(0, 0, 0), 0, mt_rng_uniform(&rng), mt_rng_uniform(&rng), &ls);
        if (ls.pdf > 0) {
            /* a sample within rounding of a cell border may read the neighbour;
             * within 2.5 degrees of the poles a direction in float does not
             * pin theta down to 1e-3 of sin(theta) */
            double q = mt__light_pdf(l, mt_v3(0, 0, 0), ls.wi);
            mt_vec3 wl = mt_transform_vector(&l->w2l, ls.wi);
            if (fabs(q - ls.pdf) > 1e-3 * ls.pdf && fabs(wl.z) < 0.999) bad++;
            acc_add(&inv, 1 / ls.pdf);
            acc_add(&imp, mt_rgb_y(ls.Li) / ls.pdf);
        } else {
            acc_add(&inv, 0);
            acc_add(&imp, 0);
        }
        {
            mt_vec3 w = mt_uniform_sample_sphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng));
            acc_add(&integ, 4 * PI_D * mt__light_pdf(l, mt_v3(0, 0, 0), w));
            acc_add(&uni, 4 * PI_D * mt_rgb_y(mt__light_le(l, w)));
        }
    }
    for (j = 0; j < 1024; ++j) {
        double th = (j + 0.5) * dt;
        for (i = 0; i < 2048; ++i) {
            double ph = (i + 0.5) * dp;
            mt_vec3 w = mt_v3((mt_real)(sin(th) * cos(ph)), (mt_real)(sin(th) * sin(ph)), (mt_real)cos(th));
            quad += mt_rgb_y(mt__light_le(l, w)) * sin(th) * dt * dp;
        }
    }
    snprintf(nm, sizeof nm, "light %s: Sample_L's pdf equals Pdf", name);
    t_check(bad <= 65536 / 10000, nm, "%ld of 65536 samples differ by more than 1e-3", bad);
    snprintf(nm, sizeof nm, "light %s: E[1/pdf] = 4 pi", name);
    t_check(fabs(acc_mean(&inv) - 4 * PI_D) <= 5 * acc_se(&inv) + 1e-4, nm, "%.6g +- %.2g",
            acc_mean(&inv), acc_se(&inv));
    snprintf(nm, sizeof nm, "light %s: Pdf integrates to 1", name);
    t_check(fabs(acc_mean(&integ) - 1) <= 5 * acc_se(&integ) + 1e-3, nm, "%.5g +- %.2g",
            acc_mean(&integ), acc_se(&integ));
    snprintf(nm, sizeof nm, "light %s: importance sampling estimates the map's integral", name);
    t_check(fabs(acc_mean(&imp) - quad) <= 5 * acc_se(&imp) + 2e-3 * quad, nm,
            "%.6g +- %.2g, quadrature %.6g", acc_mean(&imp), acc_se(&imp), quad);
    if (peaked) {
        snprintf(nm, sizeof nm, "light %s: importance sampling beats uniform sampling", name);
        t_check(acc_se(&imp) < 0.3 * acc_se(&uni), nm, "standard errors %.3g vs %.3g",
                acc_se(&imp), acc_se(&uni));
    }
}

static void test_infinite_lights(void)
{
    mt_paramset *ps = mt_paramset_create();
    mt_transform rot = mt_rotate(30, mt_v3(1, 0.5f, 0));
    mt_error err;
    mt__light l;
    mt_image img;
    const char *dir;
    int i;
    char path[600];
    if (mt__light_create(&l, "infinite", ps, &rot, MT_MODE_PBRT_V2, &err) == MT_OK) {
        check_infinite("infinite constant", &l, 0);
        mt__light_free(&l);
    }
    /* a 24x12 map, dim everywhere with a bright patch and a gradient */
    dir = t_tmpdir_create("render-light");
    if (!dir || mt_image_alloc(&img, 24, 12, 3, &err) != MT_OK) {
        t_fail("light infinite map", "no temporary directory");
        mt_paramset_destroy(ps);
        return;
    }
    for (i = 0; i < 24 * 12; ++i) {
        int x = i % 24, y = i / 24;
        float v = 0.05f + 0.01f * x + ((x == 17 && (y == 3 || y == 4)) ? 300.0f : 0);
        img.data[3 * i] = v, img.data[3 * i + 1] = 0.5f * v, img.data[3 * i + 2] = 0.2f + 0 * v;
    }
    snprintf(path, sizeof path, "%s/map.pfm", dir);
    mt_image_write(path, &img, NULL, 0, &err);
    mt_image_free(&img);
    {
        mt_param p;
        const char *names[1];
        memset(&p, 0, sizeof p);
        names[0] = path;
        p.name = "mapname";
        p.type = MT_PARAM_STRING;
        p.type_name = "string";
        p.count = 1;
        p.strings = names;
        mt_paramset_add(ps, &p, NULL);
    }
    if (mt__light_create(&l, "infinite", ps, &rot, MT_MODE_PBRT_V2, &err) == MT_OK) {
        check_infinite("infinite map", &l, 1);
        mt__light_free(&l);
    } else {
        char buf[1024];
        t_fail("light infinite map", "%s", mt_error_format(&err, buf, sizeof buf));
    }
    {
        /* pbrt-v2 reads a PFM's rows in file order (erratum pfm-rows): its
         * map is the corrected one upside down, theta -> pi - theta, which
         * in the light's frame (no transform here) is z -> -z */
        mt_transform id = mt_transform_identity();
        mt__light lv2, lc;
        mt_rng rng;
        int bad = 0, differ = 0;
        double worst = 0;
        if (mt__light_create(&lv2, "infinite", ps, &id, MT_MODE_PBRT_V2, &err) == MT_OK) {
            if (mt__light_create(&lc, "infinite", ps, &id, MT_MODE_CORRECTED, &err) == MT_OK) {
                mt_rng_seed(&rng, 5, 5);
                for (i = 0; i < 2000; ++i) {
                    mt_vec3 d = mt_uniform_sample_sphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng));
                    mt_rgb a = mt__light_le(&lv2, d), b = mt__light_le(&lc, mt_v3(d.x, d.y, -d.z));
                    mt_rgb c = mt__light_le(&lc, d);
                    /* beside the 300x patch a float ulp of theta moves the
                     * bilinear lookup by ~1e-4 absolute: relative 1e-3
                     * above 1; a map not flipped is off by up to 300 */
                    double e = fabs(a.c[0] - b.c[0]) / (fabs(b.c[0]) + 1);
                    worst = fmax(worst, e);
                    bad += e > 1e-3;
                    differ += fabs(a.c[0] - c.c[0]) > 1e-3 * (fabs(c.c[0]) + 1e-3);
                }
                t_check(bad == 0 && differ > 100,
                        "light infinite map: a PFM map upside down in pbrt-v2 mode (pfm-rows), "
                        "upright corrected",
                        "%d of 2000 directions off the flipped map (worst %.3g), %d differ between modes",
                        bad, worst, differ);
                mt__light_free(&lc);
            }
            mt__light_free(&lv2);
        }
    }
    t_tmpdir_remove();
    mt_paramset_destroy(ps);
}

static void test_delta_lights(void)
{
    mt_paramset *ps = mt_paramset_create();
    mt_transform t = mt_translate(mt_v3(1, 2, 3));
    mt_error err;
    mt__light l;
    mt__light_sample ls;
    double c, want;
    /* point: I / d^2, "from" added in world space after the transform */
    mt__light_create(&l, "point", ps, &t, MT_MODE_PBRT_V2, &err);
    mt__light_sample_l(&l, NULL, mt_v3(1, 2, 1), 0.3f, 0.3f, 0.3f, &ls);
    t_check(ls.pdf == 1 && fabs(ls.Li.c[0] - 0.25) < 1e-6 && fabs(ls.wi.z - 1) < 1e-6 &&
                fabs(mt_ray_at(&ls.shadow, 1).z - 3) < 1e-3,
            "light point: I / d^2 towards the light", "Li %g wi.z %g", (double)ls.Li.c[0], (double)ls.wi.z);
    /* spot: cone 30, delta 5, falloff ((cos t - cos 30) / (cos 25 - cos 30))^4 */
    t = mt_transform_identity();
    mt__light_create(&l, "spot", ps, &t, MT_MODE_PBRT_V2, &err);
    c = cos(27.5 * PI_D / 180);
    mt__light_sample_l(&l, NULL, mt_v3((mt_real)(2 * sin(27.5 * PI_D / 180)), 0, (mt_real)(2 * c)), 0, 0, 0, &ls);
    want = pow((c - cos(30 * PI_D / 180)) / (cos(25 * PI_D / 180) - cos(30 * PI_D / 180)), 4) / 4;
    t_rel(ls.Li.c[1], want, 1e-3, 1e-7, "light spot: pbrt-v2's quartic falloff");
    mt__light_sample_l(&l, NULL, mt_v3(0, 0, 2), 0, 0, 0, &ls);
    t_rel(ls.Li.c[1], 0.25, 1e-6, 0, "light spot: full intensity inside the inner cone");
    mt__light_sample_l(&l, NULL, mt_v3(2, 0, 1), 0, 0, 0, &ls);
    t_check(mt_rgb_is_black(ls.Li), "light spot: black outside the cone", "Li %g", (double)ls.Li.c[0]);
    /* distant: wi = from - to, L */
    mt__light_create(&l, "distant", ps, &t, MT_MODE_PBRT_V2, &err);
    mt__light_sample_l(&l, NULL, mt_v3(5, 5, 5), 0, 0, 0, &ls);
    t_check(fabs(ls.wi.z + 1) < 1e-6 && ls.pdf == 1 && ls.shadow.tmax > 1e30f,
            "light distant: towards from - to, unbounded shadow ray", "wi.z %g", (double)ls.wi.z);
    t_check(mt__light_create(&l, "goniometric", ps, &t, MT_MODE_PBRT_V2, &err) == MT_ERR_UNSUPPORTED,
            "light goniometric unsupported", "status %d", err.status);
    mt_paramset_destroy(ps);
}

int main(void)
{
    test_cameras();
    test_lens_differentials();
    test_lens_texture_filtering();
    test_specular_differentials();
    test_filters();
    test_film_normalization();
    test_crop_window();
    test_sampler();
    test_area_lights();
    test_light_errata();
    test_infinite_lights();
    test_delta_lights();
    return t_status();
}
