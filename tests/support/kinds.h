/*
 * The registered material kinds for the tests that go over all of them
 * (golden images, pbrt-v2's renders): a header function, so that only the
 * tests that call it link the material registry.
 */
#ifndef MT_TEST_KINDS_H
#define MT_TEST_KINDS_H

#include "materia/material.h"

#define T_MAX_KINDS 64

/* The registered material kinds (mt_material_kind_at), in registry order:
 * those without a BSSRDF (bssrdf 0; a path tracer renders their scenes) or
 * with one (1; the dipole integrator's). Their names go to names[] (at most
 * max); returns how many. golden/scenes/ has a scene for each (test_registry
 * checks), ../shared/reference/scenes/ one for each of pbrt-v2's. */
static inline int t_material_kinds(int bssrdf, const char **names, int max)
{
    int i, n = 0;
    for (i = 0; i < mt_material_kind_count(); ++i) {
        const mt_material_kind *k = mt_material_kind_at(i);
        if (mt_material_kind_has_bssrdf(k) == bssrdf && n < max) names[n++] = mt_material_kind_name(k);
    }
    return n;
}

#endif
