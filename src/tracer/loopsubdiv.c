/*
 * pbrt-v2's Loop subdivision surface (shapes/loopsubdiv.cpp): "indices",
 * "P", "nlevels" (default 3; "scheme" is read and ignored as in pbrt-v2).
 *
 * Each level splits every triangle in four: even (old) vertices move by
 * Loop's one-ring rule, with beta = 3/16 for valence 3 and 3 / (8 valence)
 * otherwise, or by the boundary rule (1/8, 3/4, 1/8); odd (edge) vertices
 * are 3/8, 3/8, 1/8, 1/8 of the edge's ends and opposite vertices, or the
 * midpoint on a boundary. After the last level every vertex is pushed to
 * its limit position (gamma(valence) = 1 / (valence + 3 / (8 beta)); 1/5,
 * 3/5, 1/5 on boundaries), and the limit normal is the cross product of two
 * tangents from the one-ring (Loop's cosine/sine weights inside; Hoppe et
 * al.'s boundary masks). The result is pbrt-v2's triangle mesh with that "N"
 * (not normalized, as pbrt-v2 passes it) and the same vertex and triangle
 * order as pbrt-v2's Refine.
 *
 * Erratum loop-normals (MT_FIX_LOOP_NORMALS): pbrt-v2 (and pbrt-v3) apply
 * the tangent masks to the one-ring after every vertex has been pushed to
 * its limit position; the masks give the limit tangents only when applied
 * to the control points, and the normals come out a few degrees off the
 * limit surface's. Corrected mode applies them to the control points, and
 * at boundary vertices with four faces or more, where pbrt-v2's mask does
 * not belong to its own subdivision rules, takes the across tangent from
 * the one-ring subdivided to its limit (boundary_across_limit).
 *
 * pbrt-v2 walks faces through neighbour pointers and would loop or crash on
 * meshes that are not 2-manifold; materia refuses, naming the problem: an
 * edge shared by more than two triangles, two triangles that traverse a
 * shared edge in the same direction (inconsistent orientation), a triangle
 * with a repeated vertex. Vertices that no triangle uses are carried
 * through unchanged.
 */
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include "core/alloc.h"
#include "tracer/shape_impl.h"

#define NEXT(i) (((i) + 1) % 3)
#define PREV(i) (((i) + 2) % 3)

typedef struct sd_vert {
    mt_vec3 P;
    int start; /* a face using the vertex; -1 when none */
    unsigned char regular, boundary;
} sd_vert;

typedef struct sd_face {
    int v[3];
    int f[3]; /* f[k]: the neighbour across the edge v[k] -> v[k+1]; -1 on a boundary */
} sd_face;

typedef struct sd_mesh {
    sd_vert *v;
    sd_face *f;
    int nv, nf;
    mt_vec3 *ring; /* scratch for one-rings: room for 3 times the ring */
    int ring_cap;
    mt_mode mode;
} sd_mesh;

static int vnum(const sd_face *f, int v) { return f->v[0] == v ? 0 : (f->v[1] == v ? 1 : 2); }
static int next_face(const sd_mesh *m, int f, int v) { return m->f[f].f[vnum(&m->f[f], v)]; }
static int prev_face(const sd_mesh *m, int f, int v) { return m->f[f].f[PREV(vnum(&m->f[f], v))]; }
static int next_vert(const sd_mesh *m, int f, int v) { return m->f[f].v[NEXT(vnum(&m->f[f], v))]; }
static int prev_vert(const sd_mesh *m, int f, int v) { return m->f[f].v[PREV(vnum(&m->f[f], v))]; }

/* pbrt-v2 SDVertex::valence: the faces around an interior vertex; the faces
 * plus one (the ring's vertex count) around a boundary vertex. */
static int valence(const sd_mesh *m, int v)
{
    int start = m->v[v].start, f = start, nf = 1;
    if (!m->v[v].boundary) {
        while ((f = next_face(m, f, v)) != start) ++nf;
        return nf;
    }
    while ((f = next_face(m, f, v)) >= 0) ++nf;
    f = start;
    while ((f = prev_face(m, f, v)) >= 0) ++nf;
    return nf + 1;
}

/* pbrt-v2 SDVertex::oneRing into m->ring (grown as needed); returns the
 * valence, or -1 when out of memory. */
