/*
 * The process-wide cache behind the image-map and measured BRDF caches
 * (core/cache.h): a list of entries under a mutex. An entry is inserted
 * before its value is built, marked as building, so that a second thread
 * asking for the same key waits on the condition variable instead of
 * reading the file again; the build itself runs unlocked.
 */
#include <string.h>
#include "core/alloc.h"
#include "core/cache.h"

struct mt__cache_entry {
    mt__cache_entry *next;
    void *value;  /* NULL while building */
    char key[];   /* C99 flexible array member: one allocation per entry */
};

static mt__cache_entry *find(mt__cache *c, const char *key)
{
    mt__cache_entry *e;
    for (e = c->head; e; e = e->next)
        if (!strcmp(e->key, key)) return e;
    return NULL;
}

static void unlink_entry(mt__cache *c, mt__cache_entry *gone)
{
    mt__cache_entry **p;
    for (p = &c->head; *p; p = &(*p)->next)
        if (*p == gone) {
            *p = gone->next;
            return;
        }
}

void *mt__cache_get(mt__cache *c, const char *key, const char *file, mt__cache_build build,
                    void *ctx, mt_error *err)
{
    mt__cache_entry *e;
    size_t len = strlen(key);
    void *v;
    pthread_mutex_lock(&c->lock);
    /* a build under way for this key: wait for it (it may fail, and the
     * entry go; then look again, and build here) */
    while ((e = find(c, key)) != NULL && !e->value) pthread_cond_wait(&c->built, &c->lock);
    if (e) {
        v = c->retain ? c->retain(e->value) : e->value;
        pthread_mutex_unlock(&c->lock);
        return v;
    }
    e = mt__malloc(sizeof *e + len + 1);
    if (!e) {
        pthread_mutex_unlock(&c->lock);
        mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory for the cache", file);
        return NULL;
    }
    memcpy(e->key, key, len + 1);
    e->value = NULL;
    e->next = c->head;
    c->head = e;
    pthread_mutex_unlock(&c->lock);

    v = build(ctx, err);

    pthread_mutex_lock(&c->lock);
    if (v) {
        e->value = v; /* the build's reference becomes the cache's */
        if (c->retain) v = c->retain(v);
    } else {
        unlink_entry(c, e);
        mt__free(e);
    }
    pthread_cond_broadcast(&c->built);
    pthread_mutex_unlock(&c->lock);
    return v;
}

int mt__cache_size(mt__cache *c)
{
    const mt__cache_entry *e;
    int n = 0;
    pthread_mutex_lock(&c->lock);
    for (e = c->head; e; e = e->next) n += e->value != NULL;
    pthread_mutex_unlock(&c->lock);
    return n;
}

void mt__cache_clear(mt__cache *c)
{
    mt__cache_entry **p = &c->head, *e;
    pthread_mutex_lock(&c->lock);
    while ((e = *p) != NULL) {
        if (!e->value) { /* its builder still holds it */
            p = &e->next;
            continue;
        }
        *p = e->next;
        c->release(e->value);
        mt__free(e);
    }
    pthread_mutex_unlock(&c->lock);
}
