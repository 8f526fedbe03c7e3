/*
 * materia.h -- the umbrella header of materia, a C99 reference implementation
 * of pbrt-v2's material system.
 *
 *   #include <materia.h>
 *
 *   mt_arena *arena = mt_arena_create(0);
 *   mt_error err;
 *   mt_diffgeom dg = mt_diffgeom_default();
 *   mt_bsdf *bsdf = mt_bsdf_create(arena, MT_MODE_PBRT_V2, &dg, dg.n, 1, &err);
 *   mt_bsdf_add(bsdf, mt_lambertian_create(arena, MT_MODE_PBRT_V2, mt_rgb_gray(0.5f), &err), &err);
 *   mt_rgb f = mt_bsdf_f(bsdf, wo, wi, MT_BSDF_ALL);
 *   mt_bsdf_sample s = mt_bsdf_sample_f(bsdf, wo, uc, u1, u2, MT_BSDF_ALL);
 *   mt_arena_reset(arena);     once per camera sample
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

/* The version of the library ("0.1.0") and its precision ("float"/"double"):
 * a program built against one precision's headers must link that build. */
MT_API const char *mt_version(void);
MT_API const char *mt_precision(void);

#ifdef __cplusplus
}
#endif

#endif
