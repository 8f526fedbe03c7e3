/* A material from pbrt-v2's statements, in one call. */
#include <stdio.h>
#include <materia.h>

int main(void)
{
    mt_error err = MT_ERROR_INIT;
    char msg[1024];
    mt_material *m = mt_material_from_text(
        "Material \"plastic\" \"rgb Kd\" [0.5 0.4 0.3] \"float roughness\" 0.05", NULL, &err);
    if (!m) {
        fprintf(stderr, "%s\n", mt_error_format(&err, msg, sizeof msg));
        return 1;
    }
    mt_arena *arena = mt_arena_create(0);
    mt_diffgeom dg = mt_diffgeom_default(); /* the shading point: pass your own */
    mt_bsdf *bsdf = mt_material_get_bsdf(m, &dg, &dg, arena, &err);
    mt_rgb f = mt_bsdf_f(bsdf, mt_v3(0, 0.6f, 0.8f), mt_v3(0, -0.6f, 0.8f), MT_BSDF_ALL);
    printf("plastic: f = %.5f %.5f %.5f\n", f.c[0], f.c[1], f.c[2]);

    /* a misspelt parameter is an error (or a warning: mt_state_set_warning) */
    if (!mt_material_from_text("Material \"plastic\" \"rgb Kdd\" [0.5 0.4 0.3]", NULL, &err))
        printf("error: %s\n", mt_error_format(&err, msg, sizeof msg));
    mt_arena_destroy(arena);
    mt_material_destroy(m);
    return 0;
}
