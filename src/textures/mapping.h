/*
 * Internal: pbrt-v2's texture mappings (texture.h/.cpp) -- the 2D mappings
 * uv, spherical, cylindrical and planar, and the 3D identity mapping -- as
 * plain values that textures embed.
 */
#ifndef MT_TEXTURES_MAPPING_H
#define MT_TEXTURES_MAPPING_H

#include "materia/diffgeom.h"
#include "materia/mode.h"
#include "materia/transform.h"

typedef enum mt_map2d_kind {
    MT_MAP_UV,
    MT_MAP_SPHERICAL,
    MT_MAP_CYLINDRICAL,
    MT_MAP_PLANAR
} mt_map2d_kind;

typedef struct mt_map2d {
    mt_map2d_kind kind;
    mt_mode mode;
    mt_real su, sv, du, dv;  /* uv: s = su u + du, t = sv v + dv */
    mt_transform world2tex;  /* spherical, cylindrical */
    int identity;            /* world2tex is the identity (skip it) */
    mt_vec3 vs, vt;          /* planar: s = ds + p.vs, t = dt + p.vt */
    mt_real ds, dt;
} mt_map2d;

/* Texture coordinates and their screen-space derivatives. */
typedef struct mt_st {
    mt_real s, t, dsdx, dtdx, dsdy, dtdy;
} mt_st;

/* pbrt-v2 UVMapping2D(su, sv, du, dv). */
mt_map2d mt__map2d_uv(mt_real su, mt_real sv, mt_real du, mt_real dv);
/* pbrt-v2 SphericalMapping2D / CylindricalMapping2D(Inverse(tex2world)):
 * the creators pass the inverse of the declaring transform, as pbrt-v2's do. */
mt_map2d mt__map2d_spherical(const mt_transform *tex2world, mt_mode mode);
mt_map2d mt__map2d_cylindrical(const mt_transform *tex2world, mt_mode mode);
/* pbrt-v2 PlanarMapping2D(v1, v2, udelta, vdelta). */
mt_map2d mt__map2d_planar(mt_vec3 v1, mt_vec3 v2, mt_real udelta, mt_real vdelta);
/* Every field finite; MT_ERR_INVALID naming the parameter otherwise. */
mt_status mt__map2d_check(const mt_map2d *m, const char *cls, mt_error *err);

void mt__map2d_apply(const mt_map2d *m, const mt_diffgeom *dg, mt_st *st);

/* pbrt-v2 IdentityMapping3D: p, dpdx, dpdy through world2tex. */
typedef struct mt_map3d {
    mt_transform world2tex;
    int identity;
} mt_map3d;

/* The 3D mapping of a texture declared under tex2world. pbrt-v2 passes
 * tex2world itself as WorldToTexture (erratum mapping-3d); with
 * MT_FIX_MAPPING_3D its inverse is used, as for the 2D mappings. */
mt_map3d mt__map3d(const mt_transform *tex2world, mt_mode mode);

mt_vec3 mt__map3d_apply(const mt_map3d *m, const mt_diffgeom *dg, mt_vec3 *dpdx, mt_vec3 *dpdy);

#endif
