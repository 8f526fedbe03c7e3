/*
 * The query session behind materia-query: pbrt-v2 statements change the
 * graphics state, queries evaluate the current material at the shading point.
 * The material is created again only after the state or the mode changed.
 */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/tools/cubature.h"
#include "materia/material.h"
#include "materia/tools/query.h"
#include "materia/state.h"

/* rho's relative tolerance (docs/PROTOCOL.md). The fuzzing build
 * (make fuzz) sets a looser one: there the cubature's code paths matter, not
 * its sixth digit, and at 1e-6 a glossy rho costs as much as thousands of
 * other statements. */
#ifndef MT_QUERY_RHO_TOL
#define MT_QUERY_RHO_TOL 1e-6
#endif
#include "core/alloc.h"
#include "core/numtext.h"
#include "params/parser_internal.h"

#if MT_USE_DOUBLE
#define NUM "%.17g"
#else
#define NUM "%.9g"
#endif

struct mt_query {
    mt_state *state;
    char *dir;
    mt_mode mode;
    mt_mode options;  /* added to every mode: MT_OPT_RADIANCE_TRANSMISSION */
    mt_diffgeom dg;   /* the shading point */
    mt_vec3 ng;       /* its geometric normal */
    mt_material *material; /* for the current state, or NULL */
    int dirty;        /* the state changed since material was made */
    mt_arena *arena;
    char *pending;    /* a statement waiting for its closing bracket or quote */
    size_t pending_len;
    int line_no, pending_line;
    int hex;          /* "numbers hex": answers in C99 hexadecimal floats */
    int fast;         /* conventions announce batch and numbers hex (mt_query_announce_fast) */
    mt_warning_fn warn; /* warnings: unused parameters, redefinitions */
    void *warn_ctx;
};

void mt_query_set_options(mt_query *q, mt_mode options)
{
    q->options = options & MT_OPT_RADIANCE_TRANSMISSION;
    mt_state_set_mode(q->state, q->mode | q->options);
    q->dirty = 1;
}

void mt_query_announce_fast(mt_query *q, int on) { q->fast = on != 0; }

void mt_query_set_warning(mt_query *q, mt_warning_fn warn, void *ctx)
{
    q->warn = warn;
    q->warn_ctx = ctx;
    mt_state_set_warning(q->state, warn, ctx);
}

static void reset_point(mt_query *q)
{
    q->dg = mt_diffgeom_default();
    q->ng = q->dg.n;
}

mt_query *mt_query_create(const char *dir, mt_error *err)
{
    mt_query *q = mt__calloc(1, sizeof *q);
    mt_error_clear(err);
    if (!q) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory");
        return NULL;
    }
    q->mode = MT_MODE_PBRT_V2;
    q->state = mt_state_create(q->mode);
    q->arena = mt_arena_create(0);
    q->dir = mt__strdup(dir && *dir ? dir : ".");
    if (!q->state || !q->arena || !q->dir) {
        mt_query_destroy(q);
        mt_error_set(err, MT_ERR_NOMEM, "out of memory");
        return NULL;
    }
    reset_point(q);
    q->dirty = 1;
    return q;
}

void mt_query_destroy(mt_query *q)
{
    if (!q) return;
    mt_material_destroy(q->material);
    mt_state_destroy(q->state);
    mt_arena_destroy(q->arena);
    mt__free(q->dir);
    mt__free(q->pending);
    mt__free(q);
}

static int answer(char *out, size_t size, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static int answer(char *out, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out, size, fmt, ap);
    va_end(ap);
    return 1;
}

static int fail(char *out, size_t size, const mt_error *err)
{
    char msg[768];
    size_t i;
    mt_error_format(err, msg, sizeof msg);
    for (i = 0; msg[i]; ++i) /* one answer, one line */
        if (msg[i] == '\n' || msg[i] == '\r') msg[i] = ' ';
    return answer(out, size, "error %s", msg);
}

static int fail_msg(char *out, size_t size, const char *msg)
{
    return answer(out, size, "error %s", msg);
}

/* ---- statements ----------------------------------------------------------- */
typedef struct apply_ctx {
    mt_query *q;
    int statements;
} apply_ctx;

