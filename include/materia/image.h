/*
 * materia/image.h -- float images and their files: OpenEXR (through the C
 * API, OpenEXRCore), PNG (libpng) and PFM.
 *
 * Pixels are stored as float, interleaved, row 0 at the top. Reading maps
 * EXR channels by name (files store them sorted: B, G, R): R, G, B give RGB
 * (a missing one reads 0), with A RGBA, Y alone one channel, Y and A RGBA;
 * half, float and uint channels, scanline and tiled files (level 0), the
 * data window as the image wherever it lies. PNG of every kind (1-16 bit
 * gray, gray-alpha, RGB, RGBA, palette with tRNS) is decoded from sRGB with
 * materia's own transfer function, alpha linear; gray gives one channel,
 * gray-alpha and palette-with-alpha RGBA. PFM ("PF"/"Pf", either byte
 * order, values times |scale|) is read bottom-to-top as the format requires.
 * A truncated or corrupt file is an error naming the file, never a crash.
 * Writing goes to a temporary file in the same directory that is renamed
 * into place, so an error never leaves a partial file (and an existing file
 * survives a failed overwrite).
 */
#ifndef MATERIA_IMAGE_H
#define MATERIA_IMAGE_H

#include "materia/error.h"
#include "materia/mode.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_image {
    int width, height;
    int channels; /* 1 (Y), 3 (RGB) or 4 (RGBA) */
    float *data;  /* width * height * channels values, malloc'ed */
} mt_image;

/* Allocates a zeroed image; MT_ERR_NOMEM or MT_ERR_INVALID (bad size). */
MT_API mt_status mt_image_alloc(mt_image *img, int width, int height, int channels,
                                mt_error *err);
MT_API void mt_image_free(mt_image *img);

/* Reads .exr, .png or .pfm (by extension, case-insensitive) as described
 * above: the file's own values (mt_image_read_mode with every fix). Tools
 * and comparisons of images use this. */
MT_API mt_status mt_image_read(const char *path, mt_image *img, mt_error *err);

/* The mode bits that change how a file is decoded; the reader ignores the
 * others. */
#define MT_IMAGE_MODE_BITS (MT_FIX_EXR_HALF | MT_FIX_EXR_MISSING_CHANNELS | MT_FIX_PFM_ROWS)

/* Reads a file as the image textures of the given mode see it (the image
 * map cache reads with this). pbrt-v2's ReadImage (core/imageio.cpp) gives,
 * for each bit left out of mode:
 *   MT_FIX_EXR_HALF: EXR R, G and B (and Y) rounded to half, as its HALF
 *     frame buffer holds them; finite values beyond +-65504 saturate there
 *     (OpenEXR would make them infinite);
 *   MT_FIX_EXR_MISSING_CHANNELS: as OpenEXR's RgbaInputFile reads it, a
 *     Y channel is the image (gray) even beside R, G and B, and a file with
 *     none of R, G, B and Y is black rather than an error (a Y-only file is
 *     gray in both modes);
 *   MT_FIX_PFM_ROWS: PFM rows in file order, i.e. the picture upside down.
 * Alpha, PNG and the data window are read the same way in every mode.
 * mt_image_read(p, i, e) is mt_image_read_mode(p, MT_MODE_CORRECTED, i, e). */
MT_API mt_status mt_image_read_mode(const char *path, mt_mode mode, mt_image *img,
                                    mt_error *err);

/* A string attribute for the file's header (EXR only; ignored elsewhere). */
typedef struct mt_image_attr {
    const char *name, *value;
} mt_image_attr;

/* Writes by extension: EXR as float RGB(A) -- Y for a one-channel image --
 * with ZIP compression and the string attributes, PNG as 8-bit sRGB (values
 * clamped to [0, 1] after the transfer function; alpha linear), PFM as
 * little-endian float RGB (alpha dropped) or grayscale. */
MT_API mt_status mt_image_write(const char *path, const mt_image *img, const mt_image_attr *attrs,
                                int nattrs, mt_error *err);

/* Whether mt_image_write could write path, checked before the work that
 * makes the image: a known extension and an existing, writable directory.
 * MT_OK, or an error saying which. */
MT_API mt_status mt_image_check_writable(const char *path, mt_error *err);

/* The sRGB transfer function and its inverse (IEC 61966-2-1). */
MT_API float mt_srgb_to_linear(float v);
MT_API float mt_linear_to_srgb(float v);

#ifdef __cplusplus
}
#endif

#endif
