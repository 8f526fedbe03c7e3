/*
 * pbrt-v2's texture mappings (core/texture.h, texture.cpp): the 2D mappings
 * uv, spherical, cylindrical and planar, and IdentityMapping3D. Spherical and
 * cylindrical mappings get their screen-space derivatives by forward
 * differences of 0.1 and 0.01 along dpdx and dpdy, with pbrt-v2's fix-up of
 * the t derivative (kept as it is, in both modes).
 */
#include "textures/mapping.h"

mt_map2d mt__map2d_uv(mt_real su, mt_real sv, mt_real du, mt_real dv)
{
    mt_map2d m;
    m.kind = MT_MAP_UV;
    m.mode = 0;
    m.su = su;
    m.sv = sv;
    m.du = du;
    m.dv = dv;
    m.world2tex = mt_transform_identity();
    m.identity = 1;
    m.vs = mt_v3(1, 0, 0);
    m.vt = mt_v3(0, 1, 0);
    m.ds = m.dt = 0;
    return m;
}

static mt_map2d projected(mt_map2d_kind kind, const mt_transform *tex2world, mt_mode mode)
{
    mt_map2d m = mt__map2d_uv(1, 1, 0, 0);
    m.kind = kind;
    m.mode = mode;
    /* pbrt-v2's creators: SphericalMapping2D(Inverse(tex2world)) */
    m.world2tex = mt_transform_inverse(tex2world);
    m.identity = mt_transform_is_identity(&m.world2tex);
    return m;
}

mt_map2d mt__map2d_spherical(const mt_transform *tex2world, mt_mode mode)
{
    return projected(MT_MAP_SPHERICAL, tex2world, mode);
}

mt_map2d mt__map2d_cylindrical(const mt_transform *tex2world, mt_mode mode)
{
    return projected(MT_MAP_CYLINDRICAL, tex2world, mode);
}

mt_map2d mt__map2d_planar(mt_vec3 v1, mt_vec3 v2, mt_real udelta, mt_real vdelta)
{
    mt_map2d m = mt__map2d_uv(1, 1, 0, 0);
    m.kind = MT_MAP_PLANAR;
    m.vs = v1;
    m.vt = v2;
    m.ds = udelta;
    m.dt = vdelta;
    return m;
}

mt_status mt__map2d_check(const mt_map2d *m, const char *cls, mt_error *err)
{
    const char *bad = NULL;
    if (!mt_is_finite(m->su)) bad = "uscale";
    else if (!mt_is_finite(m->sv)) bad = "vscale";
    else if (!mt_is_finite(m->du) || !mt_is_finite(m->ds)) bad = "udelta";
    else if (!mt_is_finite(m->dv) || !mt_is_finite(m->dt)) bad = "vdelta";
    else if (!mt_v3_is_finite(m->vs)) bad = "v1";
    else if (!mt_v3_is_finite(m->vt)) bad = "v2";
    if (!bad) return MT_OK;
    return mt_error_param(err, MT_ERR_INVALID, bad, "%s texture: %s is not finite", cls, bad);
}

/* The direction of p from the texture-space origin. pbrt-v2 normalizes it
 * (NaN at the origin); materia keeps a vector too short to normalize as it
 * is, so the origin maps to the direction (0, 0, 0) in both modes. */
static mt_vec3 map_direction(const mt_map2d *m, mt_vec3 p)
{
    mt_vec3 q = m->identity ? p : mt_transform_point(&m->world2tex, p);
    mt_real len = mt_v3_len(q);
    if (len == 0) return q;
    return mt_v3_scale(q, 1 / len);
}

/* pbrt-v2 SphericalMapping2D::sphere: s = theta / pi, t = phi / 2pi. */
static void sphere(const mt_map2d *m, mt_vec3 p, mt_real *s, mt_real *t)
{
    mt_vec3 v = map_direction(m, p);
    mt_real theta = mt_acos(mt_clamp(v.z, -1, 1)); /* SphericalTheta */
    mt_real phi = mt_atan2(v.y, v.x);              /* SphericalPhi */
    if (phi < 0) phi += 2 * MT_PI;
    *s = theta * MT_INV_PI;
    *t = phi * MT_INV_2PI;
}

