/*
 * Measured BRDFs (materia/measured.h): the k-d tree against brute force,
 * BRDFRemap, IrregIsotropicBRDF's search on synthetic data (radius doubling,
 * clamp, the measured-empty erratum), the real .brdf files of
 * ../shared/reference/scenes/brdfs (counts, values, reciprocity, no NaN far
 * from the data, pbrt-v2's values for mystique), broken files of both
 * formats, and MERL tables: a plastic tabulated, written, read back and
 * compared with itself within the piecewise-constant lookup's error.
 */
#include <dirent.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>
#include "core/alloc.h"
#include "core/kdtree.h"
#include "materia/measured.h"
#include "materia/spectrum.h"
#include "measured/measured_impl.h"
#include "support/check.h"
#include "support/merl_check.h"
#include "support/pbrt_values.h"
#include "support/tfiles.h"

#define M MT_MODE_PBRT_V2
#define C MT_MODE_CORRECTED

static mt_vec3 random_dir(mt_rng *r, int upper)
{
    double z = upper ? mt_rng_uniform_d(r) : 2 * mt_rng_uniform_d(r) - 1;
    double phi = 6.283185307179586 * mt_rng_uniform_d(r), s = sqrt(fmax(0, 1 - z * z));
    return mt_v3((mt_real)(s * cos(phi)), (mt_real)(s * sin(phi)), (mt_real)z);
}

/* ---- the k-d tree ---------------------------------------------------------- */

typedef struct hits {
    int n;
    int items[4096];
    mt_real d2[4096];
} hits;

static void collect(void *ctx, int item, mt_real d2, mt_real *max_d2)
{
    hits *h = ctx;
    (void)max_d2;
    if (h->n < 4096) {
        h->items[h->n] = item;
        h->d2[h->n++] = d2;
    }
}

/* A lookup that shrinks the radius to the best distance so far. */
static void nearest(void *ctx, int item, mt_real d2, mt_real *max_d2)
{
    (void)item;
    *(mt_real *)ctx = d2;
    *max_d2 = d2;
}

static mt_real dist2(const mt_real *a, const mt_real *b)
{
    mt_real dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
}

static int order_less(const mt_real *pts, int axis, int a, int b)
{
    return pts[3 * a + axis] < pts[3 * b + axis] || (pts[3 * a + axis] == pts[3 * b + axis] && a < b);
}

/* Fills buf with the items below node i and checks pbrt-v2's rules there:
 * left child i + 1, floor(m/2) points on the left, the split on the axis of
 * greatest extent at the node's point, the order respected. */
static int subtree(const mt__kdtree *t, const mt_real *pts, uint32_t i, int *buf, int *bad)
{
    const mt__kdnode *nd = &t->nodes[i];
    int nl = 0, nr = 0, m, k, c, axis;
    mt_real lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    if (nd->has_left) nl = subtree(t, pts, i + 1, buf, bad);
    if (nd->right != MT__KD_NONE) nr = subtree(t, pts, nd->right, buf + nl, bad);
    m = nl + nr + 1;
    buf[nl + nr] = nd->item;
    if (nd->p[0] != pts[3 * nd->item] || nd->p[1] != pts[3 * nd->item + 1] || nd->p[2] != pts[3 * nd->item + 2]) ++*bad;
    if (nd->axis == 3) return (m == 1 ? 0 : ++*bad), m;
    for (k = 0; k < m; ++k)
        for (c = 0; c < 3; ++c) {
            lo[c] = mt_min(lo[c], pts[3 * buf[k] + c]);
            hi[c] = mt_max(hi[c], pts[3 * buf[k] + c]);
        }
    axis = (hi[0] - lo[0] > hi[1] - lo[1] && hi[0] - lo[0] > hi[2] - lo[2]) ? 0 : (hi[1] - lo[1] > hi[2] - lo[2] ? 1 : 2);
    if (nd->axis != axis || nl != m / 2 || nd->split != pts[3 * nd->item + axis]) ++*bad;
    for (k = 0; k < nl; ++k)
        if (!order_less(pts, axis, buf[k], nd->item)) ++*bad;
    for (k = nl; k < nl + nr; ++k)
        if (!order_less(pts, axis, nd->item, buf[k])) ++*bad;
    return m;
}

static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

/* mt__kdtree_ball and mt__kdball_select against the tree's own search: the
 * same items, distances (to the bit) and order, at the radius searched and
 * at a half and a quarter of it, or -1 exactly when more than cap are
 * within; from
 * the grid (queries near points and anywhere around the data, squared radii
 * up to the indexed one, caps 1 to 64) and from the tree (no index, larger
 * radii, NaN queries). */
static void ball_case(const char *label, mt__kdtree *t, const mt_real *pts, int n, mt_rng *r,
                      int want_grid)
{
    static const mt_real index_r2[] = {0, 8e-3f, (mt_real)1 / 16};
    static const int caps[] = {1, 3, 32, 64};
    static hits h;
    int32_t item[64];
    mt_real d2[64];
    int wrong = 0, asked = 0, overflows = 0, from_grid = 0, ix, q, k, c, j;
    char name[160];
    mt_error err;
    for (ix = 0; ix < 3; ++ix) {
        if (index_r2[ix] > 0 && mt__kdtree_index(t, index_r2[ix], &err) != MT_OK) {
            t_fail(label, "k-d tree index failed");
            return;
        }
        from_grid += t->grid != NULL;
        for (q = 0; q < 300; ++q) {
            mt_real p[3], radii[7];
            if (q < 100) {
                int i = (int)mt_rng_bounded(r, (uint32_t)n);
                /* half of them exactly at a point: on its node's split */
                for (c = 0; c < 3; ++c)
                    p[c] = pts[3 * i + c] + (q < 50 ? 0 : (mt_real)(0.02 * (mt_rng_uniform_d(r) - 0.5)));
            } else {
                p[0] = (mt_real)(1.6 * mt_rng_uniform_d(r) - 0.3);
                p[1] = (mt_real)(1.6 * mt_rng_uniform_d(r) - 0.3);
                p[2] = (mt_real)(2.6 * mt_rng_uniform_d(r) - 1.3);
            }
            if (q == 299) p[1] = (mt_real)NAN;
            radii[0] = 1e-4f, radii[1] = 1e-3f, radii[2] = 4e-3f;
            radii[3] = index_r2[ix] > 0 ? index_r2[ix] : 8e-3f, radii[4] = 0.2f;
            /* the squared distances of the ties lattice's neighbours (1/8
             * apart), exactly: a point there is not within (strictly less);
             * 1/16's quarter is 1/64 again, for mt__kdball_select */
            radii[5] = (mt_real)1 / 64, radii[6] = (mt_real)1 / 16;
            for (k = 0; k < 7; ++k)
                for (c = 0; c < 4; ++c) {
                    mt_real max2 = radii[k];
                    mt__kdball b;
                    int sub;
                    mt__kdtree_ball(t, p, radii[k], caps[c], &b);
                    h.n = 0;
                    mt__kdtree_lookup(t, p, collect, &h, &max2);
                    asked++;
                    if (h.n > caps[c]) {
                        overflows++;
                        if (b.n != -1) wrong++;
                        continue;
                    }
                    if (b.n != h.n) {
                        wrong++;
                        continue;
                    }
                    /* the whole radius, then smaller ones from the same search */
                    for (sub = 0; sub < 3; ++sub) {
                        mt_real r2 = radii[k] / (mt_real)(1 << (2 * sub));
                        int got;
                        max2 = r2;
                        h.n = 0;
                        mt__kdtree_lookup(t, p, collect, &h, &max2);
                        got = mt__kdball_select(t, p, &b, r2, item, d2);
                        if (got != h.n || mt__kdball_count(&b, r2) != h.n) {
                            wrong++;
                            break;
                        }
                        for (j = 0; j < got; ++j)
                            if (item[j] != h.items[j] || d2[j] != h.d2[j]) break;
                        if (j < got) {
                            wrong++;
                            break;
                        }
                    }
                }
        }
    }
    snprintf(name, sizeof name, "k-d tree %s: ball searches give the tree's items in its order", label);
    t_check(wrong == 0 && (n < 2 || from_grid == (want_grid ? 2 : 0)), name,
            "%d of %d searches differ (%d overflow the cap); %d of 2 indexes built (%s wanted)",
            wrong, asked, overflows, from_grid, want_grid ? "both" : "none");
}

