/*
 * materia/render.h -- materia's tracer: pbrt-v2 scene files rendered with
 * pbrt-v2's cameras, film, filters, lights and surface integrators (path,
 * directlighting, dipolesubsurface), and materia's materials.
 *
 *   mt_render_options o;
 *   mt_render_options_default(&o);            -- then o.spp, o.threads, o.mode...
 *   mt_scene *s = mt_scene_load("matte.pbrt", &o, &err);
 *   mt_image img, var;
 *   mt_render_stats st;
 *   mt_scene_render(s, &o, &img, &var, &st, &err);    -- var may be NULL
 *   mt_render_write("out.exr", &img, s, &o, &err);    -- spp and seed in the header
 *   mt_image_destroy(&img); mt_image_destroy(&var); mt_scene_destroy(s);
 *
 * or, in one call, mt_render_file(path, &o, &img, &var, &st, &err).
 *
 * What a scene may contain, and what is an error, is listed in
 * docs/RENDERER.md. Everything materia does not support (volumes, object
 * instancing, other integrators, cameras, lights or samplers' options) is an
 * error naming the directive and its file:line, never a silent substitute;
 * parameters no one reads are reported through the warning callback, as
 * pbrt-v2 reports them.
 *
 * Determinism: the image depends only on the scene, the mode, the sample
 * count and the seed -- not on the number of threads. Each camera sample's
 * random numbers are a function of (pixel, sample index, dimension, seed),
 * and the tiles' film contributions are added to the image in tile order.
 *
 * Thread safety: a loaded scene is read-only: any number of threads may
 * render it at once (each call runs its own o->threads worker threads, and
 * calls the progress callbacks on the thread that called it). Loading,
 * writing and mt_render_file may run in any number of threads at once.
 */
#ifndef MATERIA_RENDER_H
#define MATERIA_RENDER_H

#include <stdint.h>
#include "materia/image.h"
#include "materia/mode.h"
#include "materia/params.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_scene mt_scene;

/* Progress of a render: the fraction of tiles finished, the seconds since the
 * render began and an estimate of the seconds left (negative before any tile
 * has finished). Called from the thread that called mt_scene_render, about
 * four times a second and once at the end; the library never prints. */
typedef void (*mt_progress_fn)(void *ctx, double fraction, double elapsed, double remaining);

/* Progress of a stage before the image (the dipolesubsurface integrator's
 * "depositing points" and "computing irradiance"): its name, the fraction
 * done (for the deposition, the longest run of rejected candidates over the
 * 2000 that end it, as pbrt-v2 reports it), a count (the points so far; the
 * points whose irradiance is computed), the seconds since the stage began
 * and an estimate of those left (negative when unknown). Called from the
 * thread that called mt_scene_render with progress_ctx. */
typedef void (*mt_stage_fn)(void *ctx, const char *stage, double fraction, long count, double elapsed,
                            double remaining);

typedef struct mt_render_options {
    mt_mode mode;          /* materials and textures: MT_MODE_PBRT_V2 (default) or corrected */
    int spp;               /* samples per pixel; 0: the scene's (pbrt-v2's count) */
    int threads;           /* 0: one per online processor */
    uint64_t seed;         /* selects the sample pattern (default 0) */
    int tile_size;         /* 0: 16 pixels */
    mt_warning_fn warn;    /* warnings while loading and rendering; may be NULL */
    void *warn_ctx;
    mt_progress_fn progress; /* may be NULL */
    void *progress_ctx;
    mt_stage_fn stage;       /* may be NULL; called with progress_ctx */
} mt_render_options;

typedef struct mt_render_stats {
    double seconds;            /* wall time of the render, preprocess included (loading excluded) */
    double samples;            /* camera samples traced */
    double samples_per_second;
    int threads;
    int spp;
    long rejected;             /* samples set to black as pbrt-v2 does (NaN, Inf, y < -1e-5) */
    long shading_failures;     /* path vertices whose BSDF could not be built (ended there) */
    double preprocess_seconds; /* of seconds: the dipolesubsurface preprocess (points, irradiance, octree) */
    long points;               /* dipolesubsurface: the irradiance points */
} mt_render_stats;

/* Fills *o with the defaults above (pbrt-v2 mode, the scene's samples per
 * pixel, one thread per processor, seed 0, no callbacks). Every function
 * below also takes o NULL for these defaults. */
MT_API void mt_render_options_default(mt_render_options *o);

/* Reads a pbrt-v2 scene file (Include resolved against the including file's
 * directory) and builds everything up to the BVH: a new scene
 * (mt_scene_destroy), or NULL with err (file, line, parameter) on any
 * error. Only o->mode, o->warn and o->warn_ctx are used; unused parameters
 * go to o->warn, and are dropped when it is NULL. */
MT_API mt_scene *mt_scene_load(const char *path, const mt_render_options *o, mt_error *err);
/* The same from text (name for messages, NULL: "<string>"; dir for relative
 * file names, NULL: the current directory). */
MT_API mt_scene *mt_scene_load_string(const char *text, const char *name, const char *dir,
                                      const mt_render_options *o, mt_error *err);
/* Frees a scene and everything it holds (its materials and textures keep
 * any references others hold). */
MT_API void mt_scene_destroy(mt_scene *s);

/* The Film's "filename" (pbrt-v2's default "pbrt.exr"), as written in the
 * scene (borrowed): pbrt-v2 resolves it against the current directory. */
MT_API const char *mt_scene_filename(const mt_scene *s);
/* The image's size: the film's crop window in pixels. */
MT_API void mt_scene_image_size(const mt_scene *s, int *width, int *height);
/* The samples per pixel the scene asks for (after pbrt-v2's rounding). */
MT_API int mt_scene_spp(const mt_scene *s);

/* Renders s. *image receives the RGB image (linear, crop-window size, row 0
 * at the top); *variance (may be NULL) the estimated variance of each pixel's
 * value, per channel, from the per-pixel sample statistics (for a box filter
 * the sample variance divided by the sample count; in general the variance
 * of the filter-weighted mean). Low-discrepancy samples are not independent,
 * so the estimate is conservative. stats may be NULL. The images are the
 * caller's (mt_image_destroy); on failure they are empty. MT_ERR_INVALID
 * for options out of range, MT_ERR_NOMEM, or the integrator's preprocess
 * errors. */
MT_API mt_status mt_scene_render(const mt_scene *s, const mt_render_options *o, mt_image *image,
                                 mt_image *variance, mt_render_stats *stats, mt_error *err);

/* Writes a rendered image (or its variance) by extension -- .exr (float RGB
 * with the attributes materia:spp, materia:seed, materia:mode,
 * materia:integrator, materia:version), .png (8-bit sRGB) or .pfm -- to a
 * temporary file renamed into place. */
MT_API mt_status mt_render_write(const char *path, const mt_image *img, const mt_scene *s,
                                 const mt_render_options *o, mt_error *err);

/* mt_scene_load + mt_scene_render + mt_scene_destroy. */
MT_API mt_status mt_render_file(const char *path, const mt_render_options *o, mt_image *image,
                                mt_image *variance, mt_render_stats *stats, mt_error *err);

#ifdef __cplusplus
}
#endif

#endif
