/*
 * PFM (portable float map, Netpbm): "PF" (RGB) or "Pf" (grayscale), width,
 * height and a scale whose sign gives the byte order (negative: little
 * endian) and whose magnitude multiplies the values (as pbrt-v2's
 * ReadImagePFM applies it when it is not 1), then 32-bit floats, rows
 * bottom to top; materia's image has row 0 at the top. pbrt-v2's reader
 * (imageio.cpp ReadImagePFM) keeps the rows in file order, i.e. upside
 * down: that is what a mode without MT_FIX_PFM_ROWS reads. "Pf" is one
 * channel, which pbrt-v2 makes gray RGB as the image map cache does here;
 * the scale is parsed as a float, as its sscanf("%f") does.
 *
 * Every size is checked against the file before anything is allocated, so a
 * corrupt header gives an error, never a huge allocation or a short read.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/alloc.h"
#include "image/formats.h"
#include "image/imageio.h"

#define HEADER_MAX 256

static int is_space(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/* The next whitespace-separated token of buf[*pos..n), NUL-terminated into
 * tok; 0 when there is none or it is too long. */
static int next_token(const char *buf, size_t n, size_t *pos, char *tok, size_t size)
{
    size_t p = *pos, k = 0;
    while (p < n && is_space((unsigned char)buf[p])) p++;
    while (p < n && !is_space((unsigned char)buf[p])) {
        if (k + 1 >= size) return 0;
        tok[k++] = buf[p++];
    }
    tok[k] = '\0';
    *pos = p;
    return k > 0;
}

static int parse_size(const char *tok, long long *out)
{
    long long v = 0;
    const char *p = tok;
    if (!*p) return 0;
    for (; *p; p++) {
        if (*p < '0' || *p > '9') return 0;
        v = v * 10 + (*p - '0');
        if (v > (long long)MT__IMAGE_MAX_SIDE * 16) return 0;
    }
    *out = v;
    return 1;
}

