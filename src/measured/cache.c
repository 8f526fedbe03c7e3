/*
 * Measured BRDF files, each read once per process (pbrt-v2 measured.cpp
 * keeps a map from file name to loaded data for each format): a list of
 * (path, data) under a mutex. A file is read with the mutex held, so that
 * two threads asking for the same file read it once. Failed reads are not
 * cached: the next call tries again and reports the error again.
 */
#include <pthread.h>
#include <string.h>
#include "core/alloc.h"
#include "measured/measured_impl.h"

typedef struct cache_entry {
    struct cache_entry *next;
    char *path;
    mt_measured *data;
} cache_entry;

static pthread_mutex_t cache_lock = PTHREAD_MUTEX_INITIALIZER;
static cache_entry *cache_head;

/* pbrt-v2 MeasuredMaterial: ".brdf" or ".BRDF" is the irregular text
 * format, any other suffix MERL's binary one. pbrt-v2 takes the suffix of
 * the whole name ("./x" has one there); here that of the last component. */
static mt_measured *read_file(const char *path, mt_error *err)
{
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

mt_measured *mt_measured_load(const char *path, mt_error *err)
{
    cache_entry *e;
    mt_measured *m = NULL;
    if (!path || !path[0]) {
        mt_error_set(err, MT_ERR_INVALID, "no measured BRDF file name given");
        return NULL;
    }
    pthread_mutex_lock(&cache_lock);
    for (e = cache_head; e; e = e->next)
        if (!strcmp(e->path, path)) {
            m = mt_measured_retain(e->data);
            break;
        }
    if (!m) {
        m = read_file(path, err);
        e = m ? mt__calloc(1, sizeof *e) : NULL;
        if (e) e->path = mt__strdup(path);
        if (e && e->path) {
            e->data = mt_measured_retain(m); /* the cache's reference */
            e->next = cache_head;
            cache_head = e;
        } else if (m) {
            mt__free(e);
            mt_measured_release(m);
            m = NULL;
            mt_error_set(err, MT_ERR_NOMEM, "out of memory caching \"%s\"", path);
        }
    }
    pthread_mutex_unlock(&cache_lock);
    return m;
}

int mt_measured_cache_size(void)
{
    const cache_entry *e;
    int n = 0;
    pthread_mutex_lock(&cache_lock);
    for (e = cache_head; e; e = e->next) n++;
    pthread_mutex_unlock(&cache_lock);
    return n;
}

void mt_measured_cache_clear(void)
{
    cache_entry *e, *next;
    pthread_mutex_lock(&cache_lock);
    for (e = cache_head; e; e = next) {
        next = e->next;
        mt_measured_release(e->data);
        mt__free(e->path);
        mt__free(e);
    }
    cache_head = NULL;
    pthread_mutex_unlock(&cache_lock);
}