static int one_ring(sd_mesh *m, int v)
{
    int n = valence(m, v), f = m->v[v].start, f2, k = 0;
    if (3 * n > m->ring_cap) {
        mt_vec3 *r = mt__realloc(m->ring, (size_t)n * 6 * sizeof *r);
        if (!r) return -1;
        m->ring = r;
        m->ring_cap = n * 6;
    }
    if (!m->v[v].boundary) {
        do {
            m->ring[k++] = m->v[next_vert(m, f, v)].P;
            f = next_face(m, f, v);
        } while (f != m->v[v].start);
    } else {
        while ((f2 = next_face(m, f, v)) >= 0) f = f2;
        m->ring[k++] = m->v[next_vert(m, f, v)].P;
        do {
            m->ring[k++] = m->v[prev_vert(m, f, v)].P;
            f = prev_face(m, f, v);
        } while (f >= 0);
    }
    return n;
}

static mt_real beta(int valence) { return valence == 3 ? (mt_real)3 / 16 : (mt_real)3 / (8 * (mt_real)valence); }
static mt_real loop_gamma(int valence) { return 1 / (valence + (mt_real)3 / (8 * beta(valence))); }

static mt_vec3 madd(mt_vec3 acc, mt_real w, mt_vec3 p) { return mt_v3_add(acc, mt_v3_scale(p, w)); }

/* pbrt-v2 weightOneRing / weightBoundary. */
static int weight_one_ring(sd_mesh *m, int v, mt_real b, mt_vec3 *out)
{
    int n = one_ring(m, v), i;
    mt_vec3 P;
    if (n < 0) return 0;
    P = mt_v3_scale(m->v[v].P, 1 - n * b);
    for (i = 0; i < n; ++i) P = madd(P, b, m->ring[i]);
    *out = P;
    return 1;
}
static int weight_boundary(sd_mesh *m, int v, mt_real b, mt_vec3 *out)
{
    int n = one_ring(m, v);
    if (n < 0) return 0;
    *out = madd(madd(mt_v3_scale(m->v[v].P, 1 - 2 * b), b, m->ring[0]), b, m->ring[n - 1]);
    return 1;
}

/* ---- the control mesh: neighbours, boundaries, and the manifold checks ---------- */

typedef struct sd_edge {
    int a, b;     /* vertex indices, a < b */
    int face, k;  /* the face and its edge number */
} sd_edge;

static int edge_cmp(const void *x, const void *y)
{
    const sd_edge *e = x, *g = y;
    if (e->a != g->a) return e->a < g->a ? -1 : 1;
    if (e->b != g->b) return e->b < g->b ? -1 : 1;
    return e->face < g->face ? -1 : (e->face > g->face);
}

static mt_status link_faces(sd_mesh *m, mt_error *err)
{
    sd_edge *e = mt__malloc(3 * (size_t)m->nf * sizeof *e);
    int i, n = 3 * m->nf;
    mt_status st = MT_OK;
    if (!e) return mt_error_set(err, MT_ERR_NOMEM, "out of memory linking %d faces", m->nf);
    for (i = 0; i < n; ++i) {
        int f = i / 3, k = i % 3, v0 = m->f[f].v[k], v1 = m->f[f].v[NEXT(k)];
        e[i].a = v0 < v1 ? v0 : v1;
        e[i].b = v0 < v1 ? v1 : v0;
        e[i].face = f;
        e[i].k = k;
        m->f[f].f[k] = -1;
    }
    qsort(e, (size_t)n, sizeof *e, edge_cmp);
    for (i = 0; i < n && st == MT_OK;) {
        int j = i + 1;
        while (j < n && e[j].a == e[i].a && e[j].b == e[i].b) ++j;
        if (j - i > 2) {
            st = mt_error_param(err, MT_ERR_INVALID, "indices",
                                "loopsubdiv: the edge between vertices %d and %d is shared by %d "
                                "triangles (the mesh must be a 2-manifold)", e[i].a, e[i].b, j - i);
        } else if (j - i == 2) {
            const sd_face *f0 = &m->f[e[i].face], *f1 = &m->f[e[i + 1].face];
            if (f0->v[e[i].k] == f1->v[e[i + 1].k])
                st = mt_error_param(err, MT_ERR_INVALID, "indices",
                                    "loopsubdiv: triangles %d and %d traverse their shared edge "
                                    "(%d, %d) in the same direction (inconsistent orientation)",
                                    e[i].face, e[i + 1].face, e[i].a, e[i].b);
            m->f[e[i].face].f[e[i].k] = e[i + 1].face;
            m->f[e[i + 1].face].f[e[i + 1].k] = e[i].face;
        }
        i = j;
    }
    mt__free(e);
    return st;
}

