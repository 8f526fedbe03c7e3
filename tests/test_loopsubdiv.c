/*
 * pbrt-v2's Loop subdivision: positions worked out by hand for a regular
 * tetrahedron, limit positions that do not depend on the level, face and
 * vertex counts, convergence of the meshes towards the limit surface (the
 * distance to it falls about fourfold per level), boundary rules on open
 * meshes, limit normals (unit, consistently oriented, agreeing with the
 * surface), and the killeroo of the reference scenes.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/tgeom.h"

#define TETRA_P "\"point P\" [1 1 1 -1 -1 1 -1 1 -1 1 -1 -1]"
#define TETRA_I "\"integer indices\" [0 1 2 0 2 3 0 3 1 1 3 2]"
#define TOL (64 * (double)MT_REAL_EPSILON)

static mt_shape *subdiv_mode(const char *mesh, int levels, mt_mode mode, mt_error *err)
{
    char text[4096];
    snprintf(text, sizeof text, "Shape \"loopsubdiv\" \"integer nlevels\" %d %s", levels, mesh);
    return t_shape_mode(text, NULL, 0, mode, NULL, err);
}
static mt_shape *subdiv(const char *mesh, int levels, mt_error *err)
{
    return subdiv_mode(mesh, levels, MT_MODE_PBRT_V2, err);
}

static double dist3(mt_vec3 a, mt_vec3 b) { return mt_v3_len(mt_v3_sub(a, b)); }

static void test_hand_values(void)
{
    /* nlevels 0: only the push to the limit, gamma(3) = 1/5:
     * 0.4 P0 + 0.2 (P1 + P2 + P3) = (0.2, 0.2, 0.2).
     * nlevels 1: the odd vertex of edge (0, 1) is 3/8 (P0 + P1) + 1/8 (P2 +
     * P3) = (0, 0, 0.5), pushed with gamma(6) = 1/12 over its ring
     * (0.25, 0.25, 0.25), (-0.25, -0.25, 0.25), (0, 0.5, 0), (-0.5, 0, 0),
     * (0.5, 0, 0), (0, -0.5, 0): (0, 0, 0.25 + 0.5 / 12) = (0, 0, 7/24);
     * the even vertex 0 goes to 7/16 P0 + 3/16 (P1 + P2 + P3) = 0.25 (1,1,1)
     * and its limit is (0.2, 0.2, 0.2) again. */
    mt_error err;
    mt_shape *s0 = subdiv(TETRA_P " " TETRA_I, 0, &err), *s1 = subdiv(TETRA_P " " TETRA_I, 1, &err);
    mt_mesh_view m0, m1;
    if (!s0 || !s1) {
        t_fail("tetrahedron", "%s", err.message);
        goto done;
    }
    mt_shape_mesh(s0, &m0);
    mt_shape_mesh(s1, &m1);
    t_check(dist3(m0.P[0], mt_v3((mt_real)0.2, (mt_real)0.2, (mt_real)0.2)) < TOL && dist3(m1.P[0], mt_v3((mt_real)0.2, (mt_real)0.2, (mt_real)0.2)) < TOL,
            "tetrahedron: limit of a valence-3 vertex, levels 0 and 1", "%g %g %g / %g %g %g",
            m0.P[0].x, m0.P[0].y, m0.P[0].z, m1.P[0].x, m1.P[0].y, m1.P[0].z);
    t_check(m1.nverts == 10 && dist3(m1.P[4], mt_v3(0, 0, (mt_real)(7.0 / 24))) < TOL,
            "tetrahedron: odd vertex of edge (0, 1) at (0, 0, 7/24), created first", "%u verts, %g %g %g",
            (unsigned)m1.nverts, m1.P[4].x, m1.P[4].y, m1.P[4].z);
    {
        /* by symmetry the limit normal at vertex 0 lies along (1, 1, 1) */
        mt_vec3 n = mt_v3_normalize(m1.N[0]);
        double c = mt_v3_dot(n, mt_v3_normalize(mt_v3(1, 1, 1)));
        t_check(fabs(fabs(c) - 1) < TOL, "tetrahedron: limit normal at a corner along (1, 1, 1)",
                "cos %.9g", c);
    }
