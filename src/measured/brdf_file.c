/*
 * pbrt-v2's irregular isotropic BRDF text format (.brdf; measured.cpp, read
 * with floatfile.cpp ReadFloatFile): numbers separated by white space, '#' a
 * comment to the end of the line. The first number is the count of
 * wavelengths n, then n wavelengths in nm, then samples of 4 + n numbers:
 * theta_i, phi_i, theta_o, phi_o (radians) and the n spectral values. Each
 * sample's spectrum becomes RGB by FromSampled and its direction pair goes
 * to BRDFRemap(wo, wi), with wo = SphericalDirection(sin theta_o,
 * cos theta_o, phi_o) and wi likewise, as pbrt-v2 does.
 *
 * Stricter than pbrt-v2, which warns about unexpected text and reads on
 * (with undefined behaviour for an empty or short file): anything that is not
 * a number of pbrt-v2's alphabet (digits . e + -), a comment that touches a
 * number (pbrt-v2 would read the comment's digits as data), a count of
 * wavelengths that is not a positive integer, a wavelength that is not
 * positive, a polar angle outside [0, pi/2], a negative spectral value, a
 * number beyond float's range, and a value count that does not make whole
 * samples are errors naming the file and line.
 */
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "core/alloc.h"
#include "materia/sampling.h"
#include "materia/spectrum.h"
#include "measured/measured_impl.h"
#include "params/numcheck.h"
#include "params/path.h"
#include "params/report.h"

#define ANGLE_SLACK 1e-5 /* radians: pi/2 written with 6 decimals is 1.570796(3) */

typedef struct number_list {
    mt_real *v;
    int *line;
    int n, cap_v, cap_line;
} number_list;

static int is_number_char(int c)
{
    return isdigit(c) || c == '.' || c == 'e' || c == '-' || c == '+';
}

static mt_status push_number(number_list *nb, mt_real v, int line)
{
    mt_real *a;
    int *b;
    if (nb->n >= MT__MAX_VALUES) return MT_ERR_LIMIT;
    a = mt__grow(nb->v, &nb->cap_v, nb->n + 1, sizeof *a);
    if (!a) return MT_ERR_NOMEM;
    nb->v = a;
    b = mt__grow(nb->line, &nb->cap_line, nb->n + 1, sizeof *b);
    if (!b) return MT_ERR_NOMEM;
    nb->line = b;
    nb->v[nb->n] = v;
    nb->line[nb->n++] = line;
    return MT_OK;
}

/* ReadFloatFile's tokens, each checked to be a whole number within float. */
static mt_status tokenize(const char *path, const char *text, size_t len, number_list *nb,
                          mt_error *err)
{
    size_t i = 0;
    int line = 1;
    while (i < len) {
        unsigned char c = (unsigned char)text[i];
        size_t start = i, k;
        char word[64], *end;
        double d;
        mt_status st;
        if (c == '\n') line++;
        if (isspace(c)) {
            i++;
            continue;
        }
        if (c == '#') {
            while (i < len && text[i] != '\n') i++;
            continue;
        }
        while (i < len && !isspace((unsigned char)text[i]) && text[i] != '#') i++;
        if (i == start) i++; /* keeps a NUL byte as a word of its own */
        for (k = start; k < i && is_number_char((unsigned char)text[k]); ++k) {}
        if (c == '\0')
            return mt__fail_at(err, MT_ERR_PARSE, path, line, 0,
                               "measured BRDF file: expected a number, found a NUL byte (a "
                               "binary file?)");
        if (k < i || i - start >= sizeof word)
            return mt__fail_at(err, MT_ERR_PARSE, path, line, 0,
                               "measured BRDF file: expected a number, found \"%.*s\"",
                               (int)(i - start > 40 ? 40 : i - start), text + start);
        memcpy(word, text + start, i - start);
        word[i - start] = '\0';
        errno = 0;
        d = strtod(word, &end);
        if (end != word + (i - start))
            return mt__fail_at(err, MT_ERR_PARSE, path, line, 0,
                               "measured BRDF file: malformed number \"%s\"", word);
        if (!mt__fits_real(d))
            return mt__fail_at(err, MT_ERR_PARSE, path, line, 0,
                               "measured BRDF file: number %s is beyond float's range", word);
        if (i < len && text[i] == '#')
            return mt__fail_at(err, MT_ERR_PARSE, path, line, 0,
                               "measured BRDF file: a comment touches the number %s (pbrt-v2 "
                               "would read the comment's digits as data)", word);
        st = push_number(nb, (mt_real)d, line);
        if (st == MT_ERR_LIMIT)
            return mt__fail_at(err, st, path, line, 0,
                               "measured BRDF file: more than %d numbers", MT__MAX_VALUES);
        if (st != MT_OK)
            return mt__fail_at(err, st, path, line, 0, "measured BRDF file: out of memory");
    }
    return MT_OK;
}

