/*
 * Renderer speed on the reference material scenes of
 * ../shared/reference/scenes (160x120, box filter, path, maxdepth 5):
 *
 *   render_<scene>_1t      camera samples per second on one thread (CPU time
 *                          of the rendering thread's process)
 *   render_<scene>_2t      camera samples per second on two threads (wall
 *                          clock)
 *   render_<scene>_cpu     CPU seconds per million camera samples on two
 *                          threads (steadier than wall time on a shared
 *                          machine)
 *
 * Renders use MATERIA_BENCH_SPP samples per pixel (default 32; the time per
 * sample does not depend on the count). This compares builds (float and
 * double in make bench), not renderers: the comparison with pbrt-v2 is timed
 * side by side, both whole processes, by tools/bench-pbrt.sh.
 * Without the shared reference data the benchmark says so and exits.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "support/check.h"
#include "support/trender.h"

static const char *scenes[] = {"matte", "plastic", "glass", "mirror", "metal", "shinymetal",
                               "substrate", "translucent", "uber", "mix", "measured"};

static double now(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Renders s; *wall and *cpu receive the render's wall time and the
 * process's CPU time. Returns the samples traced, 0 on failure. */
static double run(const mt_scene *s, int spp, int threads, double *wall, double *cpu)
{
    mt_render_options o;
    mt_render_stats st;
    mt_image img;
    mt_error err;
    double c0 = now(CLOCK_PROCESS_CPUTIME_ID), c1;
    mt_render_options_default(&o);
    o.spp = spp;
    o.threads = threads;
    if (mt_scene_render(s, &o, &img, NULL, &st, &err) != MT_OK) return 0;
    c1 = now(CLOCK_PROCESS_CPUTIME_ID);
    mt_image_destroy(&img);
    *wall = st.seconds;
    *cpu = c1 - c0;
    return st.samples;
}

int main(void)
{
    const char *shared = t_shared_dir(), *env = getenv("MATERIA_BENCH_SPP");
    int spp = env && atoi(env) > 0 ? atoi(env) : 32;
    size_t i;
    if (!shared) {
        printf("render: no ../shared/reference data; skipped\n");
        return 0;
    }
    for (i = 0; i < sizeof scenes / sizeof scenes[0]; ++i) {
        char path[1024], name[128];
        mt_render_options o;
        mt_error err;
        mt_scene *s;
        double t0, load, wall, cpu, n;
        snprintf(path, sizeof path, "%s/reference/scenes/%s.pbrt", shared, scenes[i]);
        mt_render_options_default(&o);
        t0 = now(CLOCK_MONOTONIC);
        s = mt_scene_load(path, &o, &err);
        load = now(CLOCK_MONOTONIC) - t0;
        if (!s) {
            char buf[1024];
            printf("render: %s\n", mt_error_format(&err, buf, sizeof buf));
            return 1;
        }
        if (i < 2 && (n = run(s, spp, 1, &wall, &cpu)) > 0) {
            snprintf(name, sizeof name, "render_%s_1t", scenes[i]);
            printf("BENCH %s %.4g samples/s\n", name, n / cpu);
        }
        if ((n = run(s, spp, 2, &wall, &cpu)) > 0) {
            snprintf(name, sizeof name, "render_%s_2t", scenes[i]);
            printf("BENCH %s %.4g samples/s\n", name, n / wall);
            snprintf(name, sizeof name, "render_%s_cpu", scenes[i]);
            printf("BENCH %s %.4g s/Msamples\n", name, cpu / n * 1e6);
            printf("%-12s loaded in %.3f s; %d spp on 2 threads: %.2f s wall, %.2f s CPU\n", scenes[i], load,
                   spp, wall, cpu);
        }
        mt_scene_destroy(s);
    }
    return 0;
}