static mt_status apply(void *ctx, const mt_statement *st, mt_error *err)
{
    apply_ctx *a = ctx;
    int handled = 0;
    mt_status s = mt_state_apply(a->q->state, st, &handled, err);
    if (s) return s;
    if (!handled) {
        mt_error_locate(err, st->file, st->line, st->column);
        return mt_error_set(err, MT_ERR_UNSUPPORTED, "%s is not a statement the query tool takes", st->directive);
    }
    a->statements++;
    a->q->dirty = 1;
    /* pbrt-v2 creates a material at MakeNamedMaterial; here a Material or
     * MakeNamedMaterial is created at once too, so errors show on its line */
    if (!strcmp(st->directive, "Material") || !strcmp(st->directive, "MakeNamedMaterial")) {
        int named = !strcmp(st->directive, "MakeNamedMaterial");
        mt_material_spec spec;
        mt_material *m = named ? mt_material_named_from_state(a->q->state, st->args[0].string, err)
                               : mt_material_from_state(a->q->state, NULL, err);
        if (!m) {
            if (!err->file[0]) mt_error_locate(err, st->file, st->line, st->column);
            return err->status;
        }
        mt_material_destroy(m);
        mt_error_clear(err);
        /* what the material did not read, as the renderer reports it */
        if (named ? mt_state_named_material(a->q->state, st->args[0].string, &spec, err) == MT_OK
                  : (mt_state_material(a->q->state, &spec), 1))
            mt_paramset_report_unused(named ? spec.geom : spec.material, a->q->warn, a->q->warn_ctx);
        mt_error_clear(err);
    }
    return MT_OK;
}

static int statement(mt_query *q, const char *text, int first_line, char *out, size_t size)
{
    mt_error err;
    apply_ctx a;
    a.q = q;
    a.statements = 0;
    mt_error_clear(&err);
    if (mt_parse_string(text, "<input>", q->dir, first_line, NULL, apply, &a, &err) != MT_OK) return fail(out, size, &err);
    return answer(out, size, "ok");
}

/* ---- the material at the shading point ------------------------------------ */
static const mt_material *material(mt_query *q, mt_error *err)
{
    if (q->dirty) {
        mt_material_destroy(q->material);
        q->material = mt_material_from_state(q->state, NULL, err);
        q->dirty = 0;
        if (!q->material) q->dirty = 1; /* try again next time: say why each time */
    }
    return q->material;
}

mt_bsdf *mt_query_bsdf(mt_query *q, mt_arena *arena, mt_error *err)
{
    mt_error_clear(err);
    const mt_material *m = material(q, err);
    mt_diffgeom geom = q->dg;
    if (!m) return NULL;
    geom.n = q->ng;
    return mt_material_get_bsdf(m, &geom, &q->dg, arena, err);
}

static mt_bsdf *bsdf_here(mt_query *q, mt_error *err)
{
    mt_arena_reset(q->arena);
    return mt_query_bsdf(q, q->arena, err);
}

/* ---- parsing of query arguments ------------------------------------------- */
static int numbers(const char *s, double *v, int n, const char **rest)
{
    int i;
    for (i = 0; i < n; ++i) {
        char *end;
        while (isspace((unsigned char)*s)) s++;
        if (!*s) return i;
        v[i] = mt__strtod(s, &end); /* strtod's value, faster (core/numtext.h) */
        if (end == s || !isfinite(v[i])) return -1;
        s = end;
    }
    if (rest) *rest = s;
    return n;
}

static int only_space(const char *s)
{
    while (isspace((unsigned char)*s)) s++;
    return *s == 0;
}

static int exactly(const char *args, double *v, int n)
{
    const char *rest = NULL;
    return numbers(args, v, n, &rest) == n && only_space(rest);
}

static mt_vec3 v3(const double *v) { return mt_v3((mt_real)v[0], (mt_real)v[1], (mt_real)v[2]); }

