/*
 * BVH speed on the 69k-triangle bunny of ../shared/reference/scenes/geometry
 * (with its Translate), the ray sets of ../shared/reference/README.md:
 *   primary    pinhole rays through the pixel centres of a 1024x768 image
 *              from the camera of real-bunny-measured.pbrt (LookAt 0 .2 .2
 *              -.02 .1 0 0 1 0, fov 60 on the shorter axis): closest hit
 *   incoherent 1M rays, origins uniform in the bunny's bounds, directions
 *              uniform on the sphere: closest hit
 *   occlusion  1M segments between two points uniform in the bounds: any hit
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

#define REPS 7
#define PI_D 3.14159265358979323846

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

static mt_vec3 v3(double x, double y, double z) { return mt_v3((mt_real)x, (mt_real)y, (mt_real)z); }

/* pbrt-v2 LookAt and a perspective camera with fov on the shorter axis. */
static void primary_rays(mt_ray *rays, int w, int h)
{
    double pos[3] = {0, .2, .2}, look[3] = {-.02, .1, 0}, up[3] = {0, 1, 0};
    double dir[3], left[3], nup[3], l, tanf2 = tan(60 * PI_D / 360), aspect = (double)w / h;
    int i, j;
    for (i = 0; i < 3; ++i) dir[i] = look[i] - pos[i];
    l = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (i = 0; i < 3; ++i) dir[i] /= l;
    left[0] = up[1] * dir[2] - up[2] * dir[1];
    left[1] = up[2] * dir[0] - up[0] * dir[2];
    left[2] = up[0] * dir[1] - up[1] * dir[0];
    l = sqrt(left[0] * left[0] + left[1] * left[1] + left[2] * left[2]);
    for (i = 0; i < 3; ++i) left[i] /= l;
    nup[0] = dir[1] * left[2] - dir[2] * left[1];
    nup[1] = dir[2] * left[0] - dir[0] * left[2];
    nup[2] = dir[0] * left[1] - dir[1] * left[0];
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i) {
            double sx = (2 * (i + 0.5) / w - 1) * aspect * tanf2, sy = (1 - 2 * (j + 0.5) / h) * tanf2;
            double d[3];
            int k;
            for (k = 0; k < 3; ++k) d[k] = dir[k] - sx * left[k] + sy * nup[k];
            rays[(size_t)j * w + i] = mt_ray_make(v3(pos[0], pos[1], pos[2]), v3(d[0], d[1], d[2]), 0, MT_RAY_TMAX);
        }
}

int main(int argc, char **argv)
{
    const char *dir = t_shared_dir();
    char path[512];
    mt_error err;
    mt_geometry *g = NULL;
    mt_bvh_stats st;
    double tb[REPS], build_ms;
    mt_ray *sets[3];
    size_t counts[3] = {1024 * 768, 1000000, 1000000};
    const char *names[3] = {"primary", "incoherent", "occlusion"};
    int r, k, nthreads = (int)sysconf(_SC_NPROCESSORS_ONLN);
    mt_vec3 lo, hi;
    mt_rng rng;
    size_t i;
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
    mt_geometry_bounds(g, &lo, &hi);
    printf("BVH of the bunny, %s build: %u triangles, %u inner nodes, %u leaves, depth %u, SAH cost "
           "%.1f, %.1f MB; %d threads for the all-threads figures\n",
           mt_precision(), (unsigned)st.prims, (unsigned)st.inner_nodes, (unsigned)st.leaves,
           (unsigned)st.max_depth, st.sah_cost, st.bytes / 1048576.0, nthreads);
    printf("BENCH bvh.build %.1f ms\n", build_ms);

    for (k = 0; k < 3; ++k) sets[k] = malloc(counts[k] * sizeof *sets[k]);
    if (!sets[0] || !sets[1] || !sets[2]) return 1;
    primary_rays(sets[0], 1024, 768);
    mt_rng_seed(&rng, 2024, 1);
    for (i = 0; i < counts[1]; ++i) {
        mt_vec3 o = mt_v3(lo.x + (hi.x - lo.x) * mt_rng_uniform(&rng), lo.y + (hi.y - lo.y) * mt_rng_uniform(&rng),
                          lo.z + (hi.z - lo.z) * mt_rng_uniform(&rng));
        sets[1][i] = mt_ray_make(o, mt_uniform_sample_sphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng)), 0,
                                 MT_RAY_TMAX);
    }
    for (i = 0; i < counts[2]; ++i) {
        mt_vec3 a = mt_v3(lo.x + (hi.x - lo.x) * mt_rng_uniform(&rng), lo.y + (hi.y - lo.y) * mt_rng_uniform(&rng),
                          lo.z + (hi.z - lo.z) * mt_rng_uniform(&rng));
        mt_vec3 b = mt_v3(lo.x + (hi.x - lo.x) * mt_rng_uniform(&rng), lo.y + (hi.y - lo.y) * mt_rng_uniform(&rng),
                          lo.z + (hi.z - lo.z) * mt_rng_uniform(&rng));
        sets[2][i] = mt_ray_make(a, mt_v3_sub(b, a), 0, 1);
    }
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
        for (k = 0; k < 3; ++k) free(sets[k]);
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
    for (k = 0; k < 3; ++k) free(sets[k]);
    mt_geometry_destroy(g);
    return 0;
}