/* A point with an infinite coordinate (reachable from directions that are
 * finite but far from unit length) leaves the grid without a finite box, and
 * one far from the rest stretches its cells over all the others: the index
 * must give way to the tree (ball_case wants no grid) rather than loop,
 * crawl or answer wrongly. */
static void test_kdtree_infinite(void)
{
    enum { N = 400 };
    static mt_real pts[3 * N];
    static const mt_real bad[] = {INFINITY, -INFINITY, (mt_real)1e6};
    static const char *const what[] = {"+inf", "-inf", "1e6"};
    mt_rng r;
    int i, k;
    mt_rng_seed(&r, 9, 1);
    for (k = 0; k < 3 * 3; ++k) {
        mt__kdtree t;
        mt_error err;
        char label[64];
        for (i = 0; i < 3 * N; ++i) pts[i] = mt_rng_uniform(&r);
        pts[3 * 17 + k / 3] = bad[k % 3];
        snprintf(label, sizeof label, "with a point at %s on axis %d", what[k % 3], k / 3);
        if (mt__kdtree_build(&t, pts, N, &err) != MT_OK) {
            t_fail(label, "build failed: %s", err.message);
            continue;
        }
        ball_case(label, &t, pts, N, &r, 0);
        mt__kdtree_free(&t);
    }
}

static void kdtree_case(const char *label, const mt_real *pts, int n, mt_rng *r)
{
    static const mt_real radii[] = {1e-4f, 1e-3f, 1e-2f, 0.1f, 2.048f};
    static hits h;
    mt__kdtree t;
    mt_error err;
    int *buf = malloc((size_t)n * sizeof *buf), bad = 0, wrong = 0, q, k, i;
    char name[128];
    if (mt__kdtree_build(&t, pts, n, &err) != MT_OK || !buf) {
        t_fail(label, "build failed");
        free(buf);
        return;
    }
    if (subtree(&t, pts, 0, buf, &bad) != n) bad++;
    qsort(buf, (size_t)n, sizeof *buf, cmp_int);
    for (i = 0; i < n; ++i)
        if (buf[i] != i) bad++;
    snprintf(name, sizeof name, "k-d tree %s (%d points): pbrt-v2's build", label, n);
    t_check(bad == 0, name, "%d violations of the median/axis/order/numbering rules", bad);
    for (q = 0; q < 200; ++q) {
        mt_real p[3], best = 0, max2, want_best = INFINITY;
        if (q < 40) {
            int j = (int)mt_rng_bounded(r, (uint32_t)n);
            p[0] = pts[3 * j], p[1] = pts[3 * j + 1], p[2] = pts[3 * j + 2];
        } else {
            p[0] = (mt_real)(1.4 * mt_rng_uniform_d(r) - 0.2);
            p[1] = (mt_real)(1.4 * mt_rng_uniform_d(r) - 0.2);
            p[2] = (mt_real)(2.4 * mt_rng_uniform_d(r) - 1.2);
        }
        for (k = 0; k < 5; ++k) {
            int nb = 0, j, m;
            double ws = 0, wb = 0;
            h.n = 0;
            max2 = radii[k];
            mt__kdtree_lookup(&t, p, collect, &h, &max2);
            for (j = 0; j < h.n; ++j) ws += exp(-100.0 * h.d2[j]) * (h.items[j] + 1);
            for (j = 0; j < n; ++j) {
                mt_real d2 = dist2(pts + 3 * j, p);
                if (d2 < radii[k]) {
                    nb++;
                    wb += exp(-100.0 * d2) * (j + 1);
                    for (m = 0; m < h.n && h.items[m] != j; ++m) {}
                    if (m == h.n || h.d2[m] != d2) wrong++;
                }
            }
            if (nb != h.n || fabs(ws - wb) > 1e-12 * fabs(wb)) wrong++;
        }
        for (i = 0; i < n; ++i) want_best = mt_min(want_best, dist2(pts + 3 * i, p));
        max2 = 10;
        best = 10;
        mt__kdtree_lookup(&t, p, nearest, &best, &max2);
        if (best != want_best) wrong++;
    }
    snprintf(name, sizeof name, "k-d tree %s: lookups find what brute force finds", label);
    t_check(wrong == 0, name, "%d of 1200 lookups differ (sets, distances, weighted sums or the "
            "nearest point with a shrinking radius)", wrong);
    ball_case(label, &t, pts, n, r, 1);
    mt__kdtree_free(&t);
    free(buf);
}

static void test_kdtree(void)
{
    enum { N = 1500 };
    static mt_real pts[3 * N];
    mt_rng r;
    mt__kdtree t;
    mt_error err;
    mt_real p[3] = {0, 0, 0}, max2 = 1;
    hits h;
    int i;
    mt_rng_seed(&r, 1, 1);
    for (i = 0; i < N; ++i) {
        pts[3 * i] = mt_rng_uniform(&r);
        pts[3 * i + 1] = mt_rng_uniform(&r);
        pts[3 * i + 2] = 2 * mt_rng_uniform(&r) - 1;
    }
    kdtree_case("uniform", pts, N, &r);
    for (i = 0; i < 3 * N; ++i) pts[i] = mt_floor(pts[i] * 8) / 8; /* many ties */
    kdtree_case("ties", pts, N, &r);
    for (i = 0; i < N; ++i) {
        pts[3 * i] = (mt_real)i / N;
        pts[3 * i + 1] = (mt_real)(N - i) / N;
        pts[3 * i + 2] = (mt_real)((i * 7) % 13) / 13;
    }
    kdtree_case("sorted", pts, N, &r);
    for (i = 0; i < 3 * 200; ++i) pts[i] = 0.25f;
    kdtree_case("identical", pts, 200, &r);
    kdtree_case("one point", pts, 1, &r);
    kdtree_case("two points", pts + 3 * 150, 2, &r);
    t_check(mt__kdtree_build(&t, pts, 0, &err) == MT_OK && t.n == 0, "k-d tree: empty", "build failed");
    h.n = 0;
    mt__kdtree_lookup(&t, p, collect, &h, &max2);
    t_check(h.n == 0, "k-d tree: an empty tree finds nothing", "%d found", h.n);
}

/* ---- BRDFRemap ----------------------------------------------------------- */

