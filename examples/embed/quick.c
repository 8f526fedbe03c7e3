/* The README's program: a plastic from pbrt-v2's text, evaluated and sampled. */
#include <stdio.h>
#include <materia.h>

int main(void)
{
    mt_error err = MT_ERROR_INIT;
    mt_material *m = mt_material_from_text("Material \"plastic\" \"rgb Kd\" [0.5 0.5 0.5]", NULL, &err);
    mt_arena *arena = mt_arena_create(0);                  /* one per thread */
    mt_diffgeom dg = mt_diffgeom_default();                /* your shading point: n = +z, uv = (0.5, 0.5) */
    mt_bsdf *bsdf = m ? mt_material_get_bsdf(m, &dg, &dg, arena, &err) : NULL;
    mt_vec3 wo = mt_v3(0, 0.6f, 0.8f), wi = mt_v3(0, -0.6f, 0.8f); /* world, away from the surface */
    char msg[1024];
    if (!bsdf) return fprintf(stderr, "%s\n", mt_error_format(&err, msg, sizeof msg)), 1;
    mt_rgb f = mt_bsdf_f(bsdf, wo, wi, MT_BSDF_ALL);
    mt_bsdf_sample s = mt_bsdf_sample_f(bsdf, wo, 0.25f, 0.3f, 0.6f, MT_BSDF_ALL); /* 3 uniform numbers */
    printf("f = %.5f, sampled wi = (%.4f %.4f %.4f) with pdf %.5f\n", f.c[0], s.wi.x, s.wi.y, s.wi.z, s.pdf);
    mt_arena_reset(arena);                                 /* once per shading point: no malloc */
    mt_arena_destroy(arena);
    mt_material_destroy(m);
    return 0;
}
