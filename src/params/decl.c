/*
 * Parameter declarations (pbrt-v2 pbrtparse.yy InitParamSet and lookupType,
 * paramset.cpp Add*): the type word decides the kind of the values, their
 * count and their conversion -- colours of every kind become RGB here, as in
 * pbrt-v2's RGB build.
 *
 * Where pbrt-v2 warns and carries on (values of the wrong kind, a count that
 * is not a multiple of 3, an odd number of spectrum values, a bool other than
 * "true"/"false", an unreadable SPD file), this is an error.
 */
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "core/alloc.h"
#include "materia/spectrum.h"
#include "params/decl.h"
#include "params/path.h"
#include "params/report.h"
#include "params/spectrum_internal.h"

/* pbrt-v2's type words, and what each is stored as. */
typedef enum decl_kind {
    K_FLOAT, K_INT, K_BOOL, K_STRING, K_POINT, K_VECTOR, K_NORMAL, K_RGB, K_XYZ,
    K_BLACKBODY, K_SPECTRUM, K_TEXTURE
} decl_kind;

static const struct {
    const char *word;
    decl_kind kind;
} type_words[] = {
    {"float", K_FLOAT},   {"integer", K_INT},        {"bool", K_BOOL},
    {"string", K_STRING}, {"point", K_POINT},        {"vector", K_VECTOR},
    {"normal", K_NORMAL}, {"color", K_RGB},          {"rgb", K_RGB},
    {"xyz", K_XYZ},       {"blackbody", K_BLACKBODY}, {"spectrum", K_SPECTRUM},
    {"texture", K_TEXTURE},
};
#define N_TYPE_WORDS (int)(sizeof type_words / sizeof type_words[0])

/* The declaration split at its first run of white space. */
typedef struct split_decl {
    char type[32];
    char name[256];
} split_decl;

static int split(const char *decl, split_decl *d)
{
    const char *t = decl, *te, *n, *ne;
    d->type[0] = d->name[0] = '\0';
    while (*t && isspace((unsigned char)*t)) t++;
    for (te = t; *te && !isspace((unsigned char)*te); te++) {}
    for (n = te; *n && isspace((unsigned char)*n); n++) {}
    ne = n + strlen(n);
    while (ne > n && isspace((unsigned char)ne[-1])) ne--;
    if (te == t || ne == n || (size_t)(te - t) >= sizeof d->type ||
        (size_t)(ne - n) >= sizeof d->name)
        return 0;
    memcpy(d->type, t, (size_t)(te - t));
    d->type[te - t] = '\0';
    memcpy(d->name, n, (size_t)(ne - n));
    d->name[ne - n] = '\0';
    return 1;
}

void mt__decl_name(const char *decl, char *out, size_t size)
{
    split_decl d;
    if (size == 0) return;
    out[0] = '\0';
    if (split(decl, &d) && strlen(d.name) < size) memcpy(out, d.name, strlen(d.name) + 1);
}

/* name as the parameter an error concerns; returns st. */
static mt_status with_param(mt_error *err, const char *name, mt_status st)
{
    if (err) snprintf(err->param, sizeof err->param, "%.*s", (int)sizeof err->param - 1, name ? name : "");
    return st;
}

/* An error about the parameter called name, located at its declaration. */
#define decl_error(err, st, site, name, ...)                                                    \
    with_param(err, name,                                                                       \
               mt__fail_at(err, st, (site)->file, (site)->line, (site)->column, __VA_ARGS__))

static mt_status unknown_type(const char *decl, const split_decl *d, const mt__decl_site *site,
                              mt_error *err)
{
    if (!d->type[0])
        return decl_error(err, MT_ERR_PARSE, site, "",
                          "parameter declaration \"%.200s\" is not of the form \"type name\"",
                          decl);
    return decl_error(err, MT_ERR_PARSE, site, d->name,
                      "unknown parameter type \"%.40s\" in \"%.200s\" (pbrt-v2's types: float, "
                      "integer, bool, string, point, vector, normal, rgb, color, xyz, spectrum, "
                      "blackbody, texture)",
                      d->type, decl);
}

/* Integers: pbrt-v2 reads every number as a float and truncates it; a value
 * with a fraction, or beyond an int, is an error here. */
static mt_status to_ints(const double *v, int n, int *out, const char *name,
                         const mt__decl_site *site, mt_error *err)
{
    int i;
    for (i = 0; i < n; ++i) {
        if (v[i] != floor(v[i]) || v[i] < (double)INT_MIN || v[i] > (double)INT_MAX) {
            char num[64];
            snprintf(num, sizeof num, "%.17g", v[i]);
            return decl_error(err, MT_ERR_INVALID, site, name,
                              "value %s is not an integer", num);
        }
        out[i] = (int)v[i];
    }
    return MT_OK;
}

