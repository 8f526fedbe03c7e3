/*
 * materia's BVH and Embree 3 side by side, on the same triangles and the
 * same rays (tests/support/traysets.h: primary, incoherent, occlusion), for
 * the bunny and the killeroo of ../shared/reference/scenes/geometry.
 *
 * Single rays (rtcIntersect1 / rtcOccluded1 against mt_geometry_intersect /
 * mt_geometry_occluded), one thread, on the thread's CPU time. The two
 * tracers alternate pass by pass (materia, Embree, Embree, materia, ...) so
 * that both see the same machine; each figure is the median of the passes.
 * Builds: mt_geometry_commit against rtcCommitScene on a device limited to
 * one thread, at Embree's default (medium) and high build quality, medians
 * of alternating builds. Embree is only a benchmark's dependency: this
 * program is built by make bench where Embree's headers and library are
 * found, and nothing else needs it.
 *
 * The answers are compared too: the rays whose hit or miss differs and the
 * closest hits whose distances differ by more than 1e-4 relative (watertight
 * edges and Embree's own epsilon differ, so a few may).
 *
 * usage: bvh-embree [--build] [MESH.pbrt ...]   (default: bunny.pbrt killeroo.pbrt)
 *   --build  the builds only (tools/bench-pbrt.sh sets them beside pbrt-v2's)
 * environment: MT_BENCH_PASSES (default 5)
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <embree3/rtcore.h>
#include "support/check.h"
#include "support/tgeom.h"
#include "support/traysets.h"

#define MAX_PASSES 15

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

/* The triangles of every mesh of g, world space, as Embree wants them. */
typedef struct tris {
    float *v;
    unsigned *ix;
    size_t nv, nt;
} tris;

static int gather(const mt_geometry *g, tris *t)
{
    uint32_t s, ns = mt_geometry_shape_count(g);
    size_t nv = 0, nt = 0, i;
    memset(t, 0, sizeof *t);
    for (s = 0; s < ns; ++s) {
        mt_mesh_view m;
        if (!mt_shape_mesh(mt_geometry_shape(g, s), &m)) return 0; /* meshes only */
        nv += m.nverts;
        nt += m.ntris;
    }
    t->v = malloc(3 * nv * sizeof *t->v);
    t->ix = malloc(3 * nt * sizeof *t->ix);
    if (!t->v || !t->ix) return 0;
    for (s = 0; s < ns; ++s) {
        mt_mesh_view m;
        mt_shape_mesh(mt_geometry_shape(g, s), &m);
        for (i = 0; i < 3 * (size_t)m.ntris; ++i) t->ix[3 * t->nt + i] = (unsigned)(m.indices[i] + (int)t->nv);
        for (i = 0; i < m.nverts; ++i) {
            t->v[3 * (t->nv + i)] = (float)m.P[i].x;
            t->v[3 * (t->nv + i) + 1] = (float)m.P[i].y;
            t->v[3 * (t->nv + i) + 2] = (float)m.P[i].z;
        }
        t->nv += m.nverts;
        t->nt += m.ntris;
    }
    return 1;
}

static RTCScene embree_scene(RTCDevice dev, const tris *t, enum RTCBuildQuality q, double *seconds)
{
    RTCScene sc = rtcNewScene(dev);
    RTCGeometry geo = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), t->nv);
    unsigned *ix = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), t->nt);
    double t0;
    memcpy(v, t->v, 3 * t->nv * sizeof *v);
    memcpy(ix, t->ix, 3 * t->nt * sizeof *ix);
    rtcSetGeometryBuildQuality(geo, q);
    rtcSetSceneBuildQuality(sc, q);
    rtcCommitGeometry(geo);
    rtcAttachGeometry(sc, geo);
    rtcReleaseGeometry(geo);
    t0 = cpu_seconds();
    rtcCommitScene(sc);
    *seconds = cpu_seconds() - t0;
    return sc;
}

static void to_rtc(const mt_ray *r, struct RTCRay *e)
{
    e->org_x = (float)r->o.x, e->org_y = (float)r->o.y, e->org_z = (float)r->o.z;
    e->dir_x = (float)r->d.x, e->dir_y = (float)r->d.y, e->dir_z = (float)r->d.z;
    e->tnear = (float)r->tmin;
    e->tfar = r->tmax >= MT_RAY_TMAX ? INFINITY : (float)r->tmax;
    e->time = 0;
    e->mask = 0xffffffffu;
    e->id = 0;
    e->flags = 0;
}

