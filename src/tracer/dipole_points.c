/*
 * Irradiance points: pbrt-v2's FindPoissonPointDistribution
 * (renderers/surfacepoints.cpp SurfacePointTask::Run) and its points file.
 *
 * Paths leave the camera position in uniformly random directions and bounce
 * off every surface in a uniformly random direction on the side they came
 * from (the scene's bounding sphere catches rays that leave), up to 30 rays;
 * from the fourth ray on, a hit on a surface whose material has a BSSRDF is
 * a candidate, kept unless an earlier point lies closer than
 * minsampledistance, until maxFails (2000) candidates in a row are rejected.
 *
 * pbrt-v2 runs one task per core with shared counters, so its point set
 * depends on the thread count and the schedule. Here path k draws from PCG32
 * stream k of the render's seed, batches of BATCH paths are traced by all
 * threads (each a contiguous range) and their candidates are tested one by
 * one in path order: the points are a function of (scene, seed) alone. The
 * price is the rest of the last batch, traced and not needed.
 */
#include <string.h>
#include <pthread.h>
#include <time.h>
#include "core/alloc.h"
#include "materia/sampling.h"
#include "tracer/dipole.h"
#include "tracer/scene.h"

#define BATCH 8192
#define MAX_RAYS 30

/* ---- a hash grid of points, cells of the minimum distance -------------------- */

typedef struct pgrid {
    mt_real cell;
    struct slot { int64_t x, y, z; int head; } *slots;
    size_t cap, used;
    int *next; /* per point */
    size_t next_cap;
} pgrid;

static uint64_t cell_hash(int64_t x, int64_t y, int64_t z)
{
    uint64_t h = (uint64_t)x * 0x9E3779B97F4A7C15ull ^ (uint64_t)y * 0xC2B2AE3D27D4EB4Full ^
                 (uint64_t)z * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 32);
}

static int64_t cell_of(mt_real v, mt_real cell) { return (int64_t)floor((double)v / (double)cell); }

static struct slot *grid_find(const pgrid *g, int64_t x, int64_t y, int64_t z)
{
    size_t i = (size_t)cell_hash(x, y, z) & (g->cap - 1);
    for (;; i = (i + 1) & (g->cap - 1)) {
        struct slot *s = &g->slots[i];
        if (s->head < 0 || (s->x == x && s->y == y && s->z == z)) return s;
    }
}

static mt_status grid_init(pgrid *g, mt_real cell, mt_error *err)
{
    size_t i;
    memset(g, 0, sizeof *g);
    g->cell = cell;
    g->cap = 1024;
    if (!(g->slots = mt__malloc(g->cap * sizeof *g->slots))) return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance points");
    for (i = 0; i < g->cap; ++i) g->slots[i].head = -1;
    return MT_OK;
}

static void grid_free(pgrid *g)
{
    mt__free(g->slots);
    mt__free(g->next);
}

static mt_status grid_add(pgrid *g, mt_vec3 p, int index, mt_error *err)
{
    int64_t x = cell_of(p.x, g->cell), y = cell_of(p.y, g->cell), z = cell_of(p.z, g->cell);
    struct slot *s;
    if ((size_t)index >= g->next_cap) {
        size_t cap = g->next_cap ? 2 * g->next_cap : 1024;
        int *n = mt__realloc(g->next, cap * sizeof *n);
        if (!n) return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance points");
        g->next = n;
        g->next_cap = cap;
    }
    if (2 * (g->used + 1) > g->cap) {
        pgrid bigger = *g;
        size_t i;
        bigger.cap = 2 * g->cap;
        if (!(bigger.slots = mt__malloc(bigger.cap * sizeof *bigger.slots)))
            return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance points");
        for (i = 0; i < bigger.cap; ++i) bigger.slots[i].head = -1;
        for (i = 0; i < g->cap; ++i)
            if (g->slots[i].head >= 0) *grid_find(&bigger, g->slots[i].x, g->slots[i].y, g->slots[i].z) = g->slots[i];
        mt__free(g->slots);
        g->slots = bigger.slots;
        g->cap = bigger.cap;
    }
    s = grid_find(g, x, y, z);
    if (s->head < 0) {
        s->x = x;
        s->y = y;
        s->z = z;
        g->used++;
        g->next[index] = -1;
    } else {
        g->next[index] = s->head;
    }
    s->head = index;
    return MT_OK;
}

