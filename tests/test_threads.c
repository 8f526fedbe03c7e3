/*
 * Thread safety as the headers state it: 8 threads share materials (every
 * type), textures, an image, measured data and a scene, each with its own
 * arena, and create at the same time what the library caches or
 * initializes once (the first metal's copper spectrum, an image map's
 * pyramid, a measured file, materials from text with no state). Every
 * thread's answers must equal the single-threaded ones, bit for bit.
 *
 * make check runs it as a plain test; make check-tsan builds the library and
 * this test with clang's ThreadSanitizer (build/tsan), which reports any data
 * race among them.
 */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/tfiles.h"

#define NTHREADS 8
#define NPOINTS 24

/* Shared, built before the threads start. */
static const char *const shared_text[] = {
    "Material \"matte\" \"float sigma\" 20",
    "Material \"plastic\" \"texture Kd\" \"checks\" \"float roughness\" 0.05",
    "Material \"glass\" \"float index\" 1.4",
    "Material \"mirror\"",
    "Material \"shinymetal\"",
    "Material \"substrate\" \"texture bumpmap\" \"bumps\"",
    "Material \"translucent\"",
    "Material \"uber\" \"rgb opacity\" [0.5 0.5 0.5]",
    "Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\"",
    "Material \"subsurface\" \"string name\" \"Ketchup\"",
    "Material \"kdsubsurface\" \"texture Kd\" \"checks\"",
};
#define NSHARED (int)(sizeof shared_text / sizeof shared_text[0])
/* Made first inside the threads, all at once (setup fills in the files):
 * metal converts copper's spectrum once per process, a measured file and an
 * image map are read once per process and cached. */
#define NFIRST 3
static mt_material *shared[NSHARED];
static mt_texture *checks, *image_map;
static mt_scene *scene;
static char first[NFIRST][1024];
static char imagemap_text[1024], brdf_path[512];

typedef struct answers {
    mt_rgb f[NSHARED + NFIRST][NPOINTS];
    mt_bsdf_sample s[NSHARED + NFIRST][NPOINTS];
    mt_rgb tex[NPOINTS];
    mt_rgb measured[NPOINTS];
    mt_image render;
    int failed;
    char why[512];
} answers;

static answers results[NTHREADS + 1]; /* [NTHREADS]: the single-threaded reference */

static mt_diffgeom point(int i)
{
    mt_diffgeom dg = mt_diffgeom_default();
    dg.u = (mt_real)((i * 7 % NPOINTS) + 0.5) / NPOINTS;
    dg.v = (mt_real)((i * 11 % NPOINTS) + 0.5) / NPOINTS;
    dg.p = mt_v3(dg.u, dg.v, 0);
    dg.dudx = dg.dvdy = 0.01f;
    dg.dpdx = mt_v3(0.01f, 0, 0);
    dg.dpdy = mt_v3(0, 0.01f, 0);
    return dg;
}

static void evaluate(const mt_material *m, mt_arena *a, mt_rgb *f, mt_bsdf_sample *s)
{
    int i;
    for (i = 0; i < NPOINTS; ++i) {
        mt_diffgeom dg = point(i);
        mt_bsdf *b = mt_material_get_bsdf(m, &dg, &dg, a, NULL);
        mt_vec3 wo = mt_v3_normalize(mt_v3(0.3f, (mt_real)i / NPOINTS - 0.5f, 0.8f));
        mt_vec3 wi = mt_v3_normalize(mt_v3(-0.2f, 0.4f, (mt_real)(i % 5) / 5 - 0.3f));
        f[i] = b ? mt_bsdf_f(b, wo, wi, MT_BSDF_ALL) : mt_rgb_gray(-1);
        if (b) s[i] = mt_bsdf_sample_f(b, wo, (mt_real)i / NPOINTS, 0.37f, 0.61f, MT_BSDF_ALL);
        mt_arena_reset(a);
    }
}

static void fail(answers *r, const char *fmt, const char *what)
{
    if (r->failed++) return;
    snprintf(r->why, sizeof r->why, fmt, what);
}

/* What every thread does; the reference run (r = &results[NTHREADS]) does
 * the same alone after the threads. */
