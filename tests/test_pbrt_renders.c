/*
 * materia's renders of ../shared/reference/scenes/ against pbrt-v2's own
 * (../shared/reference/pbrt-v2/NAME.exr), in pbrt-v2 mode, at each scene's
 * own sample count (1024). The metric is pbrt-v2's noise metric of
 * noise.txt (4x4 block means, |a - b| / (b + 0.01) per block and channel:
 * mean, 99th percentile, maximum; the luminance ratio), and the bound is
 * twice what two pbrt-v2 renders of the scene differ by (the reference
 * README: "a bound of twice the pbrt-v2-vs-pbrt-v2 figure, per scene, is a
 * fair test") for the mean and the 99th percentile, and for the luminance
 * ratio's distance from 1 (at least 0.002). The maximum is reported. The
 * real pbrt-v2 scenes must render without error (at 4 samples per pixel:
 * there is no pbrt-v2 image of them to compare with). The two dipole scenes
 * render at 128 samples per pixel (below: why the same bound holds).
 *
 * Skipped without ../shared, and under the sanitizers (20 million camera
 * samples per scene; the sanitizer run exercises the same code on the golden
 * scenes).
 */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "support/check.h"
#include "support/kinds.h"
#include "materia/tools/imgcmp.h"
#include "materia/render.h"

/* the material kinds (t_material_kinds): those without a BSSRDF, then the
 * dipole ones */
static const char *materials[T_MAX_KINDS];
static size_t nmaterials, ndipole;
/* The dipole scenes at DIPOLE_SPP: their noise.txt rows are dominated by the
 * difference between two pbrt-v2 runs' point sets and irradiance samples
 * (blotches over the sphere that more pixel samples do not remove: two
 * pbrt-v2 runs at 1024 differ by a mean of 0.0086 and 0.0199, ten times
 * the path-traced scenes' p99), so twice those rows bound a render at 128
 * samples per pixel as well; measured at 128 in pbrt-v2 mode with seeds 1
 * and 2: subsurface mean 0.0117, 0.0070, p99 0.123, 0.072 (bounds 0.0172,
 * 0.162); kdsubsurface mean 0.0363, 0.0288, p99 0.413, 0.370 (bounds
 * 0.0398, 0.533). */
static const char *dipole[T_MAX_KINDS];
#define DIPOLE_SPP 128
static const char *const real[] = {"real-bunny-measured", "real-killeroo-simple", "real-metal-teapot", "real-ss-envmap"};

typedef struct noise_row {
    char name[32];
    double mean, p99, max, lum;
} noise_row;

static int read_noise(const char *shared, noise_row *rows, int max)
{
    char path[512], line[256];
    FILE *f;
    int n = 0;
    snprintf(path, sizeof path, "%s/reference/pbrt-v2/noise.txt", shared);
    if (!(f = fopen(path, "r"))) return -1;
    while (fgets(line, sizeof line, f) && n < max)
        if (line[0] != '#' && sscanf(line, "%31s %lf %lf %lf %lf", rows[n].name, &rows[n].mean, &rows[n].p99,
                                     &rows[n].max, &rows[n].lum) == 5)
            n++;
    fclose(f);
    return n;
}

