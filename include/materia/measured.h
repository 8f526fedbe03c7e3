/*
 * materia/measured.h -- measured BRDFs: pbrt-v2's IrregIsotropicBRDF and
 * RegularHalfangleBRDF and their data files (materia/tools/merl.h writes MERL
 * tables of any BSDF).
 *
 * Measured data (mt_measured) is immutable and reference-counted, and may be
 * shared between threads. It is one of two kinds:
 *  - irregular isotropic samples (pbrt-v2's .brdf text files): direction
 *    pairs with an RGB value each, stored at their BRDFRemap points in a k-d
 *    tree. f(wo, wi) is pbrt-v2's IrregIsotropicBRDF::f: the samples within
 *    squared distance 0.001 of BRDFRemap(wo, wi), the squared radius doubled
 *    while fewer than 3 are found and it is at most 1.5 (so the last search
 *    uses 2.048), weighted by exp(-100 d^2), the weighted sum clamped from
 *    below at 0 and divided by the sum of the weights. Where no sample has
 *    weight pbrt-v2 divides 0 by 0; materia returns 0 in both modes
 *    (erratum "measured-empty"). pbrt-v2's remap rounds (wo, wi) and
 *    (wi, wo) an ulp apart, so its f is not exactly reciprocal; corrected
 *    mode folds the azimuth difference symmetrically (erratum
 *    "measured-remap-symmetry").
 *  - a regular half-angle table (the MERL BRDF database's binary format):
 *    RGB values on a 90 x 90 x 180 grid over (theta_h, theta_d, phi_d) with
 *    theta_h indexed by sqrt(theta_h / (pi/2)); f(wo, wi) is pbrt-v2's
 *    RegularHalfangleBRDF::f, the value of the bin the pair falls in
 *    (piecewise constant, no interpolation).
 * Both BxDFs are glossy reflection with the BxDF base's cosine sampling and
 * pdf, as in pbrt-v2.
 *
 * A BxDF made from measured data points into it: keep the data (or the
 * material holding it) alive while the BxDF is used.
 *
 * Thread safety: measured data is read-only once created: any number of
 * threads may use it and retain and destroy it; the file cache is thread-
 * safe (two threads loading one file read it once).
 */
#ifndef MATERIA_MEASURED_H
#define MATERIA_MEASURED_H

#include "materia/bsdf.h"
#include "materia/params.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_measured mt_measured;

typedef enum mt_measured_kind {
    MT_MEASURED_IRREGULAR, /* pbrt-v2 IrregIsotropicBRDF data */
    MT_MEASURED_HALFANGLE  /* pbrt-v2 RegularHalfangleBRDF data (MERL) */
} mt_measured_kind;

/* pbrt-v2's fixed MERL resolution (measured.cpp): theta_h, theta_d, phi_d. */
#define MT_MERL_THETA_H 90
#define MT_MERL_THETA_D 90
#define MT_MERL_PHI_D 180
#define MT_MERL_SAMPLES (MT_MERL_THETA_H * MT_MERL_THETA_D * MT_MERL_PHI_D)

/* pbrt-v2 BRDFRemap: the point (sin theta_i sin theta_o, dphi / pi,
 * cos theta_i cos theta_o) of a direction pair in the local frame, with the
 * azimuth difference dphi = phi_i - phi_o folded into [0, pi], rounded as
 * pbrt-v2 rounds it (the data points of both modes are remapped with it).
 * Unit directions expected. */
MT_API mt_vec3 mt_brdf_remap(mt_vec3 wo, mt_vec3 wi);

/* Irregular data from n direction pairs (unit, local frame) and their RGB
 * values (copied); the pairs are remapped with mt_brdf_remap. A new
 * reference, or NULL with err filled when n < 1, an input is not finite, or
 * memory is exhausted. */
MT_API mt_measured *mt_measured_irregular_create(const mt_vec3 *wo, const mt_vec3 *wi,
                                                 const mt_rgb *values, int n, mt_error *err);

/* A half-angle table at pbrt-v2's resolution from MT_MERL_SAMPLES RGB
 * triples in pbrt-v2's memory order (rgb[3 * index + channel], index =
 * phi_d + 180 (theta_d + 90 theta_h)), already scaled (the file's
 * 1/1500, 1.15/1500, 1.66/1500 applied), copied. Values must be finite
 * and not negative. A new reference, or NULL with err filled. */
MT_API mt_measured *mt_measured_halfangle_create(const mt_real *rgb, mt_error *err);

/* Reads a measured BRDF file as pbrt-v2's MeasuredMaterial does: a name
 * ending in ".brdf" or ".BRDF" is the irregular text format, any other
 * suffix the MERL binary format; a name without a suffix is an error. Each
 * path is read once per process: later calls with the same path return the
 * cached data (a new reference: each mt_measured_load is ended by an
 * mt_measured_destroy). Thread-safe. NULL with err naming the file
 * (and the line, for the text format) and the problem: missing file,
 * truncated or over-long data (with the counts expected and found),
 * dimensions, numbers that are malformed, not finite or out of range. */
MT_API mt_measured *mt_measured_load(const char *path, mt_error *err);

/* Drops the cache's references (tests, teardown). Data still held by
 * materials stays valid until they release it; the next load of a path
 * reads the file again. */
MT_API void mt_measured_cache_clear(void);
/* The number of files in the cache. */
MT_API int mt_measured_cache_size(void);

/* Another reference to m (returned; m may be NULL), and the end of one. */
MT_API mt_measured *mt_measured_retain(mt_measured *m);
MT_API void mt_measured_destroy(mt_measured *m);
/* Which of the two kinds the data is. */
MT_API mt_measured_kind mt_measured_kind_of(const mt_measured *m);
/* The number of samples: direction pairs, or table entries. */
MT_API int mt_measured_count(const mt_measured *m);
/* The i-th irregular sample: its remapped point and RGB value (0 <= i <
 * count); returns 0 for a half-angle table or i out of range. */
MT_API int mt_measured_sample(const mt_measured *m, int i, mt_vec3 *point, mt_rgb *value);
/* The half-angle table (MT_MERL_SAMPLES RGB triples), borrowed from m;
 * NULL for irregular data. */
MT_API const mt_real *mt_measured_table(const mt_measured *m);

/* pbrt-v2's IrregIsotropicBRDF over irregular data, in the arena (bxdf.h);
 * the BxDF points into data, which must outlive it. MT_ERR_INVALID for data
 * of the other kind. */
MT_API mt_bxdf *mt_irregular_isotropic_brdf_create(mt_arena *a, mt_mode mode,
                                                   const mt_measured *data, mt_error *err);
/* pbrt-v2's RegularHalfangleBRDF over a half-angle table, likewise. */
MT_API mt_bxdf *mt_regular_halfangle_brdf_create(mt_arena *a, mt_mode mode,
                                                 const mt_measured *data, mt_error *err);

#ifdef __cplusplus
}
#endif

#endif
