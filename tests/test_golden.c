/*
 * Golden images (golden/): each material's scene of golden/scenes/ rendered
 * at a low sample count and compared with its golden image, rendered by
 * materia at 4096 samples per pixel with its per-pixel variance of the mean
 * (tools/make-golden.sh, `make golden`). The comparison is statistical, as
 * Mitsuba 3's render tests are: a z-test of each 4x4 block and channel
 * against the golden mean with both variances, the Sidak correction over all
 * of them at significance 0.01 (materia/tools/imgcmp.h). An honest re-render (a
 * different seed from the golden one) must pass; the test also proves the
 * check has power: a 10% change of a material's colour, and corrected mode
 * on a plastic coat (its Fresnel term differs), must fail. The two dipole
 * scenes are checked differently (below): t-tests of aggregate statistics
 * against 32 golden renders with their own seeds; sigma_a 10% high, index
 * 1.2 instead of 1.3 and maxerror ten times larger must fail.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include "support/blockstats.h"
#include "support/check.h"
#include "support/kinds.h"
#include "materia/tools/imgcmp.h"
#include "materia/measured.h"
#include "materia/render.h"

/* samples per pixel of the test renders (the golden images have 4096) */
#ifndef TEST_SPP
#define TEST_SPP 256
#endif
/* the test renders' seed (the golden images have seed 1) */
#ifndef TEST_SEED
#define TEST_SEED 7
#endif

/* the material kinds without a BSSRDF (t_material_kinds), one scene each */
static const char *scenes[T_MAX_KINDS];
static int nscenes;

/* ---- the dipole scenes -------------------------------------------------------------
 * Their error is not sampling noise alone: the point set and the points'
 * irradiance samples change with the seed and lay smooth blotches over the
 * sphere, correlated over many pixels, which no per-pixel variance knows
 * about (a per-block z-test against a 4096-spp golden image fails honest
 * re-renders). Their golden set is K renders with seeds 1..K at the test's
 * own sample count (tools/materia-golden.c): golden/NAME.exr is their mean,
 * golden/NAME.var.exr its variance, golden/NAME.stats.txt each render's
 * aggregate statistics (tests/support/blockstats.h: channel means over
 * 16x16 blocks, the image and its central box). A render with another seed
 * is one more draw from the same distribution: for each statistic
 * t = (x - mean) / (sd sqrt(1 + 1/K)) is Student's t with K - 1 degrees of
 * freedom (exact for normal statistics; each is a mean over hundreds of
 * pixels), and the render passes when every |t| is below the two-sided
 * quantile at the Sidak level 1 - (1 - 0.01)^(1/m) over the m statistics
 * (those that vary: a block of sky alone, whose spread is float rounding,
 * must match within 1e-4). */
static const char *dipole_scenes[T_MAX_KINDS];
static int ndipole;

/* Student's t density with nu degrees of freedom. */
static double t_density(double x, double nu)
{
    return exp(lgamma((nu + 1) / 2) - lgamma(nu / 2) - 0.5 * log(nu * M_PI) - (nu + 1) / 2 * log1p(x * x / nu));
}

/* P(|T| > t): 1 - 2 int_0^t density (Simpson, 4000 intervals). */
static double t_two_sided(double t, double nu)
{
    int i, n = 4000;
    double h = t / n, s = t_density(0, nu) + t_density(t, nu);
    for (i = 1; i < n; ++i) s += (i & 1 ? 4 : 2) * t_density(i * h, nu);
    return 1 - 2 * s * h / 3;
}

/* The t with P(|T| > t) = p (bisection). */
static double t_quantile(double p, double nu)
{
    double lo = 0, hi = 100;
    int i;
    for (i = 0; i < 60; ++i) {
        double mid = (lo + hi) / 2;
        if (t_two_sided(mid, nu) > p) lo = mid;
        else hi = mid;
    }
    return (lo + hi) / 2;
}

typedef struct golden_stats {
    int K, spp, m;
    double *v; /* K x m */
} golden_stats;