/* The number of points within squared distance r2 of p (r2 <= (k cell)^2). */
static int grid_count(const pgrid *g, const mt__ss_point *pts, mt_vec3 p, mt_real r2, int k, int stop_at_one)
{
    int64_t x = cell_of(p.x, g->cell), y = cell_of(p.y, g->cell), z = cell_of(p.z, g->cell), dx, dy, dz;
    int n = 0, i;
    for (dx = -k; dx <= k; ++dx)
        for (dy = -k; dy <= k; ++dy)
            for (dz = -k; dz <= k; ++dz) {
                const struct slot *s = grid_find(g, x + dx, y + dy, z + dz);
                for (i = s->head; i >= 0; i = g->next[i])
                    if (mt_v3_len2(mt_v3_sub(pts[i].p, p)) < r2) {
                        if (stop_at_one) return 1;
                        n++;
                    }
            }
    return n;
}

/* ---- the scene's bounding sphere (pbrt-v2's catch for escaping rays) ---------- */

typedef struct bsphere {
    double c[3], r;
} bsphere;

/* pbrt-v2 Sphere::Intersect for a sphere at c: the first root beyond tmin. */
static int bsphere_hit(const bsphere *b, const mt_ray *ray, double *thit)
{
    double o[3] = {(double)ray->o.x - b->c[0], (double)ray->o.y - b->c[1], (double)ray->o.z - b->c[2]};
    double d[3] = {ray->d.x, ray->d.y, ray->d.z};
    double A = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double B = 2 * (d[0] * o[0] + d[1] * o[1] + d[2] * o[2]);
    double C = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - b->r * b->r;
    double disc = B * B - 4 * A * C, q, t0, t1, t;
    if (b->r <= 0 || disc < 0 || A == 0) return 0;
    q = B < 0 ? -0.5 * (B - sqrt(disc)) : -0.5 * (B + sqrt(disc));
    t0 = q / A;
    t1 = q != 0 ? C / q : t0;
    if (t0 > t1) {
        t = t0;
        t0 = t1;
        t1 = t;
    }
    if (t0 > (double)ray->tmax || t1 < (double)ray->tmin) return 0;
    t = t0;
    if (t0 < (double)ray->tmin) {
        t = t1;
        if (t > (double)ray->tmax) return 0;
    }
    *thit = t;
    return 1;
}

static mt_vec3 faceforward(mt_vec3 n, mt_vec3 v) { return mt_v3_dot(n, v) < 0 ? mt_v3_neg(n) : n; }

/* ---- tracing the paths ------------------------------------------------------- */

typedef struct deposit_job {
    const mt_scene *s;
    uint64_t seed;
    mt_vec3 origin;
    bsphere sphere;
    long first; /* the batch's first path */
    int nthreads;
    struct cand_buf {
        mt__ss_point *c;
        size_t n, cap;
        int nomem;
    } *bufs;
} deposit_job;

typedef struct deposit_arg {
    deposit_job *job;
    int index;
} deposit_arg;

/* Only whether the material has one: its coefficients (kdsubsurface's
 * inversion of Kd included) are not needed to deposit a point. */
static int has_bssrdf(const mt__prim_info *info)
{
    return info && info->material && mt_material_has_bssrdf(info->material);
}

static void push_candidate(struct cand_buf *b, const mt__ss_point *p)
{
    if (b->n == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 4096;
        mt__ss_point *c = mt__realloc(b->c, cap * sizeof *c);
        if (!c) {
            b->nomem = 1;
            return;
        }
        b->c = c;
        b->cap = cap;
    }
    b->c[b->n++] = *p;
}

