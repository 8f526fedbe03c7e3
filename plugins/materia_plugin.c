/*
 * materia's own BSDFs as a plugin of the in-process implementation
 * interface (include/materia/impl.h): a configuration's lines go through an
 * mt_query session (the code materia-query runs), and each batch calls the
 * BSDF it builds, so that the answers are, value for value, materia-query's
 * and the suite's own in-process ones. Built as
 * build/<precision>/plugins/materia_plugin.so (its entry point,
 * plugins/materia_entry.c, exports it), and linked into programs that run
 * the suite on it directly (mt_impl_run_suite).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/impl.h"
#include "materia/tools/query.h"
#include "materia_plugin.h"

typedef struct mp_config {
    mt_query *q;
    mt_arena *arena;
    const mt_bsdf *bsdf;
} mp_config;

static void mp_close(void *config)
{
    mp_config *c = config;
    if (!c) return;
    mt_query_destroy(c->q);
    mt_arena_destroy(c->arena);
    free(c);
}

static int mp_open(void *state, const char *mode, const char *const *lines, int nlines, void **config, char *msg,
                   size_t msg_size)
{
    mp_config *c = calloc(1, sizeof *c);
    mt_error err;
    mt_bsdf *b;
    char out[1024], line[64];
    int i;
    (void)state;
    *config = NULL;
    mt_error_clear(&err);
    if (!c || !(c->arena = mt_arena_create(0)) || !(c->q = mt_query_create(NULL, &err))) {
        mp_close(c);
        snprintf(msg, msg_size, "out of memory");
        return MT_IMPL_ERROR;
    }
    snprintf(line, sizeof line, "mode %.40s", mode);
    if (mt_query_line(c->q, line, out, sizeof out) && strcmp(out, "ok")) {
        snprintf(msg, msg_size, "\"%s\": %.400s", line, out);
        mp_close(c);
        return MT_IMPL_ERROR;
    }
    for (i = 0; i < nlines; ++i)
        if (mt_query_line(c->q, lines[i], out, sizeof out) && strcmp(out, "ok")) {
            snprintf(msg, msg_size, "\"%.300s\": %.400s", lines[i], out);
            mp_close(c);
            return MT_IMPL_ERROR;
        }
    if (!(b = mt_query_bsdf(c->q, c->arena, &err))) {
        mt_error_format(&err, out, sizeof out);
        snprintf(msg, msg_size, "%s", out);
        mp_close(c);
        return MT_IMPL_ERROR;
    }
    c->bsdf = b;
    *config = c;
    return MT_IMPL_OK;
}

static mt_vec3 v3(mt_impl_v3 v) { return mt_v3((mt_real)v.x, (mt_real)v.y, (mt_real)v.z); }

static int mp_eval(void *config, int n, const mt_impl_v3 *wo, const mt_impl_v3 *wi, mt_impl_eval *out, char *msg,
                   size_t msg_size)
{
    const mt_bsdf *b = ((mp_config *)config)->bsdf;
    int i, k;
    (void)msg;
    (void)msg_size;
    for (i = 0; i < n; ++i) {
        mt_vec3 a = v3(wo[i]), c = v3(wi[i]);
        mt_rgb f = mt_bsdf_f(b, a, c, MT_BSDF_ALL);
        for (k = 0; k < 3; ++k) out[i].f[k] = f.c[k];
        out[i].pdf = mt_bsdf_pdf(b, a, c, MT_BSDF_ALL);
    }
    return MT_IMPL_OK;
}

static int mp_sample(void *config, int n, const mt_impl_v3 *wo, const float (*u)[3], mt_impl_sample *out, char *msg,
                     size_t msg_size)
{
    const mt_bsdf *b = ((mp_config *)config)->bsdf;
    int i, k;
    (void)msg;
    (void)msg_size;
    for (i = 0; i < n; ++i) {
        mt_bsdf_sample s = mt_bsdf_sample_f(b, v3(wo[i]), u[i][0], u[i][1], u[i][2], MT_BSDF_ALL);
        out[i].wi[0] = s.wi.x;
        out[i].wi[1] = s.wi.y;
        out[i].wi[2] = s.wi.z;
        for (k = 0; k < 3; ++k) out[i].f[k] = s.f.c[k];
        out[i].pdf = s.pdf;
        out[i].flags = s.type;
    }
    return MT_IMPL_OK;
}

static const mt_impl_plugin materia_plugin = {
    MT_IMPL_ABI, "materia", MT_VERSION,
#if MT_USE_DOUBLE
    "double",
#else
    "float",
#endif
    "transport importance sample-numbers 3", NULL, NULL, mp_open, mp_eval, mp_sample, mp_close};

const mt_impl_plugin *mt_materia_plugin(void) { return &materia_plugin; }
