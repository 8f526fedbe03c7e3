/* File names relative to a statement's directory, and whole-file reads. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include "core/alloc.h"
#include "params/path.h"

mt_status mt__path_join(const char *dir, const char *name, char *out, size_t size,
                        mt_error *err)
{
    size_t nd = 0, nn = strlen(name);
    int slash = 0;
    if (name[0] != '/' && dir && dir[0]) {
        nd = strlen(dir);
        slash = dir[nd - 1] != '/';
    }
    if (nd + (size_t)slash + nn + 1 > size)
        return mt_error_set(err, MT_ERR_LIMIT, "file name \"%s\" is too long (more than %lu bytes)",
                            name, (unsigned long)(size ? size - 1 : 0));
    if (nd) memcpy(out, dir, nd);
    if (slash) out[nd] = '/';
    memcpy(out + nd + (size_t)slash, name, nn + 1);
    return MT_OK;
}

char *mt__path_dir(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n;
    char *d;
    if (!slash) return mt__strdup(".");
    n = slash == path ? 1 : (size_t)(slash - path);
    d = mt__malloc(n + 1);
    if (!d) return NULL;
    memcpy(d, path, n);
    d[n] = '\0';
    return d;
}

mt_status mt__read_file(const char *path, char **data, size_t *len, mt_error *err)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    size_t n = 0, cap = 0;
    *data = NULL;
    *len = 0;
    if (!f) return mt_error_set(err, MT_ERR_IO, "cannot open \"%s\": %s", path, strerror(errno));
    for (;;) {
        size_t got;
        if (cap - n < 2) {
            size_t ncap = cap ? cap * 2 : 65536;
            char *nb = ncap > cap ? mt__realloc(buf, ncap) : NULL;
            if (!nb) {
                mt__free(buf);
                fclose(f);
                return mt_error_set(err, MT_ERR_NOMEM, "out of memory reading \"%s\"", path);
            }
            buf = nb;
            cap = ncap;
        }
        got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
        if (got == 0) break;
    }
    if (ferror(f)) {
        int e = errno;
        mt__free(buf);
        fclose(f);
        return mt_error_set(err, MT_ERR_IO, "cannot read \"%s\": %s", path,
                            e ? strerror(e) : "read error");
    }
    fclose(f);
    buf[n] = '\0';
    *data = buf;
    *len = n;
    return MT_OK;
}
