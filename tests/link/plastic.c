/* A plastic made from its kind's object and a parameter list
 * (mt_material_create_kind): links the plastic and what it builds, no other
 * material kind and no image library. */
#include <materia.h>
#include <stdio.h>

int main(void)
{
    mt_param p = mt_param_rgb("Kd", 0.5, 0.5, 0.5);
    mt_paramset *ps = mt_paramset_create();
    mt_texparams tp = {0};
    mt_arena *arena = mt_arena_create(0);
    mt_diffgeom dg = mt_diffgeom_default();
    mt_material *m;
    mt_bsdf *b;
    mt_error err;
    mt_rgb f;
    mt_error_clear(&err);
    if (!ps || mt_paramset_add(ps, &p, &err)) return 1;
    tp.material = ps;
    m = mt_material_create_kind(&mt_plastic_material, NULL, &tp, NULL, &err);
    if (!m || !(b = mt_material_get_bsdf(m, &dg, &dg, arena, &err))) return 1;
    f = mt_bsdf_f(b, mt_v3(0, 0.6f, 0.8f), mt_v3(0, -0.6f, 0.8f), MT_BSDF_ALL);
    printf("%.6f\n", (double)f.c[0]);
    mt_material_destroy(m);
    mt_paramset_destroy(ps);
    mt_arena_destroy(arena);
    return 0;
}
