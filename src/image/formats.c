/*
 * The image formats by file extension (image/formats.h): mt_image_read,
 * mt_image_write and mt_image_check_writable dispatch on the extension
 * through the table of every format, and mt_image_formats lists those this
 * build has. Everything here refers to every format, so a static program
 * that calls any of it links OpenEXR and libpng (when built in).
 */
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "image/formats.h"

static const mt__image_format *const all[] = {&mt__exr_format, &mt__png_format, &mt__pfm_format};
#define NFORMATS (sizeof all / sizeof all[0])

const mt__image_format *mt__image_format_of(const char *path)
{
    size_t i;
    for (i = 0; path && i < NFORMATS; ++i)
        if (mt__image_has_ext(path, all[i]->ext)) return all[i];
    return NULL;
}

/* "exr png pfm", those this build left out missing: made once */
static char list[64];
static pthread_once_t list_once = PTHREAD_ONCE_INIT;

static void make_list(void)
{
    size_t i, n = 0;
    for (i = 0; i < NFORMATS; ++i)
        if (all[i]->read && n < sizeof list)
            n += (size_t)snprintf(list + n, sizeof list - n, "%s%s", n ? " " : "", all[i]->ext + 1);
}

const char *mt_image_formats(void)
{
    pthread_once(&list_once, make_list);
    return list;
}

mt_status mt_image_read(const char *path, mt_image *img, mt_error *err)
{
    mt_error_clear(err);
    return mt_image_read_mode(path, MT_MODE_CORRECTED, img, err);
}

mt_status mt_image_read_mode(const char *path, mt_mode mode, mt_image *img, mt_error *err)
{
    const mt__image_format *f;
    mt_error_clear(err);
    if (!img) return mt_error_set(err, MT_ERR_INVALID, "mt_image_read: no image");
    img->width = img->height = img->channels = 0;
    img->data = NULL;
    if (!path) return mt_error_set(err, MT_ERR_INVALID, "mt_image_read: no file name");
    if (!(f = mt__image_format_of(path)))
        return mt_error_set(err, MT_ERR_UNSUPPORTED,
                            "%s: unknown image type (materia reads .exr, .png and .pfm)", path);
    return mt__image_format_read(f, path, mode, img, err);
}

mt_status mt_image_write(const char *path, const mt_image *img, const mt_image_attr *attrs,
                         int nattrs, mt_error *err)
{
    const mt__image_format *f;
    int i;
    mt_error_clear(err);
    if (!path) return mt_error_set(err, MT_ERR_INVALID, "mt_image_write: no file name");
    if (!img || !img->data || img->width < 1 || img->height < 1 ||
        (img->channels != 1 && img->channels != 3 && img->channels != 4))
        return mt_error_set(err, MT_ERR_INVALID, "%s: not a valid image to write", path);
    if (nattrs < 0 || (nattrs > 0 && !attrs))
        return mt_error_set(err, MT_ERR_INVALID, "%s: invalid attribute list", path);
    for (i = 0; i < nattrs; i++)
        if (!attrs[i].name || !attrs[i].name[0] || !attrs[i].value)
            return mt_error_set(err, MT_ERR_INVALID, "%s: attribute %d has no name or value",
                                path, i);
    if (!(f = mt__image_format_of(path)))
        return mt_error_set(err, MT_ERR_UNSUPPORTED,
                            "%s: unknown image type (materia writes .exr, .png and .pfm)", path);
    if (!f->write) return mt__image_format_absent(f, path, err);
    return f->write(path, img, attrs, nattrs, err);
}

mt_status mt_image_check_writable(const char *path, mt_error *err)
{
    const mt__image_format *f;
    char dir[4096];
    const char *slash;
    struct stat sb;
    size_t n;
    mt_error_clear(err);
    if (!path || !path[0]) return mt_error_set(err, MT_ERR_INVALID, "no output file name");
    if (!(f = mt__image_format_of(path)))
        return mt_error_set(err, MT_ERR_UNSUPPORTED,
                            "%s: unknown image type (materia writes .exr, .png and .pfm)", path);
    if (!f->write) return mt__image_format_absent(f, path, err);
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return mt_error_set(err, MT_ERR_IO, "%s: is a directory", path);
    /* the image is written to a temporary file beside it, then renamed */
    slash = strrchr(path, '/');
    n = slash ? (size_t)(slash - path) : 0;
    if (n == 0) snprintf(dir, sizeof dir, "%s", slash ? "/" : ".");
    else if (n < sizeof dir) snprintf(dir, sizeof dir, "%.*s", (int)n, path);
    else return mt_error_set(err, MT_ERR_IO, "%s: the directory's name is too long", path);
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return mt_error_set(err, MT_ERR_IO, "%s: no directory \"%s\"", path, dir);
    if (access(dir, W_OK) != 0)
        return mt_error_set(err, MT_ERR_IO, "%s: directory \"%s\" is not writable", path, dir);
    return MT_OK;
}