/* pbrt-v2 CylindricalMapping2D::cylinder: s = (pi + phi) / 2pi, t = the
 * normalized direction's z. On the axis (x = y = 0) pbrt-v2's phi is
 * atan2 of two signed zeros (0 or +-pi, so s is 0, 0.5 or 1 by the signs);
 * MT_FIX_CYLINDRICAL_AXIS takes phi = 0 there. */
static void cylinder(const mt_map2d *m, mt_vec3 p, mt_real *s, mt_real *t)
{
    mt_vec3 v = map_direction(m, p);
    mt_real phi = mt_atan2(v.y, v.x);
    if ((m->mode & MT_FIX_CYLINDRICAL_AXIS) && v.x == 0 && v.y == 0) phi = 0;
    *s = (MT_PI + phi) / (2 * MT_PI);
    *t = v.z;
}

/* pbrt-v2's wrap-around fix-up of a t derivative (kept as pbrt-v2 has it:
 * it acts on the derivative, after the division by delta). */
static mt_real fix_dt(mt_real d)
{
    if (d > (mt_real)0.5) return 1 - d;
    if (d < -(mt_real)0.5) return -(d + 1);
    return d;
}

typedef void (*project_fn)(const mt_map2d *m, mt_vec3 p, mt_real *s, mt_real *t);

/* The forward-difference derivatives of SphericalMapping2D::Map and
 * CylindricalMapping2D::Map. */
static void differentiate(const mt_map2d *m, project_fn f, mt_real delta, const mt_diffgeom *dg,
                          mt_st *st)
{
    mt_real sx, tx, sy, ty;
    f(m, dg->p, &st->s, &st->t);
    f(m, mt_v3_add(dg->p, mt_v3_scale(dg->dpdx, delta)), &sx, &tx);
    st->dsdx = (sx - st->s) / delta;
    st->dtdx = fix_dt((tx - st->t) / delta);
    f(m, mt_v3_add(dg->p, mt_v3_scale(dg->dpdy, delta)), &sy, &ty);
    st->dsdy = (sy - st->s) / delta;
    st->dtdy = fix_dt((ty - st->t) / delta);
}

void mt__map2d_apply(const mt_map2d *m, const mt_diffgeom *dg, mt_st *st)
{
    switch (m->kind) {
    case MT_MAP_UV:
        st->s = m->su * dg->u + m->du;
        st->t = m->sv * dg->v + m->dv;
        st->dsdx = m->su * dg->dudx;
        st->dtdx = m->sv * dg->dvdx;
        st->dsdy = m->su * dg->dudy;
        st->dtdy = m->sv * dg->dvdy;
        return;
    case MT_MAP_SPHERICAL:
        differentiate(m, sphere, (mt_real)0.1, dg, st);
        return;
    case MT_MAP_CYLINDRICAL:
        differentiate(m, cylinder, (mt_real)0.01, dg, st);
        return;
    case MT_MAP_PLANAR:
        st->s = m->ds + mt_v3_dot(dg->p, m->vs);
        st->t = m->dt + mt_v3_dot(dg->p, m->vt);
        st->dsdx = mt_v3_dot(dg->dpdx, m->vs);
        st->dtdx = mt_v3_dot(dg->dpdx, m->vt);
        st->dsdy = mt_v3_dot(dg->dpdy, m->vs);
        st->dtdy = mt_v3_dot(dg->dpdy, m->vt);
        return;
    }
}

mt_map3d mt__map3d(const mt_transform *tex2world, mt_mode mode)
{
    mt_map3d m;
    m.world2tex = (mode & MT_FIX_MAPPING_3D) ? mt_transform_inverse(tex2world) : *tex2world;
    m.identity = mt_transform_is_identity(&m.world2tex);
    return m;
}

mt_vec3 mt__map3d_apply(const mt_map3d *m, const mt_diffgeom *dg, mt_vec3 *dpdx, mt_vec3 *dpdy)
{
    if (m->identity) {
        *dpdx = dg->dpdx;
        *dpdy = dg->dpdy;
        return dg->p;
    }
    *dpdx = mt_transform_vector(&m->world2tex, dg->dpdx);
    *dpdy = mt_transform_vector(&m->world2tex, dg->dpdy);
    return mt_transform_point(&m->world2tex, dg->p);
}