static void trace_path(const deposit_job *job, long k, struct cand_buf *out)
{
    const mt_scene *s = job->s;
    mt_rng rng;
    mt_ray ray;
    int depth;
    mt_rng_seed(&rng, job->seed, (uint64_t)k);
    {
        mt_real u1 = mt_rng_uniform(&rng), u2 = mt_rng_uniform(&rng);
        ray = mt_ray_make(job->origin, mt_uniform_sample_sphere(u1, u2), 0, MT_RAY_TMAX);
    }
    for (depth = 0; depth < MAX_RAYS; ++depth) {
        mt_hit hit;
        mt_vec3 dir, nn, p;
        mt_real u1, u2;
        if (mt_geometry_intersect(s->geom, &ray, &hit)) {
            mt_surface sf;
            mt_hit_surface_no_uv(&hit, &ray, &sf);
            nn = faceforward(sf.dg.n, mt_v3_neg(ray.d));
            if (depth >= 3 && has_bssrdf(mt_shape_user(hit.shape))) {
                mt__ss_point c;
                memset(&c, 0, sizeof c);
                c.p = sf.dg.p;
                c.n = nn;
                c.ng = sf.dg.n;
                c.p_error = sf.p_error;
                c.ray_epsilon = sf.ray_epsilon;
                c.next = -1;
                push_candidate(out, &c);
            }
            u1 = mt_rng_uniform(&rng);
            u2 = mt_rng_uniform(&rng);
            dir = faceforward(mt_uniform_sample_sphere(u1, u2), nn);
            ray = mt_surface_spawn(&sf, dir);
        } else {
            double t;
            if (!bsphere_hit(&job->sphere, &ray, &t)) break;
            p = mt_ray_at(&ray, (mt_real)t);
            nn = faceforward(mt_v3_normalize(mt_v3_sub(p, mt_v3((mt_real)job->sphere.c[0], (mt_real)job->sphere.c[1],
                                                                (mt_real)job->sphere.c[2]))),
                             mt_v3_neg(ray.d));
            u1 = mt_rng_uniform(&rng);
            u2 = mt_rng_uniform(&rng);
            dir = faceforward(mt_uniform_sample_sphere(u1, u2), nn);
            /* pbrt-v2's rayEpsilon of a quadric hit: 5e-4 t */
            ray = mt_ray_make(p, dir, (mt_real)(5e-4 * t), MT_RAY_TMAX);
        }
    }
}

static void *deposit_work(void *arg)
{
    deposit_arg *a = arg;
    deposit_job *job = a->job;
    long lo = job->first + (long)BATCH * a->index / job->nthreads;
    long hi = job->first + (long)BATCH * (a->index + 1) / job->nthreads, k;
    for (k = lo; k < hi && !job->bufs[a->index].nomem; ++k) trace_path(job, k, &job->bufs[a->index]);
    return NULL;
}

static mt_status trace_batch(deposit_job *job, mt_error *err)
{
    pthread_t th[256];
    deposit_arg args[256];
    int i, started = 0;
    for (i = 0; i < job->nthreads; ++i) {
        job->bufs[i].n = 0;
        args[i].job = job;
        args[i].index = i;
    }
    for (i = 1; i < job->nthreads; ++i) {
        if (pthread_create(&th[i], NULL, deposit_work, &args[i]) != 0) break;
        started = i;
    }
    deposit_work(&args[0]);
    for (i = 1; i <= started; ++i) pthread_join(th[i], NULL);
    if (started != job->nthreads - 1) {
        /* a thread could not start: its range, here */
        for (i = started + 1; i < job->nthreads; ++i) deposit_work(&args[i]);
    }
    for (i = 0; i < job->nthreads; ++i)
        if (job->bufs[i].nomem) return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance point candidates");
    return MT_OK;
}

static double points_now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static mt_status add_point(mt__dipole *d, size_t *cap, const mt__ss_point *p, mt_error *err)
{
    if ((size_t)d->npts == *cap) {
        size_t c = *cap ? 2 * *cap : 4096;
        mt__ss_point *n = mt__realloc(d->pts, c * sizeof *n);
        if (!n) return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance points");
        d->pts = n;
        *cap = c;
    }
    d->pts[d->npts++] = *p;
    return MT_OK;
}