static int query_at(mt_query *q, const char *args, char *out, size_t size)
{
    static const struct {
        const char *key;
        int n;
    } keys[] = {{"p", 3}, {"n", 3}, {"ng", 3}, {"dpdu", 3}, {"dpdv", 3}, {"dndu", 3}, {"dndv", 3}, {"uv", 2},
                {"dpdx", 3}, {"dpdy", 3}, {"duvdx", 2}, {"duvdy", 2}, {"flip", 1}};
    mt_diffgeom dg = q->dg;
    mt_vec3 ng = q->ng;
    const char *s = args;
    int any = 0;
    for (;;) {
        char key[16];
        int k, len = 0;
        double v[3];
        while (isspace((unsigned char)*s)) s++;
        if (!*s) break;
        while (s[len] && !isspace((unsigned char)s[len]) && len < 15) len++;
        memcpy(key, s, (size_t)len);
        key[len] = 0;
        s += len;
        for (k = 0; k < (int)(sizeof keys / sizeof keys[0]); ++k)
            if (!strcmp(key, keys[k].key)) break;
        if (k == (int)(sizeof keys / sizeof keys[0])) return answer(out, size, "error at: unknown key \"%s\"", key);
        if (numbers(s, v, keys[k].n, &s) != keys[k].n)
            return answer(out, size, "error at: \"%s\" needs %d finite numbers", key, keys[k].n);
        any = 1;
        switch (k) {
        case 0: dg.p = v3(v); break;
        case 1: dg.n = v3(v); break;
        case 2: ng = v3(v); break;
        case 3: dg.dpdu = v3(v); break;
        case 4: dg.dpdv = v3(v); break;
        case 5: dg.dndu = v3(v); break;
        case 6: dg.dndv = v3(v); break;
        case 7: dg.u = (mt_real)v[0]; dg.v = (mt_real)v[1]; break;
        case 8: dg.dpdx = v3(v); break;
        case 9: dg.dpdy = v3(v); break;
        case 10: dg.dudx = (mt_real)v[0]; dg.dvdx = (mt_real)v[1]; break;
        case 11: dg.dudy = (mt_real)v[0]; dg.dvdy = (mt_real)v[1]; break;
        case 12:
            if (v[0] != 0 && v[0] != 1) return fail_msg(out, size, "at: flip is 0 or 1");
            dg.flip = v[0] != 0;
            break;
        }
    }
    if (!any) return fail_msg(out, size, "at: give one or more of p n ng dpdu dpdv dndu dndv uv dpdx dpdy duvdx duvdy flip");
    q->dg = dg;
    q->ng = ng;
    return answer(out, size, "ok");
}

/* ---- the answers of eval and sample --------------------------------------
 * Written number by number with the fast exact "%.9g" of a float build
 * (core/numtext.h; the same text as printf's), one space before each value
 * but the first of a line. Each returns where it ended; at or past size
 * when the answer did not fit (out is then cut, not terminated there). */
static size_t put_num(char *out, size_t at, size_t size, mt_real v, int hex)
{
    if (at) {
        if (at + 1 >= size) return size;
        out[at++] = ' ';
    }
    if (size - at < 32) return size;
    if (hex) return at + (size_t)mt__format_hex(out + at, size - at, (double)v);
#if MT_USE_DOUBLE
    return at + (size_t)snprintf(out + at, size - at, NUM, (double)v);
#else
    return at + (size_t)mt__format_g9(out + at, size - at, v);
#endif
}

static size_t put_eval(mt_bsdf *b, mt_vec3 wo, mt_vec3 wi, char *out, size_t at, size_t size, int hex)
{
    mt_rgb f = mt_bsdf_f(b, wo, wi, MT_BSDF_ALL);
    at = put_num(out, at, size, f.c[0], hex);
    at = put_num(out, at, size, f.c[1], hex);
    at = put_num(out, at, size, f.c[2], hex);
    return put_num(out, at, size, mt_bsdf_pdf(b, wo, wi, MT_BSDF_ALL), hex);
}

static size_t put_sample(mt_bsdf *b, mt_vec3 wo, const double *u, char *out, size_t at, size_t size, int hex)
{
    mt_bsdf_sample s = mt_bsdf_sample_f(b, wo, (mt_real)u[0], (mt_real)u[1], (mt_real)u[2], MT_BSDF_ALL);
    at = put_num(out, at, size, s.wi.x, hex);
    at = put_num(out, at, size, s.wi.y, hex);
    at = put_num(out, at, size, s.wi.z, hex);
    at = put_num(out, at, size, s.f.c[0], hex);
    at = put_num(out, at, size, s.f.c[1], hex);
    at = put_num(out, at, size, s.f.c[2], hex);
    at = put_num(out, at, size, s.pdf, hex);
    if (size - at < 16) return size;
    return at + (size_t)snprintf(out + at, size - at, " %u", s.type);
}

static int unit_numbers(const double *u)
{
    return u[0] >= 0 && u[0] < 1 && u[1] >= 0 && u[1] < 1 && u[2] >= 0 && u[2] < 1;
}