static void test_remap(void)
{
    mt_rng r;
    int i, asym = 0, range = 0, fold = 0, iso = 0, exact = 0;
    double worst_y = 0, worst_fold = 0, worst_iso = 0;
    mt_arena *a = mt_arena_create(0);
    mt_rng_seed(&r, 2, 1);
    for (i = 0; i < 100000; ++i) {
        mt_vec3 wo = random_dir(&r, 0), wi = random_dir(&r, 0);
        mt_vec3 p = mt_brdf_remap(wo, wi), q = mt_brdf_remap(wi, wo), s;
        double dphi = fabs(atan2(wi.y, wi.x) - atan2(wo.y, wo.x)), rot = 6.283185307179586 * mt_rng_uniform_d(&r);
        double c = cos(rot), sn = sin(rot);
        if (dphi > 3.141592653589793) dphi = 6.283185307179586 - dphi;
        if (p.x != q.x || p.z != q.z || fabs(p.y - q.y) > 2 * MT_REAL_EPSILON) asym++;
        worst_y = fmax(worst_y, fabs(p.y - q.y));
        if (!(p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1 && p.z >= -1 && p.z <= 1)) range++;
        /* y is the azimuth difference folded to [0, pi], over pi */
        worst_fold = fmax(worst_fold, fabs(p.y - dphi / 3.141592653589793));
        if (fabs(p.y - dphi / 3.141592653589793) > 16 * MT_REAL_EPSILON) fold++;
        /* isotropy: turning both directions about the normal keeps the point */
        s = mt_brdf_remap(mt_v3((mt_real)(c * wo.x - sn * wo.y), (mt_real)(sn * wo.x + c * wo.y), wo.z),
                          mt_v3((mt_real)(c * wi.x - sn * wi.y), (mt_real)(sn * wi.x + c * wi.y), wi.z));
        worst_iso = fmax(worst_iso, fabs(s.y - p.y) + fabs(s.x - p.x) + fabs(s.z - p.z));
        if (fabs(s.y - p.y) + fabs(s.x - p.x) + fabs(s.z - p.z) > 64 * MT_REAL_EPSILON) iso++;
    }
    t_check(asym == 0, "BRDFRemap symmetric in wo and wi (x, z to the bit, y within 2 eps)",
            "%d of 100000 pairs beyond (worst |dy| %.3g)", asym, worst_y);
    printf("  BRDFRemap(wo, wi) - BRDFRemap(wi, wo): largest |dy| %.3g (pbrt-v2 rounds the two "
           "orders differently)\n", worst_y);
    t_check(range == 0, "BRDFRemap within [0,1] x [0,1] x [-1,1]", "%d pairs outside", range);
    t_check(fold == 0, "BRDFRemap: y = azimuth difference folded into [0, pi], over pi",
            "%d pairs beyond 16 eps (worst %.3g)", fold, worst_fold);
    t_check(iso == 0, "BRDFRemap invariant under a rotation about the normal",
            "%d pairs beyond 64 eps (worst %.3g)", iso, worst_iso);
    /* the corrected mode's query point is symmetric to the bit: f too */
    {
        mt_vec3 wo[2], wi[2];
        mt_rgb v[2] = {{{1, 2, 3}}, {{4, 5, 6}}};
        mt_measured *d;
        mt_bxdf *b;
        mt_error err;
        wo[0] = mt_v3(0, 0, 1), wi[0] = mt_v3(0.6f, 0, 0.8f), wo[1] = mt_v3(0.8f, 0, 0.6f), wi[1] = mt_v3(0, 0.8f, 0.6f);
        d = mt_measured_irregular_create(wo, wi, v, 2, &err);
        b = d ? mt_irregular_isotropic_brdf_create(a, C, d, &err) : NULL;
        for (i = 0; b && i < 20000; ++i) {
            mt_vec3 x = random_dir(&r, 1), y = random_dir(&r, 1);
            mt_rgb f1 = mt_bxdf_f(b, x, y), f2 = mt_bxdf_f(b, y, x);
            if (!mt_rgb_equal(f1, f2)) exact++;
        }
        t_check(b && exact == 0, "corrected mode: irregular f(wo, wi) = f(wi, wo) to the bit",
                "%d of 20000 pairs differ", exact);
        mt_measured_destroy(d);
    }
    mt_arena_destroy(a);
}

/* ---- IrregIsotropicBRDF on synthetic data ------------------------------- */

/* Data whose points sit at squared distances d2[i] from q (along +z) with
 * values v[i]; f at the pair that remaps to q. */
static mt_rgb synthetic_f(mt_mode mode, mt_vec3 wo, mt_vec3 wi, const double *d2, const mt_rgb *v,
                          int n, double *actual_d2)
{
    mt_vec3 q = mt_brdf_remap(wo, wi);
    mt_real *pts = malloc((size_t)n * 3 * sizeof *pts), qq[3];
    mt_rgb *vals = malloc((size_t)n * sizeof *vals), f = mt_rgb_gray(-1);
    mt_error err;
    mt_measured *d;
    mt_arena *a = mt_arena_create(0);
    int i;
    qq[0] = q.x, qq[1] = q.y, qq[2] = q.z;
    for (i = 0; pts && vals && i < n; ++i) {
        pts[3 * i] = q.x;
        pts[3 * i + 1] = q.y;
        pts[3 * i + 2] = q.z + (mt_real)sqrt(d2[i]);
        actual_d2[i] = dist2(pts + 3 * i, qq);
        vals[i] = v[i];
    }
    d = pts && vals ? mt__measured_irregular(pts, vals, n, &err) : NULL;
    if (d) f = mt_bxdf_f(mt_irregular_isotropic_brdf_create(a, mode, d, &err), wo, wi);
    mt_measured_destroy(d);
    mt_arena_destroy(a);
    return f;
}

/* sum w v / sum w over the first k samples, clamped from below. */
static double weighted(const double *d2, const mt_rgb *v, int k, int c)
{
    double s = 0, w = 0;
    int i;
    for (i = 0; i < k; ++i) {
        s += exp(-100 * d2[i]) * v[i].c[c];
        w += exp(-100 * d2[i]);
    }
    return fmax(s, 0) / w;
}

static void test_irregular_search(void)
{
    mt_vec3 wo = mt_v3(0.6f, 0, 0.8f), wi = mt_v3(0, -0.28f, 0.96f);
    const double d2a[] = {0.0004, 0.0015, 0.003, 0.006}, d2b[] = {0.1, 0.2};
    const mt_rgb va[] = {{{1, 2, 3}}, {{2, -1, 1}}, {{4, 1, -9}}, {{100, 100, 100}}};
    const mt_rgb vb[] = {{{1, 1, 1}}, {{3, 2, 1}}};
    double ad2[4];
    int c, ok = 1;
    mt_rgb f = synthetic_f(M, wo, wi, d2a, va, 4, ad2);
    /* squared radius 0.001 finds 1, 0.002 finds 2, 0.004 finds 3: stop */
    for (c = 0; c < 3; ++c) ok &= t_reldiff(f.c[c], weighted(ad2, va, 3, c), 1e-30) < 1e-5;
    t_check(ok, "irregular: the radius doubles until 3 samples are found; weights exp(-100 d2); "
            "negative sums clamped", "f = (%g, %g, %g), want (%g, %g, %g)", f.c[0], f.c[1], f.c[2],
            weighted(ad2, va, 3, 0), weighted(ad2, va, 3, 1), weighted(ad2, va, 3, 2));
    f = synthetic_f(M, wo, wi, d2b, vb, 2, ad2);
    ok = 1;
    for (c = 0; c < 3; ++c) ok &= t_reldiff(f.c[c], weighted(ad2, vb, 2, c), 1e-30) < 1e-5;
    t_check(ok, "irregular: with fewer than 3 samples within 2.048, the last search's average",
            "f = (%g, %g, %g)", f.c[0], f.c[1], f.c[2]);
    {
        const double far[] = {3.0}, under[] = {1.5};
        mt_rgb f0 = synthetic_f(M, wo, wi, far, vb, 1, ad2), f1 = synthetic_f(C, wo, wi, far, vb, 1, ad2);
        t_check(mt_rgb_is_black(f0) && mt_rgb_is_black(f1),
                "measured-empty: no sample within the last radius gives 0 in both modes (pbrt-v2: 0/0)",
                "f = (%g, %g, %g) and (%g, %g, %g)", f0.c[0], f0.c[1], f0.c[2], f1.c[0], f1.c[1], f1.c[2]);
        /* exp(-150) underflows in float (pbrt-v2's 0/0), not in double */
        f0 = synthetic_f(M, wo, wi, under, vb, 1, ad2);
        f1 = synthetic_f(C, wo, wi, under, vb, 1, ad2);
        if (MT_USE_DOUBLE)
            t_check(mt_rgb_equal(f0, vb[0]) && mt_rgb_equal(f1, vb[0]),
                    "measured-empty: double build, a sample at d2 1.5 has weight: its value",
                    "f = (%g, %g, %g)", f0.c[0], f0.c[1], f0.c[2]);
        else
            t_check(mt_rgb_is_black(f0) && mt_rgb_is_black(f1),
                    "measured-empty: float build, a sample whose weight underflows gives 0 in both modes",
                    "f = (%g, %g, %g) and (%g, %g, %g)", f0.c[0], f0.c[1], f0.c[2], f1.c[0], f1.c[1], f1.c[2]);
    }
}

