/*
 * pbrt-v2's DipoleSubsurfaceIntegrator::Preprocess and its octree
 * (integrators/dipolesubsurface.cpp): the irradiance at every point from
 * every light, the octree of points (SubsurfaceOctreeNode::Insert,
 * InitHierarchy) and the hierarchical evaluation of Mo (Jensen and Buhler,
 * "A Rapid Hierarchical Rendering Technique for Translucent Materials",
 * SIGGRAPH 2002).
 */
#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "core/alloc.h"
#include "params/path.h"
#include "tracer/dipole.h"
#include "tracer/scene.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- irradiance ----------------------------------------------------------------
 * pbrt-v2: for each light, RoundUpPow2(nSamples) samples of a scrambled
 * (0,2)-sequence (Sample02) for the position and a scrambled van der Corput
 * value for the component, the scrambles from an RNG; light from below the
 * point's normal is skipped; E += Li |wi.n| / pdf when unoccluded, divided by
 * the sample count. pbrt-v2 draws the scrambles from one RNG in point order;
 * here point i has its own PCG32 stream, so points can be shared out. */

static uint32_t van_der_corput(uint32_t n, uint32_t scramble) { return mt__reverse_bits(n) ^ scramble; }

static uint32_t sobol2(uint32_t n, uint32_t scramble)
{
    uint32_t v;
    for (v = 1u << 31; n != 0; n >>= 1, v ^= v >> 1)
        if (n & 1) scramble ^= v;
    return scramble;
}

static int round_up_pow2(int v)
{
    int p = 1;
    while (p < v && p < (1 << 24)) p <<= 1;
    return p;
}

static void point_irradiance(const mt_scene *s, uint64_t seed, int i, mt__ss_point *pt)
{
    mt_surface sf;
    mt_rng rng;
    mt_rgb E = mt_rgb_black();
    int j, k;
    memset(&sf, 0, sizeof sf);
    sf.dg.p = pt->p;
    sf.dg.n = pt->ng;
    sf.p_error = pt->p_error;
    sf.ray_epsilon = pt->ray_epsilon;
    mt_rng_seed(&rng, seed, (uint64_t)i);
    for (j = 0; j < s->nlights; ++j) {
        const mt__light *light = &s->lights[j];
        int n = round_up_pow2(light->nsamples);
        uint32_t sc0 = mt_rng_u32(&rng), sc1 = mt_rng_u32(&rng), comp = mt_rng_u32(&rng);
        mt_rgb El = mt_rgb_black();
        for (k = 0; k < n; ++k) {
            mt__light_sample ls;
            mt_real u0 = mt__u32_to_unit(van_der_corput((uint32_t)k, sc0));
            mt_real u1 = mt__u32_to_unit(sobol2((uint32_t)k, sc1));
            mt_real uc = mt__u32_to_unit(van_der_corput((uint32_t)k, comp));
            mt__light_sample_l(light, &sf, pt->p, uc, u0, u1, &ls);
            if (mt_v3_dot(ls.wi, pt->n) <= 0) continue;
            if (mt_rgb_is_black(ls.Li) || ls.pdf == 0) continue;
            if (!mt_geometry_occluded(s->geom, &ls.shadow))
                El = mt_rgb_add(El, mt_rgb_scale(ls.Li, mt_v3_absdot(ls.wi, pt->n) / ls.pdf));
        }
        E = mt_rgb_add(E, mt_rgb_divs(El, (mt_real)n));
    }
    pt->E = mt_rgb_is_finite(E) ? E : mt_rgb_black();
}

#define IRR_CHUNK 256

typedef struct irr_job {
    const mt_scene *s;
    mt__dipole *d;
    uint64_t seed;
    int next, done;
    pthread_mutex_t mu;
} irr_job;

/* Takes chunks until none is left; returns after one chunk when `once`. */
static void irr_chunks(irr_job *job, int once)
{
    for (;;) {
        int lo, hi, i;
        pthread_mutex_lock(&job->mu);
        lo = job->next;
        job->next = lo + IRR_CHUNK < job->d->npts ? lo + IRR_CHUNK : job->d->npts;
        hi = job->next;
        pthread_mutex_unlock(&job->mu);
        if (lo >= hi) return;
        for (i = lo; i < hi; ++i) point_irradiance(job->s, job->seed, i, &job->d->pts[i]);
        pthread_mutex_lock(&job->mu);
        job->done += hi - lo;
        pthread_mutex_unlock(&job->mu);
        if (once) return;
    }
}