done:
    mt_shape_destroy(s0);
    mt_shape_destroy(s1);
}

static void test_counts_and_invariance(void)
{
    mt_error err;
    mt_shape *s[5];
    int k, ok = 1;
    double worst = 0;
    uint32_t v = 4, e = 6, f = 4;
    for (k = 0; k < 5; ++k) s[k] = subdiv(TETRA_P " " TETRA_I, k, &err);
    for (k = 0; k < 5; ++k) {
        mt_mesh_view m;
        if (!s[k] || !mt_shape_mesh(s[k], &m)) {
            ok = 0;
            continue;
        }
        /* each level: V' = V + E, E' = 2E + 3F, F' = 4F */
        if (m.ntris != f || m.nverts != v) ok = 0;
        if (k > 0) {
            mt_mesh_view p;
            uint32_t i;
            mt_shape_mesh(s[k - 1], &p);
            /* a vertex keeps its index, and its limit position, across levels */
            for (i = 0; i < p.nverts; ++i) worst = fmax(worst, dist3(m.P[i], p.P[i]));
        }
        v += e;
        e = 2 * e + 3 * f;
        f *= 4;
    }
    t_check(ok, "levels multiply the triangles by 4 (vertices V + E)", "counts differ: %s", err.message);
    t_check(worst < TOL, "limit positions do not depend on the level", "moved by %.3g", worst);
    for (k = 0; k < 5; ++k) mt_shape_destroy(s[k]);
}

/* Distance from p to the triangle (a, b, c) (Ericson, Real-Time Collision
 * Detection, 5.1.5), in double. */
