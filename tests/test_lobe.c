/*
 * materia-lobe: the picture's size from its documented layout, the f cos and
 * pdf maps at a few pixels against eval of the same direction, the colour
 * of those pixels in the PNG against the colour scale, the same picture of
 * materia in-process and through materia-query (differences exactly 0),
 * and children that exit early or hang reported as errors.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "image/heatcolour.h"
#include "materia.h"
#include "materia/tools/query.h"
#include "support/check.h"
#include "support/tfiles.h"

#include "../tools/lobe.h"

#define PI 3.14159265358979323846

static char bin[1024];
static const char *plastic = "'Material \"plastic\" \"float roughness\" [0.1]'";

static int run(const char *args, int quiet)
{
    char cmd[4096];
    int rc;
    snprintf(cmd, sizeof cmd, "%s/materia-lobe %s%s", bin, args, quiet ? " >/dev/null 2>&1" : " >/dev/null");
    rc = system(cmd);
    return rc == -1 ? -1 : WEXITSTATUS(rc);
}

static int width_of(void) { return LOBE_WIDTH; }
static int height_of(int nimpl, int rows) { return LOBE_HEIGHT(nimpl, 1, rows); }

static void test_values(void)
{
    const char *png = t_tmp_path("a.png"), *raw = t_tmp_path("r");
    char args[2048], path[1024];
    mt_image img = {0, 0, 0, NULL}, fc = {0, 0, 0, NULL}, pd = {0, 0, 0, NULL};
    mt_error err;
    mt_query *q;
    static const int px[][2] = {{10, 5}, {128, 40}, {200, 60}, {70, 100}, {131, 30}};
    int i, ok = 1, colour_ok = 1;
    double theta = 40, phi = 20, wo[3], fmax_ = 0;
    char line[256], ans[512];
    snprintf(args, sizeof args, "--samples 20000 --raw %s --wo %g %g -o %s %s", raw, theta, phi, png, plastic);
    if (!t_check(run(args, 0) == 0, "lobe: runs on materia in-process", "exit status not 0")) return;
    snprintf(path, sizeof path, "%s-A-fcos.pfm", raw);
    if (mt_image_read(png, &img, &err) || mt_image_read(path, &fc, &err)) {
        t_fail("lobe: reads its picture", "%s", err.message);
        return;
    }
    snprintf(path, sizeof path, "%s-A-pdf.pfm", raw);
    if (mt_image_read(path, &pd, &err)) {
        t_fail("lobe: reads its pdf map", "%s", err.message);
        return;
    }
    t_check(img.width == width_of() && img.height == height_of(1, 1), "lobe: picture size from the layout",
            "%dx%d, wanted %dx%d", img.width, img.height, width_of(), height_of(1, 1));
    t_check(fc.width == LL_W && fc.height == LL_H, "lobe: lat-long maps are 256 x 128", "%dx%d", fc.width, fc.height);
    wo[0] = sin(theta * PI / 180) * cos(phi * PI / 180);
    wo[1] = sin(theta * PI / 180) * sin(phi * PI / 180);
    wo[2] = cos(theta * PI / 180);
    q = mt_query_create(NULL, &err);
    mt_query_line(q, "mode corrected", ans, sizeof ans);
    mt_query_line(q, "Material \"plastic\" \"float roughness\" [0.1]", ans, sizeof ans);
    for (i = 0; i < LL_W * LL_H; ++i) fmax_ = fmax(fmax_, fc.data[i]);
    for (i = 0; i < (int)(sizeof px / sizeof px[0]); ++i) {
        int x = px[i][0], y = px[i][1];
        double ph = 2 * PI * (x + 0.5) / LL_W, th = PI * (y + 0.5) / LL_H, wi[3], v[4], want_f;
        float rgb[3];
        const float *got;
        int c, y0 = LOBE_MAP_Y(1, 1, 0);
        wi[0] = sin(th) * cos(ph), wi[1] = sin(th) * sin(ph), wi[2] = cos(th);
        snprintf(line, sizeof line, "eval %.9g %.9g %.9g %.9g %.9g %.9g", wo[0], wo[1], wo[2], wi[0], wi[1], wi[2]);
        mt_query_line(q, line, ans, sizeof ans);
        if (sscanf(ans, "%lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3]) != 4) {
            ok = 0;
            continue;
        }
        want_f = (v[0] + v[1] + v[2]) / 3 * fabs(wi[2]);
        if (!(fabs(fc.data[y * LL_W + x] - want_f) <= 1e-6 * fmax(want_f, 1e-6)) ||
            !(fabs(pd.data[y * LL_W + x] - v[3]) <= 1e-6 * fmax(v[3], 1e-6))) {
            ok = 0;
            printf("  pixel (%d, %d): f cos %.9g pdf %.9g, eval gives %.9g %.9g\n", x, y, fc.data[y * LL_W + x],
                   pd.data[y * LL_W + x], want_f, v[3]);
        }
        /* the PNG's pixel: the colour scale at f cos / max, through 8-bit sRGB */
        mt__heat_colour(fc.data[y * LL_W + x] / fmax_, rgb);
        got = img.data + ((size_t)(y0 + y) * (size_t)img.width + (size_t)(LOBE_MAP_X(0) + x)) * 3;
        for (c = 0; c < 3; ++c)
            if (!(fabs(mt_linear_to_srgb(got[c]) - mt_linear_to_srgb(rgb[c])) <= 1.0 / 255)) {
                colour_ok = 0;
                printf("  pixel (%d, %d) channel %d: %.4f, the scale gives %.4f\n", x, y, c, mt_linear_to_srgb(got[c]),
                       mt_linear_to_srgb(rgb[c]));
            }
    }
    t_check(ok, "lobe: f cos and pdf at five pixels equal eval of their directions", "see above");
    t_check(colour_ok, "lobe: those pixels in the picture have the colour scale's colour", "see above");
    mt_query_destroy(q);
    mt_image_destroy(&img);
    mt_image_destroy(&fc);
    mt_image_destroy(&pd);
}

