/*
 * The generic process-wide cache (src/core/cache.c) behind the image-map and
 * measured BRDF caches: one build per key however many threads ask at once,
 * builds of different keys at the same time (the lock is not held while
 * building), failed builds not cached, the cache's own reference and the
 * callers', clearing during a build, an allocation failure.
 *
 * The concurrency checks wait on condition variables with a deadline of a
 * few seconds: the deadline only turns a deadlock into a failure, it
 * measures nothing.
 */
#include <errno.h>
#include <pthread.h>
#include <string.h>
#include <time.h>
#include "core/cache.h"
#include "materia/tools/alloc.h"
#include "support/check.h"

/* A refcounted value. */
typedef struct value {
    int refs;
    int id;
} value;

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t changed = PTHREAD_COND_INITIALIZER;
static int builds, started, released, fail_builds, hold; /* guarded by lock */
static value pool[64];

static void *retain(void *v)
{
    pthread_mutex_lock(&lock);
    ((value *)v)->refs++;
    pthread_mutex_unlock(&lock);
    return v;
}

static void release(void *v)
{
    pthread_mutex_lock(&lock);
    ((value *)v)->refs--;
    released++;
    pthread_mutex_unlock(&lock);
}

/* Waits (lock held) until cond holds or a few seconds have passed; returns
 * whether it holds. */
#define WAIT_UNTIL(cond)                                                                    \
    do {                                                                                    \
        struct timespec dl;                                                                 \
        clock_gettime(CLOCK_REALTIME, &dl);                                                 \
        dl.tv_sec += 5;                                                                     \
        while (!(cond))                                                                     \
            if (pthread_cond_timedwait(&changed, &lock, &dl) == ETIMEDOUT) break;           \
    } while (0)

/* Counts the build, then waits while hold is at least its number, so that
 * other threads arrive meanwhile; fails when fail_builds says so. */
static void *build(void *ctx, mt_error *err)
{
    value *v;
    int n;
    pthread_mutex_lock(&lock);
    n = ++started;
    pthread_cond_broadcast(&changed);
    WAIT_UNTIL(hold < n);
    builds++;
    if (fail_builds) {
        pthread_mutex_unlock(&lock);
        mt_error_set(err, MT_ERR_IO, "%s: cannot read", (const char *)ctx);
        return NULL;
    }
    v = &pool[builds % 64];
    v->refs = 1;
    v->id = builds;
    pthread_mutex_unlock(&lock);
    return v;
}

static mt__cache cache = MT__CACHE_INIT(retain, release);

typedef struct job {
    const char *key;
    void *got;
    mt_error err;
} job;

static void *ask(void *arg)
{
    job *j = arg;
    mt_error_clear(&j->err);
    j->got = mt__cache_get(&cache, j->key, j->key, build, (void *)j->key, &j->err);
    return NULL;
}

static void reset(int fail, int held)
{
    mt__cache_clear(&cache);
    pthread_mutex_lock(&lock);
    builds = started = released = 0;
    fail_builds = fail;
    hold = held;
    pthread_mutex_unlock(&lock);
}

static void let_go(void)
{
    pthread_mutex_lock(&lock);
    hold = 0;
    pthread_cond_broadcast(&changed);
    pthread_mutex_unlock(&lock);
}

enum { T = 6 };

/* T threads ask for key at once while the first build is held back: the
 * others arrive and queue behind it (20 ms makes that likely; the checks
 * hold either way). */
static void ask_at_once(job *j, const char *key, int fail)
{
    pthread_t th[T];
    int k;
    reset(fail, 1); /* the first build waits until let go */
    for (k = 0; k < T; k++) {
        j[k].key = key;
        pthread_create(&th[k], NULL, ask, &j[k]);
    }
    pthread_mutex_lock(&lock);
    WAIT_UNTIL(started >= 1);
    pthread_mutex_unlock(&lock);
    nanosleep(&(struct timespec){0, 20000000}, NULL);
    let_go();
    for (k = 0; k < T; k++) pthread_join(th[k], NULL);
}

