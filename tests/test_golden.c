/*
 * Golden images (golden/): each material's scene of golden/scenes/ rendered
 * at a low sample count and compared with its golden image, rendered by
 * materia at 4096 samples per pixel with its per-pixel variance of the mean
 * (tools/make-golden.sh, `make golden`). The comparison is statistical, as
 * Mitsuba 3's render tests are: a z-test of each 4x4 block and channel
 * against the golden mean with both variances, the Sidak correction over all
 * of them at significance 0.01 (materia/imgcmp.h). An honest re-render (a
 * different seed from the golden one) must pass; the test also proves the
 * check has power: a 10% change of a material's colour, and corrected mode
 * on a plastic coat (its Fresnel term differs), must fail.
 */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "support/check.h"
#include "materia/imgcmp.h"
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

static const char *const scenes[] = T_MATERIAL_SCENES;

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
        mt_image_free(&img);
        mt_image_free(&var);
    } else {
        snprintf(why, n, "%s", err.message);
    }
    mt_scene_destroy(s);
    mt_image_free(&gold);
    mt_image_free(&gvar);
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
    char *merl_text = read_text("golden/plastic-merl.txt");
    if (!mkdtemp(dir) || !merl_text) {
        t_fail("golden images", "no temporary directory or no golden/plastic-merl.txt (run from the source tree)");
        return t_status();
    }
    /* the measured scene's MERL table, as tools/make-golden.sh makes it */
    snprintf(merl, sizeof merl, "%s/plastic.merl", dir);
    mt_error_clear(&err);
    if (mt_merl_write_statements(merl_text, &mo, merl, &err) != MT_OK)
        t_fail("golden images: MERL table", "%s", err.message);
    for (i = 0; i < sizeof scenes / sizeof scenes[0]; ++i) {
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
    remove(merl);
    rmdir(dir);
    free(merl_text);
    return t_status();
}