/* materia in-process against materia-query: every difference is 0 */
static void test_against(void)
{
    const char *png = t_tmp_path("b.png"), *raw = t_tmp_path("d");
    const char *what[3] = {"fcos", "pdf", "hist"};
    char args[2048], path[1024];
    mt_image img = {0, 0, 0, NULL};
    mt_error err;
    int k;
    snprintf(args, sizeof args, "--samples 20000 --raw %s --against %s/materia-query --wo 60 200 -o %s %s", raw, bin,
             png, plastic);
    if (!t_check(run(args, 0) == 0, "lobe: --against materia-query runs", "exit status not 0")) return;
    if (!mt_image_read(png, &img, &err))
        t_check(img.width == width_of() && img.height == height_of(2, 3), "lobe: --against draws three rows",
                "%dx%d, wanted %dx%d", img.width, img.height, width_of(), height_of(2, 3));
    mt_image_destroy(&img);
    for (k = 0; k < 3; ++k) {
        double worst = 0, total = 0;
        int i;
        snprintf(path, sizeof path, "%s-diff-%s.pfm", raw, what[k]);
        if (mt_image_read(path, &img, &err)) {
            t_fail("lobe: --against difference maps", "%s", err.message);
            continue;
        }
        for (i = 0; i < img.width * img.height; ++i) worst = fmax(worst, fabs(img.data[i]));
        mt_image_destroy(&img);
        snprintf(path, sizeof path, "%s-B-%s.pfm", raw, what[k]);
        if (!mt_image_read(path, &img, &err)) {
            for (i = 0; i < img.width * img.height; ++i) total += img.data[i];
            mt_image_destroy(&img);
        }
        snprintf(args, sizeof args, "lobe: in-process and materia-query %s maps identical", what[k]);
        t_check(worst == 0 && total > 0, args, "largest difference %g (B's sum %g)", worst, total);
    }
}

static void test_hostile(void)
{
    const char *png = t_tmp_path("c.png");
    char args[2048];
    /* answers the mode and the statements, then exits */
    snprintf(args, sizeof args, "--samples 10 --against 'read a; echo ok; read b; echo ok' --wo 30 0 -o %s %s", png,
             plastic);
    t_check(run(args, 1) == 1, "lobe: a child that exits early is an error", "exit status not 1");
    snprintf(args, sizeof args, "--samples 10 --timeout 1 --against 'exec sleep 5' --wo 30 0 -o %s %s", png, plastic);
    t_check(run(args, 1) == 1, "lobe: a child that hangs is an error after --timeout", "exit status not 1");
    snprintf(args, sizeof args, "--samples 10 --against 'read a; echo ok; read b; echo ok; echo 1 2' --wo 30 0 -o %s %s",
             png, plastic);
    t_check(run(args, 1) == 1, "lobe: too few numbers in an answer is an error", "exit status not 1");
    snprintf(args, sizeof args, "--wo 30 -o %s %s", png, plastic);
    t_check(run(args, 1) == 2, "lobe: a usage error exits 2", "exit status not 2");
    t_check(access(png, F_OK) != 0, "lobe: no picture after an error", "%s exists", png);
}

int main(int argc, char **argv)
{
    const char *slash = strrchr(argv[0], '/');
    (void)argc;
    /* build/<precision>/tests/this -> build/<precision>/bin */
    snprintf(bin, sizeof bin, "%.*s/../bin", slash ? (int)(slash - argv[0]) : 1, slash ? argv[0] : ".");
    if (!t_tmpdir_create("lobe")) {
        t_fail("lobe", "no temporary directory");
        return 1;
    }
    /* materia-lobe draws PNG pictures */
    if (t_has_format("png", "materia-lobe (it draws a PNG)")) {
        test_values();
        test_against();
        test_hostile();
    }
    t_tmpdir_remove();
    return t_status();
}