static void test_one_key(void)
{
    job j[T];
    int k, same = 1, n;
    ask_at_once(j, "a", 0);
    for (k = 0; k < T; k++) same &= j[k].got != NULL && j[k].got == j[0].got;
    n = j[0].got ? ((value *)j[0].got)->refs : -1;
    t_check(same && builds == 1 && n == T + 1 && mt__cache_size(&cache) == 1,
            "cache: threads asking for one key share one object, built once (the cache's "
            "reference and one per caller)",
            "%d builds, %s, %d references", builds, same ? "same" : "different", n);
    for (k = 0; k < T; k++) release(j[k].got);
    pthread_mutex_lock(&lock);
    released = 0;
    pthread_mutex_unlock(&lock);
    mt__cache_clear(&cache);
    t_check(released == 1 && ((value *)j[0].got)->refs == 0 &&
                mt__cache_size(&cache) == 0,
            "cache: clear drops the cache's reference", "%d released, %d references left",
            released, ((value *)j[0].got)->refs);
}

static void test_two_keys(void)
{
    pthread_t ta, tb;
    job a, b;
    int both;
    /* each build waits until two have started: if the cache built under its
     * lock, the second could not start and the first would time out */
    reset(0, 0);
    pthread_mutex_lock(&lock);
    hold = 1000;
    pthread_mutex_unlock(&lock);
    a.key = "a";
    b.key = "b";
    pthread_create(&ta, NULL, ask, &a);
    pthread_create(&tb, NULL, ask, &b);
    pthread_mutex_lock(&lock);
    WAIT_UNTIL(started >= 2);
    both = started == 2;
    pthread_mutex_unlock(&lock);
    let_go();
    pthread_join(ta, NULL);
    pthread_join(tb, NULL);
    t_check(both && a.got && b.got && a.got != b.got && mt__cache_size(&cache) == 2,
            "cache: two keys are built at the same time", "%s", both ? "wrong values" : "serialized");
    release(a.got);
    release(b.got);
    mt__cache_clear(&cache);
}

static void test_failures(void)
{
    job j[T];
    int k, all = 1;
    ask_at_once(j, "bad", 1);
    for (k = 0; k < T; k++)
        all &= !j[k].got && j[k].err.status == MT_ERR_IO && strstr(j[k].err.message, "bad") != NULL;
    t_check(all && builds == T && mt__cache_size(&cache) == 0,
            "cache: a failed build caches nothing; each caller builds again and gets the error",
            "%d builds, %d cached", builds, mt__cache_size(&cache));
}

static void test_clear_during_build(void)
{
    pthread_t th;
    job j;
    reset(0, 1);
    j.key = "slow";
    pthread_create(&th, NULL, ask, &j);
    pthread_mutex_lock(&lock);
    WAIT_UNTIL(started >= 1);
    pthread_mutex_unlock(&lock);
    mt__cache_clear(&cache); /* the entry under construction stays */
    let_go();
    pthread_join(th, NULL);
    t_check(j.got && mt__cache_size(&cache) == 1 && ((value *)j.got)->refs == 2,
            "cache: clearing during a build leaves that build to finish and stay",
            "%d cached", mt__cache_size(&cache));
    release(j.got);
    mt__cache_clear(&cache);
}

static void test_alloc_failure(void)
{
    mt_error err;
    void *v;
    reset(0, 0);
    mt_error_clear(&err);
    mt_alloc_fail_after(0);
    v = mt__cache_get(&cache, "k", "some/file", build, (void *)"k", &err);
    mt_alloc_fail_after(-1);
    t_check(!v && err.status == MT_ERR_NOMEM && strstr(err.message, "some/file") && builds == 0 &&
                mt__cache_size(&cache) == 0,
            "cache: out of memory for the entry is an error naming the file, nothing built",
            "%s", err.message);
}

int main(void)
{
    test_one_key();
    test_two_keys();
    test_failures();
    test_clear_during_build();
    test_alloc_failure();
    mt__cache_clear(&cache);
    return t_status();
}