static float decode_float(const unsigned char *b, int little)
{
    uint32_t u = little ? (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                              (uint32_t)b[3] << 24
                        : (uint32_t)b[3] | (uint32_t)b[2] << 8 | (uint32_t)b[1] << 16 |
                              (uint32_t)b[0] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static mt_status read_pixels(FILE *f, const char *path, long header_len, long long file_size,
                             float scale, int bottom_up, mt_image *img, mt_error *err)
{
    size_t rowbytes = (size_t)img->width * (size_t)img->channels * 4, i;
    int little = scale < 0, y;
    float mag = fabsf(scale);
    unsigned char *row;
    if (fseek(f, header_len, SEEK_SET) != 0)
        return mt_error_set(err, MT_ERR_IO, "%s: cannot seek: %s", path, strerror(errno));
    row = mt__malloc(rowbytes);
    if (!row) return mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory", path);
    /* the file's first row is the image's bottom row (or, as pbrt-v2 reads
     * it, its top row) */
    for (y = 0; y < img->height; y++) {
        size_t at = bottom_up ? (size_t)(img->height - 1 - y) : (size_t)y;
        float *dst = img->data + at * (size_t)img->width * (size_t)img->channels;
        if (fread(row, 1, rowbytes, f) != rowbytes) {
            mt__free(row);
            return mt_error_set(err, MT_ERR_IO, "%s: read error", path);
        }
        for (i = 0; i < rowbytes / 4; i++) {
            float v = decode_float(row + 4 * i, little);
            dst[i] = mag != 1.f ? v * mag : v;
        }
    }
    mt__free(row);
    return MT_OK;
}

mt_status mt__pfm_read(const char *path, mt_mode mode, mt_image *img, mt_error *err)
{
    char buf[HEADER_MAX], tok[32];
    size_t n, pos = 0;
    long long w = 0, h = 0, file_size;
    int channels;
    float scale;
    char *end;
    mt_status st;
    FILE *f = fopen(path, "rb");
    if (!f) return mt_error_set(err, MT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    if (fseek(f, 0, SEEK_END) != 0 || (file_size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return mt_error_set(err, MT_ERR_IO, "%s: cannot determine the file size", path);
    }
    n = fread(buf, 1, sizeof buf, f);
    st = MT_ERR_FORMAT;
    if (!next_token(buf, n, &pos, tok, sizeof tok) ||
        (strcmp(tok, "PF") != 0 && strcmp(tok, "Pf") != 0)) {
        mt_error_set(err, st, "%s: not a PFM file (no \"PF\" or \"Pf\" signature)", path);
        goto done;
    }
    channels = tok[1] == 'F' ? 3 : 1;
    if (!next_token(buf, n, &pos, tok, sizeof tok) || !parse_size(tok, &w) ||
        !next_token(buf, n, &pos, tok, sizeof tok) || !parse_size(tok, &h)) {
        mt_error_set(err, st, "%s: bad PFM header (width and height)", path);
        goto done;
    }
    if (!next_token(buf, n, &pos, tok, sizeof tok) || (scale = strtof(tok, &end), *end) ||
        !isfinite(scale) || scale == 0) {
        mt_error_set(err, st, "%s: bad PFM header (the scale must be a non-zero number)", path);
        goto done;
    }
    /* exactly one whitespace character separates the header from the data */
    if (pos >= n || !is_space((unsigned char)buf[pos])) {
        mt_error_set(err, st, "%s: bad PFM header (no data after the scale)", path);
        goto done;
    }
    pos++;
    st = mt__image_check_size(path, w, h, channels, err);
    /* the data the header promises must be in the file before the image is
     * allocated */
    if (st == MT_OK && (unsigned long long)(file_size - (long long)pos) <
                           (unsigned long long)w * (unsigned long long)h * (unsigned)channels * 4)
        st = mt_error_set(err, MT_ERR_FORMAT,
                          "%s: truncated: %lld x %lld pixels need %llu bytes of data, the file "
                          "has %lld",
                          path, w, h, (unsigned long long)w * (unsigned long long)h * (unsigned)channels * 4,
                          file_size - (long long)pos);
    if (st == MT_OK) st = mt_image_create(img, (int)w, (int)h, channels, err);
    if (st == MT_OK)
        st = read_pixels(f, path, (long)pos, file_size, scale, (mode & MT_FIX_PFM_ROWS) != 0,
                         img, err);
done:
    fclose(f);
    return st;
}

static void encode_float(unsigned char *b, float v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    b[0] = (unsigned char)(u & 0xff);
    b[1] = (unsigned char)(u >> 8 & 0xff);
    b[2] = (unsigned char)(u >> 16 & 0xff);
    b[3] = (unsigned char)(u >> 24 & 0xff);
}

/* Little endian (scale -1), as pbrt-v2 writes on x86; RGBA loses A. */
mt_status mt__pfm_write(const char *path, const mt_image *img, mt_error *err)
{
    int nc = img->channels == 1 ? 1 : 3, x, y, c, ok;
    size_t rowbytes = (size_t)img->width * (size_t)nc * 4;
    unsigned char *row;
    mt__tmpfile tmp;
    mt_status st = mt__tmpfile_open(&tmp, path, err);
    if (st == MT_OK) st = mt__tmpfile_stdio(&tmp, path, err);
    if (st != MT_OK) return st;
    row = mt__malloc(rowbytes);
    if (!row) {
        mt__tmpfile_abort(&tmp);
        return mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory", path);
    }
    ok = fprintf(tmp.fp, "%s\n%d %d\n-1\n", nc == 1 ? "Pf" : "PF", img->width, img->height) > 0;
    for (y = img->height - 1; ok && y >= 0; y--) {
        const float *src = img->data + (size_t)y * (size_t)img->width * (size_t)img->channels;
        for (x = 0; x < img->width; x++)
            for (c = 0; c < nc; c++)
                encode_float(row + 4 * ((size_t)x * (size_t)nc + (size_t)c),
                             src[(size_t)x * (size_t)img->channels + (size_t)c]);
        ok = fwrite(row, 1, rowbytes, tmp.fp) == rowbytes;
    }
    mt__free(row);
    if (!ok) {
        mt__tmpfile_abort(&tmp);
        return mt_error_set(err, MT_ERR_IO, "%s: write failed: %s", path, strerror(errno));
    }
    return mt__tmpfile_commit(&tmp, path, err);
}

static mt_status write_plain(const char *path, const mt_image *img, const mt_image_attr *attrs, int nattrs,
                             mt_error *err)
{
    return mt__pfm_write(path, img, err); /* PFM has no attributes */
}

const mt__image_format mt__pfm_format = {
    .ext = ".pfm",
    .name = "PFM",
    /* no .omit: every build has PFM (it needs no library) */
    .read = mt__pfm_read,
    .write = write_plain,
};
