/*
 * materia.h -- materia, a C99 reference implementation of pbrt-v2's material
 * system: the library's core API. Tool and test helpers (the query protocol,
 * image comparison, contact sheets, cubature, MERL writing, fault injection)
 * are in materia_tools.h. docs/EMBEDDING.md has complete programs.
 *
 *   #include <materia.h>
 *
 *   mt_error err = MT_ERROR_INIT;
 *   mt_material *m = mt_material_from_text(
 *       "Material \"plastic\" \"rgb Kd\" [0.5 0.5 0.5]", NULL, &err);
 *   mt_arena *arena = mt_arena_create(0);              -- one per thread
 *   mt_diffgeom dg = mt_diffgeom_default();            -- your shading point
 *   mt_bsdf *bsdf = mt_material_get_bsdf(m, &dg, &dg, arena, &err);
 *   mt_rgb f = mt_bsdf_f(bsdf, wo, wi, MT_BSDF_ALL);
 *   mt_bsdf_sample s = mt_bsdf_sample_f(bsdf, wo, uc, u1, u2, MT_BSDF_ALL);
 *   mt_arena_reset(arena);                             -- once per shading point
 *   ...
 *   mt_arena_destroy(arena);
 *   mt_material_destroy(m);
 *
 * The headers, in the order a reader meets them:
 *   materia/real.h, vec.h, rgb.h, frame.h   mt_real (float, or double with
 *                                 PRECISION=double), vectors, RGB spectra, frames
 *   materia/error.h               mt_status, mt_error and its contract
 *   materia/arena.h               the memory arena BSDFs are built in
 *   materia/mode.h                pbrt-v2 mode, corrected mode, the errata
 *   materia/diffgeom.h            the shading point
 *   materia/bxdf.h, bsdf.h        pbrt-v2's BxDFs and BSDF
 *   materia/rng.h, sampling.h     PCG32 and pbrt-v2's sampling mappings
 *   materia/transform.h           4x4 transforms
 *   materia/spectrum.h            sampled spectra and blackbodies to RGB
 *   materia/params.h              parameter lists and the mt_param helpers
 *   materia/parser.h, state.h     pbrt-v2's scene syntax and graphics state
 *   materia/texture.h, bump.h     textures and bump mapping
 *   materia/image.h, mipmap.h     image files and pbrt-v2's MIP-map
 *   materia/measured.h            measured BRDF data
 *   materia/material.h            pbrt-v2's 13 materials
 *   materia/render.h              rendering a pbrt-v2 scene
 *
 * Conventions, which every header follows and states only where it differs:
 *  - Pointer arguments must not be NULL unless the declaration says "may be
 *    NULL". An mt_error *err may always be NULL (error.h).
 *  - Lifetime: what a function named *_create, *_load, *_read, *_clone or
 *    *_from_*, or documented as returning "a new reference", returns belongs
 *    to the caller, who ends it with the matching *_destroy
 *    (mt_image_destroy for an mt_image a function filled).
 *    Materials, textures and measured data are reference-counted and
 *    read-only: *_retain gives another reference, and each reference ends
 *    with one *_destroy; the object goes with its last reference. Every
 *    *_destroy accepts NULL. A returned pointer documented as "borrowed"
 *    belongs to the object it came from and stays valid as long as that
 *    object does (and, for a state, until its next change).
 *  - BxDFs and BSDFs live in an mt_arena: no destroy, the arena frees them
 *    (mt_arena_reset, mt_arena_destroy).
 *  - Failure: a NULL or an mt_status other than MT_OK, and err filled; the
 *    library never prints, exits or aborts. "No such name" is always
 *    MT_ERR_NOT_FOUND.
 *  - Directions are unit vectors pointing away from the surface; angles in
 *    pbrt-v2's units (degrees where a scene gives degrees).
 *  - Thread safety: every header says what may be shared. In short: the
 *    read-only objects -- materials, textures, MIP-maps, measured data, a
 *    loaded scene, a built BSDF -- may be used by any number of threads at
 *    once, and their reference counts and the process-wide caches are
 *    thread-safe; an arena, a parameter list, a state, a texture table, a
 *    query session, an image accumulator or an mt_rng is used by one thread
 *    at a time. tests/test_threads.c checks this with 8 threads, and
 *    `make check-tsan` runs it under ThreadSanitizer.
 */
#ifndef MATERIA_H
#define MATERIA_H

#include "materia/config.h"
#include "materia/real.h"
#include "materia/vec.h"
#include "materia/rgb.h"
#include "materia/frame.h"
#include "materia/error.h"
#include "materia/arena.h"
#include "materia/rng.h"
#include "materia/sampling.h"
#include "materia/mode.h"
#include "materia/diffgeom.h"
#include "materia/bxdf.h"
#include "materia/bsdf.h"
#include "materia/transform.h"
#include "materia/spectrum.h"
#include "materia/params.h"
#include "materia/parser.h"
#include "materia/state.h"
#include "materia/image.h"
#include "materia/mipmap.h"
#include "materia/texture.h"
#include "materia/bump.h"
#include "materia/measured.h"
#include "materia/material.h"
#include "materia/render.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The library's version ("0.1.0") and precision ("float" or "double"),
 * static strings. A program built against one precision's headers must link
 * that build: compare mt_precision() with MT_REAL_NAME. Thread-safe. */
MT_API const char *mt_version(void);
MT_API const char *mt_precision(void);

#ifdef __cplusplus
}
#endif

#endif