static void classify_vertices(sd_mesh *m)
{
    int i;
    for (i = 0; i < m->nv; ++i) {
        sd_vert *v = &m->v[i];
        int f = v->start, val;
        if (f < 0) continue;
        do f = next_face(m, f, i);
        while (f >= 0 && f != v->start);
        v->boundary = f < 0;
        val = valence(m, i);
        v->regular = (!v->boundary && val == 6) || (v->boundary && val == 4);
    }
}

static mt_status control_mesh(sd_mesh *m, int nf, const int *vi, int nv, const double *P,
                              mt_error *err)
{
    int i, k;
    m->nv = nv;
    m->nf = nf;
    m->v = mt__calloc((size_t)nv, sizeof *m->v);
    m->f = mt__calloc((size_t)nf, sizeof *m->f);
    if (!m->v || !m->f) return mt_error_set(err, MT_ERR_NOMEM, "out of memory for loopsubdiv");
    for (i = 0; i < nv; ++i) {
        m->v[i].P = mt_v3((mt_real)P[3 * i], (mt_real)P[3 * i + 1], (mt_real)P[3 * i + 2]);
        m->v[i].start = -1;
    }
    for (i = 0; i < nf; ++i) {
        for (k = 0; k < 3; ++k) {
            int v = vi[3 * i + k];
            if (v < 0 || v >= nv)
                return mt_error_param(err, MT_ERR_INVALID, "indices",
                                      "loopsubdiv has out-of-bounds vertex index %d (%d \"P\" "
                                      "values were given)", v, nv);
            m->f[i].v[k] = v;
            m->v[v].start = i; /* pbrt-v2: the last face that names the vertex */
        }
        if (m->f[i].v[0] == m->f[i].v[1] || m->f[i].v[1] == m->f[i].v[2] ||
            m->f[i].v[2] == m->f[i].v[0])
            return mt_error_param(err, MT_ERR_INVALID, "indices",
                                  "loopsubdiv: triangle %d repeats a vertex (%d %d %d)", i,
                                  m->f[i].v[0], m->f[i].v[1], m->f[i].v[2]);
    }
    {
        mt_status st = link_faces(m, err);
        if (st != MT_OK) return st;
    }
    classify_vertices(m);
    return MT_OK;
}

/* ---- one level of refinement --------------------------------------------------- */