/* The irregular BRDF's f with its data's grid index and without it (every
 * search made by the tree): the same bits, pbrt-v2 and corrected modes,
 * over the upper hemisphere and through it. */
static void grid_vs_tree(mt_arena *a, mt_measured *m, const char *label)
{
    enum { PAIRS = 3000 };
    static mt_rgb with[2][PAIRS];
    mt_bxdf *b[2];
    mt_rng r;
    mt_error err;
    char name[160];
    int i, k, differ = 0, had_grid = m->tree.grid != NULL;
    {
        /* and the index serves the first search's radius (f's 8 x 0.001) */
        mt__kdball ball;
        mt_real p[3] = {(mt_real)0.5, (mt_real)0.5, (mt_real)0.5};
        mt__kdtree_ball(&m->tree, p, 8 * MT__IRREG_FIRST_D2, 64, &ball);
        had_grid &= !ball.ordered;
    }
    b[0] = mt_irregular_isotropic_brdf_create(a, M, m, &err);
    b[1] = mt_irregular_isotropic_brdf_create(a, C, m, &err);
    snprintf(name, sizeof name, "%s: f from the grid index and from the tree alone: the same bits", label);
    if (!b[0] || !b[1]) {
        t_fail(name, "BxDF creation failed: %s", err.message);
        return;
    }
    for (k = 0; k < 2; ++k) {
        mt_rng_seed(&r, 11, 1);
        for (i = 0; i < PAIRS; ++i) {
            mt_vec3 wo = random_dir(&r, i < 2 * PAIRS / 3), wi = random_dir(&r, i < PAIRS / 3);
            mt_rgb f[2];
            f[0] = mt_bxdf_f(b[0], wo, wi);
            f[1] = mt_bxdf_f(b[1], wo, wi);
            if (k == 0) with[0][i] = f[0], with[1][i] = f[1];
            else differ += memcmp(&f[0], &with[0][i], sizeof f[0]) != 0 || memcmp(&f[1], &with[1][i], sizeof f[1]) != 0;
        }
        mt__kdtree_index_free(&m->tree);
    }
    /* the index back, as the data had it */
    if (mt__kdtree_index(&m->tree, MT__IRREG_WIDE_D2, &err) != MT_OK) differ++;
    t_check(had_grid && differ == 0, name, "%s; %d of %d pairs differ", had_grid ? "indexed" : "no index",
            differ, PAIRS);
}

static void test_irregular_grid(mt_arena *a)
{
    enum { N = 4000 };
    static mt_vec3 wo[N], wi[N];
    static mt_rgb v[N];
    mt_rng r;
    mt_error err;
    mt_measured *m;
    int i;
    mt_rng_seed(&r, 10, 1);
    for (i = 0; i < N; ++i) {
        wo[i] = random_dir(&r, 1);
        wi[i] = random_dir(&r, 1);
        v[i] = mt_rgb_make(mt_rng_uniform(&r), mt_rng_uniform(&r) - (mt_real)0.2, 3 * mt_rng_uniform(&r));
    }
    m = mt_measured_irregular_create(wo, wi, v, N, &err);
    if (!t_check(m != NULL, "irregular synthetic data: created", "%s", err.message)) return;
    grid_vs_tree(a, m, "irregular synthetic data (4000 samples)");
    mt_measured_destroy(m);
    /* directions far from unit length are admitted; a remapped point that is
     * not finite (float) or far from the rest (double: z = 1e60) leaves the
     * data without a grid, still searchable */
    wo[5] = wi[5] = mt_v3(0, 0, (mt_real)1e30); /* cos_o cos_i: inf in float */
    m = mt_measured_irregular_create(wo, wi, v, N, &err);
    if (t_check(m != NULL, "irregular data with two directions of length 1e30: created", "%s", err.message)) {
        mt_rgb f = mt_bxdf_f(mt_irregular_isotropic_brdf_create(a, M, m, &err), wo[0], wi[0]);
        t_check(mt_rgb_is_finite(f) && m->tree.grid == NULL,
                "irregular data with two directions of length 1e30: f finite, no grid index",
                "f = (%g, %g, %g), %s grid index", f.c[0], f.c[1], f.c[2], m->tree.grid ? "a" : "no");
        mt_measured_destroy(m);
    }
}

/* ---- the real .brdf files --------------------------------------------------- */

/* The file's numbers counted independently: whitespace-separated words
 * outside comments; *first_sample receives the first sample's numbers. */
static int count_numbers(const char *path, int *nwl, double *first, int nfirst)
{
    FILE *f = fopen(path, "r");
    char line[4096];
    int n = 0;
    if (!f) return -1;
    while (fgets(line, sizeof line, f)) {
        char *tok, *hash = strchr(line, '#');
        if (hash) *hash = '\0';
        for (tok = strtok(line, " \t\r\n"); tok; tok = strtok(NULL, " \t\r\n"), ++n) {
            if (n == 0) *nwl = atoi(tok);
            if (n > *nwl && n - *nwl - 1 < nfirst) first[n - *nwl - 1] = atof(tok);
        }
    }
    fclose(f);
    return n;
}

/* pbrt-v2's remapped point and RGB of one sample's numbers (all 31
 * wavelengths 400..700 nm in these files). */
static void expected_sample(const double *s, int nwl, mt_vec3 *p, mt_rgb *v)
{
    double lambda[64], vals[64];
    mt_real t[4];
    int k;
    for (k = 0; k < 4; ++k) t[k] = (mt_real)s[k];
    for (k = 0; k < nwl; ++k) {
        lambda[k] = 400 + 10 * k;
        vals[k] = (mt_real)s[4 + k];
    }
    *p = mt_brdf_remap(mt_spherical_direction(mt_sin(t[2]), mt_cos(t[2]), t[3]),
                       mt_spherical_direction(mt_sin(t[0]), mt_cos(t[0]), t[1]));
    *v = mt_spectrum_from_sampled(lambda, vals, nwl);
}

