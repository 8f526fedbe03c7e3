// A C++ program against materia's public headers: every header included (the
// umbrella), a BSDF built and evaluated, a query session driven, an error
// reported. It proves that the headers compile as C++ (extern "C" guards, no
// C-only constructs in the inline functions) and that a C++ link of
// libmateria finds the C symbols unmangled. Prints PASS/FAIL lines.
#include <materia_tools.h>

#include <cmath>
#include <cstdio>
#include <cstring>

static int failures = 0;

static void check(bool ok, const char *name, const char *why)
{
    if (ok) {
        std::printf("PASS %s\n", name);
    } else {
        std::printf("FAIL %s: %s\n", name, why);
        failures++;
    }
}

int main()
{
    check(std::strcmp(mt_version(), MT_VERSION) == 0, "c++ mt_version", mt_version());

    mt_arena *arena = mt_arena_create(0);
    mt_error err;
    mt_error_clear(&err);
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *bsdf = mt_bsdf_create(arena, MT_MODE_PBRT_V2, &dg, dg.n, 1, &err);
    mt_bxdf *lam = mt_lambertian_create(arena, MT_MODE_PBRT_V2, mt_rgb_gray(0.5f), &err);
    check(bsdf && lam && mt_bsdf_add(bsdf, lam, &err) == MT_OK, "c++ bsdf built", err.message);
    if (bsdf && lam) {
        // Lambertian: f = R / pi for any pair of directions above the surface
        mt_vec3 wo = mt_v3(0, mt_real(0.6), mt_real(0.8));
        mt_vec3 wi = mt_v3(0, mt_real(-0.6), mt_real(0.8));
        mt_rgb f = mt_bsdf_f(bsdf, wo, wi, MT_BSDF_ALL);
        double want = 0.5 / 3.14159265358979323846;
        char why[128];
        std::snprintf(why, sizeof why, "f = %.9g, want %.9g", double(f.c[0]), want);
        check(std::fabs(double(f.c[0]) - want) < 1e-6, "c++ lambertian f = R/pi", why);
    }
    mt_arena_destroy(arena);

    // the query protocol: an unknown material is an error answer naming it
    mt_query *q = mt_query_create(NULL, &err);
    check(q != NULL, "c++ query session", err.message);
    if (q) {
        char out[1024];
        int got = mt_query_line(q, "Material \"nosuch\"", out, sizeof out);
        check(got == 1 && std::strncmp(out, "error ", 6) == 0 && std::strstr(out, "nosuch"),
              "c++ query error answer", out);
        got = mt_query_line(q, "Material \"matte\"", out, sizeof out);
        check(got == 1 && std::strcmp(out, "ok") == 0, "c++ query statement", out);
        mt_query_destroy(q);
    }
    return failures ? 1 : 0;
}
