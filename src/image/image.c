/*
 * Float images: allocation, the sRGB transfer function, and the
 * temporary-file-then-rename protocol of the writers (the format dispatch
 * by file extension is formats.c's) (an error never leaves a partial file where the caller asked for
 * one, and a reader never sees one half written).
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "core/alloc.h"
#include "image/imageio.h"

mt_status mt__image_check_size(const char *path, long long w, long long h, int channels,
                               mt_error *err)
{
    if (w < 1 || h < 1 || w > MT__IMAGE_MAX_SIDE || h > MT__IMAGE_MAX_SIDE)
        return mt_error_set(err, MT_ERR_FORMAT, "%s: implausible image size %lld x %lld", path,
                            w, h);
    if ((unsigned long long)w * (unsigned long long)h * (unsigned long long)channels >
        MT__IMAGE_MAX_VALUES)
        return mt_error_set(err, MT_ERR_FORMAT,
                            "%s: image of %lld x %lld pixels is larger than materia reads",
                            path, w, h);
    return MT_OK;
}

mt_status mt_image_create(mt_image *img, int width, int height, int channels, mt_error *err)
{
    size_t n;
    mt_error_clear(err);
    if (!img) return mt_error_set(err, MT_ERR_INVALID, "mt_image_create: no image");
    img->width = img->height = img->channels = 0;
    img->data = NULL;
    if (channels != 1 && channels != 3 && channels != 4)
        return mt_error_set(err, MT_ERR_INVALID, "an image has 1, 3 or 4 channels, not %d",
                            channels);
    if (width < 1 || height < 1 || width > MT__IMAGE_MAX_SIDE || height > MT__IMAGE_MAX_SIDE ||
        (size_t)width * (size_t)height * (size_t)channels > MT__IMAGE_MAX_VALUES)
        return mt_error_set(err, MT_ERR_INVALID, "invalid image size %d x %d x %d", width,
                            height, channels);
    n = (size_t)width * (size_t)height * (size_t)channels;
    img->data = mt__calloc(n, sizeof(float));
    if (!img->data)
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for a %d x %d image", width,
                            height);
    img->width = width;
    img->height = height;
    img->channels = channels;
    return MT_OK;
}

void mt_image_destroy(mt_image *img)
{
    if (!img) return;
    mt__free(img->data);
    img->data = NULL;
    img->width = img->height = img->channels = 0;
}

/* IEC 61966-2-1, evaluated in double and rounded once. */
float mt_srgb_to_linear(float v)
{
    double x = v;
    if (x <= 0.04045) return (float)(x / 12.92);
    return (float)pow((x + 0.055) / 1.055, 2.4);
}

float mt_linear_to_srgb(float v)
{
    double x = v;
    if (x <= 0.0031308) return (float)(12.92 * x);
    return (float)(1.055 * pow(x, 1 / 2.4) - 0.055);
}

/* ---- writing through a temporary file --------------------------------- */

static void describe_errno(int e, char *buf, size_t size)
{
    if (strerror_r(e, buf, size) != 0) snprintf(buf, size, "error %d", e);
}

mt_status mt__tmpfile_open(mt__tmpfile *t, const char *final_path, mt_error *err)
{
    const char *slash = strrchr(final_path, '/');
    size_t dirlen = slash ? (size_t)(slash - final_path) + 1 : 0;
    const char *base = final_path + dirlen;
    size_t size = strlen(final_path) + 64;
    int attempt, e = 0;
    char why[128];
    t->fd = -1;
    t->fp = NULL;
    t->path = mt__malloc(size);
    if (!t->path) return mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory", final_path);
    /* O_EXCL makes a name taken by another writer (thread or process) fail
     * with EEXIST; the next attempt tries the next name. */
    for (attempt = 0; attempt < 100; attempt++) {
        snprintf(t->path, size, "%.*s.%s.%ld-%d.tmp", (int)dirlen, final_path, base,
                 (long)getpid(), attempt);
        t->fd = open(t->path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (t->fd >= 0) return MT_OK;
        e = errno;
        if (e != EEXIST) break;
    }
    describe_errno(e, why, sizeof why);
    mt__free(t->path);
    t->path = NULL;
    return mt_error_set(err, MT_ERR_IO, "%s: cannot create a file there: %s", final_path, why);
}

mt_status mt__tmpfile_stdio(mt__tmpfile *t, const char *final_path, mt_error *err)
{
    t->fp = fdopen(t->fd, "wb");
    if (t->fp) return MT_OK;
    mt__tmpfile_abort(t);
    return mt_error_set(err, MT_ERR_IO, "%s: cannot open a stream: %s", final_path,
                        strerror(errno));
}

mt_status mt__tmpfile_commit(mt__tmpfile *t, const char *final_path, mt_error *err)
{
    char why[128];
    int e, failed;
    if (t->fp) {
        failed = ferror(t->fp) != 0;
        failed = fclose(t->fp) != 0 || failed;
    } else {
        failed = close(t->fd) != 0;
    }
    t->fp = NULL;
    t->fd = -1;
    if (failed) {
        e = errno;
        describe_errno(e, why, sizeof why);
        mt__tmpfile_abort(t);
        return mt_error_set(err, MT_ERR_IO, "%s: write failed: %s", final_path, why);
    }
    if (rename(t->path, final_path) != 0) {
        e = errno;
        describe_errno(e, why, sizeof why);
        mt__tmpfile_abort(t);
        return mt_error_set(err, MT_ERR_IO, "%s: cannot rename the finished file into place: %s",
                            final_path, why);
    }
    mt__free(t->path);
    t->path = NULL;
    return MT_OK;
}

void mt__tmpfile_abort(mt__tmpfile *t)
{
    if (t->fp)
        fclose(t->fp);
    else if (t->fd >= 0)
        close(t->fd);
    t->fp = NULL;
    t->fd = -1;
    if (t->path) unlink(t->path);
    mt__free(t->path);
    t->path = NULL;
}
