/* Internal: the graphics state's record, shared by state.c and
 * state_material.c. */
#ifndef MT_PARAMS_STATE_INTERNAL_H
#define MT_PARAMS_STATE_INTERNAL_H

#include <stdarg.h>
#include <stdio.h>
#include "materia/state.h"
#include "params/gstate.h"

struct mt__frame;
struct mt__coordsys;

struct mt_state {
    mt_mode mode;
    mt_warning_fn warn;
    void *warn_ctx;
    mt_transform t[2]; /* pbrt-v2 curTransform: start and end time */
    unsigned active;   /* activeTransformBits */
    mt__gstate g;
    struct mt__frame *stack;
    int depth, cap;
    struct mt__coordsys *cs; /* namedCoordinateSystems */
    int ncs, cap_cs;
};

/* Fills err with the message, located at the statement; returns status. */
mt_status mt__state_fail(const mt_statement *st, mt_error *err, mt_status status,
                         const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
void mt__state_warn(mt_state *s, const mt_statement *st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

mt_status mt__state_texture(mt_state *s, const mt_statement *st, mt_error *err);
mt_status mt__state_material(mt_state *s, const mt_statement *st, mt_error *err);
mt_status mt__state_make_named(mt_state *s, const mt_statement *st, mt_error *err);
mt_status mt__state_named(mt_state *s, const mt_statement *st, mt_error *err);
mt_status mt__state_area_light(mt_state *s, const mt_statement *st, mt_error *err);

#endif
