/*
 * materia's own BSDFs in this process, behind the core's batched
 * operations: a configuration's lines go through materia's mt_query session
 * (the same code materia-query runs), or a catalog subject's builder makes
 * the BSDF; evals and samples call the BSDF directly, so that the answers
 * are, value for value, the ones materia-query prints.
 */
#include <float.h>
#include <stdio.h>
#include <string.h>
#include "impl.h"
#include "materia/tools/query.h"

static mt_mode mode_of(const cf_impl *im, const cf_case *c)
{
    int radiance = im->conv.transport == CF_RADIANCE || (c->flags & CF_CASE_RADIANCE);
    return im->mode | (radiance ? MT_OPT_RADIANCE_TRANSMISSION : 0u);
}

static int m_open(cf_impl *im, const cf_case *c)
{
    mt_error err;
    char out[1024];
    int i;
    mt_bsdf *b = NULL;
    mt_error_clear(&err);
    if (c->flags & CF_CASE_RADIANCE) im->conv.transport = CF_RADIANCE;
    if (!(im->arena = mt_arena_create(0))) {
        snprintf(im->msg, sizeof im->msg, "out of memory");
        return im->failed = CF_NOMEM;
    }
    if (c->subject) {
        if (c->subject->build(c->subject, im->arena, mode_of(im, c), &b, &err) != MT_OK) b = NULL;
    } else {
        mt_query *q = mt_query_create(NULL, &err);
        if (!(im->q = q)) {
            snprintf(im->msg, sizeof im->msg, "out of memory");
            return im->failed = CF_NOMEM;
        }
        if (mode_of(im, c) & MT_OPT_RADIANCE_TRANSMISSION) mt_query_set_options(q, MT_OPT_RADIANCE_TRANSMISSION);
        mt_query_line(q, im->mode == MT_MODE_PBRT_V2 ? "mode pbrt-v2" : "mode corrected", out, sizeof out);
        for (i = 0; i < c->nlines; ++i)
            if (mt_query_line(q, c->lines[i], out, sizeof out) && strcmp(out, "ok")) {
                snprintf(im->msg, sizeof im->msg, "materia answered \"%.300s\" to \"%.300s\"", out, c->lines[i]);
                return im->failed = CF_FAILED;
            }
        b = mt_query_bsdf(q, im->arena, &err);
    }
    if (!b) {
        char m[600];
        mt_error_format(&err, m, sizeof m);
        snprintf(im->msg, sizeof im->msg, "materia: %s", m);
        return im->failed = CF_FAILED;
    }
    im->bsdf = b;
    return 0;
}

static mt_vec3 v3(cf_v3 v) { return mt_v3((mt_real)v.x, (mt_real)v.y, (mt_real)v.z); }

static int m_eval(cf_impl *im, int n, const cf_v3 *wo, const cf_v3 *wi, cf_eval *out)
{
    int i, k;
    if (im->failed) return im->failed;
    for (i = 0; i < n; ++i) {
        mt_vec3 a = v3(wo[i]), b = v3(wi[i]);
        mt_rgb f = mt_bsdf_f(im->bsdf, a, b, MT_BSDF_ALL);
        for (k = 0; k < 3; ++k) out[i].f[k] = f.c[k];
        out[i].pdf = mt_bsdf_pdf(im->bsdf, a, b, MT_BSDF_ALL);
    }
    im->queries += n;
    return 0;
}

static int m_sample(cf_impl *im, int n, const cf_v3 *wo, const float (*u)[3], cf_samp *out)
{
    int i, k;
    if (im->failed) return im->failed;
    for (i = 0; i < n; ++i) {
        mt_bsdf_sample s = mt_bsdf_sample_f(im->bsdf, v3(wo[i]), u[i][0], u[i][1], u[i][2], MT_BSDF_ALL);
        out[i].wi[0] = s.wi.x;
        out[i].wi[1] = s.wi.y;
        out[i].wi[2] = s.wi.z;
        for (k = 0; k < 3; ++k) out[i].f[k] = s.f.c[k];
        out[i].pdf = s.pdf;
        out[i].flags = s.type;
    }
    im->queries += n;
    return 0;
}

static int m_close(cf_impl *im)
{
    mt_query_destroy(im->q);
    mt_arena_destroy(im->arena);
    im->q = NULL;
    im->arena = NULL;
    im->bsdf = NULL;
    return 0;
}

static const cf_impl_ops materia_ops = {"materia", m_open, m_eval, m_sample, m_close};

void cf_impl_materia(cf_impl *im, mt_mode mode)
{
    memset(im, 0, sizeof *im);
    im->ops = &materia_ops;
    im->mode = mode;
    im->conv = cf_conventions_default();
#if MT_USE_DOUBLE
    im->eps = DBL_EPSILON;
#else
    im->eps = FLT_EPSILON;
#endif
    im->direct = 1;
}

int cf_materia_open(cf_impl *im, mt_mode mode, const char *const *lines, int nlines)
{
    cf_case c;
    int i, r;
    memset(&c, 0, sizeof c);
    cf_impl_materia(im, mode);
    for (i = 0; i < nlines; ++i)
        if (cf_case_add_line(&c, lines[i], NULL)) {
            cf_case_free(&c);
            snprintf(im->msg, sizeof im->msg, "too many lines or out of memory");
            return -1;
        }
    r = im->ops->open(im, &c);
    cf_case_free(&c);
    return r ? -1 : 0;
}

void cf_impl_close(cf_impl *im) { im->ops->close(im); }
