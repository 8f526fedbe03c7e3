/* Evaluates measured data the fuzz targets read at a few direction pairs
 * through its BxDF (both modes), so that the lookup structures built from
 * hostile data are used, not only built. */
#ifndef MT_FUZZ_MEASURED_EVAL_H
#define MT_FUZZ_MEASURED_EVAL_H

#include "materia/arena.h"
#include "materia/measured.h"

static void fz_measured_eval(mt_measured *m)
{
    static const mt_real dirs[][6] = {{0, 0, 1, 0, 0, 1},           {0.6f, 0, 0.8f, -0.6f, 0, 0.8f},
                                      {0, 0.28f, 0.96f, 0.8f, 0, 0.6f}, {1, 0, 0, 0, 1, 0}};
    mt_arena *a;
    int i, k;
    if (!m) return;
    a = mt_arena_create(0);
    for (k = 0; a && k < 2; ++k) {
        mt_mode mode = k ? MT_MODE_CORRECTED : MT_MODE_PBRT_V2;
        mt_bxdf *b = mt_measured_kind_of(m) == MT_MEASURED_IRREGULAR
                         ? mt_irregular_isotropic_brdf_create(a, mode, m, NULL)
                         : mt_regular_halfangle_brdf_create(a, mode, m, NULL);
        for (i = 0; b && i < (int)(sizeof dirs / sizeof dirs[0]); ++i) {
            mt_rgb f = b->ops->f(b, mt_v3(dirs[i][0], dirs[i][1], dirs[i][2]),
                                 mt_v3(dirs[i][3], dirs[i][4], dirs[i][5]));
            (void)f;
        }
    }
    mt_arena_destroy(a);
}

#endif
