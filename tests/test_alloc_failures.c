/*
 * Allocation-failure injection (mt_alloc_fail_after) through the library's
 * largest paths: loading a scene that creates every material and texture
 * kind (an image map and measured data among them, read from files), a
 * whole tiny render of it, and a query session. Every allocation fails in
 * turn: each attempt must fail with an out-of-memory error (the render and
 * the loader return MT_ERR_NOMEM; the query session answers "error ... out
 * of memory" at the first answer that differs), nothing may crash, and
 * under ASan nothing may leak (LeakSanitizer checks at exit). The caches
 * are cleared before each attempt so that their loads fail in turn too.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia/tools/alloc.h"
#include "materia/image.h"
#include "materia/measured.h"
#include "materia/mipmap.h"
#include "materia/tools/query.h"
#include "materia/render.h"
#include "support/check.h"
#include "support/tfiles.h"

/* Every material on a shape of its own, every texture kind used. */
static const char *const scene_text =
    "LookAt 0 -6 2  0 0 0  0 0 1\n"
    "Camera \"perspective\" \"float fov\" [50]\n"
    "Film \"image\" \"integer xresolution\" [4] \"integer yresolution\" [3]\n"
    "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [1]\n"
    "SurfaceIntegrator \"path\" \"integer maxdepth\" [2]\n"
    "WorldBegin\n"
    "LightSource \"distant\" \"point from\" [0 0 10] \"point to\" [0 0 0]\n"
    "LightSource \"infinite\" \"rgb L\" [0.2 0.2 0.2]\n"
    "AttributeBegin AreaLightSource \"diffuse\" \"rgb L\" [2 2 2]\n"
    "  Shape \"disk\" \"float radius\" [0.5] AttributeEnd\n"
    "Texture \"c\" \"color\" \"checkerboard\" \"float uscale\" [4] \"float vscale\" [4]\n"
    "Texture \"c3\" \"float\" \"checkerboard\" \"integer dimension\" [3]\n"
    "Texture \"f\" \"float\" \"fbm\"\n"
    "Texture \"w\" \"float\" \"wrinkled\"\n"
    "Texture \"wi\" \"float\" \"windy\"\n"
    "Texture \"m\" \"color\" \"marble\"\n"
    "Texture \"d\" \"color\" \"dots\"\n"
    "Texture \"b\" \"float\" \"bilerp\"\n"
    "Texture \"u\" \"color\" \"uv\" \"string mapping\" \"cylindrical\"\n"
    "Texture \"k\" \"float\" \"constant\" \"float value\" [0.3]\n"
    "Texture \"s\" \"color\" \"scale\" \"texture tex1\" \"c\" \"texture tex2\" \"m\"\n"
    "Texture \"x\" \"color\" \"mix\" \"texture tex1\" \"s\" \"texture tex2\" \"d\" \"texture amount\" \"f\"\n"
    "Texture \"im\" \"color\" \"imagemap\" \"string filename\" \"tex.png\"\n"
    "MakeNamedMaterial \"a\" \"string type\" \"matte\" \"texture Kd\" \"im\"\n"
    "MakeNamedMaterial \"g\" \"string type\" \"glass\"\n"
    "Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"g\" \"texture amount\" \"c\"\n"
    "Shape \"sphere\" \"float radius\" [0.3] \"float zmax\" [0.1]\n"
    "Material \"matte\" \"texture sigma\" \"c3\"\n"
    "Shape \"sphere\" \"float radius\" [0.3]\n"
    "Material \"plastic\" \"texture Kd\" \"x\" \"texture bumpmap\" \"w\"\n"
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point P\" [-3 -3 -1 3 -3 -1 3 3 -1 -3 3 -1]\n"
    "  \"float uv\" [0 0 1 0 1 1 0 1]\n"
    "Material \"metal\" \"texture roughness\" \"b\"\n"
    "Shape \"loopsubdiv\" \"integer nlevels\" [1] \"integer indices\" [0 1 2 0 2 3 0 3 1 1 3 2]\n"
    "  \"point P\" [1 0 1 2 0 0 1 1 0 1 -1 0]\n"
    "Material \"shinymetal\" \"texture Kr\" \"u\"\n"
    "Shape \"cylinder\" \"float radius\" [0.2]\n"
    "Material \"mirror\"\n"
    "Shape \"sphere\" \"float radius\" [0.1]\n"
    "Material \"substrate\" \"texture uroughness\" \"wi\"\n"
    "Shape \"sphere\" \"float radius\" [0.2] \"float zmin\" [-0.1]\n"
    "Material \"translucent\" \"texture Kd\" \"c\"\n"
    "Shape \"disk\" \"float radius\" [0.1]\n"
    "Material \"uber\" \"texture opacity\" \"s\"\n"
    "Shape \"sphere\" \"float radius\" [0.15]\n"
    "Material \"measured\" \"string filename\" \"data.brdf\"\n"
    "Shape \"sphere\" \"float radius\" [0.25]\n"
    "Material \"subsurface\" \"string name\" \"Ketchup\"\n"
    "Shape \"sphere\" \"float radius\" [0.05]\n"
    "Material \"kdsubsurface\" \"texture Kd\" \"c\"\n"
    "Shape \"sphere\" \"float radius\" [0.07]\n"
    "Material \"matte\" \"texture sigma\" \"k\"\n"
    "Shape \"sphere\" \"float radius\" [0.09]\n"
    "WorldEnd\n";