static void test_real_file(const char *dir, const char *file, mt_arena *a)
{
    char path[512], name[160];
    double first[64];
    int nwl = 0, numbers, i, bad = 0, neg = 0, nonrecip = 0, empty = 0, beyond = 0;
    double worst = 0;
    mt_error err;
    mt_measured *m;
    mt_bxdf *bp, *bc;
    mt_rng r;
    mt_vec3 p;
    mt_rgb v, v0;
    snprintf(path, sizeof path, "%s/reference/scenes/brdfs/%s", dir, file);
    numbers = count_numbers(path, &nwl, first, 64);
    m = mt_measured_load(path, &err);
    snprintf(name, sizeof name, "%s: read", file);
    if (!t_check(m && numbers > 0 && nwl == 31, name, "%s", m ? "unexpected header" : err.message)) {
        mt_measured_destroy(m);
        return;
    }
    snprintf(name, sizeof name, "%s: sample count", file);
    t_check(mt_measured_count(m) * (4 + nwl) == numbers - 1 - nwl, name, "%d samples for %d numbers",
            mt_measured_count(m), numbers);
    expected_sample(first, nwl, &p, &v);
    mt_measured_sample(m, 0, NULL, &v0);
    {
        mt_vec3 p0;
        mt_measured_sample(m, 0, &p0, NULL);
        snprintf(name, sizeof name, "%s: first sample remapped and converted as pbrt-v2 does", file);
        t_check(p0.x == p.x && p0.y == p.y && p0.z == p.z && mt_rgb_equal(v0, v), name,
                "point (%g %g %g) rgb (%g %g %g), want (%g %g %g) (%g %g %g)", p0.x, p0.y, p0.z,
                v0.c[0], v0.c[1], v0.c[2], p.x, p.y, p.z, v.c[0], v.c[1], v.c[2]);
    }
    for (i = 0; i < mt_measured_count(m); ++i) {
        mt_measured_sample(m, i, &p, &v);
        if (!mt_rgb_is_finite(v) || !mt_v3_is_finite(p)) bad++;
        if (v.c[0] < 0 || v.c[1] < 0 || v.c[2] < 0) neg++;
    }
    snprintf(name, sizeof name, "%s: sample values finite", file);
    t_check(bad == 0, name, "%d samples with a value that is not finite", bad);
    printf("  %s: %d samples, %d with a negative RGB component (spectra outside the sRGB gamut; "
           "pbrt-v2 clamps the weighted sum)\n", file, mt_measured_count(m), neg);
    bp = mt_irregular_isotropic_brdf_create(a, M, m, &err);
    bc = mt_irregular_isotropic_brdf_create(a, C, m, &err);
    mt_rng_seed(&r, 3, 1);
    bad = 0;
    for (i = 0; i < 4000; ++i) {
        int upper = i < 2000;
        mt_vec3 wo = random_dir(&r, upper), wi = random_dir(&r, upper);
        mt_rgb f1 = mt_bxdf_f(bp, wo, wi), f2 = mt_bxdf_f(bp, wi, wo);
        mt_rgb c1 = mt_bxdf_f(bc, wo, wi), c2 = mt_bxdf_f(bc, wi, wo);
        mt_vec3 q1 = mt_brdf_remap(wo, wi), q2 = mt_brdf_remap(wi, wo);
        double d = 0;
        int k;
        if (!mt_rgb_is_finite(f1) || mt_rgb_min(f1) < 0 || !mt_rgb_is_finite(c1) || mt_rgb_min(c1) < 0) bad++;
        if (!mt_rgb_equal(c1, c2)) nonrecip++;
        /* pbrt-v2 mode: the two orders may differ only through the remap */
        if (q1.x == q2.x && q1.y == q2.y && q1.z == q2.z && !mt_rgb_equal(f1, f2)) nonrecip++;
        for (k = 0; k < 3; ++k) d = fmax(d, t_reldiff(f1.c[k], f2.c[k], 1e-30));
        if (d > (MT_USE_DOUBLE ? 1e-12 : 1e-6)) beyond++;
        worst = fmax(worst, d);
        if (!upper && mt_rgb_is_black(f1)) empty++;
    }
    snprintf(name, sizeof name, "%s: f finite and >= 0 over the sphere (no NaN far from the data)", file);
    t_check(bad == 0, name, "%d of 4000 pairs", bad);
    snprintf(name, sizeof name, "%s: reciprocity (corrected: to the bit; pbrt-v2: up to the remap's rounding)", file);
    t_check(nonrecip == 0, name, "%d of 4000 pairs", nonrecip);
    snprintf(name, sizeof name, "%s: pbrt-v2 mode reciprocity within %s", file, MT_USE_DOUBLE ? "1e-12" : "1e-6");
    if (beyond)
        t_xfail(name, "erratum measured-remap-symmetry: %d of 4000 pairs differ beyond it, by up to %.3g "
                "relative", beyond, worst);
    else
        t_pass(name);
    printf("  %s: %d of 2000 pairs over the whole sphere give 0 (black: no weight, or every "
           "channel clamped)\n", file, empty);
    grid_vs_tree(a, m, file);
    mt_measured_destroy(m);
}

static void test_real_files(mt_arena *a)
{
    static const char *const files[] = {"acryl_blue.brdf", "cayman.brdf", "garnet_red.brdf",
                                        "krylon_blue.brdf", "mystique.brdf"};
    const char *dir = t_shared_dir();
    size_t i;
    if (!dir) {
        t_skip("real .brdf files", "../shared is absent");
        return;
    }
    for (i = 0; i < sizeof files / sizeof files[0]; ++i) test_real_file(dir, files[i], a);
}

/* pbrt-v2's values for Material "measured" "string filename"
 * ["brdfs/mystique.brdf"], with the BSDF built here as MeasuredMaterial
 * builds it (the material-level test builds it through the material). */
static mt_bsdf *mystique_bsdf(void *ctx, mt_arena *a, mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    mt_measured *m = mt_measured_load(ctx, err); /* read once; the cache keeps it */
    mt_bsdf *b = m ? mt_bsdf_create(a, M, &dg, dg.n, 1, err) : NULL;
    if (b && mt_bsdf_add(b, mt_irregular_isotropic_brdf_create(a, M, m, err), err)) b = NULL;
    mt_measured_destroy(m);
    return b;
}

static void test_pbrt_values(void)
{
    char path[512];
    snprintf(path, sizeof path, "%s/reference/scenes/brdfs/mystique.brdf", t_shared_dir() ? t_shared_dir() : ".");
    t_check_pbrt_rows("measured_mystique", "pbrt-v2 values measured_mystique (BxDF)", mystique_bsdf, path);
}

/* ---- broken files ------------------------------------------------------------ */

/* Loading path fails with an error at path (and line, when > 0) whose
 * message holds needle. */
static void expect_error(const char *name, const char *path, const char *needle, int line)
{
    mt_error err;
    mt_measured *m;
    char msg[1024];
    mt_error_clear(&err);
    m = mt_measured_load(path, &err);
    mt_error_format(&err, msg, sizeof msg);
    t_check(!m && err.status != MT_OK && !strcmp(err.file, path) && strstr(err.message, needle) &&
                (line == 0 || err.line == line),
            name, "%s (wanted \"%s\" at line %d)", m ? "loaded" : msg, needle, line);
    if (!m) printf("    %s\n", msg);
    mt_measured_destroy(m);
}

static const char *write_text(const char *rel, const char *text)
{
    static char path[1024];
    const char *p = t_write_file(rel, text, (size_t)-1);
    snprintf(path, sizeof path, "%s", p ? p : "");
    return path;
}