/* One pass over n rays; returns the CPU seconds, the hits in *hits and,
 * when t is not NULL, each ray's closest-hit distance (-1: none). */
static double pass_materia(const mt_geometry *g, const mt_ray *rays, size_t n, int occlusion, long *hits, float *t)
{
    double t0 = cpu_seconds();
    long h = 0;
    size_t i;
    for (i = 0; i < n; ++i) {
        if (occlusion) {
            h += mt_geometry_occluded(g, &rays[i]);
        } else {
            mt_hit hit;
            int got = mt_geometry_intersect(g, &rays[i], &hit);
            h += got;
            if (t) t[i] = got ? (float)hit.t : -1.0f;
        }
    }
    *hits = h;
    return cpu_seconds() - t0;
}

static double pass_embree(RTCScene sc, const struct RTCRay *rays, size_t n, int occlusion, long *hits, float *t)
{
    struct RTCIntersectContext ctx;
    double t0;
    long h = 0;
    size_t i;
    rtcInitIntersectContext(&ctx);
    t0 = cpu_seconds();
    for (i = 0; i < n; ++i) {
        if (occlusion) {
            struct RTCRay r = rays[i];
            rtcOccluded1(sc, &ctx, &r);
            h += r.tfar < 0;
        } else {
            struct RTCRayHit rh;
            rh.ray = rays[i];
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(sc, &ctx, &rh);
            if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
                h++;
                if (t) t[i] = rh.ray.tfar;
            } else if (t) {
                t[i] = -1.0f;
            }
        }
    }
    *hits = h;
    return cpu_seconds() - t0;
}