typedef struct v3d {
    double x, y, z;
} v3d;
static v3d vd(mt_vec3 a)
{
    v3d r;
    r.x = a.x;
    r.y = a.y;
    r.z = a.z;
    return r;
}
static v3d sub(v3d a, v3d b)
{
    v3d r;
    r.x = a.x - b.x;
    r.y = a.y - b.y;
    r.z = a.z - b.z;
    return r;
}
static double dot(v3d a, v3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static v3d madd(v3d a, double s, v3d b)
{
    v3d r;
    r.x = a.x + s * b.x;
    r.y = a.y + s * b.y;
    r.z = a.z + s * b.z;
    return r;
}
static double point_triangle(v3d p, v3d a, v3d b, v3d c)
{
    v3d ab = sub(b, a), ac = sub(c, a), ap = sub(p, a), bp = sub(p, b), cp = sub(p, c), q;
    double d1 = dot(ab, ap), d2 = dot(ac, ap), d3 = dot(ab, bp), d4 = dot(ac, bp);
    double d5 = dot(ab, cp), d6 = dot(ac, cp), va, vb, vc, v, w, den;
    if (d1 <= 0 && d2 <= 0) q = a;
    else if (d3 >= 0 && d4 <= d3) q = b;
    else if ((vc = d1 * d4 - d3 * d2) <= 0 && d1 >= 0 && d3 <= 0) q = madd(a, d1 / (d1 - d3), ab);
    else if (d6 >= 0 && d5 <= d6) q = c;
    else if ((vb = d5 * d2 - d1 * d6) <= 0 && d2 >= 0 && d6 <= 0) q = madd(a, d2 / (d2 - d6), ac);
    else if ((va = d3 * d6 - d5 * d4) <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        q = madd(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b));
    else {
        vc = d1 * d4 - d3 * d2;
        vb = d5 * d2 - d1 * d6;
        va = d3 * d6 - d5 * d4;
        den = 1 / (va + vb + vc);
        v = vb * den;
        w = vc * den;
        q = madd(madd(a, v, ab), w, ac);
    }
    q = sub(p, q);
    return sqrt(dot(q, q));
}

/* The largest distance from the limit surface (sampled by the vertices of a
 * finer level) to the mesh of a level. */
static double mesh_distance(const mt_mesh_view *fine, const mt_mesh_view *m)
{
    uint32_t i, t;
    double worst = 0;
    for (i = 0; i < fine->nverts; ++i) {
        double best = 1e300;
        v3d p = vd(fine->P[i]);
        for (t = 0; t < m->ntris; ++t) {
            const int *v = m->indices + 3 * t;
            double d = point_triangle(p, vd(m->P[v[0]]), vd(m->P[v[1]]), vd(m->P[v[2]]));
            if (d < best) best = d;
        }
        if (best > worst) worst = best;
    }
    return worst;
}

static void test_convergence(void)
{
    mt_error err;
    mt_shape *s[6];
    mt_mesh_view m[6];
    double d[5];
    int k, ok = 1;
    char msg[256] = "";
    for (k = 0; k < 6; ++k) {
        s[k] = subdiv(TETRA_P " " TETRA_I, k, &err);
        if (!s[k] || !mt_shape_mesh(s[k], &m[k])) ok = 0;
    }
    if (ok) {
        /* a smooth surface interpolated at vertices spaced h apart deviates
         * by O(h^2): each level halves h, so the distance falls about 4x */
        for (k = 1; k < 5; ++k) d[k] = mesh_distance(&m[5], &m[k]);
        for (k = 1; k < 4; ++k) {
            double ratio = d[k] / d[k + 1];
            size_t n = strlen(msg);
            snprintf(msg + n, sizeof msg - n, " %.3g", ratio);
            if (!(ratio > 3 && ratio < 5.5)) ok = 0;
        }
    }
    t_check(ok, "tetrahedron converges to its limit surface (distance / 4 per level)",
            "ratios%s", msg);
    for (k = 0; k < 6; ++k) mt_shape_destroy(s[k]);
}

/* Whether vertex v lies on an edge of only one triangle. */
static int on_boundary(const mt_mesh_view *m, int v)
{
    uint32_t t, u;
    int k, j;
    for (t = 0; t < m->ntris; ++t)
        for (k = 0; k < 3; ++k) {
            int a = m->indices[3 * t + k], b = m->indices[3 * t + (k + 1) % 3], uses = 0;
            if (a != v && b != v) continue;
            for (u = 0; u < m->ntris; ++u)
                for (j = 0; j < 3; ++j) {
                    int c = m->indices[3 * u + j], d = m->indices[3 * u + (j + 1) % 3];
                    if ((c == a && d == b) || (c == b && d == a)) uses++;
                }
            if (uses == 1) return 1;
        }
    return 0;
}

/* The angle between two vectors in degrees, atan2(|a x b|, a . b) in
 * double (the acos of a float dot product cannot tell 0.02 degrees from 0). */
static double angle_deg(mt_vec3 a, mt_vec3 b)
{
    double ax = a.x, ay = a.y, az = a.z, bx = b.x, by = b.y, bz = b.z;
    double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    return atan2(sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz) * 180 /
           3.14159265358979;
}

/* The largest angle (degrees) between the normals N of mesh a and the
 * mean face normal around the same vertex in the finer mesh b, inside and
 * on the boundary; *mixed counts vertices whose N points to the other side
 * than the first one's (as pbrt-v2 computes them, the normals point
 * against the faces' winding: the one-ring is walked clockwise). */
static void fan_deviation(const mt_mesh_view *a, const mt_mesh_view *b, double *inside,
                          double *bound, int *mixed)
{
    mt_vec3 *avg = calloc(b->nverts, sizeof *avg);
    uint32_t i, t;
    int k;
    *inside = *bound = 0;
    *mixed = 0;
    for (t = 0; t < b->ntris; ++t) {
        const int *v = b->indices + 3 * t;
        mt_vec3 n = mt_v3_cross(mt_v3_sub(b->P[v[1]], b->P[v[0]]), mt_v3_sub(b->P[v[2]], b->P[v[0]]));
        for (k = 0; k < 3; ++k) avg[v[k]] = mt_v3_add(avg[v[k]], n);
    }
    for (i = 0; i < a->nverts; ++i) {
        double dev = angle_deg(a->N[i], mt_v3_neg(avg[i]));
        if (dev > 90) (*mixed)++;
        if (on_boundary(a, (int)i)) *bound = fmax(*bound, dev);
        else *inside = fmax(*inside, dev);
    }
    free(avg);
}

/* Limit normals at level `level`, corrected and pbrt-v2's. Corrected, they
 * are the limit surface's: non-zero, the same at a vertex whatever the
 * level (level + 2 here), and along the surface: the mean of the faces'
 * normals around the vertex 3 and 4 levels down converges to the limit
 * surface's normal, with an error O(h^2) inside, where the fan surrounds
 * the vertex, and O(h) on the boundary, where it is one-sided -- so the
 * angle to it must fall about fourfold (at least 3x) inside and twofold
 * (at least 1.7x) on the boundary from one level to the next; a normal off
 * the surface would stay off.
 *
 * Erratum loop-normals: pbrt-v2 applies Loop's tangent masks to the
 * one-ring after every vertex was pushed to its limit position, where the
 * masks are meant for the control points, and its mask across the boundary
 * at vertices of four faces or more does not belong to its own subdivision
 * rules: its normals are off the limit normals by degrees (measured against
 * the corrected ones, and required to be: more than 1). */
static void check_normals(const char *name, const char *mesh, int level)
{
    mt_error err;
    mt_shape *a = subdiv_mode(mesh, level, MT_FIX_LOOP_NORMALS, &err);
    mt_shape *c = subdiv_mode(mesh, level + 2, MT_FIX_LOOP_NORMALS, &err);
    mt_shape *f3 = subdiv_mode(mesh, level + 3, MT_FIX_LOOP_NORMALS, &err);
    mt_shape *f4 = subdiv_mode(mesh, level + 4, MT_FIX_LOOP_NORMALS, &err);
    mt_shape *v2 = subdiv_mode(mesh, level, MT_MODE_PBRT_V2, &err);
    mt_mesh_view ma, mc, m3, m4, m2;
    uint32_t i;
    int zero = 0, mixed3, mixed4;
    double in3, bd3, in4, bd4, drift = 0, off = 0;
    char buf[200];
    if (!a || !c || !f3 || !f4 || !v2) {
        t_fail(name, "%s", err.message);
        goto done;
    }
    mt_shape_mesh(a, &ma);
    mt_shape_mesh(c, &mc);
    mt_shape_mesh(f3, &m3);
    mt_shape_mesh(f4, &m4);
    mt_shape_mesh(v2, &m2);
    for (i = 0; i < ma.nverts; ++i) {
        if (!(mt_v3_len(ma.N[i]) > 0) || !mt_v3_is_finite(ma.N[i]) || !(mt_v3_len(m2.N[i]) > 0)) {
            zero++;
            continue;
        }
        drift = fmax(drift, angle_deg(ma.N[i], mc.N[i]));
        off = fmax(off, angle_deg(m2.N[i], ma.N[i]));
    }
    fan_deviation(&ma, &m3, &in3, &bd3, &mixed3);
    fan_deviation(&ma, &m4, &in4, &bd4, &mixed4);
    snprintf(buf, sizeof buf, "%s: limit normals non-zero, against the winding throughout", name);
    t_check(zero == 0 && mixed3 == 0 && mixed4 == 0, buf, "%d zero, %d and %d the other way", zero,
            mixed3, mixed4);
    snprintf(buf, sizeof buf, "%s: limit normals the same 2 levels down (loop-normals fixed)", name);
    t_check(drift < 1e-3, buf, "turn by %.3g degrees", drift);
    snprintf(buf, sizeof buf, "%s: limit normals along the fine surface (loop-normals fixed)", name);
    t_check(in4 * 3 < in3 && (bd3 == 0 || bd4 * 1.7 < bd3) && in4 < 0.05 && bd4 < 1, buf,
            "%.3g then %.3g degrees off inside, %.3g then %.3g on the boundary", in3, in4, bd3, bd4);
    snprintf(buf, sizeof buf, "%s: pbrt-v2's limit normals off the limit normals", name);
    t_check(off > 1, buf, "only %.3g degrees off", off);
    snprintf(buf, sizeof buf, "%s: limit normals", name);
    t_xfail(buf, "erratum loop-normals: pbrt-v2 takes the tangents from the pushed one-ring: "
            "up to %.2f degrees off the limit normal at level %d", off, level);
done:
    mt_shape_destroy(a);
    mt_shape_destroy(c);
    mt_shape_destroy(f3);
    mt_shape_destroy(f4);
    mt_shape_destroy(v2);
}

static void test_normals(void)
{
    check_normals("tetrahedron", TETRA_P " " TETRA_I, 2);
    /* an open box (a cube without its top): boundary vertices of valence
     * 2 to 5 */
    check_normals("open box",
                  "\"point P\" [-1 -1 -1 1 -1 -1 1 1 -1 -1 1 -1 -1 -1 1 1 -1 1 1 1 1 -1 1 1] "
                  "\"integer indices\" [0 2 1 0 3 2 0 1 5 0 5 4 2 3 7 2 7 6 1 2 6 1 6 5 0 4 7 0 7 3]",
                  2);
}

static void test_boundary(void)
{
    /* a flat grid of 2 x 6 quads (24 triangles, z = 0): every rule keeps
     * z = 0; the boundary rules keep the straight side x = 0 straight where
     * four consecutive control points on it are collinear (1 <= y <= 5;
     * the corners are cut, as cubic B-splines do); boundary edges double per
     * level; every limit normal is along z */
    char grid[2048];
    size_t n = 0;
    int gx, gy;
    n += (size_t)snprintf(grid + n, sizeof grid - n, "\"point P\" [");
    for (gy = 0; gy <= 6; ++gy)
        for (gx = 0; gx <= 2; ++gx) n += (size_t)snprintf(grid + n, sizeof grid - n, "%d %d 0 ", gx, gy);
    n += (size_t)snprintf(grid + n, sizeof grid - n, "] \"integer indices\" [");
    for (gy = 0; gy < 6; ++gy)
        for (gx = 0; gx < 2; ++gx) {
            int a = 3 * gy + gx, b = a + 1, c = a + 4, d = a + 3;
            n += (size_t)snprintf(grid + n, sizeof grid - n, "%d %d %d %d %d %d ", a, b, c, a, c, d);
        }
    snprintf(grid + n, sizeof grid - n, "]");
    mt_error err;
    int level, ok = 1, straight = 1, normals = 1, edges_ok = 1;
    for (level = 1; level <= 3; ++level) {
        mt_shape *s = subdiv(grid, level, &err);
        mt_mesh_view m;
        uint32_t i, t, nb = 0;
        if (!s) {
            ok = 0;
            continue;
        }
        mt_shape_mesh(s, &m);
        for (i = 0; i < m.nverts; ++i) {
            mt_vec3 nv = m.N[i];
            if (m.P[i].z != 0) ok = 0;
            if (m.P[i].x < 1e-3f && m.P[i].y >= 1 && m.P[i].y <= 5 && m.P[i].x != 0) straight = 0;
            if (!(mt_v3_len(nv) > 0) || nv.x != 0 || nv.y != 0) normals = 0;
        }
        /* boundary edges: those of one triangle (count each undirected edge) */
        for (t = 0; t < m.ntris; ++t) {
            int k;
            for (k = 0; k < 3; ++k) {
                int a = m.indices[3 * t + k], b = m.indices[3 * t + (k + 1) % 3], uses = 0;
                uint32_t u;
                for (u = 0; u < m.ntris; ++u) {
                    int j;
                    for (j = 0; j < 3; ++j) {
                        int c = m.indices[3 * u + j], d = m.indices[3 * u + (j + 1) % 3];
                        if ((c == a && d == b) || (c == b && d == a)) uses++;
                    }
                }
                if (uses == 1) nb++;
            }
        }
        if (nb != 16u << level) edges_ok = 0;
        mt_shape_destroy(s);
    }
    t_check(ok, "flat grid stays flat", "%s", err.message);
    t_check(straight, "a straight boundary stays straight", "moved off x = 0");
    t_check(normals, "flat grid: every limit normal (interior and boundary) along z", "not along z");
    t_check(edges_ok, "boundary edges double per level", "wrong count");
    {
        /* a single triangle: three boundary vertices of valence 2 */
        mt_shape *s = subdiv("\"point P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]", 2, &err);
        mt_mesh_view m;
        uint32_t i;
        int good = s != NULL;
        if (s) {
            mt_shape_mesh(s, &m);
            for (i = 0; i < m.nverts; ++i)
                if (!(mt_v3_len(m.N[i]) > 0) || m.N[i].x != 0 || m.N[i].y != 0) good = 0;
            good = good && m.ntris == 16;
        }
        t_check(good, "single triangle (valence-2 corners)", "%s", s ? "bad normals" : err.message);
        mt_shape_destroy(s);
    }
}

static void test_unused_vertex(void)
{
    /* a vertex no triangle names is carried through (pbrt-v2 would crash) */
    mt_error err;
    mt_shape *s = subdiv("\"point P\" [1 1 1 -1 -1 1 -1 1 -1 1 -1 -1 5 5 5] " TETRA_I, 1, &err);
    mt_mesh_view m;
    t_check(s && mt_shape_mesh(s, &m) && m.nverts == 11 && m.P[4].x == 5 && m.ntris == 16,
            "an unused vertex is carried through", "%s", s ? "wrong mesh" : err.message);
    mt_shape_destroy(s);
}

static void test_killeroo(void)
{
    const char *dir = t_shared_dir();
    char path[512];
    mt_error err;
    mt_geometry *g;
    int n;
    if (!dir) {
        t_skip("killeroo", "no shared reference data (../shared)");
        return;
    }
    snprintf(path, sizeof path, "%s/reference/scenes/geometry/killeroo.pbrt", dir);
    g = mt_geometry_create();
    n = g ? t_load_shapes(path, g, &err) : -1;
    if (t_check(n == 1 && mt_geometry_commit(g, &err) == MT_OK, "killeroo: subdivides without error",
                "%s", err.message)) {
        const mt_shape *s = mt_geometry_shape(g, 0);
        mt_mesh_view m;
        uint32_t i;
        int bad = 0;
        mt_shape_mesh(s, &m);
        for (i = 0; i < m.nverts; ++i)
            if (!(mt_v3_len(m.N[i]) > 0) || !mt_v3_is_finite(m.N[i]) || !mt_v3_is_finite(m.P[i])) bad++;
        t_check(bad == 0 && m.ntris > 1000, "killeroo: finite positions, non-zero limit normals",
                "%d bad of %u (%u triangles)", bad, (unsigned)m.nverts, (unsigned)m.ntris);
    }
    mt_geometry_destroy(g);
}

int main(void)
{
    test_hand_values();
    test_counts_and_invariance();
    test_convergence();
    test_normals();
    test_boundary();
    test_unused_vertex();
    test_killeroo();
    return t_status();
}