static void test_broken_brdf(void)
{
    static const struct {
        const char *name, *text, *needle;
        int line;
    } cases[] = {
        {"empty", "", "holds no numbers", 0},
        {"comments only", "# nothing\n# here\n", "holds no numbers", 0},
        {"count not an integer", "2.5\n500 600\n", "positive integer, found 2.5", 1},
        {"count zero", "0\n", "positive integer, found 0", 1},
        {"count beyond the data", "40\n400 500\n", "expected 40 wavelengths, found 2", 2},
        {"wavelength negative", "2\n-500 600\n0.1 0 0.2 0 1 1\n", "wavelength 1 is -500", 2},
        {"no samples", "2\n500 600\n", "no samples after its 2 wavelengths", 2},
        {"truncated sample", "2\n500 600\n0.1 0 0.2 0 0.5 0.5\n0.1 0 0.2\n",
         "expected a multiple of 6 values after the wavelengths (4 angles and 2 spectral values "
         "per sample), found 9: 1 whole samples and 3 values", 4},
        {"garbage", "2\n500 600\n0.1 0 0.2 0 abc 0.5\n", "expected a number, found \"abc\"", 3},
        {"trailing garbage", "2\n500 600\n0.1 0 0.2 0 0.5 0.5\nend\n", "found \"end\"", 4},
        {"NaN", "2\n500 600\n0.1 0 0.2 0 nan 0.5\n", "found \"nan\"", 3},
        {"beyond float", "2\n500 600\n0.1 0 0.2 0 1e39 0.5\n", "1e39 is beyond float's range", 3},
        {"malformed number", "2\n500 600\n0.1 0 0.2 0 1.2.3 0.5\n", "malformed number \"1.2.3\"", 3},
        {"comment touching a number", "2\n500 600\n0.1 0 0.2 0 0.5# 7\n0.5\n", "comment touches", 3},
        {"negative value", "2\n500 600\n0.1 0 0.2 0 0.5 -0.5\n", "negative spectral value -0.5 (at 600 nm)", 3},
        {"theta out of range", "2\n500 600\n0.1 0 2 0 0.5 0.5\n", "theta_o = 2, outside [0, pi/2]", 3},
        {"NUL byte", "2\n500 600\n0.1 0 0.2 0 0.5 0.5\n\0\n", "found a NUL byte", 4},
    };
    size_t i;
    char name[128];
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char rel[64];
        const char *path;
        size_t len = strlen(cases[i].text);
        snprintf(rel, sizeof rel, "broken/%d.brdf", (int)i);
        if (!strcmp(cases[i].name, "NUL byte")) len += 2; /* the NUL and the newline after it */
        path = t_write_file(rel, cases[i].text, len);
        snprintf(name, sizeof name, ".brdf error: %s", cases[i].name);
        if (path) {
            char copy[1024];
            snprintf(copy, sizeof copy, "%s", path);
            expect_error(name, copy, cases[i].needle, cases[i].line);
        } else {
            t_fail(name, "cannot write the test file");
        }
    }
    {
        char path[1024];
        snprintf(path, sizeof path, "%s", write_text("broken/missing.brdf", "1\n500\n0 0 0 0 1\n"));
        strcpy(path + strlen(path) - strlen("missing.brdf"), "absent.brdf");
        expect_error(".brdf error: missing file", path, "cannot open", 0);
        strcpy(path + strlen(path) - strlen("absent.brdf"), "nosuffix");
        expect_error("error: a name without a suffix", path, "has no suffix", 0);
    }
}

static void put32(unsigned char *b, int32_t v)
{
    uint32_t u = (uint32_t)v;
    b[0] = (unsigned char)u, b[1] = (unsigned char)(u >> 8), b[2] = (unsigned char)(u >> 16), b[3] = (unsigned char)(u >> 24);
}

static void put64(unsigned char *b, double d)
{
    uint64_t u;
    int i;
    memcpy(&u, &d, 8);
    for (i = 0; i < 8; ++i) b[i] = (unsigned char)(u >> (8 * i));
}

/* A MERL file of the given header and nvalues doubles (value k = 0.5,
 * except bad at index bad_at), plus extra bytes. */
static const char *write_merl(const char *rel, int d0, int d1, int d2, size_t nvalues,
                              size_t bad_at, double bad, size_t extra)
{
    static char path[1024];
    size_t size = 12 + 8 * nvalues + extra, k;
    unsigned char *b = calloc(1, size ? size : 1);
    const char *p;
    if (!b) return "";
    put32(b, d0), put32(b + 4, d1), put32(b + 8, d2);
    for (k = 0; k < nvalues; ++k) put64(b + 12 + 8 * k, k == bad_at ? bad : 0.5);
    p = t_write_file(rel, (const char *)b, size);
    free(b);
    snprintf(path, sizeof path, "%s", p ? p : "");
    return path;
}

static void test_broken_merl(void)
{
    const size_t all = 3 * (size_t)MT_MERL_SAMPLES, none = (size_t)-1;
    char path[1024];
    snprintf(path, sizeof path, "%s", write_merl("broken/short.binary", 90, 90, 180, 0, none, 0, 0));
    path[strlen(path) - strlen("short.binary")] = 0;
    strcat(path, "absent.binary");
    expect_error("MERL error: missing file", path, "cannot open", 0);
    expect_error("MERL error: empty file", write_text("broken/empty.merl", ""),
                 "expected a 12-byte header (three 32-bit dimensions), found 0 bytes", 0);
    snprintf(path, sizeof path, "%s", t_write_file("broken/hdr.merl", "\x5a\0\0\0\x5a", 5));
    expect_error("MERL error: short header", path, "found 5 bytes", 0);
    expect_error("MERL error: dimensions of MERL's full phi_d range",
                 write_merl("broken/dims.binary", 90, 90, 360, 0, none, 0, 0),
                 "dimensions 90 x 90 x 360 do not make pbrt-v2's table of 90 x 90 x 180", 0);
    expect_error("MERL error: negative dimensions",
                 write_merl("broken/neg.binary", -90, -90, 180, 0, none, 0, 0), "dimensions -90 x -90 x 180", 0);
    expect_error("MERL error: oversized dimensions",
                 write_merl("broken/big.binary", 1 << 30, 1 << 30, 1 << 30, 0, none, 0, 0), "do not make", 0);
    expect_error("MERL error: truncated", write_merl("broken/trunc.binary", 90, 90, 180, 1000, none, 0, 3),
                 "truncated: expected 4374000 values (3 channels of 1458000 doubles), found 1000 and part of another", 0);
    {
        /* a short file is refused before the table is allocated (a header
         * alone made the reader allocate 17.5 MB in float, found by fuzzing) */
        mt_error err;
        mt_measured *m;
        size_t largest;
        snprintf(path, sizeof path, "%s", write_merl("broken/hdr-only.binary", 90, 90, 180, 0, none, 0, 0));
        mt__alloc_largest(1);
        m = mt_measured_load(path, &err);
        largest = mt__alloc_largest(1);
        t_check(!m && largest < (1u << 20) && strstr(err.message, "doubles), found 0"),
                "MERL error: a header alone allocates no table",
                "largest request %zu bytes: %s", largest, m ? "loaded" : err.message);
        mt_measured_destroy(m);
    }
    snprintf(path, sizeof path, "%s", write_merl("broken/nan.binary", 90, 90, 180, all, 5, NAN, 0));
    expect_error("MERL error: NaN value", path, "red value of entry 5 (theta_h 0, theta_d 0, phi_d 5) is nan", 0);
    remove(path); /* 35 MB */
    snprintf(path, sizeof path, "%s", write_merl("broken/inf.binary", 180, 90, 90, all, 1458000 + 361, INFINITY, 0));
    expect_error("MERL error: infinite value", path,
                 "green value of entry 361 (theta_h 0, theta_d 2, phi_d 1) is inf", 0);
    remove(path);
    snprintf(path, sizeof path, "%s", write_merl("broken/trail.binary", 90, 90, 180, all, none, 0, 4));
    expect_error("MERL error: trailing data", path, "4 bytes of trailing data after the 4374000 values", 0);
    remove(path); /* 35 MB */
    {
        mt_error err;
        mt_measured *m;
        snprintf(path, sizeof path, "%s", write_merl("broken/neg-values.binary", 90, 90, 180, all, 7, -1, 0));
        m = mt_measured_load(path, &err);
        remove(path);
        const mt_real *t = m ? mt_measured_table(m) : NULL;
        const float s0 = 1.f / 1500.f, s1 = 1.15f / 1500.f, s2 = 1.66f / 1500.f; /* pbrt-v2's floats */
        t_check(t && t[3 * 7] == 0 && t[3 * 7 + 1] == (mt_real)(0.5 * (double)s1) &&
                    t[3 * 7 + 2] == (mt_real)(0.5 * (double)s2) && t[0] == (mt_real)(0.5 * (double)s0),
                "MERL: values scaled by 1/1500, 1.15/1500, 1.66/1500; MERL's negative 'no data' read as 0",
                "%s", m ? "wrong values" : err.message);
        mt_measured_destroy(m);
    }
}

