/* A Lambertian BSDF built by hand (the README's ten lines): links only the
 * arena, the BSDF and the Lambertian. */
#include <materia.h>
#include <stdio.h>

int main(void)
{
    mt_arena *arena = mt_arena_create(0);
    mt_error err;
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *bsdf;
    mt_rgb f;
    mt_error_clear(&err);
    bsdf = mt_bsdf_create(arena, MT_MODE_PBRT_V2, &dg, dg.n, 1, &err);
    if (!bsdf || mt_bsdf_add(bsdf, mt_lambertian_create(arena, MT_MODE_PBRT_V2, mt_rgb_gray(0.5f), &err), &err))
        return 1;
    f = mt_bsdf_f(bsdf, mt_v3(0, 0.6f, 0.8f), mt_v3(0, -0.6f, 0.8f), MT_BSDF_ALL);
    printf("%.6f\n", (double)f.c[0]);
    mt_arena_destroy(arena);
    return 0;
}
