/*
 * materia-render: renders a pbrt-v2 scene file with materia's materials.
 *
 *   materia-render scene.pbrt [-o out.exr|.png|.pfm] [--spp N] [--threads N]
 *                  [--seed S] [--mode pbrt-v2|corrected] [--quiet]
 *                  [--variance var.exr]
 *
 * The image goes to -o, else to the Film's "filename" (resolved against the
 * current directory, as pbrt-v2 does); its extension and directory are
 * checked before the render starts. Errors print file:line and the message
 * and exit with status 1 without writing anything; a wrong command line
 * exits with status 2. The progress line is shown only when standard error
 * is a terminal; --quiet also drops the summary and the notice that the
 * scene's Sampler is replaced by materia's own.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "materia.h"
#include "toolargs.h"
#include "materia/render.h"

static const char *usage =
    "usage: materia-render scene.pbrt [-o out.exr|.png|.pfm] [--spp N] [--threads N]\n"
    "                      [--seed S] [--mode pbrt-v2|corrected] [--quiet] [--variance var.exr]\n"
    "       materia-render --help | --version\n";

/* --help: every option with its default, and the exit statuses */
static const char *help =
    "Renders a pbrt-v2 scene file with materia's materials (docs/RENDERER.md); the image is\n"
    "the same bit for bit on any number of threads.\n"
    "  -o FILE          the image: .exr (float RGB, with the spp, seed and mode in its header),\n"
    "                   .png (8-bit sRGB) or .pfm (default: the Film's \"filename\", pbrt-v2's\n"
    "                   default pbrt.exr, relative to the current directory)\n"
    "  --variance FILE  also the estimated variance of each pixel's value (default: none)\n"
    "  --spp N          samples per pixel, 1 to 16777216 (default: the scene's Sampler's)\n"
    "  --threads N      1 to 1024 (default: one per online processor)\n"
    "  --seed S         the sample pattern, 0 to 2^63 - 1 (default 0)\n"
    "  --mode M         pbrt-v2 (the default: pbrt-v2's answers, errata included) or corrected\n"
    "  --quiet          no progress line (shown only on a terminal anyway), no summary, no\n"
    "                   notice that the scene's Sampler is replaced (default: off)\n"
    "  --help, -h       this text;  --version  materia's version and precision\n"
    "Output paths are checked before the render; the image is written to a temporary file\n"
    "and renamed. Warnings (unused parameters) go to standard error as FILE:LINE: warning.\n"
    "Exit status: 0 rendered and written, 1 error (the scene's file:line and the message on\n"
    "standard error; nothing written), 2 wrong command line.\n";

static int quiet;

static void warn(void *ctx, const char *file, int line, const char *msg)
{
    (void)ctx;
    /* a notice about materia's sampler, not a problem of the scene */
    if (quiet && strncmp(msg, "Sampler \"", 9) == 0) return;
    if (file && *file) fprintf(stderr, "%s:%d: warning: %s\n", file, line, msg);
    else fprintf(stderr, "warning: %s\n", msg);
}

static void progress(void *ctx, double f, double elapsed, double remaining)
{
    (void)ctx;
    if (remaining >= 0)
        fprintf(stderr, "\rrendering: %5.1f%%  %6.1fs elapsed, %6.1fs left ", 100 * f, elapsed, remaining);
    else
        fprintf(stderr, "\rrendering: %5.1f%%  %6.1fs elapsed ", 100 * f, elapsed);
    if (f >= 1) fputc('\n', stderr);
    fflush(stderr);
}

/* The preprocess of dipolesubsurface: one line per stage, redrawn. */
static void stage(void *ctx, const char *name, double f, long count, double elapsed, double remaining)
{
    (void)ctx;
    fprintf(stderr, "\r%s: %5.1f%%  %ld points  %6.1fs elapsed", name, 100 * f, count, elapsed);
    if (remaining >= 0 && f < 1) fprintf(stderr, ", %6.1fs left ", remaining);
    else fputs("               ", stderr);
    if (f >= 1) fputc('\n', stderr);
    fflush(stderr);
}

static int fail(const mt_error *err)
{
    char buf[1024];
    fprintf(stderr, "materia-render: %s\n", mt_error_format(err, buf, sizeof buf));
    return 1;
}

static int bad_option(const char *what, const char *value)
{
    if (!value) return tool_no_value("materia-render", what);
    fprintf(stderr, "materia-render: %s: bad value \"%s\"\n%s", what, value, usage);
    return 2;
}