static int read_stats(const char *name, golden_stats *gs)
{
    char path[512], line[1024];
    FILE *f;
    int i, j;
    snprintf(path, sizeof path, "golden/%s.stats.txt", name);
    memset(gs, 0, sizeof *gs);
    if (!(f = fopen(path, "r"))) return 0;
    while (fgets(line, sizeof line, f) && line[0] == '#') {
    }
    if (sscanf(line, "renders %d spp %d stats %d", &gs->K, &gs->spp, &gs->m) != 3 || gs->K < 3 || gs->m < 1 ||
        gs->m > T_BLOCKSTAT_MAX || !(gs->v = malloc(sizeof(double) * (size_t)gs->K * (size_t)gs->m))) {
        fclose(f);
        return 0;
    }
    for (i = 0; i < gs->K; ++i)
        for (j = 0; j < gs->m; ++j)
            if (fscanf(f, "%lf", &gs->v[i * gs->m + j]) != 1) {
                fclose(f);
                free(gs->v);
                gs->v = NULL;
                return 0;
            }
    fclose(f);
    return 1;
}

/* Renders the scene text at the golden set's sample count with `seed` and
 * tests its statistics; 1 pass, 0 fail, -1 could not run. */
static int dipole_compare(const char *name, const char *text, const char *dir, mt_mode mode, uint64_t seed,
                          const golden_stats *gs, char *why, size_t n)
{
    mt_render_options o;
    mt_scene *s;
    mt_error err;
    mt_image img;
    double x[T_BLOCKSTAT_MAX], worst = 0, thr;
    int j, k, m = 0, exact_bad = 0, worst_j = -1, r = -1;
    mt_render_options_default(&o);
    o.mode = mode;
    o.seed = seed;
    o.spp = gs->spp;
    mt_error_clear(&err);
    s = mt_scene_load_string(text, name, dir, &o, &err);
    if (!s || mt_scene_render(s, &o, &img, NULL, NULL, &err) != MT_OK) {
        snprintf(why, n, "%s", err.message);
        mt_scene_destroy(s);
        return -1;
    }
    if (t_blockstats(&img, x, T_BLOCKSTAT_MAX) != gs->m) {
        snprintf(why, n, "the render has %d statistics, the golden set %d", t_blockstats(&img, x, T_BLOCKSTAT_MAX), gs->m);
    } else {
        double tj[T_BLOCKSTAT_MAX];
        for (j = 0; j < gs->m; ++j) {
            double mu = 0, ss = 0;
            for (k = 0; k < gs->K; ++k) mu += gs->v[k * gs->m + j];
            mu /= gs->K;
            for (k = 0; k < gs->K; ++k) ss += (gs->v[k * gs->m + j] - mu) * (gs->v[k * gs->m + j] - mu);
            tj[j] = 0;
            /* no spread beyond float summation (blocks of sky alone): equal */
            if (sqrt(ss / (gs->K - 1)) <= 1e-6 * fabs(mu)) {
                if (fabs(x[j] - mu) > 1e-4 * fmax(fabs(x[j]), fabs(mu))) exact_bad++;
                continue;
            }
            tj[j] = (x[j] - mu) / (sqrt(ss / (gs->K - 1)) * sqrt(1 + 1.0 / gs->K));
            m++;
        }
        thr = m > 0 ? t_quantile(1 - pow(0.99, 1.0 / m), gs->K - 1) : 0;
        for (j = 0; j < gs->m; ++j)
            if (fabs(tj[j]) > worst) {
                worst = fabs(tj[j]);
                worst_j = j;
            }
        r = worst < thr && exact_bad == 0;
        snprintf(why, n, "max |t| %.2f (statistic %d of %d; %d vary), threshold %.2f (%d dof, Sidak 0.01), %d exact mismatches; "
                         "central box t %.2f %.2f %.2f",
                 worst, worst_j, gs->m, m, thr, gs->K - 1, exact_bad, tj[gs->m - 3], tj[gs->m - 2], tj[gs->m - 1]);
    }
    mt_image_destroy(&img);
    mt_scene_destroy(s);
    return r;
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    long n;
    char *s;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    s = malloc((size_t)n + 1);
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
        free(s);
        s = NULL;
    }
    if (s) s[n] = 0;
    fclose(f);
    return s;
}

/* Renders the scene text at the test's sample count and z-tests it against
 * the golden image; returns 1 when it passes, -1 when it could not run. */
