/*
 * pbrt-v2's Material::Bump (core/material.cpp): the displaced surface
 * P' = P + d N is differentiated by forward differences of d over du and dv
 * (half the screen-space footprint in u and v, 0.01 without differentials):
 *   dP'/du = dpdu + (d(u + du) - d(u)) / du N + d dN/du,  likewise v,
 * and the shading normal becomes their normalized cross product, flipped
 * with the shape's orientation and turned to the geometric normal's side.
 * The d dN/du term is what distinguishes the displaced surface's tangent
 * from a bumped plane's; MT_BUMP_DROP_DNDU omits it for studies.
 */
#include "materia/bump.h"
#include "textures/tex.h"

/* The normal pbrt-v2 gives the shifted evaluation point:
 * Normalize(Cross(dpdu, dpdv) + delta dndu) (no texture of pbrt-v2 reads it;
 * kept for textures that might). The shading normal where it is degenerate. */
static mt_vec3 shifted_normal(const mt_diffgeom *dgs, mt_vec3 dndu, mt_real delta)
{
    mt_vec3 n = mt_v3_add(mt_v3_cross(dgs->dpdu, dgs->dpdv), mt_v3_scale(dndu, delta));
    mt_real len = mt_v3_len(n);
    return len > 0 && mt_is_finite(len) ? mt_v3_scale(n, 1 / len) : dgs->n;
}

/* pbrt-v2: du = .5 (|dudx| + |dudy|), 0.01 when that is 0. */
static mt_real shift(mt_real dx, mt_real dy)
{
    mt_real d = (mt_real)0.5 * (mt_fabs(dx) + mt_fabs(dy));
    return d == 0 ? (mt_real)0.01 : d;
}

/* dpdu + (shifted - displace) / delta n (+ displace dndu). */
static mt_vec3 bumped_tangent(mt_vec3 dpdu, mt_vec3 n, mt_vec3 dndu, mt_real shifted,
                              mt_real displace, mt_real delta, int drop_dndu)
{
    mt_vec3 t = mt_v3_add(dpdu, mt_v3_scale(n, (shifted - displace) / delta));
    return drop_dndu ? t : mt_v3_add(t, mt_v3_scale(dndu, displace));
}

void mt_bump(const mt_texture *d, const mt_diffgeom *dg_geom, const mt_diffgeom *dgs,
             mt_diffgeom *dg_bump, unsigned options)
{
    mt_real du = shift(dgs->dudx, dgs->dudy), dv = shift(dgs->dvdx, dgs->dvdy);
    mt_real u_displace, v_displace, displace, len;
    mt_vec3 dpdu, dpdv, n;
    int drop = (options & MT_BUMP_DROP_DNDU) != 0;

    *dg_bump = *dgs;
    if (!d) return;
    displace = mt_texture_eval_float(d, dgs);
    if (mt__texture_is_constant(d)) {
        /* the shifted points would give the same value (shinymetal bumps
         * with a constant 0 at every hit): the same numbers, without
         * building them */
        u_displace = v_displace = displace;
    } else {
        mt_diffgeom e = *dgs;
        /* shift the evaluation point du along u */
        e.p = mt_v3_add(dgs->p, mt_v3_scale(dgs->dpdu, du));
        e.u = dgs->u + du;
        e.n = shifted_normal(dgs, dgs->dndu, du);
        u_displace = mt_texture_eval_float(d, &e);
        /* and dv along v */
        e.p = mt_v3_add(dgs->p, mt_v3_scale(dgs->dpdv, dv));
        e.u = dgs->u;
        e.v = dgs->v + dv;
        e.n = shifted_normal(dgs, dgs->dndv, dv);
        v_displace = mt_texture_eval_float(d, &e);
    }

    dpdu = bumped_tangent(dgs->dpdu, dgs->n, dgs->dndu, u_displace, displace, du, drop);
    dpdv = bumped_tangent(dgs->dpdv, dgs->n, dgs->dndv, v_displace, displace, dv, drop);
    n = mt_v3_cross(dpdu, dpdv);
    len = mt_v3_len(n);
    /* parallel or non-finite bumped tangents: keep the unbumped geometry
     * (pbrt-v2 would normalize a zero vector; erratum bump-degenerate) */
    if (!(len > 0 && mt_is_finite(len)) || !mt_v3_is_finite(dpdu) || !mt_v3_is_finite(dpdv))
        return;
    n = mt_v3_scale(n, 1 / len);
    if (dgs->flip) n = mt_v3_neg(n);
    dg_bump->dpdu = dpdu;
    dg_bump->dpdv = dpdv;
    /* pbrt-v2 Faceforward(n, ng): the shading normal on the geometric side */
    dg_bump->n = mt_v3_faceforward(n, dg_geom->n);
}