static mt_status to_bools(const char *const *s, int n, int *out, const char *name,
                          const mt__decl_site *site, mt_error *err)
{
    int i;
    for (i = 0; i < n; ++i) {
        if (strcmp(s[i], "true") == 0)
            out[i] = 1;
        else if (strcmp(s[i], "false") == 0)
            out[i] = 0;
        else
            return decl_error(err, MT_ERR_INVALID, site, name,
                              "expected \"true\" or \"false\", found \"%.60s\"", s[i]);
    }
    return MT_OK;
}

/* "spectrum" with numbers: wavelength (nm) / value pairs, one spectrum. */
static mt_status sampled_rgb(const double *v, int n, double *rgb)
{
    double *lambda = mt__malloc((size_t)n / 2 * sizeof *lambda);
    double *vals = mt__malloc((size_t)n / 2 * sizeof *vals);
    mt_rgb c;
    int i;
    if (!lambda || !vals) {
        mt__free(lambda);
        mt__free(vals);
        return MT_ERR_NOMEM;
    }
    for (i = 0; i < n / 2; ++i) {
        lambda[i] = v[2 * i];
        vals[i] = v[2 * i + 1];
    }
    c = mt_spectrum_from_sampled(lambda, vals, n / 2);
    mt__free(lambda);
    mt__free(vals);
    for (i = 0; i < 3; ++i) rgb[i] = c.c[i];
    return MT_OK;
}

/* "spectrum" with strings: SPD files, relative to the statement's directory. */
static mt_status spd_rgb(const char *file, const char *name, const mt__decl_site *site,
                         double *rgb, mt_error *err)
{
    char path[4096];
    double *lambda, *vals;
    mt_rgb c;
    mt_error why;
    int n, i;
    mt_status st;
    mt_error_clear(&why);
    st = mt__path_join(site->dir, file, path, sizeof path, &why);
    if (st == MT_OK) st = mt_spd_read(path, &lambda, &vals, &n, &why);
    if (st != MT_OK) {
        char where[64] = "";
        if (why.line > 0) snprintf(where, sizeof where, " (line %d)", why.line);
        mt_error_param(err, st, name, "SPD file \"%.300s\"%s: %.150s", file, where, why.message);
        mt_error_locate(err, site->file, site->line, site->column);
        return st;
    }
    c = mt_spectrum_from_sampled(lambda, vals, n);
    mt__free(lambda);
    mt__free(vals);
    for (i = 0; i < 3; ++i) rgb[i] = c.c[i];
    return MT_OK;
}

/* The values of a colour type as RGB triples (n elements). */
static mt_status colours(decl_kind k, const mt__decl_values *v, const char *name,
                         const mt__decl_site *site, double *rgb, int n, mt_error *err)
{
    int i, j;
    for (i = 0; i < n; ++i) {
        double *out = rgb + 3 * i;
        mt_status st = MT_OK;
        if (k == K_RGB) {
            for (j = 0; j < 3; ++j) out[j] = v->nums[3 * i + j];
        } else if (k == K_XYZ) {
            mt_rgb c = mt_xyz_to_rgb(v->nums + 3 * i);
            for (j = 0; j < 3; ++j) out[j] = c.c[j];
        } else if (k == K_BLACKBODY) {
            double kelvin = v->nums[2 * i], scale = v->nums[2 * i + 1];
            mt_rgb c;
            char num[64];
            snprintf(num, sizeof num, "%g", kelvin);
            if (!(kelvin > 0))
                return decl_error(err, MT_ERR_INVALID, site, name,
                                  "blackbody temperature %s K is not positive (pbrt-v2 gives "
                                  "black)", num);
            if (mt__blackbody_rgb(kelvin, scale, &c) != MT_OK)
                return decl_error(err, MT_ERR_INVALID, site, name,
                                  "blackbody at %s K overflows: temperature too low", num);
            for (j = 0; j < 3; ++j) out[j] = c.c[j];
        } else if (k == K_SPECTRUM && v->nstrs) {
            st = spd_rgb(v->strs[i], name, site, out, err);
        } else {
            st = sampled_rgb(v->nums, v->nnums, out);
            if (st != MT_OK) return decl_error(err, st, site, name, "out of memory");
        }
        if (st != MT_OK) return st;
    }
    return MT_OK;
}

/* Values per element of kind k (pbrt-v2: triples, blackbody pairs, and a
 * sampled spectrum's pairs all make one spectrum), 0 for "any count". */
static int group_of(decl_kind k, const mt__decl_values *v)
{
    switch (k) {
    case K_POINT: case K_VECTOR: case K_NORMAL: case K_RGB: case K_XYZ: return 3;
    case K_BLACKBODY: return 2;
    case K_SPECTRUM: return v->nstrs ? 1 : 2;
    default: return 1;
    }
}