static int render_and_compare(const char *name, const char *text, const char *dir, mt_mode mode,
                              uint64_t seed, char *why, size_t n)
{
    char gpath[512], vpath[512];
    mt_image gold, gvar, img, var;
    mt_render_options o;
    mt_scene *s;
    mt_error err;
    mt_ztest_result res;
    int r = -1;
    snprintf(gpath, sizeof gpath, "golden/%s.exr", name);
    snprintf(vpath, sizeof vpath, "golden/%s.var.exr", name);
    mt_error_clear(&err);
    if (mt_image_read(gpath, &gold, &err) || mt_image_read(vpath, &gvar, &err)) {
        snprintf(why, n, "%s", err.message);
        return -1;
    }
    mt_render_options_default(&o);
    o.mode = mode;
    o.seed = seed;
    o.spp = TEST_SPP;
    s = mt_scene_load_string(text, name, dir, &o, &err);
    if (s && mt_scene_render(s, &o, &img, &var, NULL, &err) == MT_OK) {
        if (mt_imgcmp_ztest(&img, &var, &gold, &gvar, NULL, &res, NULL, &err) == MT_OK) {
            r = res.pass;
            snprintf(why, n, "max |z| %.2f at block (%d, %d) channel %d, threshold %.2f, %ld of %ld blocks beyond; "
                             "bias z %.2f channel %d, threshold %.2f; mean rel diff %.4f",
                     res.max_abs_z, res.max_bx, res.max_by, res.max_c, res.z_threshold, res.beyond, res.tests,
                     res.bias_c >= 0 ? res.bias_z[res.bias_c] : 0.0, res.bias_c, res.bias_z_threshold,
                     res.mean_rel);
        } else {
            snprintf(why, n, "%s", err.message);
        }
        mt_image_destroy(&img);
        mt_image_destroy(&var);
    } else {
        snprintf(why, n, "%s", err.message);
    }
    mt_scene_destroy(s);
    mt_image_destroy(&gold);
    mt_image_destroy(&gvar);
    return r;
}

/* text with the first occurrence of `from` replaced by `to` */
static char *replace(const char *text, const char *from, const char *to)
{
    const char *p = strstr(text, from);
    size_t a, b, c;
    char *out;
    if (!p) return NULL;
    a = (size_t)(p - text);
    b = strlen(to);
    c = strlen(p + strlen(from));
    out = malloc(a + b + c + 1);
    if (!out) return NULL;
    memcpy(out, text, a);
    memcpy(out + a, to, b);
    memcpy(out + a + b, p + strlen(from), c + 1);
    return out;
}