/* The header: the wavelength count and the wavelengths, checked. */
static mt_status header(const char *path, const number_list *nb, int *nwl, mt_error *err)
{
    mt_real c;
    int i;
    if (nb->n == 0)
        return mt__fail_at(err, MT_ERR_FORMAT, path, 0, 0,
                           "measured BRDF file holds no numbers (expected the number of "
                           "wavelengths, the wavelengths, then the samples)");
    c = nb->v[0];
    if (!(c >= 1 && c <= MT__MAX_VALUES) || c != mt_floor(c))
        return mt__fail_at(err, MT_ERR_FORMAT, path, nb->line[0], 0,
                           "measured BRDF file: the number of wavelengths must be a positive "
                           "integer, found %g", (double)c);
    *nwl = (int)c;
    if (*nwl > nb->n - 1)
        return mt__fail_at(err, MT_ERR_FORMAT, path, nb->line[nb->n - 1], 0,
                           "measured BRDF file is truncated: expected %d wavelengths, found %d "
                           "numbers after the count", *nwl, nb->n - 1);
    for (i = 1; i <= *nwl; ++i)
        if (!(nb->v[i] > 0))
            return mt__fail_at(err, MT_ERR_FORMAT, path, nb->line[i], 0,
                               "measured BRDF file: wavelength %d is %g nm (must be positive)",
                               i, (double)nb->v[i]);
    return MT_OK;
}

/* One sample's numbers (4 angles, nwl values) checked; *bad names the
 * first wrong one. */
static int sample_ok(const mt_real *s, int nwl, int *bad)
{
    int k;
    for (k = 0; k < 4; k += 2)
        if (!(s[k] >= 0 && s[k] <= MT_PI / 2 + (mt_real)ANGLE_SLACK)) {
            *bad = k;
            return 0;
        }
    for (k = 4; k < 4 + nwl; ++k)
        if (s[k] < 0) {
            *bad = k;
            return 0;
        }
    return 1;
}

static mt_status sample_error(const char *path, const number_list *nb, int at, int index, int bad,
                              mt_error *err)
{
    static const char *const angle[] = {"theta_i", "phi_i", "theta_o", "phi_o"};
    double v = (double)nb->v[at + bad];
    if (bad < 4)
        return mt__fail_at(err, MT_ERR_FORMAT, path, nb->line[at + bad], 0,
                           "measured BRDF file: sample %d has %s = %g, outside [0, pi/2]", index,
                           angle[bad], v);
    return mt__fail_at(err, MT_ERR_FORMAT, path, nb->line[at + bad], 0,
                       "measured BRDF file: sample %d has a negative spectral value %g (at %g nm)",
                       index, v, (double)nb->v[1 + bad - 4]);
}

/* The samples: remapped points, RGB values (pbrt-v2 measured.cpp). */
static mt_measured *samples(const char *path, const number_list *nb, int nwl, mt_error *err)
{
    int per = 4 + nwl, rest = nb->n - 1 - nwl, n = rest / per, i, k, bad;
    mt_real *pts;
    mt_rgb *vals;
    double *lambda, *spec;
    if (rest == 0) {
        mt__fail_at(err, MT_ERR_FORMAT, path, nb->line[nb->n - 1], 0,
                    "measured BRDF file has no samples after its %d wavelengths", nwl);
        return NULL;
    }
    if (rest % per != 0) {
        mt__fail_at(err, MT_ERR_FORMAT, path, nb->line[1 + nwl + n * per], 0,
                    "measured BRDF file is truncated or has extra numbers: expected a multiple "
                    "of %d values after the wavelengths (4 angles and %d spectral values per "
                    "sample), found %d: %d whole samples and %d values from this line on", per,
                    nwl, rest, n, rest - n * per);
        return NULL;
    }
    pts = mt__malloc((size_t)n * 3 * sizeof *pts);
    vals = mt__malloc((size_t)n * sizeof *vals);
    lambda = mt__malloc((size_t)nwl * 2 * sizeof *lambda);
    if (!pts || !vals || !lambda) {
        mt__free(pts);
        mt__free(vals);
        mt__free(lambda);
        mt__fail_at(err, MT_ERR_NOMEM, path, 0, 0, "measured BRDF file: out of memory");
        return NULL;
    }
    spec = lambda + nwl;
    for (k = 0; k < nwl; ++k) lambda[k] = nb->v[1 + k];
    for (i = 0; i < n; ++i) {
        int at = 1 + nwl + i * per;
        const mt_real *s = nb->v + at;
        mt_vec3 wo, wi, p;
        if (!sample_ok(s, nwl, &bad)) {
            sample_error(path, nb, at, i + 1, bad, err);
            mt__free(pts);
            mt__free(vals);
            mt__free(lambda);
            return NULL;
        }
        wi = mt_spherical_direction(mt_sin(s[0]), mt_cos(s[0]), s[1]);
        wo = mt_spherical_direction(mt_sin(s[2]), mt_cos(s[2]), s[3]);
        for (k = 0; k < nwl; ++k) spec[k] = s[4 + k];
        p = mt_brdf_remap(wo, wi);
        pts[3 * i] = p.x;
        pts[3 * i + 1] = p.y;
        pts[3 * i + 2] = p.z;
        vals[i] = mt_spectrum_from_sampled(lambda, spec, nwl);
    }
    mt__free(lambda);
    return mt__measured_irregular(pts, vals, n, err);
}

mt_measured *mt__brdf_file_read(const char *path, mt_error *err)
{
    number_list nb;
    char *text;
    size_t len;
    int nwl = 0;
    mt_measured *m = NULL;
    if (mt__read_file(path, &text, &len, err) != MT_OK) {
        mt_error_locate(err, path, 0, 0);
        return NULL;
    }
    memset(&nb, 0, sizeof nb);
    if (tokenize(path, text, len, &nb, err) == MT_OK && header(path, &nb, &nwl, err) == MT_OK)
        m = samples(path, &nb, nwl, err);
    mt__free(text);
    mt__free(nb.v);
    mt__free(nb.line);
    return m;
}