/* ---- MERL tables ---------------------------------------------------------------- */

/* pbrt-v2's plastic (plastic.cpp) with Kd (0.3, 0.1, 0.1), the default Ks
 * 0.25 and roughness 0.05, built by hand. */
static mt_bsdf *plastic(mt_arena *a, mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *b = mt_bsdf_create(a, M, &dg, dg.n, 1, err);
    if (!b || mt_bsdf_add(b, mt_lambertian_create(a, M, mt_rgb_make(0.3f, 0.1f, 0.1f), err), err) ||
        mt_bsdf_add(b, mt_microfacet_create(a, M, mt_rgb_gray(0.25f), mt_fresnel_dielectric(1.5f, 1),
                                            mt_blinn(1 / 0.05f), err), err))
        return NULL;
    return b;
}

/* The number of values of two tables that differ beyond 4 ulps, in theta_h
 * bins from `from` on and below it. */
static void table_diff(const double *x, const double *y, int from, long *above, long *below)
{
    size_t k;
    *above = *below = 0;
    for (k = 0; k < 3 * (size_t)MT_MERL_SAMPLES; ++k)
        if (t_reldiff(x[k], y[k], 1e-300) > 4 * MT_REAL_EPSILON) {
            if ((int)(k % MT_MERL_SAMPLES / (MT_MERL_THETA_D * MT_MERL_PHI_D)) >= from)
                ++*above;
            else
                ++*below;
        }
}

/* A plastic tabulated at `at`, written to dir/name, read back: the table
 * against the plastic, entries below the horizon, and tabulating the
 * table's own BRDF again (the same table at the bin centres; at the corners,
 * which lie on bin edges, lookups pick either bin). Returns the data. */
static mt_measured *merl_roundtrip(mt_arena *a, mt_bsdf *truth, mt_merl_at at, const char *path,
                                   double *values, double *again)
{
    const char *label = at == MT_MERL_AT_CENTRE ? "MERL plastic at the bin centres" : "MERL plastic at the grid points";
    char name[160];
    mt_error err;
    mt_measured *m = NULL;
    mt_bsdf *table;
    mt_diffgeom dg = mt_diffgeom_default();
    double off = at == MT_MERL_AT_CENTRE ? 0.5 : 0;
    int ith, itd, ipd, below = 0, above = 0;
    snprintf(name, sizeof name, "%s: tabulate, write, read", label);
    if (!t_check(mt_merl_tabulate(truth, at, values, &err) == MT_OK && mt_merl_write(path, values, &err) == MT_OK &&
                     (m = mt_measured_load(path, &err)) != NULL,
                 name, "%s", err.message))
        return NULL;
    for (ith = 0; ith < MT_MERL_THETA_H; ++ith)
        for (itd = 0; itd < MT_MERL_THETA_D; ++itd)
            for (ipd = 0; ipd < MT_MERL_PHI_D; ++ipd) {
                mt_vec3 wo, wi;
                const mt_real *t = mt_measured_table(m) + 3 * (ipd + MT_MERL_PHI_D * (itd + MT_MERL_THETA_D * ith));
                mt_merl_directions(ith + off, itd + off, ipd + off, &wo, &wi);
                if (wo.z <= 0 || wi.z <= 0) below += t[0] != 0 || t[1] != 0 || t[2] != 0;
                else above += t[0] > 0;
            }
    snprintf(name, sizeof name, "%s: 0 where a direction is below the horizon", label);
    t_check(below == 0 && above > 0, name, "%d such entries are not 0", below);
    table = mt_bsdf_create(a, M, &dg, dg.n, 1, &err);
    if (!table || mt_bsdf_add(table, mt_regular_halfangle_brdf_create(a, M, m, &err), &err) != MT_OK) {
        t_fail(label, "%s", err.message);
        return m;
    }
    t_merl_roundtrip_checks(label, truth, table, at);
    if (mt_merl_tabulate(table, at, again, &err) == MT_OK) {
        long d, low;
        table_diff(values, again, 8, &d, &low);
        snprintf(name, sizeof name, "%s: the table of the table's BRDF is the same table (theta_h "
                 "bins 8 on)", label);
        if (at == MT_MERL_AT_CENTRE)
            t_check(d == 0, name, "%ld of %ld values differ", d, 3L * MT_MERL_SAMPLES);
        else
            printf("  %s: tabulating the table's BRDF again changes %.1f%% of the values (corners "
                   "lie on bin edges)\n", label, 100.0 * (d + low) / (3.0 * MT_MERL_SAMPLES));
        if (at == MT_MERL_AT_CENTRE)
            printf("  %s: the table of the table's BRDF differs in %ld values of theta_h bins 0-7 "
                   "(the half vector's frame is ill-conditioned in float there)\n", label, low);
    }
    return m;
}

typedef struct loader {
    const char *path;
    mt_measured *got;
} loader;

static void *load_thread(void *arg)
{
    loader *l = arg;
    mt_error err;
    l->got = mt_measured_load(l->path, &err);
    return NULL;
}

/* Threads asking for one file at once get one object, read once. */
static void test_cache_threads(const char *path)
{
    enum { T = 4 };
    pthread_t th[T];
    loader l[T];
    int i, started = 0, same = 1;
    mt_measured_cache_clear();
    for (i = 0; i < T; ++i) {
        l[i].path = path;
        l[i].got = NULL;
        if (pthread_create(&th[i], NULL, load_thread, &l[i]) == 0) started++;
    }
    for (i = 0; i < started; ++i) pthread_join(th[i], NULL);
    for (i = 0; i < started; ++i) same &= l[i].got && l[i].got == l[0].got;
    t_check(started == T && same && mt_measured_cache_size() == 1,
            "cache: threads loading one file at once share one object", "%d threads, %s, %d cached",
            started, same ? "same" : "different objects", mt_measured_cache_size());
    for (i = 0; i < started; ++i) mt_measured_destroy(l[i].got);
    mt_measured_cache_clear();
}