static void *irr_work(void *arg)
{
    irr_chunks(arg, 0);
    return NULL;
}

mt_status mt__dipole_irradiance(const mt_scene *s, uint64_t seed, int nthreads, const mt_render_options *o,
                                mt__dipole *d, mt_error *err)
{
    irr_job job;
    pthread_t th[256];
    int i, started = 0;
    double t0 = now_s(), last = -1;
    (void)err;
    memset(&job, 0, sizeof job);
    job.s = s;
    job.d = d;
    job.seed = seed * 0xD1B54A32D192ED03ull + 0x1ad1a9ce5ull;
    pthread_mutex_init(&job.mu, NULL);
    if (nthreads > 256) nthreads = 256;
    for (i = 1; i < nthreads; ++i) {
        if (pthread_create(&th[i], NULL, irr_work, &job) != 0) break;
        started = i;
    }
    for (;;) {
        int before, total = d->npts, finished;
        pthread_mutex_lock(&job.mu);
        before = job.next;
        pthread_mutex_unlock(&job.mu);
        if (before < total) irr_chunks(&job, 1);
        pthread_mutex_lock(&job.mu);
        finished = job.done;
        pthread_mutex_unlock(&job.mu);
        if (o && o->stage) {
            double t = now_s();
            if (t - last >= 0.25 || finished >= total) {
                double f = total > 0 ? (double)finished / total : 1, el = t - t0;
                /* the line for 100% is drawn once, after the workers are joined */
                if (finished < total)
                    o->stage(o->progress_ctx, "computing irradiance", f, total, el, f > 0 ? el * (1 - f) / f : -1);
                last = t;
            }
        }
        if (before >= total) break;
    }
    for (i = 1; i <= started; ++i) pthread_join(th[i], NULL);
    if (o && o->stage) o->stage(o->progress_ctx, "computing irradiance", 1, d->npts, now_s() - t0, 0);
    pthread_mutex_destroy(&job.mu);
    return MT_OK;
}

/* ---- the octree ------------------------------------------------------------------ */

struct mt__ss_node {
    mt_vec3 p;       /* the cluster's position: irradiance-weighted mean */
    mt_rgb E;        /* the cluster's irradiance */
    mt_real sum_area;
    int leaf, count, head; /* a leaf: its points, a list through mt__ss_point.next */
    mt__ss_node *child[8];
};

/* Beyond this depth a leaf takes any number of points: pbrt-v2 recurses
 * without end when more than 8 points share a position (a points file can
 * hold them). */
#define OCT_MAX_DEPTH 40

static void child_bound(int c, const mt_vec3 *lo, const mt_vec3 *hi, mt_vec3 mid, mt_vec3 *clo, mt_vec3 *chi)
{
    /* pbrt-v2 octreeChildBound */
    clo->x = (c & 4) ? mid.x : lo->x;
    chi->x = (c & 4) ? hi->x : mid.x;
    clo->y = (c & 2) ? mid.y : lo->y;
    chi->y = (c & 2) ? hi->y : mid.y;
    clo->z = (c & 1) ? mid.z : lo->z;
    chi->z = (c & 1) ? hi->z : mid.z;
}

static mt_vec3 midpoint(const mt_vec3 *lo, const mt_vec3 *hi)
{
    return mt_v3((mt_real)0.5 * lo->x + (mt_real)0.5 * hi->x, (mt_real)0.5 * lo->y + (mt_real)0.5 * hi->y,
                 (mt_real)0.5 * lo->z + (mt_real)0.5 * hi->z);
}

static int child_of(mt_vec3 p, mt_vec3 mid) { return (p.x > mid.x ? 4 : 0) + (p.y > mid.y ? 2 : 0) + (p.z > mid.z ? 1 : 0); }

static mt__ss_node *new_node(mt_arena *a)
{
    mt__ss_node *n = mt_arena_alloc(a, sizeof *n);
    if (n) {
        memset(n, 0, sizeof *n);
        n->leaf = 1;
        n->head = -1;
    }
    return n;
}

