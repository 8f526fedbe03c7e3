/*
 * The renderer (pbrt-v2 renderers/samplerrenderer.cpp): tiles of sample
 * pixels on pthreads, one arena per thread reset after every camera sample,
 * pbrt-v2's rejection of NaN, infinite and negative samples, and a film
 * whose sums do not depend on the schedule: every tile accumulates into a
 * buffer of its own, and buffers are added to the image strictly in tile
 * order (a finished tile waits in its buffer until the tiles before it are
 * in; a thread takes a new tile only when a buffer is free, and buffers go
 * to tiles in tile order, so the tile everyone waits for always has one).
 */
#include <math.h>
#include <pthread.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "core/alloc.h"
#include "tracer/scene.h"

typedef struct render_job {
    const mt_scene *s;
    int spp;
    uint64_t seed;
    int tile, ntx, ntiles;
    mt__sobol_tables tables;
    mt__film_buf image;
    mt__film_buf *pool;
    int npool, *free_list, nfree;
    mt__film_buf **pending;
    int next_tile, next_merge;
    pthread_mutex_t mu;
    pthread_cond_t buffer_cv, progress_cv;
    long rejected, shading_failures;
    const mt__dipole *dipole;
} render_job;

typedef struct worker {
    render_job *job;
    mt_arena *arena;
    pthread_t thread;
} worker;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* pbrt-v2 SamplerRendererTask::Run: NaN, y < -1e-5 and infinite y become black. */
static int reject(mt_rgb L)
{
    mt_real y;
    if (mt_is_nan(L.c[0]) || mt_is_nan(L.c[1]) || mt_is_nan(L.c[2])) return 1;
    y = mt_rgb_y(L);
    return y < (mt_real)-1e-5 || !mt_is_finite(y);
}

static void render_tile(render_job *job, mt__thread_ctx *tc, int t, mt__film_buf *buf)
{
    const mt_scene *s = job->s;
    const mt__film *film = &s->film;
    int tx = t % job->ntx, ty = t / job->ntx;
    int x0 = film->sx0 + tx * job->tile, y0 = film->sy0 + ty * job->tile;
    int x1 = x0 + job->tile < film->sx1 ? x0 + job->tile : film->sx1;
    int y1 = y0 + job->tile < film->sy1 ? y0 + job->tile : film->sy1;
    mt_real diff_scale = 1 / mt_sqrt((mt_real)job->spp);
    int x, y, i;
    mt__film_buf_cover(film, buf, x0, x1, y0, y1);
    for (y = y0; y < y1; ++y)
        for (x = x0; x < x1; ++x) {
            mt__dim_seeds image_seeds, lens_seeds;
            mt__thread_start_pixel(tc, &job->tables, job->seed, x, y);
            mt__dim_seeds_init(&tc->sampler, MT__DIM_IMAGE, &image_seeds);
            mt__dim_seeds_init(&tc->sampler, MT__DIM_LENS, &lens_seeds);
            for (i = 0; i < job->spp; ++i) {
                mt__camera_sample cs;
                mt_raydiff rd;
                mt_real u[2];
                mt_rgb L;
                tc->index = (uint32_t)i;
                tc->rindex = mt__reverse_bits((uint32_t)i);
                mt__sample_2d_rev(&job->tables, &image_seeds, tc->rindex, u);
                if (s->independent_image) mt__independent_pair(tc, MT__DIM_IMAGE, tc->index, 3u, u);
                cs.image_x = (mt_real)x + u[0];
                cs.image_y = (mt_real)y + u[1];
                cs.lens_u = cs.lens_v = (mt_real)0.5;
                if (s->camera.lens_radius > 0) {
                    mt__sample_2d_rev(&job->tables, &lens_seeds, tc->rindex, u);
                    cs.lens_u = u[0];
                    cs.lens_v = u[1];
                }
                mt__camera_ray(&s->camera, &cs, &rd);
                L = mt__li(tc, &rd, diff_scale);
                if (reject(L)) {
                    L = mt_rgb_black();
                    tc->rejected++;
                }
                mt__film_add(film, buf, cs.image_x, cs.image_y, L);
                mt_arena_reset(tc->arena);
            }
        }
}