static int bench_mesh(const char *shared, const char *mesh, int passes, int build_only)
{
    char path[1024];
    mt_error err;
    mt_geometry *g = NULL;
    tris t = {NULL, NULL, 0, 0};
    mt_ray *sets[T_RAY_SETS] = {NULL, NULL, NULL};
    size_t counts[T_RAY_SETS];
    double tm[MAX_PASSES], te[MAX_PASSES], teh[MAX_PASSES], bm, be, beh;
    RTCDevice dev;
    RTCScene sc = NULL;
    int p, k;
    snprintf(path, sizeof path, "%s/reference/scenes/geometry/%s", shared, mesh);
    dev = rtcNewDevice("threads=1");
    if (!dev) {
        fprintf(stderr, "bvh-embree: rtcNewDevice failed\n");
        return 1;
    }
    /* builds, alternating: materia, Embree medium, Embree high */
    for (p = 0; p < passes; ++p) {
        RTCScene s1, s2;
        double t0;
        mt_geometry_destroy(g);
        g = mt_geometry_create();
        if (!g || t_load_shapes(path, g, &err) < 1) {
            fprintf(stderr, "bvh-embree: %s: %s\n", path, err.message);
            return 1;
        }
        t0 = cpu_seconds();
        if (mt_geometry_commit(g, &err) != MT_OK) {
            fprintf(stderr, "bvh-embree: build: %s\n", err.message);
            return 1;
        }
        tm[p] = cpu_seconds() - t0;
        if (p == 0 && !gather(g, &t)) {
            fprintf(stderr, "bvh-embree: %s: not only triangle meshes, or out of memory\n", path);
            return 1;
        }
        s1 = embree_scene(dev, &t, RTC_BUILD_QUALITY_MEDIUM, &te[p]);
        s2 = embree_scene(dev, &t, RTC_BUILD_QUALITY_HIGH, &teh[p]);
        if (sc) rtcReleaseScene(sc);
        sc = s1;
        rtcReleaseScene(s2);
    }
    bm = median(tm, passes) * 1e3;
    be = median(te, passes) * 1e3;
    beh = median(teh, passes) * 1e3;
    printf("%s: %lu triangles; build, one thread: materia %.1f ms, Embree %.1f ms (medium quality), "
           "%.1f ms (high)\n",
           mesh, (unsigned long)t.nt, bm, be, beh);
    printf("BENCH embree.%s.build.materia %.2f ms\nBENCH embree.%s.build.embree %.2f ms\n", mesh, bm, mesh, be);
    printf("  build time materia/Embree: %.2f (medium), %.2f (high)\n", bm / be, bm / beh);
    if (build_only) k = T_RAY_SETS;
    else if (!t_ray_sets(g, strcmp(mesh, "bunny.pbrt") == 0, sets, counts)) return 1;
    else k = 0;
    for (; k < T_RAY_SETS; ++k) {
        size_t n = counts[k], i, differ = 0, tdiff = 0;
        struct RTCRay *er = malloc(n * sizeof *er);
        float *t1 = malloc(n * sizeof *t1), *t2 = malloc(n * sizeof *t2);
        long hm = 0, he = 0;
        double rm, re;
        int occl = k == T_RAYS_OCCLUSION;
        if (!er || !t1 || !t2) return 1;
        for (i = 0; i < n; ++i) to_rtc(&sets[k][i], &er[i]);
        /* answers first (not timed) */
        pass_materia(g, sets[k], n, occl, &hm, occl ? NULL : t1);
        pass_embree(sc, er, n, occl, &he, occl ? NULL : t2);
        if (occl) {
            for (i = 0; i < n; ++i) {
                struct RTCIntersectContext ctx;
                struct RTCRay r = er[i];
                rtcInitIntersectContext(&ctx);
                rtcOccluded1(sc, &ctx, &r);
                differ += (r.tfar < 0) != mt_geometry_occluded(g, &sets[k][i]);
            }
        } else {
            for (i = 0; i < n; ++i) {
                if ((t1[i] < 0) != (t2[i] < 0)) differ++;
                else if (t1[i] >= 0 && fabsf(t1[i] - t2[i]) > 1e-4f * t2[i]) tdiff++;
            }
        }
        for (p = 0; p < passes; ++p) {
            long h;
            if (p % 2 == 0) {
                tm[p] = pass_materia(g, sets[k], n, occl, &h, NULL);
                te[p] = pass_embree(sc, er, n, occl, &h, NULL);
            } else {
                te[p] = pass_embree(sc, er, n, occl, &h, NULL);
                tm[p] = pass_materia(g, sets[k], n, occl, &h, NULL);
            }
        }
        rm = (double)n / median(tm, passes) / 1e6;
        re = (double)n / median(te, passes) / 1e6;
        printf("  %-10s materia %6.2f Mrays/s, Embree %6.2f Mrays/s, materia/Embree %.2f; hits %ld / %ld, "
               "%lu ray(s) hit by one only, %lu distance(s) differing\n",
               t_ray_set_names[k], rm, re, rm / re, hm, he, (unsigned long)differ, (unsigned long)tdiff);
        printf("BENCH embree.%s.%s.materia %.3f Mrays/s\nBENCH embree.%s.%s.embree %.3f Mrays/s\n", mesh,
               t_ray_set_names[k], rm, mesh, t_ray_set_names[k], re);
        free(er), free(t1), free(t2);
    }
    t_ray_sets_free(sets);
    free(t.v), free(t.ix);
    rtcReleaseScene(sc);
    rtcReleaseDevice(dev);
    mt_geometry_destroy(g);
    return 0;
}

int main(int argc, char **argv)
{
    const char *shared = t_shared_dir(), *env = getenv("MT_BENCH_PASSES");
    static const char *const defaults[] = {"bunny.pbrt", "killeroo.pbrt"};
    int passes = env && atoi(env) > 0 ? atoi(env) : 5, i, status = 0, build_only = 0, first = 1;
    if (passes > MAX_PASSES) passes = MAX_PASSES;
    if (!shared) {
        printf("bvh-embree: SKIP, no shared reference data (../shared) for the meshes\n");
        return 0;
    }
    printf("materia's BVH (%s build) and Embree %d.%d.%d, single rays, one thread, median of %d "
           "alternating passes\n",
           mt_precision(), RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH, passes);
    if (argc > 1 && strcmp(argv[1], "--build") == 0) build_only = 1, first = 2;
    for (i = first; i < argc; ++i) status |= bench_mesh(shared, argv[i], passes, build_only);
    if (argc <= first)
        for (i = 0; i < 2; ++i) status |= bench_mesh(shared, defaults[i], passes, build_only);
    return status;
}
