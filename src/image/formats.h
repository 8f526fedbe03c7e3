/*
 * Internal: the image file formats as a table. Each format's file defines
 * its descriptor (mt__exr_format, mt__png_format, mt__pfm_format); a build
 * may leave OpenEXR or libpng out (make NO_EXR=1 / NO_PNG=1; the macros
 * MATERIA_HAVE_EXR and MATERIA_HAVE_PNG, 0 when not defined), and the
 * descriptor then has no reader or writer.
 *
 * Two lookups, so that a static program links OpenEXR and libpng only when
 * it asks for images by name:
 *   mt__image_format_of (formats.c) knows every format; mt_image_read,
 *     mt_image_write, mt_image_formats (and so the renderer, which writes
 *     and reads environment maps) go through it and link them all;
 *   mt__image_read_linked (linked.c) reads through the formats the program
 *     has linked anyway: imagemap textures made from statements, so that
 *     parsing a scene statement does not link the image libraries. On ELF
 *     with gcc or clang its references are weak; elsewhere they are strong
 *     and every format is linked.
 */
#ifndef MT_IMAGE_FORMATS_H
#define MT_IMAGE_FORMATS_H

#include "materia/image.h"

#ifndef MATERIA_HAVE_EXR
#define MATERIA_HAVE_EXR 0
#endif
#ifndef MATERIA_HAVE_PNG
#define MATERIA_HAVE_PNG 0
#endif

typedef struct mt__image_format {
    const char *ext;  /* ".exr", lower case */
    const char *name; /* "OpenEXR" */
    const char *omit; /* how a build leaves it out: "make NO_EXR=1" */
    /* NULL in a build without the format. mode: MT_IMAGE_MODE_BITS. */
    mt_status (*read)(const char *path, mt_mode mode, mt_image *img, mt_error *err);
    mt_status (*write)(const char *path, const mt_image *img, const mt_image_attr *attrs,
                       int nattrs, mt_error *err);
} mt__image_format;

extern const mt__image_format mt__exr_format, mt__png_format, mt__pfm_format;

/* The format of path's extension (any case), NULL when none. Links every
 * format. */
const mt__image_format *mt__image_format_of(const char *path);

/* linked.c, which references no format strongly: */
/* Reads path with f's reader (img emptied first, freed on failure):
 * MT_ERR_UNSUPPORTED naming the file, the format and the build option that
 * left it out when the build has no reader. */
mt_status mt__image_format_read(const mt__image_format *f, const char *path, mt_mode mode,
                                mt_image *img, mt_error *err);
/* MT_ERR_UNSUPPORTED: path is an f file and this build has no f. */
mt_status mt__image_format_absent(const mt__image_format *f, const char *path, mt_error *err);
/* mt_image_read_mode through the formats linked into the program. */
mt_status mt__image_read_linked(const char *path, mt_mode mode, mt_image *img, mt_error *err);
/* 1 when path's extension (after its last '/') is ext (".exr"), in any case. */
int mt__image_has_ext(const char *path, const char *ext);

#endif