static void *work(void *arg)
{
    worker *w = arg;
    render_job *job = w->job;
    mt__thread_ctx tc;
    memset(&tc, 0, sizeof tc);
    tc.scene = job->s;
    tc.arena = w->arena;
    tc.dipole = job->dipole;
    {
        int v;
        for (v = 0; v < MT__INDEPENDENT_VERTICES; ++v) tc.any_independent |= job->s->independent[v] != 0;
    }
    for (;;) {
        int t, b;
        mt__film_buf *buf;
        pthread_mutex_lock(&job->mu);
        while (job->nfree == 0 && job->next_tile < job->ntiles)
            pthread_cond_wait(&job->buffer_cv, &job->mu);
        if (job->next_tile >= job->ntiles) {
            job->rejected += tc.rejected;
            job->shading_failures += tc.shading_failures;
            pthread_mutex_unlock(&job->mu);
            return NULL;
        }
        t = job->next_tile++;
        b = job->free_list[--job->nfree];
        buf = &job->pool[b];
        pthread_mutex_unlock(&job->mu);

        render_tile(job, &tc, t, buf);

        pthread_mutex_lock(&job->mu);
        job->pending[t] = buf;
        while (job->next_merge < job->ntiles && job->pending[job->next_merge]) {
            mt__film_buf *p = job->pending[job->next_merge];
            mt__film_buf_merge(&job->image, p);
            job->pending[job->next_merge++] = NULL;
            job->free_list[job->nfree++] = (int)(p - job->pool);
        }
        pthread_cond_broadcast(&job->buffer_cv);
        pthread_cond_signal(&job->progress_cv);
        pthread_mutex_unlock(&job->mu);
    }
}

static int online_processors(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (n > 256 ? 256 : (int)n);
}

static void job_free(render_job *job, worker *w, int nthreads)
{
    int i;
    for (i = 0; i < nthreads; ++i) mt_arena_destroy(w[i].arena);
    for (i = 0; i < job->npool; ++i) mt__film_buf_free(&job->pool[i]);
    mt__film_buf_free(&job->image);
    mt__free(job->pool);
    mt__free(job->free_list);
    mt__free(job->pending);
    mt__free(w);
}

static mt_status job_init(render_job *job, worker **wout, int nthreads, mt_error *err)
{
    const mt__film *film = &job->s->film;
    int nty = (film->sy1 - film->sy0 + job->tile - 1) / job->tile, i;
    size_t cap = mt__film_tile_pixels(film, job->tile);
    worker *w;
    job->ntx = (film->sx1 - film->sx0 + job->tile - 1) / job->tile;
    job->ntiles = job->ntx * nty;
    job->npool = 2 * nthreads + 2;
    job->pool = mt__calloc((size_t)job->npool, sizeof *job->pool);
    job->free_list = mt__calloc((size_t)job->npool, sizeof *job->free_list);
    job->pending = mt__calloc((size_t)job->ntiles + 1, sizeof *job->pending);
    *wout = w = mt__calloc((size_t)nthreads, sizeof *w);
    if (!job->pool || !job->free_list || !job->pending || !w) {
        job->npool = 0;
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the render");
    }
    for (i = 0; i < job->npool; ++i) {
        if (mt__film_buf_alloc(&job->pool[i], cap, err) != MT_OK) {
            job->npool = i;
            return MT_ERR_NOMEM;
        }
        job->free_list[job->nfree++] = i;
    }
    if (mt__film_buf_alloc(&job->image, (size_t)film->width * (size_t)film->height, err) != MT_OK)
        return MT_ERR_NOMEM;
    job->image.x0 = film->x0;
    job->image.y0 = film->y0;
    job->image.w = film->width;
    job->image.h = film->height;
    for (i = 0; i < nthreads; ++i) {
        w[i].job = job;
        if (!(w[i].arena = mt_arena_create(0)))
            return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the arenas");
    }
    mt__sobol_tables_init(&job->tables);
    return MT_OK;
}

