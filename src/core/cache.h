/*
 * Internal: a process-wide cache of objects made from files, keyed by a
 * string (pbrt-v2 reads each image map and each measured BRDF file once per
 * process). The image-map cache (src/image/cache.c) and the measured BRDF
 * cache (src/measured/cache.c) are its users.
 *
 * mt__cache_get finds the value of a key or builds it: the builder runs
 * without the cache's lock, so different keys are built at the same time,
 * while threads asking for a key that is being built wait for it and share
 * the one object. A failed build caches nothing: the next caller builds
 * again and gets the error itself. The cache holds one reference to each
 * value; retain gives each caller its own (NULL: callers borrow the cache's,
 * valid until mt__cache_clear); release drops the cache's.
 */
#ifndef MT_CORE_CACHE_H
#define MT_CORE_CACHE_H

#include <pthread.h>
#include "materia/error.h"

typedef struct mt__cache_entry mt__cache_entry;

typedef struct mt__cache {
    pthread_mutex_t lock;
    pthread_cond_t built;     /* broadcast when a build ends, made or failed */
    mt__cache_entry *head;
    void *(*retain)(void *value);
    void (*release)(void *value);
} mt__cache;

/* A static cache: static mt__cache c = MT__CACHE_INIT(retain, release); */
#define MT__CACHE_INIT(retain_fn, release_fn)                                               \
    { .lock = PTHREAD_MUTEX_INITIALIZER, .built = PTHREAD_COND_INITIALIZER, .head = NULL,   \
      .retain = (retain_fn), .release = (release_fn) }

/* Builds the value of a key; NULL with err filled when it cannot. */
typedef void *(*mt__cache_build)(void *ctx, mt_error *err);

/* The value of key (retained for the caller when the cache has a retain),
 * built with build(ctx, err) when the cache has none. NULL with err filled
 * when the build fails or the entry cannot be allocated (a message naming
 * file, the file the value comes from). */
void *mt__cache_get(mt__cache *c, const char *key, const char *file, mt__cache_build build,
                    void *ctx, mt_error *err);

/* The number of values in the cache (builds under way not counted). */
int mt__cache_size(mt__cache *c);

/* Drops the cache's reference to every value; builds under way finish and
 * stay. */
void mt__cache_clear(mt__cache *c);

#endif
