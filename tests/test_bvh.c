/*
 * The BVH against brute force (every primitive tested, same tie rule) on
 * random triangle soups with spheres, disks and cylinders among them and on
 * the shared bunny, for random rays and for rays aimed exactly at vertices
 * and edges and running along edges; watertightness of closed meshes (rays
 * aimed at shared edges and vertices never slip through); occlusion versus
 * intersection; degenerate scenes; determinism; four threads querying at
 * once.
 */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/tgeom.h"

static mt_real urand(mt_rng *r) { return mt_rng_uniform(r); }
static mt_vec3 rand_in(mt_rng *r, mt_vec3 lo, mt_vec3 hi)
{
    return mt_v3(lo.x + (hi.x - lo.x) * urand(r), lo.y + (hi.y - lo.y) * urand(r),
                 lo.z + (hi.z - lo.z) * urand(r));
}
static mt_vec3 rand_dir(mt_rng *r)
{
    mt_real z = 1 - 2 * urand(r), phi = 2 * MT_PI * urand(r), s = mt_sqrt(mt_max(0, 1 - z * z));
    return mt_v3(s * mt_cos(phi), s * mt_sin(phi), z);
}

/* ---- scenes -------------------------------------------------------------------------- */

/* n random triangles in the unit cube (sizes from tiny to large, some
 * sharing vertices: fans), plus a few quadrics when quadrics. */
static mt_geometry *soup(uint64_t seed, int n, int quadrics, mt_error *err)
{
    mt_geometry *g = mt_geometry_create();
    mt_rng rng;
    mt_vec3 *P = malloc(3 * (size_t)n * sizeof *P);
    int *idx = malloc(3 * (size_t)n * sizeof *idx), i;
    mt_transform id = mt_transform_identity();
    mt_shape *s;
    mt_rng_seed(&rng, seed, 3);
    for (i = 0; i < n; ++i) {
        mt_vec3 c = rand_in(&rng, mt_v3(0, 0, 0), mt_v3(1, 1, 1));
        mt_real size = (mt_real)(0.003 * pow(100, urand(&rng)));
        int k;
        for (k = 0; k < 3; ++k) {
            P[3 * i + k] = mt_v3_add(c, mt_v3_scale(rand_dir(&rng), size));
            /* every fourth triangle shares an edge with the previous one */
            idx[3 * i + k] = (i % 4 == 3 && k < 2) ? 3 * (i - 1) + k : 3 * i + k;
        }
    }
    s = mt_shape_create_mesh(&id, 0, n, idx, 3 * n, P, NULL, NULL, NULL, NULL, err);
    free(P);
    free(idx);
    if (!g || !s || mt_geometry_attach(g, s, err) != MT_OK) goto fail;
    if (quadrics) {
        const char *texts[] = {"Shape \"sphere\" \"float radius\" 0.1",
                               "Shape \"sphere\" \"float radius\" 0.2 \"float zmax\" 0.1 \"float phimax\" 200",
                               "Shape \"disk\" \"float radius\" 0.3 \"float innerradius\" 0.1",
                               "Shape \"cylinder\" \"float radius\" 0.15 \"float zmin\" -0.2 \"float zmax\" 0.3"};
        for (i = 0; i < 8; ++i) {
            mt_transform t = mt_translate(rand_in(&rng, mt_v3(0, 0, 0), mt_v3(1, 1, 1)));
            mt_transform r = mt_rotate(360 * urand(&rng), rand_dir(&rng)), tr = mt_transform_compose(&t, &r);
            s = t_shape(texts[i % 4], &tr, i & 1, NULL, err);
            if (!s || mt_geometry_attach(g, s, err) != MT_OK) goto fail;
        }
    }
    if (mt_geometry_commit(g, err) != MT_OK) goto fail;
    return g;
fail:
    mt_geometry_destroy(g);
    return NULL;
}