static void clear_caches(void)
{
    mt_mipmap_cache_clear();
    mt_measured_cache_clear();
}

static int write_inputs(void)
{
    mt_image img;
    int i;
    char brdf[2048];
    size_t n = 0;
    if (mt_image_create(&img, 4, 4, 3, NULL) != MT_OK) return 0;
    for (i = 0; i < 48; ++i) img.data[i] = (float)(i % 5) / 4.f;
    i = mt_image_write(t_tmp_path("tex.png"), &img, NULL, 0, NULL) == MT_OK;
    mt_image_destroy(&img);
    n += (size_t)snprintf(brdf, sizeof brdf, "2\n450 650\n");
    for (i = 0; i < 20 && n < sizeof brdf - 64; ++i)
        n += (size_t)snprintf(brdf + n, sizeof brdf - n, "%.3f %.3f %.3f %.3f %.3f %.3f\n",
                              0.07 * i, 0.05 * i, 1.4 - 0.06 * i, 0.1 * i, 0.2 + 0.01 * i, 0.5);
    return i && t_write_file("data.brdf", brdf, n) != NULL;
}

static void test_scene_load(const char *dir)
{
    mt_render_options o;
    long n, before;
    int runs = 0, wrong = 0, recovered = 0, ok = 0;
    mt_render_options_default(&o);
    for (n = 0; n < 100000; ++n) {
        mt_error err;
        mt_scene *s;
        clear_caches();
        mt_error_clear(&err);
        mt_alloc_fail_after(n);
        before = (long)mt_alloc_count();
        s = mt_scene_load_string(scene_text, "alloc.pbrt", dir, &o, &err);
        mt_alloc_fail_after(-1);
        if ((long)mt_alloc_count() - before <= n) { /* nothing failed: the end */
            ok = s != NULL;
            mt_scene_destroy(s);
            break;
        }
        if (s) { /* a failure made good: the scene must be whole */
            recovered++;
            mt_scene_destroy(s);
            continue;
        }
        runs++;
        if (err.status != MT_ERR_NOMEM) {
            if (wrong++ < 5) printf("  allocation %ld: status %d: %s\n", n, (int)err.status, err.message);
        }
    }
    clear_caches();
    t_check(n < 100000 && ok && runs > 100 && wrong == 0,
            "scene loading (every material and texture kind): each of the allocations failing "
            "in turn is an out-of-memory error",
            "%d attempts, %d with another error", runs, wrong);
    printf("  scene loading: %d allocations, each made to fail (%d made good)\n", runs, recovered);
}

static void test_render(const char *dir)
{
    mt_render_options o;
    mt_error err;
    mt_scene *s;
    mt_image want, img, var;
    long n;
    int runs = 0, wrong = 0, same = 0;
    mt_render_options_default(&o);
    o.threads = 1; /* the injector counts one thread's allocations */
    mt_error_clear(&err);
    s = mt_scene_load_string(scene_text, "alloc.pbrt", dir, &o, &err);
    if (!t_check(s != NULL, "render under allocation failures: the scene loads", "%s", err.message))
        return;
    if (!t_check(mt_scene_render(s, &o, &want, NULL, NULL, &err) == MT_OK,
                 "render under allocation failures: the scene renders", "%s", err.message)) {
        mt_scene_destroy(s);
        return;
    }
    for (n = 0; n < 100000; ++n) {
        mt_status st;
        mt_error_clear(&err);
        mt_alloc_fail_after(n);
        st = mt_scene_render(s, &o, &img, &var, NULL, &err);
        mt_alloc_fail_after(-1);
        if (st == MT_OK) {
            same = img.width == want.width && img.height == want.height &&
                   memcmp(img.data, want.data, sizeof(float) * 3 * (size_t)img.width * (size_t)img.height) == 0;
            mt_image_destroy(&img);
            mt_image_destroy(&var);
            break;
        }
        runs++;
        if (st != MT_ERR_NOMEM || img.data || var.data) {
            if (wrong++ < 5) printf("  allocation %ld: status %d: %s\n", n, (int)st, err.message);
        }
    }
    t_check(n < 100000 && runs > 5 && wrong == 0 && same,
            "a whole render: each allocation failing in turn is an out-of-memory error, then the "
            "same image",
            "%d attempts, %d wrong, image %s", runs, wrong, same ? "the same" : "different");
    printf("  render: %d allocations, each made to fail\n", runs);
    mt_image_destroy(&want);
    mt_scene_destroy(s);
    clear_caches();
}