static void work(answers *r, int render)
{
    mt_arena *a = mt_arena_create(0);
    mt_material *made[NFIRST];
    mt_measured *md;
    mt_texture *t;
    int i, k;
    /* what is made once per process: made by every thread at once */
    for (k = 0; k < NFIRST; ++k) {
        made[k] = mt_material_from_text(first[k], NULL, NULL);
        if (!made[k]) fail(r, "%s not made", first[k]);
    }
    t = mt_texture_from_text(imagemap_text, NULL, NULL);
    md = mt_measured_load(brdf_path, NULL);
    if (!t || !md) fail(r, "%s", "the image map or the measured data not made");
    for (k = 0; k < NSHARED; ++k) {
        mt_material *m = mt_material_retain(shared[k]); /* reference counts from every thread */
        evaluate(m, a, r->f[k], r->s[k]);
        mt_material_destroy(m);
    }
    for (k = 0; k < NFIRST; ++k)
        if (made[k]) evaluate(made[k], a, r->f[NSHARED + k], r->s[NSHARED + k]);
    for (i = 0; i < NPOINTS; ++i) {
        mt_diffgeom dg = point(i);
        mt_vec3 wo = mt_v3(0, 0.6f, 0.8f), wi = mt_v3(0.6f, 0, 0.8f);
        r->tex[i] = t ? mt_texture_eval_rgb(t, &dg) : mt_rgb_gray(-1);
        r->tex[i] = mt_rgb_add(r->tex[i], mt_texture_eval_rgb(image_map, &dg));
        r->tex[i] = mt_rgb_add(r->tex[i], mt_texture_eval_rgb(checks, &dg));
        if (md) {
            mt_bxdf *x = mt_irregular_isotropic_brdf_create(a, MT_MODE_PBRT_V2, md, NULL);
            r->measured[i] = x ? mt_bxdf_f(x, wo, mt_v3_normalize(mt_v3(wi.x, (mt_real)i / NPOINTS, wi.z)))
                               : mt_rgb_gray(-1);
        }
    }
    if (render) {
        mt_render_options o;
        mt_render_options_default(&o);
        o.threads = 2;
        if (mt_scene_render(scene, &o, &r->render, NULL, NULL, NULL) != MT_OK) fail(r, "%s", "render failed");
    }
    for (k = 0; k < NFIRST; ++k) mt_material_destroy(made[k]);
    mt_texture_destroy(t);
    mt_measured_destroy(md);
    mt_arena_destroy(a);
}

static void *thread_main(void *arg)
{
    int id = (int)(size_t)arg;
    work(&results[id], id < 2); /* two threads render the one scene at once */
    return NULL;
}

static int same_rgb(const mt_rgb *a, const mt_rgb *b, int n)
{
    return memcmp(a, b, (size_t)n * sizeof *a) == 0;
}

static int same_samples(const mt_bsdf_sample *a, const mt_bsdf_sample *b)
{
    int i;
    for (i = 0; i < NPOINTS; ++i)
        if (memcmp(&a[i].wi, &b[i].wi, sizeof a[i].wi) || memcmp(&a[i].f, &b[i].f, sizeof a[i].f) ||
            memcmp(&a[i].pdf, &b[i].pdf, sizeof a[i].pdf) || a[i].type != b[i].type)
            return 0;
    return 1;
}

