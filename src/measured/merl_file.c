/*
 * The MERL BRDF database's binary format, as pbrt-v2's measured.cpp reads
 * it: three little-endian 32-bit integers (the table's dimensions, whose
 * product pbrt-v2 requires to be 90 * 90 * 180), then the table as
 * little-endian doubles, one channel after the other (red, green, blue),
 * each in pbrt-v2's index order (phi_d fastest, then theta_d, then
 * theta_h). Each value is multiplied by its channel's scale (1/1500,
 * 1.15/1500, 1.66/1500) and clamped from below at 0 (MERL marks missing data
 * with negative values).
 *
 * Stricter than pbrt-v2: a short file (pbrt-v2: an error, and no BRDF),
 * bytes after the table (pbrt-v2 ignores them), dimensions that are not
 * positive (pbrt-v2 multiplies them as given), and values that are NaN,
 * infinite or beyond float's range after scaling (pbrt-v2: NaN becomes 0,
 * infinity stays) are errors naming the file.
 */
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "core/alloc.h"
#include "materia/tools/merl.h"
#include "measured/measured_impl.h"
#include "params/numcheck.h"
#include "params/report.h"

#define VALUES (3 * (size_t)MT_MERL_SAMPLES)
#define CHUNK 4096 /* doubles per read or write */

static uint64_t get_le(const unsigned char *b, int n)
{
    uint64_t v = 0;
    int i;
    for (i = n - 1; i >= 0; --i) v = (v << 8) | b[i];
    return v;
}

static void put_le(unsigned char *b, uint64_t v, int n)
{
    int i;
    for (i = 0; i < n; ++i, v >>= 8) b[i] = (unsigned char)(v & 0xff);
}

