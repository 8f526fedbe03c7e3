/*
 * BVH speed on the 69k-triangle bunny of ../shared/reference/scenes/geometry
 * (with its Translate; MT_BENCH_SCENE names another mesh of that folder),
 * the ray sets of tests/support/traysets.h (primary, incoherent, occlusion),
 * float against double. bench/embree/bvh_embree.c traces the same rays
 * through Embree side by side.
 * Every figure is the best of 7 passes or builds: the machine is shared, and
 * the least disturbed pass is the closest to what the code can do (a median
 * of contended passes measures the neighbours). Single-thread rates and the
 * build time use the thread's CPU time (not inflated by waiting for a
 * processor); the all-threads rates are wall-clock over one thread per
 * online processor. tools/run-bench.sh pairs the float and double builds.
 *
 * "bvh SET N" (SET primary, incoherent or occlusion) traces N rays spread
 * evenly over one set, once, without timing: for instruction counts, e.g.
 *   valgrind --tool=callgrind --toggle-collect=mt_geometry_intersect \
 *            --toggle-collect=mt_geometry_occluded build/float/bench/bvh incoherent 100000
 */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "support/check.h"
#include "support/tgeom.h"
#include "support/traysets.h"

#define REPS 7

/* Seconds on clock c (CPU time of this thread, or wall time). */
static double seconds(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
/* The best of n figures: the smallest time (low) or the highest rate. */
static double best_low(const double *v, int n)
{
    double b = v[0];
    while (--n > 0) b = v[n] < b ? v[n] : b;
    return b;
}
static double best_high(const double *v, int n)
{
    double b = v[0];
    while (--n > 0) b = v[n] > b ? v[n] : b;
    return b;
}

typedef struct job {
    const mt_geometry *g;
    const mt_ray *rays;
    size_t begin, end;
    int occlusion;
    double sum;
    long hits;
} job;

static void *run(void *arg)
{
    job *j = arg;
    size_t i;
    double s = 0;
    long h = 0;
    for (i = j->begin; i < j->end; ++i) {
        if (j->occlusion) {
            h += mt_geometry_occluded(j->g, &j->rays[i]);
        } else {
            mt_hit hit;
            if (mt_geometry_intersect(j->g, &j->rays[i], &hit)) {
                h++;
                s += hit.t;
            }
        }
    }
    j->sum = s;
    j->hits = h;
    return NULL;
}

/* Million rays per second: one thread (CPU time) or nthreads (wall). */
static double rate(const mt_geometry *g, const mt_ray *rays, size_t n, int occlusion, int nthreads,
                   long *hits)
{
    double t[REPS];
    int r;
    for (r = 0; r < REPS; ++r) {
        job jobs[64];
        pthread_t th[64];
        int k;
        double t0 = seconds(nthreads == 1 ? CLOCK_THREAD_CPUTIME_ID : CLOCK_MONOTONIC);
        for (k = 0; k < nthreads; ++k) {
            jobs[k].g = g;
            jobs[k].rays = rays;
            jobs[k].begin = n * (size_t)k / (size_t)nthreads;
            jobs[k].end = n * (size_t)(k + 1) / (size_t)nthreads;
            jobs[k].occlusion = occlusion;
            if (nthreads == 1) run(&jobs[k]);
            else if (pthread_create(&th[k], NULL, run, &jobs[k]) != 0) run(&jobs[k]), th[k] = 0;
        }
        *hits = 0;
        for (k = 0; k < nthreads; ++k) {
            if (nthreads > 1 && th[k]) pthread_join(th[k], NULL);
            *hits += jobs[k].hits;
        }
        t[r] = (double)n / (seconds(nthreads == 1 ? CLOCK_THREAD_CPUTIME_ID : CLOCK_MONOTONIC) - t0) / 1e6;
    }
    return best_high(t, REPS);
}

int main(int argc, char **argv)
{
    const char *dir = t_shared_dir();
    char path[512];
    mt_error err;
    mt_geometry *g = NULL;
    mt_bvh_stats st;
    double tb[REPS], build_ms;
    mt_ray *sets[T_RAY_SETS];
    size_t counts[T_RAY_SETS];
    const char *const *names = t_ray_set_names;
    int r, k, nthreads = (int)sysconf(_SC_NPROCESSORS_ONLN);
    if (!dir) {
        printf("bvh: SKIP, no shared reference data (../shared) for the bunny\n");
        return 0;
    }
    if (nthreads < 1) nthreads = 1;
    if (nthreads > 64) nthreads = 64;
    snprintf(path, sizeof path, "%s/reference/scenes/geometry/%s", dir, getenv("MT_BENCH_SCENE") ? getenv("MT_BENCH_SCENE") : "bunny.pbrt");
    for (r = 0; r < REPS; ++r) {
        double t0;
        mt_geometry_destroy(g);
        g = mt_geometry_create();
        if (!g || t_load_shapes(path, g, &err) < 1) {
            fprintf(stderr, "bench: %s: %s\n", path, err.message);
            return 1;
        }
        t0 = seconds(CLOCK_THREAD_CPUTIME_ID);
        if (mt_geometry_commit(g, &err) != MT_OK) {
            fprintf(stderr, "bench: build: %s\n", err.message);
            return 1;
        }
        tb[r] = (seconds(CLOCK_THREAD_CPUTIME_ID) - t0) * 1e3;
    }
    build_ms = best_low(tb, REPS);
    mt_geometry_stats(g, &st);
    printf("BVH of the bunny, %s build: %u triangles, %u inner nodes, %u leaves, depth %u, SAH cost "
           "%.1f, %.1f MB; %d threads for the all-threads figures\n",
           mt_precision(), (unsigned)st.prims, (unsigned)st.inner_nodes, (unsigned)st.leaves,
           (unsigned)st.max_depth, st.sah_cost, st.bytes / 1048576.0, nthreads);
    printf("BENCH bvh.build %.1f ms\n", build_ms);

    if (!t_ray_sets(g, !getenv("MT_BENCH_SCENE") || strcmp(getenv("MT_BENCH_SCENE"), "bunny.pbrt") == 0, sets,
                    counts))
        return 1;
    if (argc == 3) {
        size_t n = (size_t)strtoul(argv[2], NULL, 10);
        for (k = 0; k < 3 && strcmp(argv[1], names[k]) != 0; ++k) continue;
        if (k == 3 || n == 0 || n > counts[k]) {
            fprintf(stderr, "usage: bvh [primary|incoherent|occlusion N]\n");
            return 2;
        }
        {
            job j;
            size_t i2;
            for (i2 = 0; i2 < n; ++i2) sets[k][i2] = sets[k][i2 * (counts[k] / n)];
            j.g = g;
            j.rays = sets[k];
            j.begin = 0;
            j.end = n;
            j.occlusion = k == 2;
            run(&j);
            printf("%s: %lu rays, %ld hits\n", names[k], (unsigned long)n, j.hits);
        }
        t_ray_sets_free(sets);
        mt_geometry_destroy(g);
        return 0;
    }
    for (k = 0; k < 3; ++k) {
        long hits;
        double one = rate(g, sets[k], counts[k], k == 2, 1, &hits);
        double all = rate(g, sets[k], counts[k], k == 2, nthreads, &hits);
        printf("BENCH bvh.%s.1thread %.3f Mrays/s\n", names[k], one);
        printf("BENCH bvh.%s.%dthreads %.3f Mrays/s\n", names[k], nthreads, all);
        printf("  %s: %.1f%% hit\n", names[k], 100.0 * hits / counts[k]);
    }
    t_ray_sets_free(sets);
    mt_geometry_destroy(g);
    return 0;
}