static int query_eval(mt_query *q, const char *args, char *out, size_t size)
{
    double v[6];
    mt_error err;
    mt_bsdf *b;
    mt_vec3 wo, wi;
    size_t at;
    if (!exactly(args, v, 6)) return fail_msg(out, size, "eval: needs wox woy woz wix wiy wiz");
    mt_error_clear(&err);
    if (!(b = bsdf_here(q, &err))) return fail(out, size, &err);
    wo = v3(v);
    wi = v3(v + 3);
    at = put_eval(b, wo, wi, out, 0, size, q->hex);
    return at < size ? 1 : fail_msg(out, size, "eval: the answer does not fit the caller's buffer");
}

static int query_sample(mt_query *q, const char *args, char *out, size_t size)
{
    double v[6];
    mt_error err;
    mt_bsdf *b;
    size_t at;
    if (!exactly(args, v, 6)) return fail_msg(out, size, "sample: needs wox woy woz uc u1 u2");
    if (!unit_numbers(v + 3)) return fail_msg(out, size, "sample: uc, u1 and u2 must be in [0, 1)");
    mt_error_clear(&err);
    if (!(b = bsdf_here(q, &err))) return fail(out, size, &err);
    at = put_sample(b, v3(v), v + 3, out, 0, size, q->hex);
    return at < size ? 1 : fail_msg(out, size, "sample: the answer does not fit the caller's buffer");
}

/* ---- batched queries (protocol 3) ----------------------------------------
 * "evals wo wi wi ..." and "samples wo u u ...": one wo, then one to
 * MT_QUERY_BATCH triples, answered on one line with 4 (8) numbers per
 * triple, in order. Any bad number is an error for the whole line, naming
 * the value; the client asks again one query a line to learn which. */
static int batch_numbers(const char *word, const char *args, double *v, int *k, char *out, size_t size)
{
    const char *s = args;
    int n = 0;
    for (;;) {
        char *end;
        while (isspace((unsigned char)*s)) s++;
        if (!*s) break;
        if (n == 3 + 3 * MT_QUERY_BATCH)
            return answer(out, size, "error %s: more than %d triples after wo on one line (conventions: batch %d)", word,
                          MT_QUERY_BATCH, MT_QUERY_BATCH);
        v[n] = mt__strtod(s, &end);
        if (end == s || !isfinite(v[n]) || (*end && !isspace((unsigned char)*end)))
            return answer(out, size, "error %s: value %d is not a finite number", word, n + 1);
        s = end;
        n++;
    }
    if (n < 6 || n % 3)
        return answer(out, size, "error %s: needs wox woy woz and one or more triples (%d numbers, not 3 + a multiple of 3)",
                      word, n);
    *k = n / 3 - 1;
    return 0;
}

/* evals (sample 0) or samples (sample 1). */
static int query_batch(mt_query *q, const char *args, char *out, size_t size, int sample)
{
    double v[3 + 3 * MT_QUERY_BATCH];
    const char *word = sample ? "samples" : "evals";
    mt_error err;
    mt_bsdf *b;
    mt_vec3 wo;
    size_t at = 0;
    int k = 0, i;
    if (batch_numbers(word, args, v, &k, out, size)) return 1;
    for (i = 0; sample && i < k; ++i)
        if (!unit_numbers(v + 3 + 3 * i))
            return answer(out, size, "error samples: uc, u1 and u2 of triple %d must be in [0, 1)", i + 1);
    mt_error_clear(&err);
    if (!(b = bsdf_here(q, &err))) return fail(out, size, &err);
    wo = v3(v);
    for (i = 0; i < k && at < size; ++i)
        at = sample ? put_sample(b, wo, v + 3 + 3 * i, out, at, size, q->hex)
                   : put_eval(b, wo, v3(v + 3 + 3 * i), out, at, size, q->hex);
    if (at >= size) return answer(out, size, "error %s: the answer to %d triples does not fit in %zu bytes", word, k, size);
    return 1;
}

static int query_evals(mt_query *q, const char *args, char *out, size_t size) { return query_batch(q, args, out, size, 0); }

static int query_samples(mt_query *q, const char *args, char *out, size_t size)
{
    return query_batch(q, args, out, size, 1);
}

