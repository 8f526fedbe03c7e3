/*
 * Internal: the scene loader's state while statements arrive -- the options
 * recorded before WorldBegin (built into camera, film, sampler and
 * integrator at WorldBegin, when all of them are known, as pbrt-v2 builds
 * them at WorldEnd) and the graphics state.
 */
#ifndef MT_TRACER_SCENE_LOAD_H
#define MT_TRACER_SCENE_LOAD_H

#include "materia/state.h"
#include "tracer/scene.h"

/* An options statement: its type name, a copy of its parameters, where it was. */
typedef struct mt__option {
    char *type; /* NULL: not given (pbrt-v2's default applies) */
    mt_paramset *ps;
    char *file;
    int line, column;
} mt__option;

typedef enum mt__phase { MT__PHASE_OPTIONS, MT__PHASE_WORLD, MT__PHASE_DONE } mt__phase;

typedef struct mt__loader {
    mt_scene *scene;
    mt_state *state;
    mt_warning_fn warn;
    void *warn_ctx;
    mt__phase phase;
    mt__option camera, film, filter, sampler, surface, volume, renderer, accelerator;
    mt_transform camera_to_world;
    char last_file[256]; /* the last statement, for errors at the end of the file */
    int last_line;
    const void **reported; /* parameter lists already checked for unused entries */
    int nreported, cap_reported;
} mt__loader;

/* At WorldBegin: camera, film, filter, sampler and integrator from the
 * recorded options (pbrt-v2's defaults for those not given). */
mt_status mt__scene_build_options(mt__loader *ld, mt_error *err);

/* Reports the unused parameters of ps once (the same list may serve many
 * shapes). */
void mt__loader_report_unused(mt__loader *ld, const mt_paramset *ps);

/* A warning located at file:line, printf-style. */
void mt__loader_warn(mt__loader *ld, const char *file, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Sets err's location to the option's statement when it has none. */
mt_status mt__option_fail(const mt__option *o, mt_status st, mt_error *err);

#endif