static mt_status refine(sd_mesh *m, mt_error *err)
{
    int nv = m->nv, nf = m->nf, j, k, nnv = nv;
    sd_vert *V = mt__calloc((size_t)nv + 3 * (size_t)nf, sizeof *V);
    sd_face *F = mt__calloc(4 * (size_t)nf, sizeof *F);
    int *ev = mt__malloc(3 * (size_t)nf * sizeof *ev);
    if (!V || !F || !ev) goto nomem;

    /* even vertices: the children keep their parents' indices and flags */
    for (j = 0; j < nv; ++j) {
        const sd_vert *v = &m->v[j];
        V[j].regular = v->regular;
        V[j].boundary = v->boundary;
        V[j].start = v->start < 0 ? -1 : 4 * v->start + vnum(&m->f[v->start], j);
        if (v->start < 0) V[j].P = v->P;
        else if (v->boundary) {
            if (!weight_boundary(m, j, (mt_real)1 / 8, &V[j].P)) goto nomem;
        } else if (!weight_one_ring(m, j, v->regular ? (mt_real)1 / 16 : beta(valence(m, j)),
                                    &V[j].P))
            goto nomem;
    }
    /* odd vertices, one per edge, in pbrt-v2's order of creation */
    for (j = 0; j < 3 * nf; ++j) ev[j] = -1;
    for (j = 0; j < nf; ++j)
        for (k = 0; k < 3; ++k) {
            const sd_face *f = &m->f[j];
            int a = f->v[k], b = f->v[NEXT(k)], g = f->f[k], lo = a < b ? a : b, hi = a ^ b ^ lo;
            sd_vert *o;
            if (ev[3 * j + k] >= 0) continue;
            o = &V[nnv];
            o->regular = 1;
            o->boundary = g < 0;
            o->start = 4 * j + 3;
            if (o->boundary) {
                o->P = madd(mt_v3_scale(m->v[lo].P, (mt_real)0.5), (mt_real)0.5, m->v[hi].P);
            } else {
                int e, c0 = f->v[PREV(k)], c1 = -1;
                for (e = 0; e < 3; ++e)
                    if (m->f[g].v[e] != a && m->f[g].v[e] != b) c1 = m->f[g].v[e];
                o->P = mt_v3_scale(m->v[lo].P, (mt_real)3 / 8);
                o->P = madd(o->P, (mt_real)3 / 8, m->v[hi].P);
                o->P = madd(o->P, (mt_real)1 / 8, m->v[c0].P);
                o->P = madd(o->P, (mt_real)1 / 8, m->v[c1].P);
                for (e = 0; e < 3; ++e)
                    if (m->f[g].f[e] == j && ((m->f[g].v[e] == a && m->f[g].v[NEXT(e)] == b) ||
                                              (m->f[g].v[e] == b && m->f[g].v[NEXT(e)] == a)))
                        ev[3 * g + e] = nnv;
            }
            ev[3 * j + k] = nnv++;
        }
    /* the four children of each face: neighbours, then vertices */
    for (j = 0; j < nf; ++j) {
        const sd_face *f = &m->f[j];
        sd_face *c = &F[4 * j];
        for (k = 0; k < 3; ++k) {
            int g = f->f[k], h = f->f[PREV(k)];
            c[3].f[k] = 4 * j + NEXT(k);
            c[k].f[NEXT(k)] = 4 * j + 3;
            c[k].f[k] = g >= 0 ? 4 * g + vnum(&m->f[g], f->v[k]) : -1;
            c[k].f[PREV(k)] = h >= 0 ? 4 * h + vnum(&m->f[h], f->v[k]) : -1;
        }
        for (k = 0; k < 3; ++k) {
            int o = ev[3 * j + k];
            c[k].v[k] = f->v[k];
            c[k].v[NEXT(k)] = o;
            c[NEXT(k)].v[k] = o;
            c[3].v[k] = o;
        }
    }
    mt__free(ev);
    mt__free(m->v);
    mt__free(m->f);
    m->v = V;
    m->f = F;
    m->nv = nnv;
    m->nf = 4 * nf;
    return MT_OK;
nomem:
    mt__free(V);
    mt__free(F);
    mt__free(ev);
    return mt_error_set(err, MT_ERR_NOMEM, "out of memory subdividing %d faces", nf);
}

/* ---- limit positions and normals ------------------------------------------------ */

/* pbrt-v2's boundary tangent across the boundary (Hoppe et al. 1994) from
 * the one-ring r[0..n-1] of the boundary vertex P. */
static mt_vec3 boundary_across(const mt_vec3 *r, int n, mt_vec3 P)
{
    mt_vec3 T = mt_v3(0, 0, 0);
    int k;
    if (n == 2) return mt_v3_sub(mt_v3_add(r[0], r[1]), mt_v3_scale(P, 2));
    if (n == 3) return mt_v3_sub(r[1], P);
    if (n == 4) /* regular */
        return mt_v3_add(mt_v3_add(mt_v3_scale(r[0], -1), mt_v3_scale(r[1], 2)),
                         mt_v3_add(mt_v3_add(mt_v3_scale(r[2], 2), mt_v3_scale(r[3], -1)),
                                   mt_v3_scale(P, -2)));
    {
        mt_real th = MT_PI / (mt_real)(n - 1);
        T = mt_v3_scale(mt_v3_add(r[0], r[n - 1]), mt_sin(th));
        for (k = 1; k < n - 1; ++k) T = madd(T, (2 * mt_cos(th) - 2) * mt_sin(k * th), r[k]);
    }
    return mt_v3_neg(T);
}