static mt_geometry *from_text(const char *text, const mt_transform *xf, mt_error *err)
{
    mt_geometry *g = mt_geometry_create();
    mt_shape *s = t_shape(text, xf, 0, NULL, err);
    if (!g || !s || mt_geometry_attach(g, s, err) != MT_OK || mt_geometry_commit(g, err) != MT_OK) {
        if (g && s && !err->status) mt_shape_destroy(s);
        mt_geometry_destroy(g);
        return NULL;
    }
    return g;
}

/* ---- ray sets -------------------------------------------------------------------------- */

/* A mix: random rays through the bounds (some with a finite tmax), rays
 * aimed exactly at vertices and at points on edges, and rays running along
 * edges (in the triangles' planes). */
static mt_ray make_ray(const mt_geometry *g, mt_rng *rng, int i)
{
    mt_vec3 lo, hi, ext, o, target;
    const mt_shape *s = mt_geometry_shape(g, 0);
    mt_mesh_view m;
    mt_ray r;
    mt_geometry_bounds(g, &lo, &hi);
    ext = mt_v3_sub(hi, lo);
    lo = mt_v3_sub(lo, mt_v3_scale(ext, 0.2f));
    hi = mt_v3_add(hi, mt_v3_scale(ext, 0.2f));
    o = rand_in(rng, lo, hi);
    if (!mt_shape_mesh(s, &m) || i % 4 == 0) {
        r = mt_ray_make(o, rand_dir(rng), 0, MT_RAY_TMAX);
        if (i % 8 == 4) r.tmax = urand(rng) * mt_v3_len(ext);
        return r;
    } else {
        uint32_t t = mt_rng_bounded(rng, m.ntris);
        mt_vec3 a = m.P[m.indices[3 * t]], b = m.P[m.indices[3 * t + 1]];
        if (i % 4 == 1) target = a;
        else target = mt_v3_add(a, mt_v3_scale(mt_v3_sub(b, a), urand(rng)));
        if (i % 4 == 3) /* along the edge, from behind a */
            return mt_ray_make(mt_v3_sub(a, mt_v3_sub(b, a)), mt_v3_sub(b, a), 0, MT_RAY_TMAX);
        return mt_ray_make(o, mt_v3_sub(target, o), 0, MT_RAY_TMAX);
    }
}

typedef struct result {
    int hit;
    mt_real t;
    uint32_t id;
} result;

/* Field by field: a struct copied by value need not keep its padding (gcc -O3
 * returns this one in registers), so memcmp of two equal results may differ. */
static int same_result(const result *a, const result *b)
{
    return a->hit == b->hit && memcmp(&a->t, &b->t, sizeof a->t) == 0 && a->id == b->id;
}

static int same_stats(const mt_bvh_stats *a, const mt_bvh_stats *b)
{
    return a->inner_nodes == b->inner_nodes && a->leaves == b->leaves && a->prims == b->prims &&
           a->max_depth == b->max_depth && a->max_leaf_prims == b->max_leaf_prims &&
           memcmp(&a->sah_cost, &b->sah_cost, sizeof a->sah_cost) == 0 && a->bytes == b->bytes;
}

static result query(const mt_geometry *g, const mt_ray *r)
{
    result res;
    mt_hit h;
    memset(&res, 0, sizeof res);
    res.hit = mt_geometry_intersect(g, r, &h);
    if (res.hit) {
        res.t = h.t;
        res.id = h.id;
    }
    return res;
}

static void compare_brute(const char *name, const mt_geometry *g, int nrays, uint64_t seed)
{
    mt_rng rng;
    int i, bad = 0, hits = 0, occ_bad = 0;
    char buf[160];
    mt_rng_seed(&rng, seed, 9);
    for (i = 0; i < nrays; ++i) {
        mt_ray r = make_ray(g, &rng, i);
        mt_hit hb;
        result a = query(g, &r);
        int b = t_brute_intersect(g, &r, &hb);
        if (a.hit != b || (b && (a.t != hb.t || a.id != hb.id))) {
            if (bad < 3)
                fprintf(stderr, "%s ray %d: bvh %d t %.9g id %u, brute %d t %.9g id %u\n", name, i,
                        a.hit, (double)a.t, (unsigned)a.id, b, b ? (double)hb.t : 0.0,
                        b ? (unsigned)hb.id : 0);
            bad++;
        }
        hits += b;
        if (mt_geometry_occluded(g, &r) != a.hit) occ_bad++;
    }
    snprintf(buf, sizeof buf, "%s: closest hit (t, primitive) as brute force, %d rays", name, nrays);
    t_check(bad == 0 && hits > nrays / 20, buf, "%d differ, %d hits", bad, hits);
    snprintf(buf, sizeof buf, "%s: occluded() agrees with intersect()", name);
    t_check(occ_bad == 0, buf, "%d differ", occ_bad);
}