static int setup(void)
{
    mt_error err = MT_ERROR_INIT;
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_image img;
    mt_render_options o;
    char brdf[8192];
    size_t n = 0;
    int i, k;
    if (!s || !t_tmpdir_create("threads")) return 0;
    /* an 8 x 8 image for the image map, and an irregular measured BRDF */
    if (mt_image_create(&img, 8, 8, 3, &err) != MT_OK) return 0;
    for (i = 0; i < 8 * 8 * 3; ++i) img.data[i] = (float)((i * 37) % 11) / 10;
    mt_image_write(t_tmp_path("map.pfm"), &img, NULL, 0, &err);
    mt_image_destroy(&img);
    n += (size_t)snprintf(brdf + n, sizeof brdf - n, "3\n450 550 650\n");
    for (i = 0; i < 60; ++i)
        n += (size_t)snprintf(brdf + n, sizeof brdf - n, "%g %g %g %g %g %g %g\n", 0.02 + 0.025 * i,
                              0.1 * (i % 7), 0.05 + 0.02 * i, 0.3 * (i % 5), 0.1 + 0.01 * i, 0.2, 0.05 * (i % 3));
    snprintf(brdf_path, sizeof brdf_path, "%s", t_write_file("data.brdf", brdf, (size_t)-1));
    snprintf(imagemap_text, sizeof imagemap_text,
             "Texture \"map\" \"color\" \"imagemap\" \"string filename\" \"%s\" \"bool trilinear\" \"false\"",
             t_tmp_path("map.pfm"));
    snprintf(first[0], sizeof first[0], "Material \"metal\"");
    snprintf(first[1], sizeof first[1], "Material \"measured\" \"string filename\" \"%s\"", brdf_path);
    snprintf(first[2], sizeof first[2],
             "Texture \"map\" \"color\" \"imagemap\" \"string filename\" \"%s\"\n"
             "Texture \"half\" \"color\" \"scale\" \"texture tex1\" \"map\" \"color tex2\" [0.5 0.5 0.5]\n"
             "Material \"matte\" \"texture Kd\" \"half\"", t_tmp_path("map.pfm"));
    if (mt_state_apply_text(s, "Texture \"checks\" \"color\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4\n"
                               "Texture \"bumps\" \"float\" \"fbm\" \"integer octaves\" 4\n"
                               "MakeNamedMaterial \"a\" \"string type\" \"plastic\"\n"
                               "MakeNamedMaterial \"b\" \"string type\" \"translucent\"", &err) != MT_OK)
        return t_check(0, "threads: setup", "%s", err.message);
    for (k = 0; k < NSHARED; ++k)
        if (!(shared[k] = mt_material_from_text(shared_text[k], s, &err)))
            return t_check(0, "threads: setup", "%s: %s", shared_text[k], err.message);
    checks = mt_texture_retain(mt_texture_table_get(mt_state_textures(s), "checks", 0));
    image_map = mt_texture_from_text("Texture \"m\" \"color\" \"marble\" \"float scale\" 3", NULL, &err);
    mt_render_options_default(&o);
    scene = mt_scene_load_string("Film \"image\" \"integer xresolution\" [12] \"integer yresolution\" [8]\n"
                                 "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [4]\n"
                                 "WorldBegin\nLightSource \"point\" \"point from\" [0 2 0]\n"
                                 "Material \"plastic\"\nTranslate 0 0 4\nShape \"sphere\"\nWorldEnd\n",
                                 NULL, NULL, &o, &err);
    mt_state_destroy(s);
    return checks && image_map && scene;
}

int main(void)
{
    pthread_t th[NTHREADS];
    answers *ref = &results[NTHREADS];
    int i, k, bad = 0;
    if (!setup()) {
        t_fail("threads: setup", "the shared objects could not be made");
        return t_status();
    }
    for (i = 0; i < NTHREADS; ++i) pthread_create(&th[i], NULL, thread_main, (void *)(size_t)i);
    for (i = 0; i < NTHREADS; ++i) pthread_join(th[i], NULL);
    work(ref, 1);
    t_check(!ref->failed, "threads: the single-threaded run", "%s", ref->why);
    for (i = 0; i < NTHREADS; ++i) {
        answers *r = &results[i];
        if (r->failed) {
            t_fail("threads: each thread's work", "thread %d: %s", i, r->why);
            bad++;
            continue;
        }
        for (k = 0; k < NSHARED + NFIRST; ++k)
            if (!same_rgb(r->f[k], ref->f[k], NPOINTS) || !same_samples(r->s[k], ref->s[k])) {
                t_fail("threads: materials", "thread %d: %s differs from the single-threaded answers", i,
                       k < NSHARED ? shared_text[k] : first[k - NSHARED]);
                bad++;
            }
        if (!same_rgb(r->tex, ref->tex, NPOINTS) || !same_rgb(r->measured, ref->measured, NPOINTS)) {
            t_fail("threads: textures and measured data", "thread %d differs from the single-threaded answers", i);
            bad++;
        }
        if (i < 2 && (r->render.width != ref->render.width ||
                      memcmp(r->render.data, ref->render.data,
                             (size_t)ref->render.width * (size_t)ref->render.height * 3 * sizeof(float)))) {
            t_fail("threads: one scene rendered by two threads at once", "thread %d's image differs", i);
            bad++;
        }
    }
    t_check(bad == 0, "threads: 8 threads sharing materials, textures, images, measured data and a scene "
            "give the single-threaded answers", "%d differences", bad);
    for (i = 0; i <= NTHREADS; ++i) mt_image_destroy(&results[i].render);
    for (k = 0; k < NSHARED; ++k) mt_material_destroy(shared[k]);
    mt_texture_destroy(checks);
    mt_texture_destroy(image_map);
    mt_scene_destroy(scene);
    mt_mipmap_cache_clear();
    mt_measured_cache_clear();
    t_tmpdir_remove();
    return t_status();
}
