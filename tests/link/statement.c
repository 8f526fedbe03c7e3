/* A material from a pbrt-v2 statement: the parser, the graphics state and
 * the material made from it. Reads no image file. */
#include <materia.h>
#include <stdio.h>

static mt_status apply(void *ctx, const mt_statement *st, mt_error *err)
{
    int handled = 0;
    return mt_state_apply((mt_state *)ctx, st, &handled, err);
}

int main(void)
{
    const char *text = "Texture \"c\" \"color\" \"checkerboard\" \"float uscale\" [4]\n"
                       "Material \"plastic\" \"texture Kd\" \"c\" \"float roughness\" [0.05]\n";
    mt_state *s = mt_state_create(MT_MODE_PBRT_V2);
    mt_arena *arena = mt_arena_create(0);
    mt_diffgeom dg = mt_diffgeom_default();
    mt_material *m;
    mt_bsdf *b;
    mt_error err;
    mt_rgb f;
    mt_error_clear(&err);
    if (!s || mt_parse_string(text, "statement", NULL, 1, NULL, apply, s, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    m = mt_material_from_state(s, NULL, &err);
    if (!m || !(b = mt_material_get_bsdf(m, &dg, &dg, arena, &err))) return 1;
    f = mt_bsdf_f(b, mt_v3(0, 0.6f, 0.8f), mt_v3(0, -0.6f, 0.8f), MT_BSDF_ALL);
    printf("%.6f\n", (double)f.c[0]);
    mt_material_destroy(m);
    mt_state_destroy(s);
    mt_arena_destroy(arena);
    return 0;
}