static void test_soups(void)
{
    mt_error err;
    int k, nrays = T_SANITIZED ? 20000 : 100000;
    for (k = 0; k < 3; ++k) {
        char name[64];
        mt_geometry *g = soup(100 + k, k == 0 ? 400 : 150, k != 0, &err);
        snprintf(name, sizeof name, "soup %d (%s)", k, k == 0 ? "400 triangles" : "150 triangles, 8 quadrics");
        if (!g) {
            t_fail(name, "%s", err.message);
            continue;
        }
        compare_brute(name, g, k == 0 ? nrays : nrays / 2, 7 + k);
        mt_geometry_destroy(g);
    }
}

/* ---- watertightness -------------------------------------------------------------------------- */

/* Rays from inside a closed mesh aimed exactly at each vertex and at points
 * on each edge, and from outside at the same points: none may slip through. */
static void check_watertight(const char *name, const mt_geometry *g, mt_vec3 inside, int per_edge)
{
    const mt_shape *s = mt_geometry_shape(g, 0);
    mt_mesh_view m;
    mt_rng rng;
    uint32_t t;
    int k, j, miss_in = 0, miss_out = 0, n = 0;
    mt_vec3 lo, hi;
    char buf[160];
    mt_shape_mesh(s, &m);
    mt_geometry_bounds(g, &lo, &hi);
    mt_rng_seed(&rng, 77, 1);
    for (t = 0; t < m.ntris; ++t)
        for (k = 0; k < 3; ++k)
            for (j = 0; j <= per_edge; ++j) {
                mt_vec3 a = m.P[m.indices[3 * t + k]], b = m.P[m.indices[3 * t + (k + 1) % 3]];
                mt_vec3 target = j == 0 ? a : mt_v3_add(a, mt_v3_scale(mt_v3_sub(b, a), urand(&rng)));
                mt_vec3 out = mt_v3_add(target, mt_v3_scale(mt_v3_sub(target, inside), 3));
                mt_ray r = mt_ray_make(inside, mt_v3_sub(target, inside), 0, MT_RAY_TMAX);
                mt_ray r2 = mt_ray_make(out, mt_v3_sub(target, out), 0, MT_RAY_TMAX);
                n++;
                if (!mt_geometry_occluded(g, &r)) miss_in++;
                if (!mt_geometry_occluded(g, &r2)) miss_out++;
            }
    snprintf(buf, sizeof buf, "%s: %d rays at shared vertices and edges never slip through", name,
             2 * n);
    t_check(miss_in == 0 && miss_out == 0, buf, "%d from inside and %d from outside missed",
            miss_in, miss_out);
}