static mt_param_type stored_type(decl_kind k)
{
    switch (k) {
    case K_FLOAT: return MT_PARAM_FLOAT;
    case K_INT: return MT_PARAM_INTEGER;
    case K_BOOL: return MT_PARAM_BOOL;
    case K_STRING: return MT_PARAM_STRING;
    case K_POINT: return MT_PARAM_POINT;
    case K_VECTOR: return MT_PARAM_VECTOR;
    case K_NORMAL: return MT_PARAM_NORMAL;
    case K_TEXTURE: return MT_PARAM_TEXTURE;
    default: return MT_PARAM_SPECTRUM;
    }
}

static mt_status check_values(decl_kind k, const split_decl *d, const mt__decl_values *v,
                              const mt__decl_site *site, mt_error *err)
{
    int wants_strings = k == K_STRING || k == K_TEXTURE || k == K_BOOL;
    int n = v->nstrs ? v->nstrs : v->nnums, group = group_of(k, v);
    if (n == 0)
        return decl_error(err, MT_ERR_PARSE, site, d->name, "\"%s\" has no values", d->type);
    if (v->nstrs && v->nnums)
        return decl_error(err, MT_ERR_PARSE, site, d->name,
                          "\"%s\" mixes strings and numbers", d->type);
    if (k != K_SPECTRUM && wants_strings != (v->nstrs > 0))
        return decl_error(err, MT_ERR_PARSE, site, d->name,
                          "type \"%s\" takes %s, found %s", d->type,
                          wants_strings ? "quoted strings" : "numbers",
                          wants_strings ? "numbers" : "strings");
    if (k == K_TEXTURE && n != 1)
        return decl_error(err, MT_ERR_INVALID, site, d->name,
                          "\"%s\" takes one texture name, found %d", d->type, n);
    if (n % group != 0)
        return decl_error(err, MT_ERR_INVALID, site, d->name,
                          "\"%s\" takes values in %s, found %d value%s", d->type,
                          group == 2 ? "pairs" : "threes", n, n == 1 ? "" : "s");
    return MT_OK;
}

mt_status mt__param_declare(mt_paramset *ps, const char *decl, const mt__decl_values *v,
                            const mt__decl_site *site, mt_error *err)
{
    split_decl d;
    decl_kind k = K_FLOAT;
    mt_param p;
    int i, n, found = 0, *ints = NULL;
    double *reals = NULL;
    mt_status st;
    if (split(decl, &d))
        for (i = 0; i < N_TYPE_WORDS && !found; ++i)
            if (strcmp(d.type, type_words[i].word) == 0) {
                k = type_words[i].kind;
                found = 1;
            }
    if (!found) return unknown_type(decl, &d, site, err);
    st = check_values(k, &d, v, site, err);
    if (st != MT_OK) return st;

    memset(&p, 0, sizeof p);
    p.name = d.name;
    p.type = stored_type(k);
    p.type_name = d.type;
    p.file = site->file;
    p.line = site->line;
    p.column = site->column;
    p.dir = site->dir;
    n = v->nstrs ? v->nstrs : v->nnums;
    switch (k) {
    case K_FLOAT: case K_POINT: case K_VECTOR: case K_NORMAL:
        p.nvalues = n;
        p.doubles = v->nums;
        break;
    case K_STRING: case K_TEXTURE:
        p.nvalues = n;
        p.strings = v->strs;
        break;
    case K_INT: case K_BOOL:
        ints = mt__malloc((size_t)n * sizeof *ints);
        if (!ints) return decl_error(err, MT_ERR_NOMEM, site, d.name, "out of memory");
        st = k == K_INT ? to_ints(v->nums, n, ints, d.name, site, err)
                        : to_bools(v->strs, n, ints, d.name, site, err);
        p.nvalues = n;
        p.ints = ints;
        break;
    default: { /* colours, as RGB triples */
        /* a sampled spectrum's pairs make one spectrum (AddSampledSpectrum) */
        int nspectra = k == K_SPECTRUM && !v->nstrs ? 1 : n / group_of(k, v);
        reals = mt__malloc((size_t)nspectra * 3 * sizeof *reals);
        if (!reals) return decl_error(err, MT_ERR_NOMEM, site, d.name, "out of memory");
        st = colours(k, v, d.name, site, reals, nspectra, err);
        p.nvalues = 3 * nspectra;
        p.doubles = reals;
        break;
    }
    }
    if (st == MT_OK) st = mt_paramset_add(ps, &p, err);
    mt__free(ints);
    mt__free(reals);
    return st;
}