static double get_double(const unsigned char *b)
{
    uint64_t u = get_le(b, 8);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static mt_status bad(mt_error *err, mt_status st, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static mt_status bad(mt_error *err, mt_status st, const char *path, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return mt__fail_at(err, st, path, 0, 0, "MERL file: %s", msg);
}

static mt_status read_header(FILE *f, const char *path, mt_error *err)
{
    unsigned char b[12];
    size_t got = fread(b, 1, sizeof b, f);
    int32_t d[3];
    int i;
    long long n = 1;
    if (got < sizeof b)
        return bad(err, MT_ERR_FORMAT, path,
                   "truncated: expected a 12-byte header (three 32-bit dimensions), found %lu "
                   "bytes", (unsigned long)got);
    for (i = 0; i < 3; ++i) {
        d[i] = (int32_t)(uint32_t)get_le(b + 4 * i, 4);
        /* each factor is at most 2^31 and n stays within 2^31 * MT_MERL_SAMPLES */
        if (n <= MT_MERL_SAMPLES) n *= d[i] > 0 ? d[i] : 0;
    }
    if (n != MT_MERL_SAMPLES)
        return bad(err, MT_ERR_FORMAT, path,
                   "dimensions %ld x %ld x %ld do not make pbrt-v2's table of %d x %d x %d = %d "
                   "entries", (long)d[0], (long)d[1], (long)d[2], MT_MERL_THETA_H,
                   MT_MERL_THETA_D, MT_MERL_PHI_D, MT_MERL_SAMPLES);
    return MT_OK;
}

static mt_status truncated(mt_error *err, const char *path, unsigned long values, int partial)
{
    return bad(err, MT_ERR_FORMAT, path,
               "truncated: expected %lu values (3 channels of %d doubles), found %lu%s",
               (unsigned long)VALUES, MT_MERL_SAMPLES, values, partial ? " and part of another" : "");
}

/* The 3 * MT_MERL_SAMPLES values, scaled and clamped into table. */
static mt_status read_values(FILE *f, const char *path, mt_real *table, mt_error *err)
{
    static const char *const channel[] = {"red", "green", "blue"};
    unsigned char buf[8 * CHUNK];
    size_t k = 0, j;
    while (k < VALUES) {
        size_t want = VALUES - k < CHUNK ? VALUES - k : CHUNK;
        size_t got = fread(buf, 1, 8 * want, f);
        for (j = 0; j < got / 8; ++j, ++k) {
            size_t c = k / MT_MERL_SAMPLES, i = k % MT_MERL_SAMPLES;
            double v = get_double(buf + 8 * j) * (double)mt__merl_scale[c];
            if (!mt__fits_real(v))
                return bad(err, MT_ERR_FORMAT, path,
                           "%s value of entry %lu (theta_h %lu, theta_d %lu, phi_d %lu) is %g "
                           "after scaling (must be finite and within float's range)", channel[c],
                           (unsigned long)i, (unsigned long)(i / (MT_MERL_THETA_D * MT_MERL_PHI_D)),
                           (unsigned long)(i / MT_MERL_PHI_D % MT_MERL_THETA_D),
                           (unsigned long)(i % MT_MERL_PHI_D), v);
            /* pbrt-v2: max(0., value * scale) */
            table[3 * i + c] = (mt_real)(v > 0 ? v : 0);
        }
        if (got < 8 * want) {
            if (ferror(f))
                return bad(err, MT_ERR_IO, path, "read error: %s", strerror(errno));
            return truncated(err, path, (unsigned long)k, got % 8 != 0);
        }
    }
    {
        unsigned long extra = 0;
        while (fgetc(f) != EOF) extra++;
        if (extra)
            return bad(err, MT_ERR_FORMAT, path, "%lu bytes of trailing data after the %lu values",
                       extra, (unsigned long)VALUES);
    }
    return MT_OK;
}

/* A file too short for the table is refused before the table (17.5 MB in
 * float, 35 MB in double) is allocated: a 12-byte header alone asked for it
 * (fuzzing's merl target spent its time allocating and poisoning it). A
 * stream whose size cannot be told is read as it comes. The position is
 * left just after the header. */
static mt_status check_size(FILE *f, const char *path, mt_error *err)
{
    long size;
    if (fseek(f, 0, SEEK_END) != 0) {
        clearerr(f); /* not seekable: still just after the header */
        return MT_OK;
    }
    size = ftell(f);
    if (size < 12 || fseek(f, 12, SEEK_SET) != 0)
        return bad(err, MT_ERR_IO, path, "cannot seek: %s", strerror(errno));
    if ((unsigned long)(size - 12) < 8 * VALUES)
        return truncated(err, path, (unsigned long)(size - 12) / 8, (size - 12) % 8 != 0);
    return MT_OK;
}

mt_measured *mt__merl_file_read(const char *path, mt_error *err)
{
    FILE *f = fopen(path, "rb");
    mt_real *table = NULL;
    mt_status st;
    if (!f) {
        bad(err, MT_ERR_IO, path, "cannot open \"%s\": %s", path, strerror(errno));
        return NULL;
    }
    st = read_header(f, path, err);
    if (st == MT_OK) st = check_size(f, path, err);
    if (st == MT_OK) {
        table = mt__malloc(VALUES * sizeof *table);
        st = table ? read_values(f, path, table, err)
                   : bad(err, MT_ERR_NOMEM, path, "out of memory for the table");
    }
    fclose(f);
    if (st != MT_OK) {
        mt__free(table);
        return NULL;
    }
    return mt__measured_halfangle(table, err);
}

static mt_status write_all(FILE *f, const double *values)
{
    unsigned char buf[8 * CHUNK];
    size_t k = 0, j, n;
    put_le(buf, MT_MERL_THETA_H, 4);
    put_le(buf + 4, MT_MERL_THETA_D, 4);
    put_le(buf + 8, MT_MERL_PHI_D, 4);
    if (fwrite(buf, 1, 12, f) != 12) return MT_ERR_IO;
    while (k < VALUES) {
        n = VALUES - k < CHUNK ? VALUES - k : CHUNK;
        for (j = 0; j < n; ++j) {
            uint64_t u;
            memcpy(&u, &values[k + j], sizeof u);
            put_le(buf + 8 * j, u, 8);
        }
        if (fwrite(buf, 8, n, f) != n) return MT_ERR_IO;
        k += n;
    }
    return MT_OK;
}

mt_status mt_merl_write(const char *path, const double *values, mt_error *err)
{
    size_t k, len;
    char *tmp;
    int fd;
    FILE *f;
    mt_status st;
    mt_error_clear(err);
    if (!path || !path[0]) return mt_error_set(err, MT_ERR_INVALID, "MERL file: no file name");
    for (k = 0; k < VALUES; ++k)
        if (!isfinite(values[k]))
            return bad(err, MT_ERR_INVALID, path, "value %lu to write is not finite",
                       (unsigned long)k);
    len = strlen(path);
    tmp = mt__malloc(len + 8);
    if (!tmp) return bad(err, MT_ERR_NOMEM, path, "out of memory");
    memcpy(tmp, path, len);
    memcpy(tmp + len, ".XXXXXX", 8);
    fd = mkstemp(tmp);
    if (fd < 0) {
        st = bad(err, MT_ERR_IO, path, "cannot create a temporary file next to \"%s\": %s", path,
                 strerror(errno));
        mt__free(tmp);
        return st;
    }
    f = fdopen(fd, "wb");
    if (!f) close(fd);
    st = f && fchmod(fd, 0644) == 0 ? write_all(f, values) : MT_ERR_IO;
    if (f && fclose(f) != 0) st = MT_ERR_IO;
    if (st == MT_OK && rename(tmp, path) != 0) st = MT_ERR_IO;
    if (st != MT_OK) {
        bad(err, st, path, "cannot write \"%s\": %s", path, strerror(errno));
        unlink(tmp);
    }
    mt__free(tmp);
    return st;
}