static void test_watertight(void)
{
    mt_error err;
    mt_transform far = mt_translate(mt_v3(3000, -1000, 2000)), id = mt_transform_identity();
    /* a cube of 12 triangles and Loop-subdivided closed meshes (fans of
     * 3 to 6 thin triangles at every vertex) */
    const char *cube = "Shape \"trianglemesh\" \"point P\" [-1 -1 -1 1 -1 -1 1 1 -1 -1 1 -1 "
                       "-1 -1 1 1 -1 1 1 1 1 -1 1 1] \"integer indices\" [0 2 1 0 3 2 4 5 6 4 6 7 "
                       "0 1 5 0 5 4 2 3 7 2 7 6 1 2 6 1 6 5 0 4 7 0 7 3]";
    const char *tetra = "Shape \"loopsubdiv\" \"integer nlevels\" 4 "
                        "\"integer indices\" [0 1 2 0 2 3 0 3 1 1 3 2] "
                        "\"point P\" [1 1 1 -1 -1 1 -1 1 -1 1 -1 -1]";
    mt_geometry *g = from_text(cube, &id, &err);
    if (g) check_watertight("cube", g, mt_v3(0.1f, -0.2f, 0.3f), 8);
    else t_fail("cube", "%s", err.message);
    mt_geometry_destroy(g);
    g = from_text(tetra, &id, &err);
    if (g) check_watertight("subdivided tetrahedron", g, mt_v3(0, 0, 0), 4);
    else t_fail("subdivided tetrahedron", "%s", err.message);
    mt_geometry_destroy(g);
    g = from_text(tetra, &far, &err);
    if (g) check_watertight("subdivided tetrahedron at (3000, -1000, 2000)", g, mt_v3(3000, -1000, 2000), 4);
    else t_fail("far tetrahedron", "%s", err.message);
    mt_geometry_destroy(g);
}

/* ---- degenerate scenes and rays -------------------------------------------------------- */