static int query_rho(mt_query *q, const char *args, char *out, size_t size)
{
    double v[3];
    mt_error err;
    mt_bsdf *b;
    mt_rgb r;
    if (!exactly(args, v, 3)) return fail_msg(out, size, "rho: needs wox woy woz");
    mt_error_clear(&err);
    if (!(b = bsdf_here(q, &err))) return fail(out, size, &err);
    r = mt_bsdf_rho_quad(b, v3(v), MT_BSDF_ALL, MT_QUERY_RHO_TOL);
    return answer(out, size, NUM " " NUM " " NUM, (double)r.c[0], (double)r.c[1], (double)r.c[2]);
}

static int query_bssrdf(mt_query *q, const char *args, char *out, size_t size)
{
    mt_error err;
    const mt_material *m;
    mt_bssrdf s;
    mt_diffgeom geom = q->dg;
    if (!only_space(args)) return fail_msg(out, size, "bssrdf: takes no arguments");
    mt_error_clear(&err);
    if (!(m = material(q, &err))) return fail(out, size, &err);
    geom.n = q->ng;
    if (!mt_material_has_bssrdf(m)) return answer(out, size, "none");
    if (mt_material_get_bssrdf(m, &geom, &q->dg, &s, &err) != MT_OK) return fail(out, size, &err);
    return answer(out, size, NUM " " NUM " " NUM " " NUM " " NUM " " NUM " " NUM, (double)s.sigma_a.c[0],
                  (double)s.sigma_a.c[1], (double)s.sigma_a.c[2], (double)s.sigma_prime_s.c[0],
                  (double)s.sigma_prime_s.c[1], (double)s.sigma_prime_s.c[2], (double)s.eta);
}

static int query_shading(mt_query *q, const char *args, char *out, size_t size)
{
    mt_error err;
    mt_bsdf *b;
    const mt_diffgeom *d;
    if (!only_space(args)) return fail_msg(out, size, "shading: takes no arguments");
    mt_error_clear(&err);
    if (!(b = bsdf_here(q, &err))) return fail(out, size, &err);
    d = mt_bsdf_shading(b);
    return answer(out, size, NUM " " NUM " " NUM " " NUM " " NUM " " NUM " " NUM " " NUM " " NUM, (double)d->n.x,
                  (double)d->n.y, (double)d->n.z, (double)d->dpdu.x, (double)d->dpdu.y, (double)d->dpdu.z,
                  (double)d->dpdv.x, (double)d->dpdv.y, (double)d->dpdv.z);
}

static int query_texture(mt_query *q, const char *args, char *out, size_t size)
{
    char name[256];
    const char *s = args, *e;
    const mt_texture *t;
    while (isspace((unsigned char)*s)) s++;
    if (*s != '"' || !(e = strchr(s + 1, '"')) || (size_t)(e - s - 1) >= sizeof name || !only_space(e + 1))
        return fail_msg(out, size, "texture: needs a quoted texture name");
    memcpy(name, s + 1, (size_t)(e - s - 1));
    name[e - s - 1] = 0;
    /* pbrt-v2 keeps float and spectrum textures apart; a name may be in both:
     * the float one answers first */
    if ((t = mt_texture_table_get(mt_state_textures(q->state), name, 1)))
        return answer(out, size, NUM, (double)mt_texture_eval_float(t, &q->dg));
    if ((t = mt_texture_table_get(mt_state_textures(q->state), name, 0))) {
        mt_rgb c = mt_texture_eval_rgb(t, &q->dg);
        return answer(out, size, NUM " " NUM " " NUM, (double)c.c[0], (double)c.c[1], (double)c.c[2]);
    }
    return answer(out, size, "error texture: no texture named \"%s\"", name);
}

static int query_mode(mt_query *q, const char *args, char *out, size_t size)
{
    char word[32];
    mt_mode m;
    int end = 0;
    if (sscanf(args, " %31s%n", word, &end) != 1 || !only_space(args + end) || mt_mode_parse(word, &m, NULL) != MT_OK)
        return fail_msg(out, size, "mode: pbrt-v2 or corrected");
    q->mode = m;
    mt_state_set_mode(q->state, m | q->options);
    q->dirty = 1;
    return answer(out, size, "ok");
}

/* The conventions of its answers (docs/PROTOCOL.md): pbrt-v2's BTDF values
 * (importance) unless the session's radiance-transmission option is on,
 * pbrt-v2's three random numbers, and when the program serving the session
 * asked for it (mt_query_announce_fast) the batched queries (evals,
 * samples) of up to MT_QUERY_BATCH triples a line and hexadecimal numbers. */