static int insert(mt__dipole *d, mt__ss_node *node, mt_vec3 lo, mt_vec3 hi, int ip, int depth)
{
    mt__ss_point *pts = d->pts;
    for (;;) {
        mt_vec3 mid = midpoint(&lo, &hi), clo, chi;
        int c;
        if (node->leaf) {
            if (node->count < 8 || depth >= OCT_MAX_DEPTH) {
                /* appended: the leaf keeps pbrt-v2's insertion order */
                int *link = &node->head;
                while (*link >= 0) link = &pts[*link].next;
                *link = ip;
                pts[ip].next = -1;
                node->count++;
                return 1;
            }
            {
                /* the leaf becomes an interior node: its points go down */
                int q = node->head, next;
                node->leaf = 0;
                node->head = -1;
                node->count = 0;
                for (; q >= 0; q = next) {
                    next = pts[q].next;
                    c = child_of(pts[q].p, mid);
                    if (!node->child[c] && !(node->child[c] = new_node(d->arena))) return 0;
                    child_bound(c, &lo, &hi, mid, &clo, &chi);
                    if (!insert(d, node->child[c], clo, chi, q, depth + 1)) return 0;
                }
            }
        }
        c = child_of(pts[ip].p, mid);
        if (!node->child[c] && !(node->child[c] = new_node(d->arena))) return 0;
        child_bound(c, &lo, &hi, mid, &clo, &chi);
        node = node->child[c];
        lo = clo;
        hi = chi;
        depth++;
    }
}

/* pbrt-v2 InitHierarchy: a node's irradiance is the plain mean of its
 * points' (a leaf) or of its children's (an interior node), its position
 * the mean weighted by y(E), its area the sum. The mean of the children
 * ignores how much area each holds: a cluster's E * area is not the sum of
 * its points' E * area (erratum octree-cluster). Corrected, both means are
 * weighted by area. */
static void init_hierarchy(mt__dipole *d, mt__ss_node *n)
{
    int weighted = (d->mode & MT_FIX_OCTREE_CLUSTER) != 0, count = 0, i;
    mt_real sum_wt = 0, sum_a = 0;
    mt_vec3 p = mt_v3(0, 0, 0), pa = mt_v3(0, 0, 0);
    mt_rgb E = mt_rgb_black();
    if (n->leaf) {
        for (i = n->head; i >= 0; i = d->pts[i].next) {
            const mt__ss_point *q = &d->pts[i];
            mt_real w = weighted ? q->area : 1, wt = mt_rgb_y(q->E) * w;
            E = mt_rgb_add(E, mt_rgb_scale(q->E, w));
            p = mt_v3_add(p, mt_v3_scale(q->p, wt));
            pa = mt_v3_add(pa, mt_v3_scale(q->p, q->area));
            sum_wt += wt;
            sum_a += q->area;
            count++;
        }
    } else {
        for (i = 0; i < 8; ++i) {
            mt__ss_node *c = n->child[i];
            mt_real w, wt;
            if (!c) continue;
            init_hierarchy(d, c);
            w = weighted ? c->sum_area : 1;
            wt = mt_rgb_y(c->E) * w;
            E = mt_rgb_add(E, mt_rgb_scale(c->E, w));
            p = mt_v3_add(p, mt_v3_scale(c->p, wt));
            pa = mt_v3_add(pa, mt_v3_scale(c->p, c->sum_area));
            sum_wt += wt;
            sum_a += c->sum_area;
            count++;
        }
    }
    n->sum_area = sum_a;
    if (sum_wt > 0) p = mt_v3_scale(p, 1 / sum_wt);
    /* pbrt-v2 leaves p at the origin when no point is lit; corrected, the
     * area-weighted centre (E = 0 there: only the error criterion sees it) */
    else if (weighted && sum_a > 0) p = mt_v3_scale(pa, 1 / sum_a);
    n->p = p;
    if (weighted) n->E = sum_a > 0 ? mt_rgb_divs(E, sum_a) : mt_rgb_black();
    else n->E = count > 0 ? mt_rgb_divs(E, (mt_real)count) : mt_rgb_black();
}