int main(void)
{
    char dir[] = "/tmp/materia-golden-XXXXXX", merl[600], why[512], name[128];
    size_t i;
    mt_error err;
    mt_merl_options mo = {MT_MODE_PBRT_V2, MT_MERL_AT_CORNER, NULL, NULL, NULL};
    char *merl_text;
    if (!t_has_format("exr", "golden images (golden/*.exr)")) return t_status();
    merl_text = read_text("golden/plastic-merl.txt");
    if (!mkdtemp(dir) || !merl_text) {
        t_fail("golden images", "no temporary directory or no golden/plastic-merl.txt (run from the source tree)");
        return t_status();
    }
    /* the measured scene's MERL table, as tools/make-golden.sh makes it */
    snprintf(merl, sizeof merl, "%s/plastic.merl", dir);
    mt_error_clear(&err);
    if (mt_merl_write_statements(merl_text, &mo, merl, &err) != MT_OK)
        t_fail("golden images: MERL table", "%s", err.message);
    nscenes = t_material_kinds(0, scenes, T_MAX_KINDS);
    ndipole = t_material_kinds(1, dipole_scenes, T_MAX_KINDS);
    for (i = 0; i < (size_t)nscenes; ++i) {
        char path[256];
        char *text;
        int r;
        snprintf(path, sizeof path, "golden/scenes/%s.pbrt", scenes[i]);
        text = read_text(path);
        snprintf(name, sizeof name, "golden %s: honest re-render at %d spp passes the z-test", scenes[i], TEST_SPP);
        if (!text) {
            t_fail(name, "cannot read %s", path);
            continue;
        }
        r = render_and_compare(scenes[i], text, dir, MT_MODE_PBRT_V2, TEST_SEED, why, sizeof why);
        t_check(r == 1, name, "%s", why);
        if (r == 1) printf("  %s: %s\n", scenes[i], why);
        free(text);
    }
    /* power: changes the check must see */
    {
        static const struct {
            const char *scene, *from, *to, *what;
            mt_mode mode;
        } wrong[] = {
            {"matte", "[0.7 0.3 0.2]", "[0.63 0.27 0.18]", "Kd 10% darker", MT_MODE_PBRT_V2},
            {"plastic", "[0.4 0.4 0.4]", "[0.44 0.44 0.44]", "Ks 10% brighter", MT_MODE_PBRT_V2},
            {"plastic", "", "", "corrected mode (the coat's Fresnel term, erratum dielectric-side)", MT_MODE_CORRECTED},
            {"metal", "[0.02]", "[0.04]", "roughness doubled", MT_MODE_PBRT_V2},
        };
        for (i = 0; i < sizeof wrong / sizeof wrong[0]; ++i) {
            char path[256], *text, *changed;
            int r;
            snprintf(path, sizeof path, "golden/scenes/%s.pbrt", wrong[i].scene);
            text = read_text(path);
            changed = text && wrong[i].from[0] ? replace(text, wrong[i].from, wrong[i].to) : text;
            snprintf(name, sizeof name, "golden %s: a wrong change is caught (%s)", wrong[i].scene, wrong[i].what);
            if (!changed) {
                t_fail(name, "cannot prepare the changed scene");
            } else {
                r = render_and_compare(wrong[i].scene, changed, dir, wrong[i].mode, TEST_SEED, why, sizeof why);
                t_check(r == 0, name, "the changed render passed: %s", why);
                if (r == 0) printf("  %s\n", why);
            }
            if (changed != text) free(changed);
            free(text);
        }
    }
    /* the dipole scenes: an honest re-render passes, planted errors fail */
    for (i = 0; i < (size_t)ndipole; ++i) {
        static const struct {
            const char *from, *to, *what;
        } wrong[] = {{"\"rgb sigma_a\" [0.1 0.25 0.5]", "\"rgb sigma_a\" [0.11 0.275 0.55]", "sigma_a 10% high"},
                     {"\"float index\" [1.3]", "\"float index\" [1.2]", "index 1.2 instead of 1.3"},
                     {"\"float maxerror\" [0.05]", "\"float maxerror\" [0.5]", "maxerror ten times larger"}};
        char path[256], *text;
        golden_stats gs;
        size_t k;
        int r;
        snprintf(path, sizeof path, "golden/scenes/%s.pbrt", dipole_scenes[i]);
        text = read_text(path);
        snprintf(name, sizeof name, "golden %s: honest re-render (another seed) passes the t-tests of its statistics",
                 dipole_scenes[i]);
        if (!text || !read_stats(dipole_scenes[i], &gs)) {
            t_fail(name, "cannot read %s or golden/%s.stats.txt", path, dipole_scenes[i]);
            free(text);
            continue;
        }
        r = dipole_compare(dipole_scenes[i], text, "golden/scenes", MT_MODE_PBRT_V2, 1000 + TEST_SEED, &gs, why, sizeof why);
        t_check(r == 1, name, "%s", why);
        if (r == 1) printf("  %s: %s\n", dipole_scenes[i], why);
        for (k = 0; k < sizeof wrong / sizeof wrong[0]; ++k) {
            char *changed = replace(text, wrong[k].from, wrong[k].to);
            if (!changed) continue; /* not a parameter of this scene */
            snprintf(name, sizeof name, "golden %s: a wrong change is caught (%s)", dipole_scenes[i], wrong[k].what);
            r = dipole_compare(dipole_scenes[i], changed, "golden/scenes", MT_MODE_PBRT_V2, 1000 + TEST_SEED, &gs, why, sizeof why);
            t_check(r == 0, name, "the changed render passed: %s", why);
            if (r == 0) printf("  %s\n", why);
            free(changed);
        }
        free(gs.v);
        free(text);
    }
    remove(merl);
    rmdir(dir);
    free(merl_text);
    return t_status();
}