mt_status mt__dipole_deposit(const mt_scene *s, uint64_t seed, int nthreads, mt_real min_dist,
                             const mt_render_options *o, mt__dipole *d, mt_error *err)
{
    deposit_job job;
    pgrid grid;
    mt_vec3 lo, hi;
    size_t cap = 0;
    mt_status st = MT_OK;
    int repeated = 0, done = 0, i;
    double t0 = points_now_s(), last = -1;
    mt_real area = MT_PI * (min_dist / 2) * (min_dist / 2), d2 = min_dist * min_dist;
    memset(&job, 0, sizeof job);
    job.s = s;
    job.seed = seed * 0x9E3779B97F4A7C15ull + 0x5eed0d1b01e5ull;
    job.nthreads = nthreads < 1 ? 1 : (nthreads > 256 ? 256 : nthreads);
    job.origin = mt_transform_point(&s->camera.camera_to_world, mt_v3(0, 0, 0));
    mt_geometry_bounds(s->geom, &lo, &hi);
    {
        /* pbrt-v2 BBox::BoundingSphere: the centre, and the radius to pMax
         * when the centre is inside (0 for an empty scene) */
        double c[3] = {0.5 * lo.x + 0.5 * hi.x, 0.5 * lo.y + 0.5 * hi.y, 0.5 * lo.z + 0.5 * hi.z};
        int inside = lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z;
        memcpy(job.sphere.c, c, sizeof c);
        job.sphere.r = inside ? sqrt((hi.x - c[0]) * (hi.x - c[0]) + (hi.y - c[1]) * (hi.y - c[1]) +
                                     (hi.z - c[2]) * (hi.z - c[2]))
                              : 0;
    }
    if (!(job.bufs = mt__calloc((size_t)job.nthreads, sizeof *job.bufs)))
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance points");
    if ((st = grid_init(&grid, min_dist, err)) != MT_OK) {
        mt__free(job.bufs);
        return st;
    }
    d->npts = 0;
    while (!done && st == MT_OK) {
        if ((st = trace_batch(&job, err)) != MT_OK) break;
        job.first += BATCH;
        d->paths = job.first;
        for (i = 0; i < job.nthreads && !done && st == MT_OK; ++i) {
            size_t j;
            for (j = 0; j < job.bufs[i].n; ++j) {
                mt__ss_point *c = &job.bufs[i].c[j];
                d->candidates++;
                if (grid_count(&grid, d->pts, c->p, d2, 1, 1)) {
                    if (++repeated > d->max_repeated_fails) d->max_repeated_fails = repeated;
                    if (repeated >= MT__DIPOLE_MAX_FAILS) {
                        done = 1;
                        break;
                    }
                } else {
                    c->area = area;
                    if ((st = add_point(d, &cap, c, err)) != MT_OK ||
                        (st = grid_add(&grid, c->p, d->npts - 1, err)) != MT_OK)
                        break;
                    repeated = 0;
                }
            }
        }
        if (!done && job.first > 50000 && d->npts == 0) {
            if (o && o->warn)
                o->warn(o->warn_ctx, NULL, 0, "There don't seem to be any objects with BSSRDFs in this scene.  Giving up.");
            done = 1;
        }
        if (o && o->stage) {
            double t = points_now_s();
            if (done || t - last >= 0.25) {
                double f = (double)d->max_repeated_fails / MT__DIPOLE_MAX_FAILS, el = t - t0;
                o->stage(o->progress_ctx, "depositing points", done ? 1.0 : f, d->npts, el,
                         done ? 0 : (f > 0 ? el * (1 - f) / f : -1));
                last = t;
            }
        }
    }
    for (i = 0; i < job.nthreads; ++i) mt__free(job.bufs[i].c);
    mt__free(job.bufs);
    grid_free(&grid);
    return st;
}

/* Corrected areas (MT_FIX_DIPOLE_AREA): pbrt-v2 gives every point the disk
 * of diameter minsampledistance, pi d^2 / 4, but a Poisson-disk set covers
 * only about half the surface with those disks, so the sum of the areas is
 * about half the surface's. Each point gets instead the area per point of
 * its neighbourhood: pi R^2 / (points within R), R = 3 d, which on a sphere
 * (or a plane) is exact for the cap the ball cuts out. */
void mt__dipole_fix_areas(mt__dipole *d, mt_real min_dist)
{
    pgrid grid;
    mt_error err;
    mt_real R = 3 * min_dist;
    int i;
    if (d->npts == 0 || grid_init(&grid, min_dist, &err) != MT_OK) return;
    for (i = 0; i < d->npts; ++i)
        if (grid_add(&grid, d->pts[i].p, i, &err) != MT_OK) {
            grid_free(&grid);
            return; /* out of memory: pbrt-v2's areas stay */
        }
    for (i = 0; i < d->npts; ++i) {
        int n = grid_count(&grid, d->pts, d->pts[i].p, R * R, 3, 0);
        d->pts[i].area = MT_PI * R * R / (mt_real)(n > 0 ? n : 1);
    }
    grid_free(&grid);
}
