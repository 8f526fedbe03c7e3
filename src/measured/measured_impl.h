/*
 * Internal: measured BRDF data (materia/measured.h) -- the object, and the
 * readers of pbrt-v2's two file formats that the cache calls.
 */
#ifndef MT_MEASURED_IMPL_H
#define MT_MEASURED_IMPL_H

#include "materia/measured.h"
#include "core/kdtree.h"

struct mt_measured {
    int refs;
    mt_measured_kind kind;
    int n;          /* samples (irregular) or table entries (half-angle) */
    /* irregular: the remapped points (3 n), their values, the k-d tree */
    mt_real *points;
    mt_rgb *values;
    mt__kdtree tree;
    /* half-angle: 3 * MT_MERL_SAMPLES values, pbrt-v2's layout */
    mt_real *table;
};

/* pbrt-v2 IrregIsotropicBRDF::f's first squared search radius, and the
 * wider one of the search that serves its first tries (bxdfs/measured.c);
 * the data's grid index (core/kdball.c) is built for the wider one. */
#define MT__IRREG_FIRST_D2 ((mt_real)0.001)
#define MT__IRREG_WIDE_D2 (8 * MT__IRREG_FIRST_D2)

/* Whether b is one of the measured BxDFs (bxdfs/measured.c), whose f is a
 * lookup in tabulated data: discontinuous wherever a table bin or the
 * irregular search's set of samples changes (mt_bxdf_rho_quad). */
int mt__bxdf_is_measured(const mt_bxdf *b);

/* Irregular data owning points (3 n remapped coordinates) and values (n),
 * both from mt__malloc: they are freed here on failure too. */
mt_measured *mt__measured_irregular(mt_real *points, mt_rgb *values, int n, mt_error *err);
/* Half-angle data owning table (3 * MT_MERL_SAMPLES, from mt__malloc). */
mt_measured *mt__measured_halfangle(mt_real *table, mt_error *err);

/* The file readers (errors located at the file, and its line for text). */
mt_measured *mt__brdf_file_read(const char *path, mt_error *err);
mt_measured *mt__merl_file_read(const char *path, mt_error *err);

/* pbrt-v2 measured.cpp: the MERL file's values are scaled by these as read
 * (float constants, as pbrt-v2 declares them). */
extern const float mt__merl_scale[3];

#endif