mt_status mt__dipole_octree(mt__dipole *d, mt_error *err)
{
    int i;
    d->root = NULL;
    if (d->npts == 0) return MT_OK;
    if (!d->arena && !(d->arena = mt_arena_create(0)))
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance octree");
    d->lo = d->hi = d->pts[0].p;
    for (i = 1; i < d->npts; ++i) {
        mt_vec3 q = d->pts[i].p;
        d->lo = mt_v3(mt_min(d->lo.x, q.x), mt_min(d->lo.y, q.y), mt_min(d->lo.z, q.z));
        d->hi = mt_v3(mt_max(d->hi.x, q.x), mt_max(d->hi.y, q.y), mt_max(d->hi.z, q.z));
    }
    if (!(d->root = new_node(d->arena))) return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance octree");
    for (i = 0; i < d->npts; ++i) d->pts[i].next = -1;
    for (i = 0; i < d->npts; ++i)
        if (!insert(d, d->root, d->lo, d->hi, i, 0)) {
            d->root = NULL;
            return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance octree");
        }
    init_hierarchy(d, d->root);
    return MT_OK;
}

static int inside(mt_vec3 p, mt_vec3 lo, mt_vec3 hi)
{
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
}

static mt_rgb node_mo(const mt__dipole *d, const mt__ss_node *n, mt_vec3 lo, mt_vec3 hi, mt_vec3 pt,
                      const mt__diffusion *rd, mt_real maxerror)
{
    mt_real d2 = mt_v3_len2(mt_v3_sub(pt, n->p));
    mt_rgb Mo = mt_rgb_black();
    int i;
    if (n->sum_area < maxerror * d2 && !inside(pt, lo, hi))
        return mt_rgb_scale(mt_rgb_mul(mt__diffusion_eval(rd, d2), n->E), n->sum_area);
    if (n->leaf) {
        for (i = n->head; i >= 0; i = d->pts[i].next) {
            const mt__ss_point *q = &d->pts[i];
            mt_real qd2 = mt_v3_len2(mt_v3_sub(pt, q->p));
            Mo = mt_rgb_add(Mo, mt_rgb_scale(mt_rgb_mul(mt__diffusion_eval(rd, qd2), q->E), q->area));
        }
    } else {
        mt_vec3 mid = midpoint(&lo, &hi), clo, chi;
        for (i = 0; i < 8; ++i) {
            if (!n->child[i]) continue;
            child_bound(i, &lo, &hi, mid, &clo, &chi);
            Mo = mt_rgb_add(Mo, node_mo(d, n->child[i], clo, chi, pt, rd, maxerror));
        }
    }
    return Mo;
}

mt_rgb mt__dipole_mo(const mt__dipole *d, mt_vec3 p, const mt__diffusion *rd, mt_real maxerror)
{
    if (!d->root) return mt_rgb_black();
    return node_mo(d, d->root, d->lo, d->hi, p, rd, maxerror);
}

mt_rgb mt__dipole_mo_brute(const mt__dipole *d, mt_vec3 p, const mt__diffusion *rd)
{
    mt_rgb Mo = mt_rgb_black();
    int i;
    for (i = 0; i < d->npts; ++i) {
        const mt__ss_point *q = &d->pts[i];
        Mo = mt_rgb_add(Mo, mt_rgb_scale(mt_rgb_mul(mt__diffusion_eval(rd, mt_v3_len2(mt_v3_sub(p, q->p))), q->E), q->area));
    }
    return Mo;
}

/* ---- the whole preprocess ----------------------------------------------------------- */

void mt__dipole_free(mt__dipole *d)
{
    if (!d) return;
    mt__free(d->pts);
    if (d->arena) mt_arena_destroy(d->arena);
    memset(d, 0, sizeof *d);
}

mt_status mt__dipole_build(const mt_scene *s, const mt_render_options *o, int nthreads, mt__dipole *d,
                           mt_error *err)
{
    const mt__dipole_params *dp = &s->dipole;
    mt_status st;
    double t0 = now_s();
    memset(d, 0, sizeof *d);
    d->maxerror = dp->maxerror;
    d->mode = s->mode;
    /* pbrt-v2: no lights, no preprocess and no subsurface light */
    if (s->nlights == 0) return MT_OK;
    if (dp->nfile_pts > 0) {
        if (!(d->pts = mt__malloc((size_t)dp->nfile_pts * sizeof *d->pts)))
            return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the irradiance points");
        memcpy(d->pts, dp->file_pts, (size_t)dp->nfile_pts * sizeof *d->pts);
        d->npts = dp->nfile_pts;
    } else {
        if ((st = mt__dipole_deposit(s, o->seed, nthreads, dp->min_dist, o, d, err)) != MT_OK) return st;
        if (s->mode & MT_FIX_DIPOLE_AREA) mt__dipole_fix_areas(d, dp->min_dist);
    }
    d->seconds_points = now_s() - t0;
    t0 = now_s();
    if ((st = mt__dipole_irradiance(s, o->seed, nthreads, o, d, err)) != MT_OK) return st;
    if ((st = mt__dipole_octree(d, err)) != MT_OK) return st;
    d->seconds_irradiance = now_s() - t0;
    return MT_OK;
}

