/*
 * materia-golden: the golden image of a scene whose error is not sampling
 * noise alone (the dipole integrator's point set changes with the seed):
 * K renders with seeds 1..K, their mean, the variance of that mean from
 * their spread, and the aggregate statistics of each render
 * (tests/support/blockstats.h) that tests/test_golden.c compares with.
 *
 *   materia-golden scene.pbrt --renders K --spp N -o mean.exr --variance var.exr
 *                  --stats stats.txt [--mode pbrt-v2|corrected] [--threads N]
 *   materia-golden scene.pbrt --points points.txt [--seed S]
 *
 * The second form writes the irradiance points that the scene's
 * dipolesubsurface integrator deposits with seed S (default 1) in pbrt-v2's
 * points file format (SurfacePointsRenderer: position, normal, area, ray
 * epsilon per line), for a scene's "string pointsfile".
 *
 * Exit status 0 when everything was written, 1 on an error (naming the
 * file), 2 on a bad option. Files are written to temporary names and renamed.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/tools/imgcmp.h"
#include "materia/render.h"
#include "support/blockstats.h"
#include "tracer/scene.h"
#include "toolargs.h"

static const char *prog = "materia-golden";

static int usage_to(FILE *f)
{
    fprintf(f, "usage: %s scene.pbrt --renders K --spp N -o mean.exr --variance var.exr --stats stats.txt\n"
               "       [--mode pbrt-v2|corrected] [--threads N]\n"
               "       %s scene.pbrt --points points.txt [--seed S]\n"
               "       %s --help | --version\n",
            prog, prog, prog);
    if (f == stdout) /* --help: every option with its default */
        fputs("K >= 2 renders with seeds 1..K: their mean, the variance of the mean, and each render's\n"
              "block statistics (the golden images of the dipole scenes, make golden); or the scene's\n"
              "dipole irradiance points.\n"
              "  --renders K        renders, 2 to 4096 (required)\n"
              "  --spp N            samples per pixel of each render, 1 to 16777216 (required)\n"
              "  -o FILE            their mean, an image (.exr, .png, .pfm; required)\n"
              "  --variance FILE    the variance of the mean (required)\n"
              "  --stats FILE       each render's block statistics, one line a render (required)\n"
              "  --mode M           pbrt-v2 (the default) or corrected\n"
              "  --threads N        1 to 4096 (default: one per online processor)\n"
              "  --points FILE      instead: the irradiance points of the scene's dipole integrator\n"
              "  --seed S           with --points: the points' seed, 0 to 4e9 (default 1)\n"
              "  --help, -h         this text;  --version  materia's version and precision\n"
              "Exit status: 0 written, 1 failure (the message on standard error, nothing written),\n"
              "2 wrong command line.\n",
              f);
    return f == stdout ? 0 : 2;
}

static int usage(void) { return usage_to(stderr); }

/* A wrong command line: why, then the usage. */
static int bad_usage(const char *why, const char *arg)
{
    fprintf(stderr, "%s: %s%s\n", prog, why, arg ? arg : "");
    return usage();
}

static int fail(const mt_error *err)
{
    char buf[1024];
    fprintf(stderr, "%s: %s\n", prog, mt_error_format(err, buf, sizeof buf));
    return 1;
}

/* The points of the scene's Poisson deposition, to path (pbrt-v2's format,
 * every float exactly: %.9g). */