/* The creators from memory, the kinds, and their errors. */
static void test_api(mt_arena *a, const mt_measured *m)
{
    size_t n = 3 * (size_t)MT_MERL_SAMPLES;
    mt_real *copy = m ? malloc(n * sizeof *copy) : NULL;
    mt_measured *h = NULL, *bad;
    mt_error err;
    mt_vec3 w = mt_v3(0, 0, 1), nan3 = mt_v3(NAN, 0, 1);
    mt_rgb one = mt_rgb_gray(1);
    mt_bxdf *x, *y;
    int i, same = 1;
    if (!copy) {
        t_fail("measured API", "no table");
        return;
    }
    memcpy(copy, mt_measured_table(m), n * sizeof *copy);
    h = mt_measured_halfangle_create(copy, &err);
    x = h ? mt_regular_halfangle_brdf_create(a, M, h, &err) : NULL;
    y = mt_regular_halfangle_brdf_create(a, M, m, &err);
    for (i = 0; x && y && i < 64; ++i) {
        mt_vec3 wo = mt_v3(0.1f * (i % 8), 0.05f * (i / 8), 0.9f), wi = mt_v3(-0.3f, 0.02f * i, 0.7f);
        same &= mt_rgb_equal(mt_bxdf_f(x, wo, wi), mt_bxdf_f(y, wo, wi));
    }
    t_check(x && same && mt_measured_kind_of(h) == MT_MEASURED_HALFANGLE && mt_measured_count(h) == MT_MERL_SAMPLES &&
                !mt_measured_sample(h, 0, NULL, NULL),
            "measured API: a half-angle table from memory is the file's BRDF", "%s", h ? "differs" : err.message);
    copy[3 * 1000 + 2] = -1;
    bad = mt_measured_halfangle_create(copy, &err);
    t_check(!bad && strstr(err.message, "entry 1000 channel 2 is -1"), "measured API: a negative table entry is an error",
            "%s", bad ? "accepted" : err.message);
    x = mt_irregular_isotropic_brdf_create(a, M, m, &err);
    t_check(!x && strstr(err.message, "other kind"), "measured API: a BxDF of the other kind of data is an error",
            "%s", x ? "created" : err.message);
    bad = mt_measured_irregular_create(&w, &w, &one, 0, &err);
    t_check(!bad && strstr(err.message, "no samples"), "measured API: no irregular samples is an error", "%s",
            bad ? "accepted" : err.message);
    bad = mt_measured_irregular_create(&w, &nan3, &one, 1, &err);
    t_check(!bad && strstr(err.message, "sample 0 has a value that is not finite"),
            "measured API: a NaN direction is an error", "%s", bad ? "accepted" : err.message);
    mt_measured_destroy(h);
    free(copy);
}

static void test_merl_roundtrip(mt_arena *a)
{
    double *values = malloc(3 * (size_t)MT_MERL_SAMPLES * sizeof *values);
    double *again = malloc(3 * (size_t)MT_MERL_SAMPLES * sizeof *again);
    char path[1024];
    mt_error err;
    mt_measured *m, *c, *same;
    mt_bsdf *truth = plastic(a, &err);
    int n;
    const char *dir = t_write_file("merl/.keep", "", 0);
    if (!values || !again || !truth || !dir) {
        t_fail("MERL round trip", "setup failed");
        free(values);
        free(again);
        return;
    }
    snprintf(path, sizeof path, "%s", dir);
    strcpy(strrchr(path, '/') + 1, "centre.binary");
    c = merl_roundtrip(a, truth, MT_MERL_AT_CENTRE, path, values, again);
    remove(path);
    strcpy(strrchr(path, '/') + 1, "plastic.binary");
    m = merl_roundtrip(a, truth, MT_MERL_AT_CORNER, path, values, again);
    test_api(a, m);
    n = mt_measured_cache_size();
    same = mt_measured_load(path, &err);
    t_check(m && same == m && mt_measured_cache_size() == n, "cache: the same file gives the same data",
            "%p then %p, %d then %d files cached", (void *)m, (void *)same, n, mt_measured_cache_size());
    mt_measured_destroy(same);
    mt_measured_cache_clear();
    same = mt_measured_load(path, &err);
    t_check(same && same != m && mt_measured_cache_size() == 1,
            "cache: cleared, the file is read again (data still held stays valid)", "%s",
            same ? "same object" : err.message);
    mt_measured_destroy(same);
    mt_measured_destroy(m);
    mt_measured_destroy(c);
    mt_measured_cache_clear();
    t_check(mt_measured_cache_size() == 0, "cache: empty after clearing", "%d entries", mt_measured_cache_size());
    test_cache_threads(path);
    remove(path);
    /* a write that fails after the temporary file was made (renaming it
     * over a directory) removes it */
    strcpy(strrchr(path, '/') + 1, "adir");
    if (mkdir(path, 0700) == 0) {
        DIR *d;
        struct dirent *e;
        int left = 0;
        mt_status st = mt_merl_write(path, values, &err);
        *strrchr(path, '/') = '\0';
        if ((d = opendir(path)) != NULL) {
            while ((e = readdir(d)) != NULL) left += !strncmp(e->d_name, "adir.", 5);
            closedir(d);
        }
        t_check(st == MT_ERR_IO && strstr(err.message, "cannot write") && left == 0,
                "MERL write: a failed rename reports the file and leaves no temporary file",
                "status %d, %d left: %s", st, left, err.message);
        strcat(path, "/adir");
        rmdir(path);
    }
    free(values);
    free(again);
}

/* Every allocation of a load made to fail in turn: a clean NOMEM error,
 * nothing cached, nothing leaked (the sanitizer build checks the last). */
static void test_alloc_failures(const char *path, const char *label)
{
    long n;
    int clean = 1, done = 0;
    char name[128];
    mt_measured_cache_clear();
    for (n = 0; n < 200 && !done; ++n) {
        mt_error err;
        mt_measured *m;
        mt_error_clear(&err);
        mt_alloc_fail_after(n);
        m = mt_measured_load(path, &err);
        mt_alloc_fail_after(-1);
        if (m) {
            done = 1;
            mt_measured_destroy(m);
        } else if (err.status != MT_ERR_NOMEM || mt_measured_cache_size() != 0) {
            clean = 0;
            printf("  allocation %ld failed: %s\n", n, err.message);
        }
        mt_measured_cache_clear();
    }
    remove(path);
    snprintf(name, sizeof name, "%s: every allocation failure reported as out of memory", label);
    t_check(clean && done, name, "%s", done ? "another error, or something cached" : "never loaded");
}

int main(void)
{
    mt_arena *a = mt_arena_create(0);
    test_kdtree();
    test_kdtree_infinite();
    test_remap();
    test_irregular_search();
    test_irregular_grid(a);
    test_real_files(a);
    test_pbrt_values();
    if (!t_tmpdir_create("measured")) {
        t_fail("temporary directory", "cannot create one");
        mt_arena_destroy(a);
        return t_status();
    }
    test_broken_brdf();
    test_broken_merl();
    test_alloc_failures(write_text("alloc.brdf", "2\n500 600\n0.1 0 0.2 0 0.5 0.5\n0.3 1 0.2 2 0.5 0.6\n"
                                   "0.5 0 0.4 3 0.1 0.2\n"), ".brdf load");
    test_alloc_failures(write_merl("alloc.binary", 90, 90, 180, 3 * (size_t)MT_MERL_SAMPLES, (size_t)-1, 0, 0),
                        "MERL load");
    test_merl_roundtrip(a);
    t_tmpdir_remove();
    mt_measured_cache_clear();
    mt_arena_destroy(a);
    return t_status();
}
