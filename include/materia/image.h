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
 *
 * Thread safety: every function may be called from any thread at once; an
 * mt_image is plain data that its owner shares or not.
 */
#ifndef MATERIA_IMAGE_H
#define MATERIA_IMAGE_H

#include "materia/error.h"
#include "materia/mode.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An image is a value the caller holds; the functions that fill one
 * (mt_image_create, mt_image_read, mt_scene_render, ...) allocate data, which
 * mt_image_destroy frees. A function that fails leaves *img empty (zero
 * size, data NULL), which mt_image_destroy accepts, as it accepts NULL. */
typedef struct mt_image {
    int width, height;
    int channels; /* 1 (Y), 3 (RGB) or 4 (RGBA) */
    float *data;  /* width * height * channels values, row 0 at the top */
} mt_image;

/* Fills *img with a zeroed image; MT_ERR_INVALID for a size out of range
 * (sides 1 to 2^24, channels 1, 3 or 4, at most 2^29 values), MT_ERR_NOMEM. */
MT_API mt_status mt_image_create(mt_image *img, int width, int height, int channels,
                                 mt_error *err);
/* Frees img's data and empties it. */
MT_API void mt_image_destroy(mt_image *img);

/* Fills *img from a .exr, .png or .pfm file (by extension, case-insensitive)
 * as described above: the file's own values (mt_image_read_mode with every
 * fix). Tools and comparisons of images use this. MT_ERR_IO (a file that
 * cannot be opened), MT_ERR_FORMAT (a malformed one), MT_ERR_UNSUPPORTED
 * (another extension, deep EXR), MT_ERR_NOMEM, each naming the file. */
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

/* The image formats this build of materia reads and writes, by extension:
 * "exr png pfm" (a build made with NO_EXR=1 or NO_PNG=1 lacks that word).
 * Reading or writing a format the build lacks is MT_ERR_UNSUPPORTED naming
 * the file and the format.
 * Linking: imagemap textures made from statements (mt_texture_create, a
 * scene's or a query's Texture) read the formats a static program links for
 * another reason; calling mt_image_formats, mt_image_read(_mode),
 * mt_image_write or the renderer links them all. A program that reads no
 * image thus links neither OpenEXR nor libpng; one that reads an .exr or
 * .png texture from a statement without having linked the format gets an
 * error naming the file and what to call. The shared library has them all. */
MT_API const char *mt_image_formats(void);

/* A string attribute for the file's header (EXR only; ignored elsewhere). */
typedef struct mt_image_attr {
    const char *name, *value;
} mt_image_attr;

/* Writes by extension: EXR as float RGB(A) -- Y for a one-channel image --
 * with ZIP compression and the nattrs string attributes (attrs may be NULL
 * when nattrs is 0), PNG as 8-bit sRGB (values clamped to [0, 1] after the
 * transfer function; alpha linear), PFM as little-endian float RGB (alpha
 * dropped) or grayscale. Through a temporary file renamed into place;
 * MT_ERR_IO or MT_ERR_UNSUPPORTED naming the file. */
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