/* Erratum loop-normals, boundary vertices with four faces or more: the
 * mask above is not a left eigenvector of the rules pbrt-v2 subdivides
 * with there (the boundary rule for the vertex, Loop's interior edge rule
 * for the edges inside), so even on the control points it misses the limit
 * tangent (3.4 degrees at a valence-5 corner of an open box, turning with
 * every level). The one-ring is closed under those rules: subdividing it
 * alone, level after level, leaves the dominant across component, and the
 * mask applied then gives its direction (32 levels; the other components
 * shrink relative to it by the ratio of their eigenvalues each level). That
 * is the limit tangent for four and five faces. From six faces on, these
 * rules have a second across eigenvalue at least as large (1/2 doubled at
 * six faces, above the first from seven on, by a numerical eigen-analysis
 * of the one-ring's subdivision matrix): the limit surface has no single
 * tangent plane there and the direction found is a choice, no better
 * defined than pbrt-v2's. The tests cover four faces. tmp holds 2n points. */
static mt_vec3 boundary_across_limit(const mt_vec3 *r, int n, mt_vec3 P, mt_vec3 *tmp)
{
    mt_vec3 *a = tmp, *b = tmp + n, v = P, T0 = boundary_across(r, n, P), T;
    mt_real l0 = mt_v3_len(T0), l;
    int k, it;
    for (k = 0; k < n; ++k) a[k] = r[k];
    for (it = 0; it < 32; ++it) {
        mt_vec3 nv = madd(madd(mt_v3_scale(v, (mt_real)3 / 4), (mt_real)1 / 8, a[0]),
                          (mt_real)1 / 8, a[n - 1]);
        b[0] = mt_v3_scale(mt_v3_add(v, a[0]), (mt_real)0.5);
        b[n - 1] = mt_v3_scale(mt_v3_add(v, a[n - 1]), (mt_real)0.5);
        for (k = 1; k < n - 1; ++k)
            b[k] = madd(madd(mt_v3_scale(mt_v3_add(v, a[k]), (mt_real)3 / 8), (mt_real)1 / 8,
                             a[k - 1]),
                        (mt_real)1 / 8, a[k + 1]);
        /* about the new vertex and twice as large: the tangents' components
         * (eigenvalue 1/2) keep their size */
        for (k = 0; k < n; ++k) a[k] = mt_v3_scale(mt_v3_sub(b[k], nv), 2);
        v = mt_v3(0, 0, 0);
    }
    T = boundary_across(a, n, v);
    l = mt_v3_len(T);
    return l > 0 && mt_is_finite(l) ? mt_v3_scale(T, l0 / l) : T0;
}

static int limit_normal(sd_mesh *m, int i, mt_vec3 *N)
{
    int n = one_ring(m, i), k;
    mt_vec3 S = mt_v3(0, 0, 0), T = mt_v3(0, 0, 0), P = m->v[i].P, *r = m->ring;
    if (n < 0) return 0;
    if (!m->v[i].boundary) {
        for (k = 0; k < n; ++k) {
            mt_real a = 2 * MT_PI * (mt_real)k / (mt_real)n;
            S = madd(S, mt_cos(a), r[k]);
            T = madd(T, mt_sin(a), r[k]);
        }
    } else {
        S = mt_v3_sub(r[n - 1], r[0]);
        if (n >= 5 && (m->mode & MT_FIX_LOOP_NORMALS)) T = boundary_across_limit(r, n, P, r + n);
        else T = boundary_across(r, n, P);
    }
    *N = mt_v3_cross(S, T);
    return 1;
}

