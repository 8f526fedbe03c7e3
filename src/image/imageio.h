/*
 * Internal: the image file formats behind mt_image_read / mt_image_write, the
 * write-to-a-temporary-then-rename helper they share, and the half-float
 * conversions. Tests include this header to write the files the public
 * writer does not make (half, uint and tiled EXR, 16-bit PNG).
 */
#ifndef MT_IMAGE_IMAGEIO_H
#define MT_IMAGE_IMAGEIO_H

#include <stdint.h>
#include <stdio.h>
#include "materia/image.h"

/* Largest side and largest number of values (width * height * channels) an
 * image may have, and the most memory a reader may ask for to read one (the
 * image and its decode buffers together, checked before any of them is
 * allocated): a corrupt header cannot make the reader allocate more. */
#define MT__IMAGE_MAX_SIDE (1 << 24)
#define MT__IMAGE_MAX_VALUES ((size_t)1 << 29)
#define MT__IMAGE_MAX_BYTES ((size_t)1 << 31)

/* The readers. mode: the MT_IMAGE_MODE_BITS of mt_image_read_mode (PNG has
 * none: pbrt-v2 reads no PNG). */
mt_status mt__exr_read(const char *path, mt_mode mode, mt_image *img, mt_error *err);
mt_status mt__png_read(const char *path, mt_image *img, mt_error *err);
mt_status mt__pfm_read(const char *path, mt_mode mode, mt_image *img, mt_error *err);

/* How an EXR file is written. mt_image_write uses float pixels, ZIP
 * compression, scanlines and a data window at the origin. */
typedef struct mt__exr_options {
    int pixel_type;   /* 0 uint, 1 half, 2 float (OpenEXR's EXR_PIXEL_*) */
    int compression;  /* OpenEXR's EXR_COMPRESSION_* */
    int tile_w, tile_h; /* 0: scanline file */
    int x0, y0;       /* the data window's origin */
    /* NULL: R, G, B (and A), or Y for one channel. Otherwise the name of
     * each image channel's EXR channel, NULL to leave one out (a Y-and-A
     * file, a file with no colour channel). */
    const char *const *names;
} mt__exr_options;
void mt__exr_default_options(mt__exr_options *o);
mt_status mt__exr_write(const char *path, const mt_image *img, const mt_image_attr *attrs,
                        int nattrs, const mt__exr_options *opt, mt_error *err);
/* bits: 8 or 16. */
mt_status mt__png_write(const char *path, const mt_image *img, int bits, mt_error *err);
mt_status mt__pfm_write(const char *path, const mt_image *img, mt_error *err);

/* A file created next to its final path (same directory, so that rename()
 * is atomic), opened with O_EXCL so that concurrent writers never share one.
 * mt__tmpfile_stdio gives it a stdio stream (which then owns the
 * descriptor); commit flushes, closes and renames it into place; abort
 * closes and removes it. */
typedef struct mt__tmpfile {
    char *path; /* the temporary file's name, allocated */
    int fd;
    FILE *fp;   /* NULL until mt__tmpfile_stdio */
} mt__tmpfile;
mt_status mt__tmpfile_open(mt__tmpfile *t, const char *final_path, mt_error *err);
mt_status mt__tmpfile_stdio(mt__tmpfile *t, const char *final_path, mt_error *err);
mt_status mt__tmpfile_commit(mt__tmpfile *t, const char *final_path, mt_error *err);
void mt__tmpfile_abort(mt__tmpfile *t);

/* IEEE 754 binary16 <-> binary32; float_to_half rounds to nearest even and
 * overflows to infinity as OpenEXR's half does. */
float mt__half_to_float(uint16_t h);
uint16_t mt__float_to_half(float f);
/* f as pbrt-v2's HALF frame buffer holds it (erratum exr-half): rounded to
 * half, finite values beyond +-65504 saturated there. */
float mt__float_through_half(float f);

/* Checks a size read from a file: sides in [1, MT__IMAGE_MAX_SIDE] and at
 * most MT__IMAGE_MAX_VALUES values. MT_ERR_FORMAT naming path otherwise. */
mt_status mt__image_check_size(const char *path, long long w, long long h, int channels,
                               mt_error *err);

#endif