static void test_degenerate(void)
{
    mt_error err;
    mt_geometry *g = mt_geometry_create();
    mt_ray r = mt_ray_make(mt_v3(0, 0, 5), mt_v3(0, 0, -1), 0, MT_RAY_TMAX);
    mt_hit h;
    mt_vec3 lo, hi;
    mt_shape *s;
    int i, ok;
    if (!g) {
        t_fail("empty geometry", "create");
        return;
    }
    ok = mt_geometry_commit(g, &err) == MT_OK && !mt_geometry_intersect(g, &r, &h) &&
         !mt_geometry_occluded(g, &r);
    mt_geometry_bounds(g, &lo, &hi);
    t_check(ok && lo.x > hi.x, "empty geometry: no hits, empty bounds", "%s", err.message);
    s = t_shape("Shape \"sphere\"", NULL, 0, NULL, &err);
    t_check(s && mt_geometry_attach(g, s, &err) == MT_ERR_INVALID, "attach after commit is an error",
            "%s", err.message);
    mt_geometry_destroy(g);

    /* one primitive: the root is a leaf */
    g = from_text("Shape \"sphere\"", NULL, &err);
    t_check(g && mt_geometry_intersect(g, &r, &h) && mt_fabs(h.t - 4) < 1e-5f && h.prim == 0 &&
                mt_shape_kind_of(h.shape) == MT_SHAPE_SPHERE,
            "one sphere: hit at t = 4", "%s", g ? "wrong hit" : err.message);
    mt_geometry_destroy(g);

    /* a material scene's geometry (two spheres over a floor): each sphere in
     * a leaf of its own, since a quadric costs eight triangle tests */
    {
        mt_transform t1 = mt_translate(mt_v3(0, 0, 1)), t2 = mt_translate(mt_v3(3, -3, 6));
        mt_shape *sh[3];
        mt_bvh_stats st;
        g = mt_geometry_create();
        sh[0] = t_shape("Shape \"sphere\"", &t1, 0, NULL, &err);
        sh[1] = t_shape("Shape \"sphere\"", &t2, 0, NULL, &err);
        sh[2] = t_shape("Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] "
                        "\"point P\" [-8 -8 0 8 -8 0 8 8 0 -8 8 0]", NULL, 0, NULL, &err);
        ok = g && sh[0] && sh[1] && sh[2];
        for (i = 0; i < 3; ++i)
            if (ok) ok = mt_geometry_attach(g, sh[i], &err) == MT_OK;
            else mt_shape_destroy(sh[i]);
        ok = ok && mt_geometry_commit(g, &err) == MT_OK;
        if (ok) mt_geometry_stats(g, &st);
        t_check(ok && st.leaves == 3, "two spheres and a floor: three leaves", "%u leaves: %s",
                ok ? (unsigned)st.leaves : 0, err.message);
        mt_geometry_destroy(g);
    }

    /* 3000 copies of one triangle: coincident centroids, halved by index */
    {
        int n = 3000, *idx = malloc(3 * (size_t)n * sizeof *idx);
        mt_vec3 P[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
        mt_transform id = mt_transform_identity();
        mt_bvh_stats st;
        for (i = 0; i < 3 * n; ++i) idx[i] = i % 3;
        g = mt_geometry_create();
        s = mt_shape_create_mesh(&id, 0, n, idx, 3, P, NULL, NULL, NULL, NULL, &err);
        free(idx);
        ok = g && s && mt_geometry_attach(g, s, &err) == MT_OK && mt_geometry_commit(g, &err) == MT_OK;
        r = mt_ray_make(mt_v3(0.2f, 0.2f, 1), mt_v3(0, 0, -1), 0, MT_RAY_TMAX);
        ok = ok && mt_geometry_intersect(g, &r, &h) && h.id == 0;
        mt_geometry_stats(g, &st);
        t_check(ok && st.max_leaf_prims <= 8 && st.max_depth < 96,
                "3000 coincident triangles: leaves of at most 8, the smallest id wins",
                "hit id %u, leaf %u, depth %u", (unsigned)h.id, (unsigned)st.max_leaf_prims,
                (unsigned)st.max_depth);
        mt_geometry_destroy(g);
    }

    /* pbrt-v2's 568b432: a range of more than 255 primitives whose centroids
     * coincide became one leaf, whose 8-bit count wrapped (primitives
     * lost). 300 triangles through one centroid, each in its own vertical
     * plane about the z axis, and 300 concentric spheres: each is found by
     * a ray that meets it first. */
    {
        int n = 300, *idx = malloc(3 * (size_t)n * sizeof *idx), lost = 0, k;
        mt_vec3 *P = malloc(3 * (size_t)n * sizeof *P);
        mt_transform id = mt_transform_identity();
        mt_bvh_stats st;
        for (k = 0; k < n; ++k) {
            /* a = (u, 1), b = (u, -1), c = (-2u, 0), u at azimuth pi k / n:
             * centroid (0, 0, 0) */
            double ph = MT_PI * k / n;
            mt_vec3 u = mt_v3((mt_real)cos(ph), (mt_real)sin(ph), 0);
            P[3 * k] = mt_v3(u.x, u.y, 1);
            P[3 * k + 1] = mt_v3(u.x, u.y, -1);
            P[3 * k + 2] = mt_v3(-2 * u.x, -2 * u.y, 0);
            idx[3 * k] = 3 * k, idx[3 * k + 1] = 3 * k + 1, idx[3 * k + 2] = 3 * k + 2;
        }
        g = mt_geometry_create();
        s = mt_shape_create_mesh(&id, 0, n, idx, 3 * n, P, NULL, NULL, NULL, NULL, &err);
        ok = g && s && mt_geometry_attach(g, s, &err) == MT_OK && mt_geometry_commit(g, &err) == MT_OK;
        for (k = 0; ok && k < n; ++k) {
            /* from 1e-3 in front of the triangle's plane near its edge ab
             * (the planes are 0.01 apart there), towards it */
            double ph = MT_PI * k / n;
            mt_vec3 nk = mt_v3((mt_real)-sin(ph), (mt_real)cos(ph), 0);
            mt_vec3 q = mt_v3((mt_real)(0.95 * cos(ph)), (mt_real)(0.95 * sin(ph)), 0.3f);
            r = mt_ray_make(mt_v3_add(q, mt_v3_scale(nk, 1e-3f)), mt_v3_neg(nk), 0, MT_RAY_TMAX);
            if (!mt_geometry_intersect(g, &r, &h) || h.id != (uint32_t)k) lost++;
        }
        if (ok) mt_geometry_stats(g, &st);
        t_check(ok && lost == 0 && st.max_leaf_prims <= 8,
                "300 triangles with one centroid: every one found (pbrt-v2 568b432)",
                "%d lost, leaves of up to %u", lost, ok ? (unsigned)st.max_leaf_prims : 0);
        mt_geometry_destroy(g);
        free(idx);
        free(P);

        g = mt_geometry_create();
        ok = g != NULL;
        for (k = 0; ok && k < n; ++k) {
            char text[80];
            snprintf(text, sizeof text, "Shape \"sphere\" \"float radius\" [%g]", 1 + 0.01 * k);
            s = t_shape(text, NULL, 0, NULL, &err);
            ok = s && mt_geometry_attach(g, s, &err) == MT_OK;
        }
        ok = ok && mt_geometry_commit(g, &err) == MT_OK;
        for (lost = 0, k = 0; ok && k < n; ++k) {
            /* outwards from just inside sphere k */
            r = mt_ray_make(mt_v3(0, 0, (mt_real)(1 + 0.01 * k - 0.004)), mt_v3(0, 0, 1), 0, MT_RAY_TMAX);
            if (!mt_geometry_intersect(g, &r, &h) || mt_fabs(h.t - 0.004f) > 1e-4f) lost++;
        }
        t_check(ok && lost == 0, "300 concentric spheres: every one found (pbrt-v2 568b432)",
                "%d lost: %s", lost, err.message);
        mt_geometry_destroy(g);
    }

    /* rays with zero direction components through an axis-aligned grid of
     * triangles, starting exactly on box planes */
    g = from_text("Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3 4 5 6 4 6 7] "
                  "\"point P\" [0 0 0 1 0 0 1 1 0 0 1 0  0 0 1 1 0 1 1 1 1 0 1 1]",
                  NULL, &err);
    if (g) {
        int bad = 0;
        struct {
            mt_vec3 o, d;
            int hit;
            mt_real t;
        } cases[] = {
            {{0.5f, 0.5f, 2}, {0, 0, -1}, 1, 1},     /* straight down onto z = 1 */
            {{0, 0, 2}, {0, 0, -1}, 1, 1},           /* exactly through corner vertices */
            {{1, 0.5f, 2}, {0, 0, -2}, 1, 0.5f},     /* along a box face, through an edge */
            {{0.5f, 0.5f, 0.5f}, {1, 0, 0}, 0, 0},   /* between the planes, parallel to them */
            {{0.5f, 0.5f, 1}, {0, 0, 1}, 1, 0},      /* starts on z = 1 going up: t = 0 hit is rejected */
            {{0.5f, 0.5f, 1}, {0, 0, -1}, 1, 1},     /* starts on z = 1 going down: the other plane */
            {{2, 2, 2}, {0, 0, -1}, 0, 0},           /* outside the bounds */
        };
        for (i = 0; i < (int)(sizeof cases / sizeof cases[0]); ++i) {
            mt_ray rr = mt_ray_make(cases[i].o, cases[i].d, 0, MT_RAY_TMAX);
            int got = mt_geometry_intersect(g, &rr, &h);
            if (i == 4) {
                if (got) bad++;
                continue;
            }
            if (got != cases[i].hit || (got && h.t != cases[i].t)) {
                fprintf(stderr, "axis case %d: hit %d t %g\n", i, got, got ? (double)h.t : 0.0);
                bad++;
            }
        }
        r = mt_ray_make(mt_v3(0.5f, 0.5f, 2), mt_v3(0, 0, -1), 1.5f, 1.2f);
        if (mt_geometry_intersect(g, &r, &h)) bad++; /* tmin > tmax */
        r = mt_ray_make(mt_v3(0.5f, 0.5f, 2), mt_v3(0, 0, -1), 0, 1);
        if (!mt_geometry_intersect(g, &r, &h) || h.t != 1) bad++; /* tmax inclusive */
        r = mt_ray_make(mt_v3(0.5f, 0.5f, 2), mt_v3(0, 0, -1), 1.5f, MT_RAY_TMAX);
        if (!mt_geometry_intersect(g, &r, &h) || h.t != 2) bad++; /* tmin skips the first */
        t_check(bad == 0, "axis-aligned rays, rays on box planes, tmin and tmax", "%d bad", bad);
    } else {
        t_fail("axis-aligned grid", "%s", err.message);
    }
    mt_geometry_destroy(g);
}

/* ---- the bunny ------------------------------------------------------------------------- */

static mt_geometry *load_scene(const char *rel, mt_error *err)
{
    const char *dir = t_shared_dir();
    char path[512];
    mt_geometry *g;
    if (!dir) return NULL;
    snprintf(path, sizeof path, "%s/reference/scenes/%s", dir, rel);
    g = mt_geometry_create();
    if (!g || t_load_shapes(path, g, err) < 1 || mt_geometry_commit(g, err) != MT_OK) {
        mt_geometry_destroy(g);
        return NULL;
    }
    return g;
}

static void test_bunny(void)
{
    mt_error err;
    mt_geometry *g = load_scene("geometry/bunny.pbrt", &err);
    mt_bvh_stats st;
    if (!t_shared_dir()) {
        t_skip("bunny", "no shared reference data (../shared)");
        return;
    }
    if (!g) {
        t_fail("bunny: load and build", "%s", err.message);
        return;
    }
    mt_geometry_stats(g, &st);
    t_check(mt_geometry_prim_count(g) > 60000 && st.max_depth < 96 && st.leaves > 1000,
            "bunny: loaded and built", "%u triangles, depth %u", (unsigned)mt_geometry_prim_count(g),
            (unsigned)st.max_depth);
    compare_brute("bunny", g, T_SANITIZED ? 200 : 1000, 99);
    mt_geometry_destroy(g);
}

/* ---- determinism and threads ------------------------------------------------------------- */

#define NT 4
#define TRAYS 20000

typedef struct work {
    const mt_geometry *g;
    const mt_ray *rays;
    result *out;
    int occluded[TRAYS];
} work;

static void *run(void *arg)
{
    work *w = arg;
    int i;
    for (i = 0; i < TRAYS; ++i) {
        w->out[i] = query(w->g, &w->rays[i]);
        w->occluded[i] = mt_geometry_occluded(w->g, &w->rays[i]);
    }
    return NULL;
}

static void test_threads(void)
{
    mt_error err;
    mt_geometry *g = soup(5, 3000, 1, &err), *g2 = soup(5, 3000, 1, &err);
    mt_ray *rays = malloc(TRAYS * sizeof *rays);
    result *ref = malloc(TRAYS * sizeof *ref), *outs = malloc(NT * TRAYS * sizeof *outs);
    work *w = malloc(NT * sizeof *w);
    pthread_t th[NT];
    mt_rng rng;
    int i, k, same = 1, det = 1, started = 0;
    if (!g || !g2 || !rays || !ref || !outs || !w) {
        t_fail("threads: setup", "%s", err.message);
        goto done;
    }
    mt_rng_seed(&rng, 8, 8);
    for (i = 0; i < TRAYS; ++i) rays[i] = make_ray(g, &rng, i);
    for (i = 0; i < TRAYS; ++i) {
        result b;
        ref[i] = query(g, &rays[i]);
        b = query(g2, &rays[i]);
        if (!same_result(&ref[i], &b)) det = 0;
    }
    {
        mt_bvh_stats s1, s2;
        mt_geometry_stats(g, &s1);
        mt_geometry_stats(g2, &s2);
        t_check(det && same_stats(&s1, &s2),
                "determinism: two builds give the same tree and answers", "differ");
    }
    for (k = 0; k < NT; ++k) {
        w[k].g = g;
        w[k].rays = rays;
        w[k].out = outs + k * TRAYS;
        if (pthread_create(&th[k], NULL, run, &w[k]) == 0) started++;
    }
    for (k = 0; k < started; ++k) pthread_join(th[k], NULL);
    for (k = 0; k < started; ++k)
        for (i = 0; i < TRAYS; ++i)
            if (!same_result(&w[k].out[i], &ref[i]) || w[k].occluded[i] != ref[i].hit)
                same = 0;
    t_check(started == NT && same, "threads: 4 threads querying at once give the same answers",
            "%d threads started, same %d", started, same);
done:
    mt_geometry_destroy(g);
    mt_geometry_destroy(g2);
    free(rays);
    free(ref);
    free(outs);
    free(w);
}

int main(void)
{
    test_soups();
    test_watertight();
    test_degenerate();
    test_bunny();
    test_threads();
    return t_status();
}