/* The calling thread reports progress while the workers render. */
static void watch(render_job *job, const mt_render_options *o, double t0)
{
    double last = -1;
    pthread_mutex_lock(&job->mu);
    for (;;) {
        double t = now(), f = (double)job->next_merge / (double)job->ntiles;
        int done = job->next_merge >= job->ntiles;
        if (o->progress && (done || t - last >= 0.25)) {
            double el = t - t0, rem = f > 0 ? el * (1 - f) / f : -1;
            pthread_mutex_unlock(&job->mu);
            o->progress(o->progress_ctx, f, el, rem);
            pthread_mutex_lock(&job->mu);
            last = t;
        }
        if (done) break;
        {
            struct timespec ts;
            clock_gettime(CLOCK_REALTIME, &ts);
            ts.tv_nsec += 250000000L;
            if (ts.tv_nsec >= 1000000000L) {
                ts.tv_sec += 1;
                ts.tv_nsec -= 1000000000L;
            }
            if (job->next_merge < job->ntiles)
                pthread_cond_timedwait(&job->progress_cv, &job->mu, &ts);
        }
    }
    pthread_mutex_unlock(&job->mu);
}

mt_status mt_scene_render(const mt_scene *s, const mt_render_options *o, mt_image *image,
                          mt_image *variance, mt_render_stats *stats, mt_error *err)
{
    mt_render_options def;
    render_job job;
    mt__dipole dip;
    worker *w = NULL;
    int nthreads, started = 0, i;
    double t0, t1;
    mt_status st;
    mt_error_clear(err);
    if (!o) {
        mt_render_options_default(&def);
        o = &def;
    }
    mt_error_clear(err);
    memset(image, 0, sizeof *image);
    if (variance) memset(variance, 0, sizeof *variance);
    if (o->spp < 0 || o->spp > (1 << 24) || o->threads < 0 || o->tile_size < 0)
        return mt_error_set(err, MT_ERR_INVALID, "render options: spp must be in [0, 2^24], "
                                                 "threads and tile_size >= 0");
    memset(&job, 0, sizeof job);
    job.s = s;
    job.spp = o->spp > 0 ? o->spp : s->spp;
    job.seed = o->seed;
    job.tile = o->tile_size > 0 ? o->tile_size : 16;
    nthreads = o->threads > 0 ? o->threads : online_processors();
    if ((st = job_init(&job, &w, nthreads, err)) != MT_OK) {
        job_free(&job, w, w ? nthreads : 0);
        return st;
    }
    /* the sums of squared weights serve the variance only */
    for (i = 0; i < job.npool; ++i) job.pool[i].second_moments = variance != NULL;
    t0 = now();
    memset(&dip, 0, sizeof dip);
    if (s->integrator == MT__INTEGRATOR_DIPOLE) {
        /* pbrt-v2's Preprocess, once per render: the points depend on the seed */
        if ((st = mt__dipole_build(s, o, nthreads, &dip, err)) != MT_OK) {
            mt__dipole_free(&dip);
            job_free(&job, w, nthreads);
            return st;
        }
        job.dipole = &dip;
    }
    t1 = now();
    pthread_mutex_init(&job.mu, NULL);
    pthread_cond_init(&job.buffer_cv, NULL);
    pthread_cond_init(&job.progress_cv, NULL);
    for (i = 0; i < nthreads; ++i)
        if (pthread_create(&w[i].thread, NULL, work, &w[i]) == 0) started++;
        else break;
    if (started == 0) {
        st = mt_error_set(err, MT_ERR_LIMIT, "cannot start a render thread");
    } else {
        watch(&job, o, t1);
        for (i = 0; i < started; ++i) pthread_join(w[i].thread, NULL);
        st = mt__film_develop(&s->film, &job.image, image, variance, err);
    }
    if (stats) {
        double el = now() - t0;
        memset(stats, 0, sizeof *stats);
        stats->seconds = el;
        stats->preprocess_seconds = t1 - t0;
        stats->points = dip.npts;
        stats->samples = (double)(s->film.sx1 - s->film.sx0) * (double)(s->film.sy1 - s->film.sy0) *
                         (double)job.spp;
        stats->samples_per_second = el > 0 ? stats->samples / el : 0;
        stats->threads = started;
        stats->spp = job.spp;
        stats->rejected = job.rejected;
        stats->shading_failures = job.shading_failures;
    }
    pthread_cond_destroy(&job.progress_cv);
    pthread_cond_destroy(&job.buffer_cv);
    pthread_mutex_destroy(&job.mu);
    job_free(&job, w, nthreads);
    mt__dipole_free(&dip);
    return st;
}
