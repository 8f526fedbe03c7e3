/*
 * Reading an image through the formats the program links anyway
 * (image/formats.h): the imagemap textures' reader. The references to the
 * OpenEXR and PNG descriptors are weak, so a static program that makes
 * textures from statements links neither library unless something else of
 * it reads or writes images by name (mt_image_read, mt_image_write,
 * mt_image_formats, the renderer). PFM needs no library: always linked.
 */
#include <stddef.h>
#include <string.h>
#include "image/formats.h"

/* Weak only where the format is built (a build without it has a descriptor
 * without a reader, which says so: linked strongly, it costs nothing), and
 * not in the amalgamation, where every format is in the one object. */
#if defined(__GNUC__) && defined(__ELF__) && !defined(MATERIA_AMALGAMATION)
#if MATERIA_HAVE_EXR
extern const mt__image_format mt__exr_format __attribute__((weak));
#endif
#if MATERIA_HAVE_PNG
extern const mt__image_format mt__png_format __attribute__((weak));
#endif
#endif

int mt__image_has_ext(const char *path, const char *ext)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) return 0;
    for (; *dot && *ext; dot++, ext++) {
        char c = *dot;
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != *ext) return 0;
    }
    return *dot == *ext;
}

mt_status mt__image_format_absent(const mt__image_format *f, const char *path, mt_error *err)
{
    return mt_error_set(err, MT_ERR_UNSUPPORTED, "%s: this build of materia has no %s support (built with %s)", path,
                        f->name, f->omit);
}

mt_status mt__image_format_read(const mt__image_format *f, const char *path, mt_mode mode,
                                mt_image *img, mt_error *err)
{
    mt_status st;
    if (!img) return mt_error_set(err, MT_ERR_INVALID, "mt_image_read: no image");
    img->width = img->height = img->channels = 0;
    img->data = NULL;
    if (!f->read) return mt__image_format_absent(f, path, err);
    st = f->read(path, mode & MT_IMAGE_MODE_BITS, img, err);
    if (st != MT_OK) mt_image_destroy(img);
    return st;
}

mt_status mt__image_read_linked(const char *path, mt_mode mode, mt_image *img, mt_error *err)
{
    /* the same descriptors as formats.c's, here by address: NULL when weak
     * and not linked */
    const mt__image_format *const any[] = {&mt__exr_format, &mt__png_format, &mt__pfm_format};
    static const struct {
        const char *ext, *name;
    } names[] = {{".exr", "OpenEXR"}, {".png", "PNG"}, {".pfm", "PFM"}};
    size_t i;
    if (!img) return mt_error_set(err, MT_ERR_INVALID, "mt_image_read: no image");
    img->width = img->height = img->channels = 0;
    img->data = NULL;
    if (!path) return mt_error_set(err, MT_ERR_INVALID, "mt_image_read: no file name");
    for (i = 0; i < sizeof names / sizeof names[0]; ++i) {
        if (!mt__image_has_ext(path, names[i].ext)) continue;
        if (any[i]) return mt__image_format_read(any[i], path, mode, img, err);
        return mt_error_set(err, MT_ERR_UNSUPPORTED,
                            "%s: materia's %s reader is not linked into this program (a program linked with "
                            "libmateria.a links the image formats when it calls mt_image_formats(), "
                            "mt_image_read or mt_image_write)",
                            path, names[i].name);
    }
    return mt_error_set(err, MT_ERR_UNSUPPORTED, "%s: unknown image type (materia reads .exr, .png and .pfm)",
                        path);
}
