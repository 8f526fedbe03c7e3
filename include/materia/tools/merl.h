/*
 * materia/tools/merl.h -- MERL tables of any BSDF: what materia-merl writes,
 * to test a measured-BRDF reader (materia's own or another renderer's)
 * against an analytic material.
 *
 * Thread safety: every function may be called from any thread at once.
 */
#ifndef MATERIA_TOOLS_MERL_H
#define MATERIA_TOOLS_MERL_H

#include "materia/measured.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- MERL tables of any BSDF ------------------------------------------------
 * Positions in the table are continuous MERL coordinates in bin units: uh
 * in [0, 90) on the square-root scale (theta_h = (uh / 90)^2 pi/2), ud in
 * [0, 90) (theta_d = ud / 90 pi/2), up in [0, 180) (phi_d = up / 180 pi).
 * pbrt-v2's lookup (RegularHalfangleBRDF::f), like MERL's own, maps the bin
 * [i, i+1) of each coordinate to entry i: piecewise constant. */

/* The direction pair (local frame) at a position: the half vector in the
 * xz-plane (phi_h = 0), wi at (theta_d, phi_d) about it in pbrt-v2's
 * half-angle frame, wo the reflection of wi about the half vector. */
MT_API void mt_merl_directions(double uh, double ud, double up, mt_vec3 *wo, mt_vec3 *wi);

/* Where in its bin each entry is sampled. MERL's convention puts entry i at
 * the bin's lower corner (the integer position): the table is exact there,
 * but a lookup at a corner sits on a bin edge, where rounding picks either
 * bin. The bin centre halves the largest lookup error and makes tabulating
 * a table's own BRDF give the same table back. */
typedef enum mt_merl_at { MT_MERL_AT_CORNER, MT_MERL_AT_CENTRE } mt_merl_at;

/* The MERL file values of a BSDF (its reflection, f(wo, wi) with all flags
 * at each entry's direction pair turned to world space): 3 * MT_MERL_SAMPLES
 * doubles in file order (channel-major, then theta_h, theta_d, phi_d), each
 * f divided by the channel's scale, so that reading the file gives f back.
 * Entries with a direction at or below the horizon get 0. MT_ERR_INVALID if f
 * is not finite somewhere. */
MT_API mt_status mt_merl_tabulate(const mt_bsdf *b, mt_merl_at at, double *values,
                                  mt_error *err);

/* Writes a MERL file (header 90 90 180, then the 3 * MT_MERL_SAMPLES
 * little-endian doubles) to a temporary file next to path and renames it
 * into place, so that path is never seen half-written. Errors name the
 * file. */
MT_API mt_status mt_merl_write(const char *path, const double *values, mt_error *err);

/* materia-merl's work: parses pbrt-v2 statements into a graphics state,
 * creates the material they leave current (mt_material_from_state; at least
 * one Material or NamedMaterial statement is required), builds its BSDF at
 * mt_diffgeom_default() and writes its MERL table to path (mt_merl_tabulate,
 * mt_merl_write). Errors name the statement, parameter or file. */
typedef struct mt_merl_options {
    mt_mode mode;         /* MT_MODE_PBRT_V2 by default */
    mt_merl_at at;        /* MT_MERL_AT_CORNER by default */
    const char *dir;      /* relative file names resolve against it; NULL: "." */
    mt_warning_fn warn;   /* unused parameters and other warnings; may be NULL */
    void *warn_ctx;
} mt_merl_options;

/* opt may be NULL (all defaults). */
MT_API mt_status mt_merl_write_statements(const char *statements, const mt_merl_options *opt,
                                          const char *path, mt_error *err);

#ifdef __cplusplus
}
#endif

#endif
