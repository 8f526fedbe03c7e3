/* Textures: one evaluated alone, one named in a state and used by a material. */
#include <stdio.h>
#include <materia.h>

int main(void)
{
    mt_error err = MT_ERROR_INIT;
    char msg[1024];
    mt_state *state = mt_state_create(MT_MODE_PBRT_V2); /* keeps named textures and materials */
    mt_texture *checks = mt_texture_from_text(
        "Texture \"checks\" \"color\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4", state, &err);
    const mt_param params[] = {mt_param_texture("Kd", "checks")};
    mt_material *m = checks ? mt_material_from_params("matte", params, 1, state, &err) : NULL;
    if (!m) {
        fprintf(stderr, "%s\n", mt_error_format(&err, msg, sizeof msg));
        return 1;
    }
    mt_arena *arena = mt_arena_create(0);
    for (int i = 0; i < 3; ++i) {
        mt_diffgeom dg = mt_diffgeom_default();
        dg.u = 0.1f + 0.2f * (float)i; /* the texture reads u, v (and p and the differentials) */
        dg.v = 0.1f;
        mt_rgb t = mt_texture_eval_rgb(checks, &dg);
        mt_bsdf *bsdf = mt_material_get_bsdf(m, &dg, &dg, arena, &err);
        mt_rgb f = mt_bsdf_f(bsdf, mt_v3(0, 0, 1), mt_v3(0, 0.6f, 0.8f), MT_BSDF_ALL);
        printf("u = %.1f: texture %.0f, matte f = %.5f\n", dg.u, t.c[0], f.c[0]);
        mt_arena_reset(arena); /* once per shading point: no malloc after the first */
    }
    mt_arena_destroy(arena);
    mt_material_destroy(m);
    mt_texture_destroy(checks);
    mt_state_destroy(state);
    return 0;
}
