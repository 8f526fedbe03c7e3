/*
 * Internal: a loaded scene -- geometry, the material and area light of each
 * shape, lights, camera, film, sampler and integrator settings -- and the
 * per-thread context the integrators run in.
 */
#ifndef MT_TRACER_SCENE_H
#define MT_TRACER_SCENE_H

#include "materia/arena.h"
#include "materia/material.h"
#include "materia/render.h"
#include "tracer/camera.h"
#include "tracer/dipole.h"
#include "tracer/film.h"
#include "tracer/light.h"
#include "tracer/sampler.h"
#include "materials/bssrdf_cache.h"

/* Vertices with their own entry in mt_scene.independent. */
#define MT__INDEPENDENT_VERTICES 8

typedef enum mt__integrator { MT__INTEGRATOR_PATH, MT__INTEGRATOR_DIRECT, MT__INTEGRATOR_DIPOLE } mt__integrator;

/* What the renderer attaches to each shape (mt_shape_user). */
typedef struct mt__prim_info {
    const mt_material *material;
    int light; /* index of its area light in the scene's lights, -1 when none */
    /* the material reads no (u, v) and no differentials
     * (mt__material_is_uniform): its vertices are shaded without them */
    int uniform;
} mt__prim_info;

struct mt_scene {
    mt_mode mode;
    mt_geometry *geom;
    mt__camera camera;
    mt__film film;
    char *filename;      /* Film "filename" */
    char *sampler_name;  /* as the scene names it */
    int spp;             /* pixel samples the scene asks for, after pbrt-v2's rounding */
    int round_pow2;      /* the sampler rounds light sample counts up to powers of two */
    mt__integrator integrator;
    int maxdepth;
    int strategy_all;    /* directlighting: "all" (1) or "one" (0); 1 for dipolesubsurface */
    mt__dipole_params dipole; /* dipolesubsurface */
    mt__light *lights;
    int nlights, cap_lights;
    int *light_samples;  /* per light: samples for strategy "all" (pbrt-v2's RoundSize) */
    int *infinite;       /* indices of the infinite lights (Le of escaping rays) */
    int ninfinite;
    mt__prim_info **prims;
    int nprims, cap_prims;
    mt_material **materials;
    int nmaterials, cap_materials;
    /* For measurements only (tradeoff/variance.c; 0 in every other render):
     * values drawn independently at random instead of from their
     * low-discrepancy pair, to measure what each pair's stratification
     * buys. Bit 2k + c of independent[v] is value c of pair k of vertex v
     * (deeper vertices follow the last entry); independent_image the image
     * position. */
    uint16_t independent[MT__INDEPENDENT_VERTICES];
    int independent_image;
    /* For measurements too: pbrt-v2's own design decisions, to measure what
     * each costs -- the light chosen by a value of its own rather than by
     * the light sample's first value (measure_own_choice), and direct
     * lighting's BSDF sample drawn for the chosen light only, with a ray of
     * its own, rather than the path's continuation counting for every light
     * (measure_chosen_bsdf; path integrator). */
    int measure_own_choice, measure_chosen_bsdf;
};

/* ---- the integrators' per-thread context ------------------------------------ */

/* Path vertices (directlighting depths) whose pairs' seeds a thread keeps. */
#define MT__SEED_CACHE_VERTICES 8
/* The dimension pairs whose seeds a thread keeps for the current pixel. */
#define MT__SEED_CACHE_PAIRS 32

typedef struct mt__seed_slot {
    uint32_t gen; /* valid when equal to the thread's pixel generation */
    mt__dim_seeds seeds;
} mt__seed_slot;