static int query_conventions(mt_query *q, const char *args, char *out, size_t size)
{
    if (!only_space(args)) return fail_msg(out, size, "conventions: takes no arguments");
    return answer(out, size, "transport %s sample-numbers 3%s",
                  (q->options & MT_OPT_RADIANCE_TRANSMISSION) ? "radiance" : "importance",
                  q->fast ? " batch " MT_QUERY_BATCH_TEXT " numbers hex" : "");
}

/* "numbers hex|decimal" (protocol 3): the form of the numbers of eval,
 * sample, evals and samples answers from now on. Queries are read in either
 * form whatever it says. */
static int query_numbers(mt_query *q, const char *args, char *out, size_t size)
{
    char word[16];
    int end = 0;
    if (sscanf(args, " %15s%n", word, &end) != 1 || !only_space(args + end) || (strcmp(word, "hex") && strcmp(word, "decimal")))
        return fail_msg(out, size, "numbers: hex or decimal");
    q->hex = !strcmp(word, "hex");
    return answer(out, size, "ok");
}

/* The protocol's version (docs/PROTOCOL.md), materia's, and the precision
 * whose formatting the numbers follow: a client checks them before it
 * relies on an answer's shape. */
static int query_version(mt_query *q, const char *args, char *out, size_t size)
{
    (void)q;
    if (!only_space(args)) return fail_msg(out, size, "version: takes no arguments");
    return answer(out, size, "protocol %d materia %s precision %s", MT_QUERY_PROTOCOL_VERSION, MT_VERSION,
                  MT_USE_DOUBLE ? "double" : "float");
}

static int dispatch(mt_query *q, const char *line, char *out, size_t size)
{
    static const struct {
        const char *word;
        int (*fn)(mt_query *, const char *, char *, size_t);
    } queries[] = {{"mode", query_mode},     {"at", query_at},         {"eval", query_eval},
                   {"sample", query_sample}, {"rho", query_rho},       {"bssrdf", query_bssrdf},
                   {"shading", query_shading}, {"texture", query_texture}, {"version", query_version},
                   {"conventions", query_conventions}, {"evals", query_evals}, {"samples", query_samples},
                   {"numbers", query_numbers}};
    const char *s = line;
    size_t len = 0, i;
    while (isspace((unsigned char)*s)) s++;
    while (s[len] && !isspace((unsigned char)s[len])) len++;
    for (i = 0; i < sizeof queries / sizeof queries[0]; ++i)
        if (strlen(queries[i].word) == len && !strncmp(s, queries[i].word, len)) return queries[i].fn(q, s + len, out, size);
    return -1; /* not a query word: a statement */
}

int mt_query_line(mt_query *q, const char *line, char *out, size_t size)
{
    const char *s = line;
    mt_status st;
    int r, inc;
    q->line_no++;
    if (q->pending) {
        /* continue the open statement (dropped when memory runs out) */
        size_t n = strlen(line);
        char *p = mt__realloc(q->pending, q->pending_len + n + 2);
        if (!p) {
            mt__free(q->pending);
            q->pending = NULL;
            return fail_msg(out, size, "out of memory");
        }
        q->pending = p;
        q->pending[q->pending_len++] = '\n';
        memcpy(q->pending + q->pending_len, line, n + 1);
        q->pending_len += n;
        inc = mt__parse_incomplete(q->pending, &st);
        if (st != MT_OK) {
            mt__free(q->pending);
            q->pending = NULL;
            return fail_msg(out, size, "out of memory");
        }
        if (inc) return 0;
        r = statement(q, q->pending, q->pending_line, out, size);
        mt__free(q->pending);
        q->pending = NULL;
        return r;
    }
    while (isspace((unsigned char)*s)) s++;
    if (!*s || *s == '#') return 0;
    r = dispatch(q, s, out, size);
    if (r >= 0) return r;
    inc = mt__parse_incomplete(line, &st);
    if (st != MT_OK) return fail_msg(out, size, "out of memory");
    if (inc) {
        q->pending = mt__strdup(line);
        if (!q->pending) return fail_msg(out, size, "out of memory");
        q->pending_len = strlen(line);
        q->pending_line = q->line_no;
        return 0;
    }
    return statement(q, line, q->line_no, out, size);
}

int mt_query_finish(mt_query *q, char *out, size_t size)
{
    if (!q->pending) return 0;
    mt__free(q->pending);
    q->pending = NULL;
    return answer(out, size, "error end of input inside a statement begun on line %d (unclosed bracket or string)",
                  q->pending_line);
}
