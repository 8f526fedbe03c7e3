/*
 * Measured BRDF files, each read once per process (pbrt-v2 measured.cpp
 * keeps a map from file name to loaded data for each format), in the
 * generic cache of core/cache.h keyed by the path: two threads asking for
 * the same file read it once, and each caller gets its own reference.
 * Failed reads are not cached: the next call tries again and reports the
 * error again.
 */
#include <string.h>
#include "core/cache.h"
#include "measured/measured_impl.h"

/* pbrt-v2 MeasuredMaterial: ".brdf" or ".BRDF" is the irregular text
 * format, any other suffix MERL's binary one. pbrt-v2 takes the suffix of
 * the whole name ("./x" has one there); here that of the last component. */
static void *read_file(void *ctx, mt_error *err)
{
    const char *path = ctx;
    const char *base = strrchr(path, '/'), *dot;
    base = base ? base + 1 : path;
    dot = strrchr(base, '.');
    if (!dot) {
        mt_error_set(err, MT_ERR_INVALID,
                     "measured BRDF file name \"%s\" has no suffix: cannot tell its format "
                     "(\".brdf\" for the irregular text format, any other suffix for MERL's "
                     "binary format)", path);
        mt_error_locate(err, path, 0, 0);
        return NULL;
    }
    if (!strcmp(dot, ".brdf") || !strcmp(dot, ".BRDF")) return mt__brdf_file_read(path, err);
    return mt__merl_file_read(path, err);
}

static void *retain(void *m) { return mt_measured_retain(m); }
static void release(void *m) { mt_measured_destroy(m); }

static mt__cache cache = MT__CACHE_INIT(retain, release);

mt_measured *mt_measured_load(const char *path, mt_error *err)
{
    mt_error_clear(err);
    if (!path || !path[0]) {
        mt_error_set(err, MT_ERR_INVALID, "no measured BRDF file name given");
        return NULL;
    }
    return mt__cache_get(&cache, path, path, read_file, (void *)path, err);
}

int mt_measured_cache_size(void) { return mt__cache_size(&cache); }

void mt_measured_cache_clear(void) { mt__cache_clear(&cache); }