int main(void)
{
    const char *shared = t_shared_dir();
    noise_row noise[32];
    int nnoise, i;
    size_t k;
    if (!shared) {
        t_skip("pbrt-v2 renders", "../shared is absent");
        return 0;
    }
    if (T_SANITIZED) {
        t_skip("pbrt-v2 renders", "not under the sanitizers (20 million samples per scene); the unsanitized builds run it");
        return 0;
    }
    if (!t_has_format("exr", "pbrt-v2 renders (its images are EXR)")) return 0;
    nnoise = read_noise(shared, noise, 32);
    if (nnoise <= 0) {
        t_fail("pbrt-v2 renders", "cannot read noise.txt");
        return t_status();
    }
    nmaterials = (size_t)t_material_kinds(0, materials, T_MAX_KINDS);
    ndipole = (size_t)t_material_kinds(1, dipole, T_MAX_KINDS);
    for (k = 0; k < nmaterials + ndipole; ++k) {
        const size_t nmat = nmaterials;
        int is_dipole = k >= nmat;
        const char *mat = is_dipole ? dipole[k - nmat] : materials[k];
        char scene[512], ref[512], name[128];
        mt_render_options o;
        mt_render_stats st;
        mt_image img, pbrt;
        mt_noise_metric m;
        mt_error err;
        const noise_row *nr = NULL;
        for (i = 0; i < nnoise; ++i)
            if (!strcmp(noise[i].name, mat)) nr = &noise[i];
        snprintf(scene, sizeof scene, "%s/reference/scenes/%s.pbrt", shared, mat);
        snprintf(ref, sizeof ref, "%s/reference/pbrt-v2/%s.exr", shared, mat);
        snprintf(name, sizeof name, is_dipole ? "pbrt-v2 render %s at 128 spp: within twice pbrt-v2's own noise" : "pbrt-v2 render %s: within twice pbrt-v2's own noise", mat);
        mt_render_options_default(&o);
        o.mode = MT_MODE_PBRT_V2;
        o.seed = 3;
        if (is_dipole) o.spp = DIPOLE_SPP;
        mt_error_clear(&err);
        if (access(scene, R_OK) != 0) { /* a kind pbrt-v2 does not have */
            t_skip(name, "%s: pbrt-v2's reference data has no scene of this material", scene);
            continue;
        }
        if (!nr || mt_image_read(ref, &pbrt, &err)) {
            t_fail(name, "no reference: %s", nr ? err.message : "not in noise.txt");
            continue;
        }
        if (mt_render_file(scene, &o, &img, NULL, &st, &err) != MT_OK) {
            t_fail(name, "render failed: %s", err.message);
            mt_image_destroy(&pbrt);
            continue;
        }
        if (mt_imgcmp_noise(&img, &pbrt, 4, &m, &err) != MT_OK) {
            t_fail(name, "%s", err.message);
        } else {
            double lum_bound = fmax(2 * fabs(1 - nr->lum), 0.002);
            t_check(m.mean <= 2 * nr->mean && m.p99 <= 2 * nr->p99 && fabs(1 - m.lum_ratio) <= lum_bound, name,
                    "mean %.4f (bound %.4f), p99 %.4f (bound %.4f), lum ratio %.4f (bound 1 +- %.4f)", m.mean,
                    2 * nr->mean, m.p99, 2 * nr->p99, m.lum_ratio, lum_bound);
            printf("  %-11s mean %.4f p99 %.4f max %.4f lum %.4f | pbrt-v2 vs pbrt-v2: %.4f %.4f %.4f %.4f | %.1f s, "
                   "%.3g samples/s\n",
                   mat, m.mean, m.p99, m.max, m.lum_ratio, nr->mean, nr->p99, nr->max, nr->lum, st.seconds,
                   st.samples_per_second);
        }
        mt_image_destroy(&img);
        mt_image_destroy(&pbrt);
    }
    for (k = 0; k < sizeof real / sizeof real[0]; ++k) {
        char scene[512], name[128];
        mt_render_options o;
        mt_image img;
        mt_error err;
        size_t p, bad = 0;
        snprintf(scene, sizeof scene, "%s/reference/scenes/%s.pbrt", shared, real[k]);
        snprintf(name, sizeof name, "pbrt-v2 scene %s renders without error", real[k]);
        mt_render_options_default(&o);
        o.spp = 4;
        mt_error_clear(&err);
        if (mt_render_file(scene, &o, &img, NULL, NULL, &err) != MT_OK) {
            t_fail(name, "%s", err.message);
            continue;
        }
        for (p = 0; p < (size_t)img.width * img.height * img.channels; ++p)
            if (!isfinite(img.data[p]) || img.data[p] < 0) bad++;
        t_check(bad == 0, name, "%zu pixel values not finite or negative", bad);
        mt_image_destroy(&img);
    }
    return t_status();
}
