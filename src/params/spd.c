/*
 * SPD files: the two-column text of pbrt-v2's spds/ directory, wavelength in
 * nm then value, read as pbrt-v2's ReadFloatFile reads them (a flat list of
 * numbers, '#' to the end of the line a comment) -- except that anything that
 * is not a number, and a wavelength without its value, are errors here
 * (pbrt-v2 warns and carries on).
 */
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "core/alloc.h"
#include "params/report.h"
#include "materia/spectrum.h"
#include "params/path.h"

typedef struct spd_list {
    double *lambda, *values;
    int n, cap_lambda, cap_values;
} spd_list;

static int spd_push(spd_list *l, double lambda, double v)
{
    double *a = mt__grow(l->lambda, &l->cap_lambda, l->n + 1, sizeof *a), *b;
    if (!a) return 0;
    l->lambda = a;
    b = mt__grow(l->values, &l->cap_values, l->n + 1, sizeof *b);
    if (!b) return 0;
    l->values = b;
    l->lambda[l->n] = lambda;
    l->values[l->n] = v;
    l->n++;
    return 1;
}

/* One whitespace-delimited word as a finite number, or 0. */
static int spd_number(const char *s, size_t n, double *out)
{
    char word[64], *end;
    if (n == 0 || n >= sizeof word) return 0;
    memcpy(word, s, n);
    word[n] = '\0';
    errno = 0;
    *out = strtod(word, &end);
    return end == word + n && isfinite(*out) && !(errno == ERANGE && *out != 0);
}

static mt_status spd_parse(const char *path, const char *text, size_t len, spd_list *l,
                           mt_error *err)
{
    size_t i = 0;
    int line = 1, have_lambda = 0, lambda_line = 0;
    double lambda = 0;
    while (i < len) {
        unsigned char c = (unsigned char)text[i];
        size_t start;
        double v;
        if (c == '\n') {
            line++;
            i++;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\r') {
            i++;
            continue;
        }
        if (c == '#') {
            while (i < len && text[i] != '\n') i++;
            continue;
        }
        start = i;
        while (i < len && !isspace((unsigned char)text[i]) && text[i] != '#' && text[i] != '\0')
            i++;
        if (i == start) i++; /* a NUL byte: a word of its own */
        if (!spd_number(text + start, i - start, &v)) {
            mt_error_locate(err, path, line, 0);
            return mt_error_set(err, MT_ERR_FORMAT,
                                "SPD file: expected a number (wavelength or value), found \"%.*s\"",
                                (int)(i - start > 40 ? 40 : i - start), text + start);
        }
        if (!have_lambda) {
            lambda = v;
            lambda_line = line;
            have_lambda = 1;
        } else {
            if (!spd_push(l, lambda, v)) {
                mt_error_locate(err, path, line, 0);
                return mt_error_set(err, MT_ERR_NOMEM, "SPD file: out of memory");
            }
            have_lambda = 0;
        }
    }
    if (have_lambda) {
        mt_error_locate(err, path, lambda_line, 0);
        return mt_error_set(err, MT_ERR_FORMAT, "SPD file: wavelength %g has no value", lambda);
    }
    if (l->n == 0) {
        mt_error_locate(err, path, 0, 0);
        return mt_error_set(err, MT_ERR_FORMAT, "SPD file holds no wavelength/value pairs");
    }
    return MT_OK;
}

mt_status mt_spd_read(const char *path, double **lambda, double **values, int *n, mt_error *err)
{
    spd_list l = {NULL, NULL, 0, 0, 0};
    char *text;
    size_t len;
    mt_status st;
    mt_error_clear(err);
    *lambda = *values = NULL;
    *n = 0;
    st = mt__read_file(path, &text, &len, err);
    if (st != MT_OK) {
        mt_error_locate(err, path, 0, 0);
        return st;
    }
    st = spd_parse(path, text, len, &l, err);
    mt__free(text);
    if (st != MT_OK) {
        mt__free(l.lambda);
        mt__free(l.values);
        return st;
    }
    *lambda = l.lambda;
    *values = l.values;
    *n = l.n;
    return MT_OK;
}