static const char *const query_lines[] = {
    "Texture \"c\" \"color\" \"checkerboard\" \"float uscale\" [4] \"float vscale\" [4]",
    "Texture \"im\" \"color\" \"imagemap\" \"string filename\" \"tex.png\"",
    "Material \"plastic\" \"texture Kd\" \"c\" \"float roughness\" [0.05]",
    "eval 0 0.6 0.8 0 -0.6 0.8",
    "sample 0 0.6 0.8 0.3 0.5 0.5",
    "MakeNamedMaterial \"n\" \"string type\" \"matte\" \"texture Kd\" \"im\"",
    "Material \"mix\" \"string namedmaterial1\" \"n\" \"string namedmaterial2\" \"n\"",
    "at uv 0.1 0.1",
    "texture \"im\"",
    "eval 0 0 1 0 0.6 0.8",
    "Material \"measured\" \"string filename\" \"data.brdf\"",
    "eval 0 0 1 0 0.6 0.8",
    "Material \"subsurface\" \"string name\" \"Ketchup\"",
    "bssrdf",
    "Material \"glass\" \"float index\" [",
    "1.33 ]",
    "sample 0 0.6 0.8 0.9 0.5 0.5",
    "shading",
};
#define NQ (int)(sizeof query_lines / sizeof query_lines[0])

/* The session's answers, one per line ("" for none); 0 when the session
 * cannot be created. */
static int session(const char *dir, char answers[][512], mt_error *err)
{
    mt_query *q = mt_query_create(dir, err);
    int i;
    if (!q) return 0;
    for (i = 0; i < NQ; ++i)
        if (!mt_query_line(q, query_lines[i], answers[i], 512)) answers[i][0] = '\0';
    mt_query_destroy(q);
    return 1;
}

static void test_query(const char *dir)
{
    static char want[NQ][512], got[NQ][512];
    mt_error err;
    long n, before;
    int runs = 0, wrong = 0, recovered = 0, i;
    clear_caches();
    if (!t_check(session(dir, want, &err), "query under allocation failures: a session", "%s",
                 err.message))
        return;
    for (n = 0; n < 100000; ++n) {
        int ok;
        clear_caches();
        mt_error_clear(&err);
        before = (long)mt_alloc_count();
        mt_alloc_fail_after(n);
        ok = session(dir, got, &err);
        mt_alloc_fail_after(-1);
        if ((long)mt_alloc_count() - before <= n) break; /* nothing failed: the end */
        runs++;
        if (!ok) {
            if (err.status != MT_ERR_NOMEM && wrong++ < 5)
                printf("  allocation %ld: session: %s\n", n, err.message);
            continue;
        }
        for (i = 0; i < NQ && strcmp(got[i], want[i]) == 0; ++i) {
        }
        /* the first answer that differs reports the failure; none differs
         * when the failure was made good (mt_parse_incomplete, asked
         * whether a statement goes on, takes a failed look for a complete
         * statement, which is then parsed again) */
        if (i == NQ) {
            recovered++;
            continue;
        }
        if (!strstr(got[i], "out of memory")) {
            if (wrong++ < 5)
                printf("  allocation %ld: line %d: \"%s\" (wanted \"%s\")\n", n, i + 1,
                       i < NQ ? got[i] : "", i < NQ ? want[i] : "");
        }
    }
    clear_caches();
    t_check(n < 100000 && runs > 50 && wrong == 0,
            "a query session: each allocation failing in turn answers \"error ... out of memory\" "
            "at the first answer it changes",
            "%d attempts, %d wrong", runs, wrong);
    printf("  query session: %d allocations, each made to fail (%d made good, the same answers)\n",
           runs, recovered);
}

int main(void)
{
    const char *dir = t_tmpdir_create("alloc-failures");
    char d[512];
    if (!dir) {
        t_fail("temporary directory", "cannot create one");
        return t_status();
    }
    snprintf(d, sizeof d, "%s", dir);
    /* the scene's image map is a PNG file */
    if (t_has_format("png", "allocation failures (the scene reads a PNG image map)") &&
        t_check(write_inputs(), "allocation failures: the image and .brdf inputs", "not written")) {
        test_scene_load(d);
        test_render(d);
        test_query(d);
    }
    t_tmpdir_remove();
    return t_status();
}