/* ---- pbrt-v2's points file (core/floatfile.cpp ReadFloatFile) -------------------- */

mt_status mt__dipole_read_points(const char *path, mt__ss_point **out, int *nout, mt_error *err)
{
    char *data = NULL, *c;
    size_t len, n = 0, cap = 0;
    double *v = NULL;
    int line = 1, i;
    mt_status st;
    *out = NULL;
    *nout = 0;
    if ((st = mt__read_file(path, &data, &len, err)) != MT_OK) return st;
    for (c = data; *c;) {
        if (*c == '\n') {
            line++;
            c++;
        } else if (*c == '#') {
            while (*c && *c != '\n') c++;
        } else if (*c == ' ' || *c == '\t' || *c == '\r' || *c == ',') {
            c++;
        } else {
            char *end;
            double x;
            errno = 0;
            x = strtod(c, &end);
            if (end == c || !(*end == 0 || *end == ' ' || *end == '\t' || *end == '\r' || *end == '\n' ||
                              *end == '#' || *end == ',') || !isfinite(x)) {
                st = mt_error_param(err, MT_ERR_PARSE, "pointsfile", "points file: \"%.*s\" is not a finite number",
                                    (int)strcspn(c, " \t\r\n#"), c);
                goto fail;
            }
            if (n == cap) {
                size_t nc = cap ? 2 * cap : 1024;
                double *nv = mt__realloc(v, nc * sizeof *nv);
                if (!nv) {
                    st = mt_error_set(err, MT_ERR_NOMEM, "out of memory reading the points file");
                    goto fail;
                }
                v = nv;
                cap = nc;
            }
            v[n++] = x;
            c = end;
        }
        continue;
    fail:
        mt_error_locate(err, path, line, 0);
        mt__free(v);
        mt__free(data);
        return st;
    }
    mt__free(data);
    if (n % 8 != 0) {
        mt__free(v);
        mt_error_param(err, MT_ERR_PARSE, "pointsfile",
                       "points file: %zu values, not a multiple of 8 (position, normal, area, ray epsilon per point): %zu in excess",
                       n, n % 8);
        mt_error_locate(err, path, line, 0);
        return MT_ERR_PARSE;
    }
    if (n / 8 > 0x7fffffff / 2) {
        mt__free(v);
        return mt_error_param(err, MT_ERR_LIMIT, "pointsfile", "points file: too many points");
    }
    if (n > 0 && !(*out = mt__calloc(n / 8, sizeof **out))) {
        mt__free(v);
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory reading the points file");
    }
    for (i = 0; i < (int)(n / 8); ++i) {
        const double *f = v + 8 * i;
        mt__ss_point *p = &(*out)[i];
        mt_vec3 nn = mt_v3((mt_real)f[3], (mt_real)f[4], (mt_real)f[5]);
        if (!(mt_v3_len2(nn) > 0) || !(f[6] >= 0) || !(f[7] >= 0)) {
            mt_error_param(err, MT_ERR_INVALID, "pointsfile",
                           "points file: point %d has a zero normal or a negative area or ray epsilon", i + 1);
            mt_error_locate(err, path, 0, 0);
            mt__free(*out);
            *out = NULL;
            mt__free(v);
            return MT_ERR_INVALID;
        }
        p->p = mt_v3((mt_real)f[0], (mt_real)f[1], (mt_real)f[2]);
        p->n = p->ng = nn; /* pbrt-v2 uses the normal as it is */
        p->area = (mt_real)f[6];
        p->ray_epsilon = (mt_real)f[7];
        p->p_error = mt_v3(p->ray_epsilon, p->ray_epsilon, p->ray_epsilon);
        p->next = -1;
    }
    *nout = (int)(n / 8);
    mt__free(v);
    return MT_OK;
}
