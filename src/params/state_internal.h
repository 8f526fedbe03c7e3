/* Internal: the graphics state's record, shared by state.c and
 * state_material.c. */
#ifndef MT_PARAMS_STATE_INTERNAL_H
#define MT_PARAMS_STATE_INTERNAL_H

#include "materia/state.h"
#include "params/gstate.h"
#include "params/report.h"

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

/* An error located at the statement; a warning about it. */
#define mt__state_fail(st, err, status, ...)                                                    \
    mt__fail_at(err, status, (st)->file, (st)->line, (st)->column, __VA_ARGS__)
#define mt__state_warn(s, st, ...) mt__warnf((s)->warn, (s)->warn_ctx, (st)->file, (st)->line, __VA_ARGS__)

mt_status mt__state_texture(mt_state *s, const mt_statement *st, mt_error *err);
mt_status mt__state_material(mt_state *s, const mt_statement *st, mt_error *err);
mt_status mt__state_make_named(mt_state *s, const mt_statement *st, mt_error *err);
mt_status mt__state_named(mt_state *s, const mt_statement *st, mt_error *err);
mt_status mt__state_area_light(mt_state *s, const mt_statement *st, mt_error *err);

#endif