static mt_status build_limit(mt_shape *s, sd_mesh *m, mt_error *err)
{
    mt_vec3 *Pl = mt__malloc((size_t)m->nv * sizeof *Pl);
    mt_vec3 *N = mt__malloc((size_t)m->nv * sizeof *N);
    int *idx = mt__malloc(3 * (size_t)m->nf * sizeof *idx);
    int i, k, ok = Pl && N && idx;
    mt_status st;
    for (i = 0; ok && i < m->nv; ++i) {
        if (m->v[i].start < 0) Pl[i] = m->v[i].P;
        else if (m->v[i].boundary) ok = weight_boundary(m, i, (mt_real)1 / 5, &Pl[i]);
        else ok = weight_one_ring(m, i, loop_gamma(valence(m, i)), &Pl[i]);
    }
    /* pbrt-v2 pushes every vertex to its limit position before it applies
     * the tangent masks, which are meant for the control points (erratum
     * loop-normals); corrected mode applies them first */
    if (!(s->mode & MT_FIX_LOOP_NORMALS))
        for (i = 0; ok && i < m->nv; ++i) m->v[i].P = Pl[i];
    for (i = 0; ok && i < m->nv; ++i) {
        if (m->v[i].start < 0) N[i] = mt_v3(0, 0, 0);
        else ok = limit_normal(m, i, &N[i]);
    }
    for (i = 0; ok && i < m->nf; ++i)
        for (k = 0; k < 3; ++k) idx[3 * i + k] = m->f[i].v[k];
    if (ok) st = mt__mesh_init(s, m->nf, idx, m->nv, Pl, N, NULL, NULL, err);
    else st = mt_error_set(err, MT_ERR_NOMEM, "out of memory for the limit surface");
    mt__free(Pl);
    mt__free(N);
    mt__free(idx);
    return st;
}

/* The most triangles a subdivision may make, 4,194,304: under half a
 * gigabyte of vertex and face records while refining (pbrt-v2's scenes
 * subdivide a few thousand triangles 3 times),
 * checked before anything is allocated so that a parameter cannot make the
 * loader ask for more. The fuzzing build (make fuzz) sets a lower limit: a
 * few bytes of nlevels otherwise make inputs of seconds under the
 * sanitizers, which run the same code as a level or two less. */
#ifndef MT_LOOPSUBDIV_MAX_TRIANGLES
#define MT_LOOPSUBDIV_MAX_TRIANGLES (1 << 22)
#endif

mt_status mt__loopsubdiv_init(mt_shape *s, const mt_paramset *ps, mt_error *err)
{
    const int *vi;
    const double *P;
    const char *scheme;
    int nlevels, nvi, npi, level;
    long long faces;
    sd_mesh m;
    mt_status st;
    s->kind = MT_SHAPE_TRIANGLES;
    if ((st = mt_params_int(ps, "nlevels", 3, &nlevels, err)) != MT_OK ||
        (st = mt_params_ints(ps, "indices", &vi, &nvi, err)) != MT_OK ||
        (st = mt_params_points(ps, "P", &P, &npi, err)) != MT_OK ||
        (st = mt_params_string(ps, "scheme", "loop", &scheme, err)) != MT_OK)
        return st;
    if (!vi || !P) {
        const char *miss = !vi ? "indices" : "P";
        return mt_error_param(err, MT_ERR_INVALID, miss, "loopsubdiv needs \"%s\"", miss);
    }
    if (nvi % 3 != 0 || nvi == 0) {
        mt__locate_param(err, ps, "indices");
        return mt_error_param(err, MT_ERR_INVALID, "indices",
                              "%d indices is not a whole, non-zero number of triangles", nvi);
    }
    if (nlevels < 0) {
        mt__locate_param(err, ps, "nlevels");
        return mt_error_param(err, MT_ERR_INVALID, "nlevels", "nlevels %d is negative", nlevels);
    }
    for (faces = nvi / 3, level = 0; level < nlevels; ++level) {
        faces *= 4;
        if (faces > MT_LOOPSUBDIV_MAX_TRIANGLES) {
            mt__locate_param(err, ps, "nlevels");
            return mt_error_param(err, MT_ERR_LIMIT, "nlevels",
                                  "%d levels of %d triangles make more than %d triangles "
                                  "(materia's limit for a subdivision surface)",
                                  nlevels, nvi / 3, MT_LOOPSUBDIV_MAX_TRIANGLES);
        }
    }
    memset(&m, 0, sizeof m);
    m.mode = s->mode;
    st = control_mesh(&m, nvi / 3, vi, npi, P, err);
    for (level = 0; st == MT_OK && level < nlevels; ++level) st = refine(&m, err);
    if (st == MT_OK) st = build_limit(s, &m, err);
    if (st != MT_OK) mt__locate_param(err, ps, "indices");
    mt__free(m.v);
    mt__free(m.f);
    mt__free(m.ring);
    return st;
}