typedef struct mt__thread_ctx {
    const mt_scene *scene;
    mt_arena *arena;
    mt__pixel_sampler sampler;
    uint32_t pixel_gen; /* changes with every pixel: invalidates the cache */
    mt__seed_slot seed_cache[MT__SEED_CACHE_VERTICES][MT__SEED_CACHE_PAIRS];
    uint32_t index;   /* the camera sample's index in its pixel */
    uint32_t rindex;  /* index with its bits reversed (mt__sample_2d_rev) */
    int any_independent; /* the scene's independent[] is not all 0 (measurements) */
    long shading_failures;
    long rejected;    /* samples set to black (NaN, Inf, negative) */
    mt_error err;     /* scratch for mt_material_get_bsdf */
    const mt__dipole *dipole; /* dipolesubsurface: the render's points and octree */
    mt_real fdr_eta, fdr;     /* the last Fdr computed (corrected mode integrates it) */
    int fdr_valid;
    mt__bssrdf_cache bssrdf_cache; /* the last kdsubsurface inversion */
} mt__thread_ctx;

/* Dimension pairs of a camera sample: the image position, the lens, then
 * per path vertex (or directlighting depth) a block of pairs (numbered
 * vertex * 2^16 + k), for the first MT__LD_VERTICES vertices; deeper vertices draw from
 * the PCG stream seeded by (pixel, sample) (pbrt-v2 likewise switches to its
 * RNG after SAMPLE_DEPTH = 3 vertices). */
#define MT__DIM_IMAGE 0u
#define MT__DIM_LENS 1u
#define MT__DIM_VERTEX0 2u

/* Starts a pixel: its sampler, and the seed cache emptied. */
void mt__thread_start_pixel(mt__thread_ctx *tc, const mt__sobol_tables *tables, uint64_t seed,
                            int x, int y);

/* Two uniform values for pair `k` of vertex `vertex`, array element `j` of
 * `n` (n = 1 for a single sample). The common case -- a low-discrepancy
 * vertex and a pair whose seeds the thread keeps -- is inlined into the
 * integrators (each call site has constant k, j and n); the rest, and the
 * first use of a pair in a pixel, go through mt__vertex_sample_slow and
 * mt__seed_slot_fill with the same arithmetic. */
void mt__vertex_sample_slow(mt__thread_ctx *tc, int vertex, unsigned k, int j, int n, mt_real out[2]);
void mt__seed_slot_fill(mt__thread_ctx *tc, int vertex, unsigned k);
/* Two values of dimension pair dim, array element `element`, drawn
 * independently at random (a hash of the pixel, the pair, the element and
 * the value's number), for the values whose bits are set in mask (bit 0:
 * out[0], bit 1: out[1]); the others are left. Measurements only. */
void mt__independent_pair(const mt__thread_ctx *tc, uint32_t dim, uint32_t element, unsigned mask,
                          mt_real out[2]);
static inline void mt__vertex_sample(mt__thread_ctx *tc, int vertex, unsigned k, int j, int n, mt_real out[2])
{
    if (!tc->any_independent && vertex < MT__SEED_CACHE_VERTICES && k < MT__SEED_CACHE_PAIRS) {
        uint32_t rindex = n == 1 ? tc->rindex : mt__reverse_bits(tc->index * (uint32_t)n + (uint32_t)j);
        mt__seed_slot *slot = &tc->seed_cache[vertex][k];
        if (slot->gen != tc->pixel_gen) mt__seed_slot_fill(tc, vertex, k);
        mt__sample_2d_rev(tc->sampler.tables, &slot->seeds, rindex, out);
        return;
    }
    mt__vertex_sample_slow(tc, vertex, k, j, n, out);
}

/* The radiance along a camera ray (pbrt-v2 SamplerRenderer::Li with the
 * scene's surface integrator). rd's differentials are scaled by diff_scale
 * (mt_raydiff_scale) where they are used: pbrt-v2 scales them for every
 * camera ray, but a first hit whose material is uniform (path integrator)
 * never reads them. */
mt_rgb mt__li(mt__thread_ctx *tc, const mt_raydiff *rd, mt_real diff_scale);

/* Radiance of infinite lights along a ray that leaves the scene. */
mt_rgb mt__escaped(const mt_scene *s, mt_vec3 d);

#endif