static int write_points(const char *scene, const char *path, uint64_t seed, const mt_render_options *o)
{
    mt_error err;
    mt__dipole d;
    char tmp[1100];
    FILE *f;
    int i;
    mt_scene *s = mt_scene_load(scene, o, &err);
    if (!s) return fail(&err);
    if (s->integrator != MT__INTEGRATOR_DIPOLE) {
        fprintf(stderr, "%s: %s does not use the dipolesubsurface integrator\n", prog, scene);
        mt_scene_destroy(s);
        return 1;
    }
    memset(&d, 0, sizeof d);
    d.mode = s->mode;
    if (mt__dipole_deposit(s, seed, o->threads > 0 ? o->threads : 2, s->dipole.min_dist, o, &d, &err) != MT_OK) {
        mt__dipole_free(&d);
        mt_scene_destroy(s);
        return fail(&err);
    }
    if (s->mode & MT_FIX_DIPOLE_AREA) mt__dipole_fix_areas(&d, s->dipole.min_dist);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    if (!(f = fopen(tmp, "w"))) {
        fprintf(stderr, "%s: cannot write %s\n", prog, tmp);
        mt__dipole_free(&d);
        mt_scene_destroy(s);
        return 1;
    }
    fprintf(f, "# points deposited by %s for %s, seed %llu, minsampledistance %g\n", prog, scene,
            (unsigned long long)seed, (double)s->dipole.min_dist);
    fprintf(f, "# position (x,y,z), normal (x,y,z), area, rayEpsilon\n");
    for (i = 0; i < d.npts; ++i) {
        const mt__ss_point *p = &d.pts[i];
        fprintf(f, "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", (double)p->p.x, (double)p->p.y, (double)p->p.z,
                (double)p->n.x, (double)p->n.y, (double)p->n.z, (double)p->area, (double)p->ray_epsilon);
    }
    i = fclose(f);
    mt__dipole_free(&d);
    mt_scene_destroy(s);
    if (i != 0 || rename(tmp, path) != 0) {
        fprintf(stderr, "%s: cannot write %s\n", prog, path);
        remove(tmp);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    const char *scene = NULL, *out = NULL, *var_path = NULL, *stats_path = NULL, *points = NULL;
    uint64_t seed = 1;
    mt_render_options o;
    mt_error err;
    mt_status st;
    mt_scene *s;
    mt_imgacc *acc = NULL;
    mt_image mean, var;
    double v, stats[T_BLOCKSTAT_MAX];
    int renders = 0, spp = 0, i, k, n = 0, w, h;
    char tmp[1100];
    FILE *f;
    mt_render_options_default(&o);
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) return usage_to(stdout);
        if (!strcmp(a, "--version")) {
            printf("%s (materia) %s, %s\n", prog, mt_version(), mt_precision());
            return 0;
        }
    }
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!val && (!strcmp(a, "-o") || !strcmp(a, "--variance") || !strcmp(a, "--stats") ||
                     !strcmp(a, "--points") || !strcmp(a, "--mode")))
            return tool_no_value(prog, a);
        if (!strcmp(a, "--renders") || !strcmp(a, "--spp") || !strcmp(a, "--threads")) {
            if (!tool_number(prog, a, val, 1, a[2] == 's' ? (1 << 24) : 4096, 1, &v)) return 2;
            if (a[2] == 'r') renders = (int)v;
            else if (a[2] == 's') spp = (int)v;
            else o.threads = (int)v;
            ++i;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--variance") || !strcmp(a, "--stats")) {
            if (a[1] == 'o') out = val;
            else if (a[2] == 'v') var_path = val;
            else stats_path = val;
            ++i;
        } else if (!strcmp(a, "--points")) {
            points = val;
            ++i;
        } else if (!strcmp(a, "--seed")) {
            if (!tool_number(prog, a, val, 0, 4e9, 1, &v)) return 2;
            seed = (uint64_t)v;
            ++i;
        } else if (!strcmp(a, "--mode")) {
            if (mt_mode_parse(val, &o.mode, NULL) != MT_OK) return bad_usage("--mode is pbrt-v2 or corrected, not ", val);
            ++i;
        } else if (a[0] == '-') {
            return bad_usage("unknown option ", a);
        } else if (scene) {
            return bad_usage("more than one scene: ", a);
        } else {
            scene = a;
        }
    }
    if (!scene) return bad_usage("no scene file", NULL);
    if (points) return write_points(scene, points, seed, &o);
    if (!out || !var_path || !stats_path)
        return bad_usage(!out ? "no -o mean.exr" : !var_path ? "no --variance var.exr" : "no --stats stats.txt", NULL);
    if (renders < 2 || spp < 1)
        return bad_usage(renders < 2 ? "--renders K needs K >= 2 (the variance comes from their spread)"
                                     : "no --spp N", NULL);
    o.spp = spp;
    /* a typo in an output path fails now, not after the renders */
    if (mt_image_check_writable(out, &err) != MT_OK || mt_image_check_writable(var_path, &err) != MT_OK)
        return fail(&err);
    if (!(s = mt_scene_load(scene, &o, &err))) return fail(&err);
    mt_scene_image_size(s, &w, &h);
    if (!(acc = mt_imgacc_create(w, h, 3, &err))) {
        mt_scene_destroy(s);
        return fail(&err);
    }
    snprintf(tmp, sizeof tmp, "%s.tmp", stats_path);
    if (!(f = fopen(tmp, "w"))) {
        fprintf(stderr, "%s: cannot write %s\n", prog, tmp);
        mt_imgacc_destroy(acc);
        mt_scene_destroy(s);
        return 1;
    }
    fprintf(f, "# %s: %d renders of %s, seeds 1..%d, %d samples per pixel, mode %s; per render the mean of\n"
               "# each channel over blocks of %d x %d pixels (row by row), then over the whole image, then over\n"
               "# its central box [w/4, 3w/4) x [h/6, 5h/6)\n",
            prog, renders, scene, renders, spp, mt_mode_name(o.mode), T_BLOCKSTAT_SIDE, T_BLOCKSTAT_SIDE);
    for (k = 1; k <= renders; ++k) {
        mt_image img;
        o.seed = (uint64_t)k;
        fprintf(stderr, "%s: render %d of %d\n", prog, k, renders);
        if (mt_scene_render(s, &o, &img, NULL, NULL, &err) != MT_OK || mt_imgacc_add_image(acc, &img, &err) != MT_OK) {
            fclose(f);
            remove(tmp);
            mt_imgacc_destroy(acc);
            mt_scene_destroy(s);
            return fail(&err);
        }
        n = t_blockstats(&img, stats, T_BLOCKSTAT_MAX);
        if (k == 1) fprintf(f, "renders %d spp %d stats %d\n", renders, spp, n);
        for (i = 0; i < n; ++i) fprintf(f, "%.9g%c", stats[i], i + 1 < n ? ' ' : '\n');
        mt_image_destroy(&img);
    }
    if (fclose(f) != 0 || n == 0) {
        fprintf(stderr, "%s: cannot write %s\n", prog, tmp);
        remove(tmp);
        mt_imgacc_destroy(acc);
        mt_scene_destroy(s);
        return 1;
    }
    /* nothing written on failure: each file written goes when a later one fails */
    st = mt_imgacc_finish(acc, &mean, &var, &err);
    if (st == MT_OK) {
        if ((st = mt_render_write(out, &mean, s, &o, &err)) == MT_OK &&
            (st = mt_render_write(var_path, &var, s, &o, &err)) != MT_OK)
            remove(out);
        mt_image_destroy(&mean);
        mt_image_destroy(&var);
    }
    mt_imgacc_destroy(acc);
    mt_scene_destroy(s);
    if (st != MT_OK) {
        remove(tmp);
        return fail(&err);
    }
    if (rename(tmp, stats_path) != 0) {
        fprintf(stderr, "%s: cannot rename %s to %s\n", prog, tmp, stats_path);
        remove(tmp);
        remove(out);
        remove(var_path);
        return 1;
    }
    return 0;
}