/* A whole decimal number within [lo, hi]. */
static int parse_long(const char *s, long long lo, long long hi, long long *out)
{
    char *end;
    long long v;
    if (!s || !*s) return 0;
    errno = 0;
    v = strtoll(s, &end, 10);
    if (errno || *end || v < lo || v > hi) return 0;
    *out = v;
    return 1;
}

int main(int argc, char **argv)
{
    const char *scene = NULL, *out = NULL, *var_path = NULL;
    mt_render_options o;
    mt_render_stats stats;
    mt_image img, var;
    mt_scene *s;
    mt_error err;
    int i;
    long long v;
    mt_render_options_default(&o);
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(usage, stdout);
            fputs(help, stdout);
            return 0;
        } else if (strcmp(a, "--version") == 0) {
            printf("materia-render (materia) %s, %s\n", mt_version(), mt_precision());
            return 0;
        } else if (strcmp(a, "-o") == 0) {
            if (!val) return bad_option(a, val);
            out = val, ++i;
        } else if (strcmp(a, "--variance") == 0) {
            if (!val) return bad_option(a, val);
            var_path = val, ++i;
        } else if (strcmp(a, "--spp") == 0) {
            if (!parse_long(val, 1, 1 << 24, &v)) return bad_option(a, val);
            o.spp = (int)v, ++i;
        } else if (strcmp(a, "--threads") == 0) {
            if (!parse_long(val, 1, 1024, &v)) return bad_option(a, val);
            o.threads = (int)v, ++i;
        } else if (strcmp(a, "--seed") == 0) {
            if (!parse_long(val, 0, 0x7fffffffffffffffLL, &v)) return bad_option(a, val);
            o.seed = (uint64_t)v, ++i;
        } else if (strcmp(a, "--mode") == 0) {
            if (!val || mt_mode_parse(val, &o.mode, NULL) != MT_OK) return bad_option(a, val);
            ++i;
        } else if (strcmp(a, "--quiet") == 0) {
            quiet = 1;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "materia-render: unknown option %s\n%s", a, usage);
            return 2;
        } else if (!scene) {
            scene = a;
        } else {
            fprintf(stderr, "materia-render: more than one scene file\n%s", usage);
            return 2;
        }
    }
    if (!scene) {
        fputs(usage, stderr);
        return 2;
    }
    o.warn = warn;
    if (!quiet && isatty(STDERR_FILENO)) {
        o.progress = progress;
        o.stage = stage;
    }
    if (!(s = mt_scene_load(scene, &o, &err))) return fail(&err);
    if (!out) out = mt_scene_filename(s);
    /* a typo in the output path fails now, not after the render */
    if (mt_image_check_writable(out, &err) != MT_OK ||
        (var_path && mt_image_check_writable(var_path, &err) != MT_OK)) {
        mt_scene_destroy(s);
        return fail(&err);
    }
    if (mt_scene_render(s, &o, &img, var_path ? &var : NULL, &stats, &err) != MT_OK) {
        mt_scene_destroy(s);
        return fail(&err);
    }
    if (var_path && mt_render_write(var_path, &var, s, &o, &err) != MT_OK) {
        mt_image_destroy(&img);
        mt_image_destroy(&var);
        mt_scene_destroy(s);
        return fail(&err);
    }
    if (mt_render_write(out, &img, s, &o, &err) != MT_OK) {
        if (var_path) remove(var_path); /* nothing written on failure */
        mt_image_destroy(&img);
        if (var_path) mt_image_destroy(&var);
        mt_scene_destroy(s);
        return fail(&err);
    }
    if (!quiet)
        fprintf(stderr, "%s: %dx%d, %d spp, %d threads: %.2f s, %.3g samples/s%s -> %s\n", scene,
                img.width, img.height, stats.spp, stats.threads, stats.seconds,
                stats.samples_per_second, "", out);
    if (!quiet && stats.points > 0)
        fprintf(stderr, "dipolesubsurface: %ld irradiance points, preprocess %.2f s of the %.2f s\n", stats.points,
                stats.preprocess_seconds, stats.seconds);
    if (stats.rejected || stats.shading_failures)
        fprintf(stderr, "materia-render: %ld samples set to black (NaN, Inf or negative), %ld "
                        "path vertices without a BSDF\n", stats.rejected, stats.shading_failures);
    mt_image_destroy(&img);
    if (var_path) mt_image_destroy(&var);
    mt_scene_destroy(s);
    return 0;
}
