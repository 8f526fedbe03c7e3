/*
 * Shapes: creation by pbrt-v2 type name, the per-kind dispatch, and the
 * helpers the quadrics share (object-space rays in double precision, the
 * Weingarten equations, world-space DifferentialGeometry with error bounds).
 */
#include <string.h>
#include "core/alloc.h"
#include "params/report.h"
#include "tracer/triangle.h"

/* pbrt-v2 api.cpp MakeShape knows these; materia implements the first five. */
static const char *const unsupported_types[] = {"cone", "paraboloid", "hyperboloid",
                                                "heightfield", "nurbs", "plymesh", NULL};

void mt__locate_param(mt_error *err, const mt_paramset *ps, const char *name)
{
    const mt_param *p = mt_paramset_find(ps, name);
    if (err && p && p->file) mt_error_locate(err, p->file, p->line, p->column);
}

/* The scale of a similarity L = k Q (Q orthogonal): L^T L = k^2 I within a
 * relative 1e-5 (the rounding of the float parameters of Rotate and
 * LookAt); 0 otherwise. */
static double similarity_scale(const mt_transform *t)
{
    const double(*m)[4] = t->m.m;
    double g[3][3], k2;
    int i, j, l;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j)
            for (g[i][j] = 0, l = 0; l < 3; ++l) g[i][j] += m[l][i] * m[l][j];
    k2 = (g[0][0] + g[1][1] + g[2][2]) / 3;
    if (!(k2 > 0) || !isfinite(k2)) return 0;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j)
            if (fabs(g[i][j] - (i == j ? k2 : 0)) > 1e-5 * k2) return 0;
    return sqrt(k2);
}

/* Whether m is a translation: identity linear part, last row (0, 0, 0, 1). */
static int is_translation(const mt_matrix4 *m)
{
    int i, j;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 3; ++j)
            if (m->m[i][j] != (i == j ? 1 : 0)) return 0;
    return m->m[3][3] == 1;
}

static mt_shape *shape_new(const mt_transform *o2w, int ro, const mt_shape_options *opt)
{
    mt_shape *s = mt__calloc(1, sizeof *s);
    if (!s) return NULL;
    s->mode = opt ? opt->mode : MT_MODE_PBRT_V2;
    s->o2w = *o2w;
    s->w2o = mt_transform_inverse(o2w);
    s->reverse_orientation = ro != 0;
    s->swaps_handedness = mt_transform_swaps_handedness(o2w);
    s->flip = s->reverse_orientation ^ s->swaps_handedness;
    s->sim_scale = similarity_scale(o2w);
    s->w2o_translation = is_translation(&s->w2o.m);
    return s;
}

mt_shape *mt_shape_create(const char *type, const mt_paramset *ps, const mt_transform *o2w,
                          int reverse_orientation, const mt_shape_options *opt, mt_error *err)
{
    static const mt_shape_options none = {NULL, NULL, MT_MODE_PBRT_V2};
    mt_shape *s;
    mt_status st;
    int i;
    if (!opt) opt = &none;
    for (i = 0; unsupported_types[i]; ++i)
        if (strcmp(type, unsupported_types[i]) == 0) {
            mt_error_set(err, MT_ERR_UNSUPPORTED,
                         "shape \"%s\" is not supported (materia implements sphere, disk, "
                         "cylinder, trianglemesh and loopsubdiv)", type);
            return NULL;
        }
    s = shape_new(o2w, reverse_orientation, opt);
    if (!s) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory creating shape \"%s\"", type);
        return NULL;
    }
    if (strcmp(type, "sphere") == 0) st = mt__sphere_init(s, ps, err);
    else if (strcmp(type, "disk") == 0) st = mt__disk_init(s, ps, err);
    else if (strcmp(type, "cylinder") == 0) st = mt__cylinder_init(s, ps, err);
    else if (strcmp(type, "trianglemesh") == 0) st = mt__trianglemesh_init(s, ps, opt, err);
    else if (strcmp(type, "loopsubdiv") == 0) st = mt__loopsubdiv_init(s, ps, err);
    else st = mt_error_set(err, MT_ERR_NOT_FOUND, "shape \"%s\" unknown", type);
    if (st == MT_OK) st = mt__shape_areas_init(s, err);
    if (st != MT_OK) {
        mt_shape_destroy(s);
        return NULL;
    }
    return s;
}

mt_shape *mt_shape_from_statement(const mt_statement *st, const mt_transform *o2w,
                                  int reverse_orientation, const mt_shape_options *opt,
                                  mt_error *err)
{
    mt_shape *s;
    if (st->nargs < 1 || !st->args[0].is_string) {
        mt__fail_at(err, MT_ERR_PARSE, st->file, st->line, st->column,
                    "Shape needs a type name");
        return NULL;
    }
    s = mt_shape_create(st->args[0].string, st->params, o2w, reverse_orientation, opt, err);
    if (!s) {
        if (err && !err->file[0]) mt_error_locate(err, st->file, st->line, st->column);
        return NULL;
    }
    if (opt) mt_paramset_report_unused(st->params, opt->warn, opt->warn_ctx);
    return s;
}

mt_shape *mt_shape_create_mesh(const mt_transform *o2w, int reverse_orientation, int ntris,
                               const int *indices, int nverts, const mt_vec3 *P,
                               const mt_vec3 *N, const mt_vec3 *S, const mt_real *uv,
                               const mt_shape_options *opt, mt_error *err)
{
    mt_shape *s = shape_new(o2w, reverse_orientation, opt);
    if (!s) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory creating a triangle mesh");
        return NULL;
    }
    if (mt__mesh_init(s, ntris, indices, nverts, P, N, S, uv, err) != MT_OK ||
        mt__shape_areas_init(s, err) != MT_OK) {
        mt_shape_destroy(s);
        return NULL;
    }
    return s;
}

void mt_shape_destroy(mt_shape *s)
{
    if (!s) return;
    mt__free(s->indices);
    mt__free(s->P);
    mt__free(s->N);
    mt__free(s->S);
    mt__free(s->uv);
    mt__free(s->tri_frames);
    mt__free(s->areas);
    mt__free(s->cdf);
    mt__free(s);
}

mt_shape_kind mt_shape_kind_of(const mt_shape *s) { return s->kind; }
uint32_t mt__shape_nprims(const mt_shape *s) { return s->kind == MT_SHAPE_TRIANGLES ? s->ntris : 1; }
uint32_t mt_shape_prim_count(const mt_shape *s) { return mt__shape_nprims(s); }
int mt_shape_flip(const mt_shape *s) { return s->flip; }
int mt_shape_reverse_orientation(const mt_shape *s) { return s->reverse_orientation; }
mt_mode mt_shape_mode(const mt_shape *s) { return s->mode; }
const mt_transform *mt_shape_object_to_world(const mt_shape *s) { return &s->o2w; }
void mt_shape_set_user(mt_shape *s, void *user) { s->user = user; }
void *mt_shape_user(const mt_shape *s) { return s->user; }

int mt_shape_mesh(const mt_shape *s, mt_mesh_view *out)
{
    if (s->kind != MT_SHAPE_TRIANGLES) return 0;
    out->ntris = s->ntris;
    out->nverts = s->nverts;
    out->indices = s->indices;
    out->P = s->P;
    out->N = s->N;
    out->S = s->S;
    out->uv = s->uv;
    return 1;
}

void mt__quadric_object_bounds(const mt_shape *s, double lo[3], double hi[3])
{
    double r = s->radius;
    lo[0] = lo[1] = -r;
    hi[0] = hi[1] = r;
    lo[2] = s->kind == MT_SHAPE_DISK ? s->height : s->zmin;
    hi[2] = s->kind == MT_SHAPE_DISK ? s->height : s->zmax;
}

/* Rounds a double bound outwards to mt_real. */
static mt_real round_down(double x)
{
    mt_real r = (mt_real)x;
    return (double)r > x ? mt__next_toward(r, -MT_REAL_MAX) : r;
}
static mt_real round_up(double x)
{
    mt_real r = (mt_real)x;
    return (double)r < x ? mt__next_toward(r, MT_REAL_MAX) : r;
}

void mt_shape_prim_bounds(const mt_shape *s, uint32_t prim, mt_vec3 *lo, mt_vec3 *hi)
{
    if (s->kind == MT_SHAPE_TRIANGLES) {
        const int *v = s->indices + 3 * (size_t)prim;
        mt_vec3 a = s->P[v[0]], b = s->P[v[1]], c = s->P[v[2]];
        *lo = mt_v3(mt_min(a.x, mt_min(b.x, c.x)), mt_min(a.y, mt_min(b.y, c.y)),
                    mt_min(a.z, mt_min(b.z, c.z)));
        *hi = mt_v3(mt_max(a.x, mt_max(b.x, c.x)), mt_max(a.y, mt_max(b.y, c.y)),
                    mt_max(a.z, mt_max(b.z, c.z)));
    } else {
        /* pbrt-v2 Shape::WorldBound: the eight corners of the object bounds,
         * transformed (in double) and rounded outwards. */
        double olo[3], ohi[3], wlo[3], whi[3];
        const double(*m)[4] = s->o2w.m.m;
        int c, i;
        mt__quadric_object_bounds(s, olo, ohi);
        for (i = 0; i < 3; ++i) {
            wlo[i] = MT_REAL_MAX;
            whi[i] = -MT_REAL_MAX;
        }
        for (c = 0; c < 8; ++c) {
            double p[3], q[4];
            p[0] = (c & 1) ? ohi[0] : olo[0];
            p[1] = (c & 2) ? ohi[1] : olo[1];
            p[2] = (c & 4) ? ohi[2] : olo[2];
            for (i = 0; i < 4; ++i) q[i] = m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3];
            for (i = 0; i < 3; ++i) {
                double w = q[3] == 1 ? q[i] : q[i] / q[3];
                /* a few double ulps of slack for the product's own rounding */
                double e = mt__gamma_d(4) * (fabs(m[i][0] * p[0]) + fabs(m[i][1] * p[1]) +
                                             fabs(m[i][2] * p[2]) + fabs(m[i][3]) + fabs(w));
                if (w - e < wlo[i]) wlo[i] = w - e;
                if (w + e > whi[i]) whi[i] = w + e;
            }
        }
        *lo = mt_v3(round_down(wlo[0]), round_down(wlo[1]), round_down(wlo[2]));
        *hi = mt_v3(round_up(whi[0]), round_up(whi[1]), round_up(whi[2]));
    }
}

/* ---- intersection dispatch ---------------------------------------------------- */

void mt__ray_to_object(const mt_shape *s, const mt_ray *r, mt__oray *out)
{
    const double(*m)[4] = s->w2o.m.m;
    double o[3], w;
    int i;
    o[0] = r->o.x;
    o[1] = r->o.y;
    o[2] = r->o.z;
    out->tmin = r->tmin;
    out->tmax = r->tmax;
    if (s->w2o_translation) {
        /* The sums below with a translation's ones and zeros: o_i + z1 + z2
         * + t_i and d_i + z1 + z2, z1 and z2 the signed zeros the other
         * (finite) components make. Adding a signed zero to a non-zero value
         * leaves it, so when every component is finite and not zero (q
         * checks both at once) they are exactly o_i + t_i and d_i; a zero
         * component takes the general sums, whose sign they decide. */
        const double d[3] = {r->d.x, r->d.y, r->d.z};
        double q = o[0] * o[1] * o[2] * d[0] * d[1] * d[2];
        if (q != 0 && q - q == 0) {
            for (i = 0; i < 3; ++i) {
                out->o[i] = o[i] + m[i][3];
                out->d[i] = d[i];
            }
            return;
        }
    }
    for (i = 0; i < 3; ++i) {
        out->o[i] = m[i][0] * o[0] + m[i][1] * o[1] + m[i][2] * o[2] + m[i][3];
        out->d[i] = m[i][0] * r->d.x + m[i][1] * r->d.y + m[i][2] * r->d.z;
    }
    w = m[3][0] * o[0] + m[3][1] * o[1] + m[3][2] * o[2] + m[3][3];
    if (w != 1)
        for (i = 0; i < 3; ++i) out->o[i] /= w;
}

static int quadric_hit(const mt_shape *s, const mt_ray *r, mt_real tmax, double *t, double p[3])
{
    mt__oray o;
    mt__ray_to_object(s, r, &o);
    o.tmax = tmax;
    switch (s->kind) {
    case MT_SHAPE_SPHERE: return mt__sphere_hit(s, &o, t, p);
    case MT_SHAPE_DISK: return mt__disk_hit(s, &o, t, p);
    case MT_SHAPE_CYLINDER: return mt__cylinder_hit(s, &o, t, p);
    case MT_SHAPE_TRIANGLES: break;
    }
    return 0;
}

int mt__quadric_intersect_to(const mt_shape *s, const mt_ray *r, mt_real tmax, mt_hit *hit)
{
    double t, p[3];
    if (!quadric_hit(s, r, tmax, &t, p)) return 0;
    if (!hit) return 1;
    hit->t = (mt_real)t;
    hit->pobj[0] = p[0];
    hit->pobj[1] = p[1];
    hit->pobj[2] = p[2];
    hit->b1 = hit->b2 = 0;
    return 1;
}

static void load3(mt_vec3 v, mt_real out[3])
{
    out[0] = v.x;
    out[1] = v.y;
    out[2] = v.z;
}

int mt_shape_intersect(const mt_shape *s, uint32_t prim, const mt_ray *r, mt_hit *hit)
{
    if (s->kind == MT_SHAPE_TRIANGLES) {
        const int *v = s->indices + 3 * (size_t)prim;
        mt__tri_ray tr;
        mt_real a[3][3], t, b1, b2;
        load3(s->P[v[0]], a[0]);
        load3(s->P[v[1]], a[1]);
        load3(s->P[v[2]], a[2]);
        mt__tri_ray_init(&tr, r);
        if (!mt__tri_hit(&tr, a[0], a[1], a[2], 1, r->tmin, r->tmax, &t, &b1, &b2)) return 0;
        hit->t = t;
        hit->b1 = b1;
        hit->b2 = b2;
        hit->pobj[0] = hit->pobj[1] = hit->pobj[2] = 0;
    } else if (!mt__quadric_intersect_to(s, r, r->tmax, hit)) {
        return 0;
    }
    hit->shape = s;
    hit->prim = prim;
    hit->id = prim;
    return 1;
}

int mt_shape_missed(const mt_shape *s, uint32_t prim, const mt_ray *r)
{
    (void)prim;
    return s->kind == MT_SHAPE_SPHERE && mt__sphere_missed(s, r);
}

int mt_shape_occluded(const mt_shape *s, uint32_t prim, const mt_ray *r)
{
    mt_hit hit;
    return mt_shape_intersect(s, prim, r, &hit);
}

static void hit_surface(const mt_hit *hit, const mt_ray *r, int want_uv, mt_surface *sf)
{
    const mt_shape *s = hit->shape;
    memset(sf, 0, sizeof *sf);
    sf->shape = s;
    sf->prim = hit->prim;
    switch (s->kind) {
    case MT_SHAPE_SPHERE: mt__sphere_surface(s, hit->pobj, want_uv, sf); break;
    case MT_SHAPE_DISK: mt__disk_surface(s, hit->pobj, sf); break;
    case MT_SHAPE_CYLINDER: mt__cylinder_surface(s, hit->pobj, sf); break;
    case MT_SHAPE_TRIANGLES: mt__triangle_surface(s, hit->prim, hit->b1, hit->b2, hit->t, r, sf); return;
    }
    /* pbrt-v2 quadrics: rayEpsilon = 5e-4 tHit */
    sf->ray_epsilon = (mt_real)5e-4 * hit->t;
}

void mt_hit_surface(const mt_hit *hit, const mt_ray *r, mt_surface *sf) { hit_surface(hit, r, 1, sf); }
void mt_hit_surface_no_uv(const mt_hit *hit, const mt_ray *r, mt_surface *sf) { hit_surface(hit, r, 0, sf); }

mt_vec3 mt_hit_normal(const mt_hit *hit, const mt_ray *r)
{
    mt_surface sf;
    if (hit->shape->kind == MT_SHAPE_TRIANGLES) return mt__triangle_normal(hit->shape, hit->prim);
    hit_surface(hit, r, 0, &sf);
    return sf.dg.n;
}

int mt_surface_has_shading(const mt_surface *sf)
{
    return sf->shape->kind == MT_SHAPE_TRIANGLES && (sf->shape->N || sf->shape->S);
}

void mt_surface_shading(const mt_surface *sf, mt_diffgeom *shading)
{
    if (sf->shape->kind == MT_SHAPE_TRIANGLES) mt__triangle_shading(sf, shading);
    else *shading = sf->dg;
}

/* ---- helpers shared by the quadrics ------------------------------------------ */

double mt__phi(double x, double y)
{
    double phi = atan2(y, x);
    return phi < 0 ? phi + 2 * 3.14159265358979323846 : phi;
}

int mt__pick_root(const mt_shape *s, const mt__oray *r, double t0, double t1,
                  mt__point_ok_fn point_ok, double *t, double p[3])
{
    if (t0 > r->tmax || t1 < r->tmin) return 0;
    if (t0 >= r->tmin) {
        if (point_ok(s, r, t0, p)) {
            *t = t0;
            return 1;
        }
        if (t1 == t0) return 0;
    }
    if (t1 > r->tmax || !point_ok(s, r, t1, p)) return 0;
    *t = t1;
    return 1;
}

int mt__quadratic(double a, double b, double c, double disc4, double *t0, double *t1)
{
    double q, r;
    if (!(disc4 >= 0) || a == 0) return 0;
    r = sqrt(disc4);
    q = b < 0 ? -b + r : -b - r; /* -(b + sign(b) r): no cancellation */
    if (q == 0) {
        *t0 = *t1 = -b / a;
        return 1;
    }
    *t0 = q / a;
    *t1 = c / q;
    if (*t0 > *t1) {
        double tmp = *t0;
        *t0 = *t1;
        *t1 = tmp;
    }
    return 1;
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

void mt__weingarten(const double dpdu[3], const double dpdv[3], const double d2pduu[3],
                    const double d2pduv[3], const double d2pdvv[3], double dndu[3],
                    double dndv[3])
{
    /* pbrt-v2 sphere.cpp: E, F, G and e, f, g, the coefficients of the first
     * and second fundamental forms; dndu = ((f F - e G) dpdu + (e F - f E) dpdv)
     * / (E G - F^2), dndv likewise with (g F - f G) and (f F - g E). */
    double E = dot3(dpdu, dpdu), F = dot3(dpdu, dpdv), G = dot3(dpdv, dpdv);
    double N[3], len, e, f, g, inv;
    int i;
    cross3(dpdu, dpdv, N);
    len = sqrt(dot3(N, N));
    inv = 1 / (E * G - F * F);
    if (!(len > 0) || !isfinite(inv)) {
        for (i = 0; i < 3; ++i) dndu[i] = dndv[i] = 0;
        return;
    }
    for (i = 0; i < 3; ++i) N[i] /= len;
    e = dot3(N, d2pduu);
    f = dot3(N, d2pduv);
    g = dot3(N, d2pdvv);
    for (i = 0; i < 3; ++i) {
        dndu[i] = (f * F - e * G) * inv * dpdu[i] + (e * F - f * E) * inv * dpdv[i];
        dndv[i] = (g * F - f * G) * inv * dpdu[i] + (f * F - g * E) * inv * dpdv[i];
    }
}

static void xf_vector(const double m[4][4], const double v[3], double out[3])
{
    int i;
    for (i = 0; i < 3; ++i) out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}
/* Normals by the inverse transpose (minv read by columns). */
static void xf_normal(const double minv[4][4], const double n[3], double out[3])
{
    int i;
    for (i = 0; i < 3; ++i) out[i] = minv[0][i] * n[0] + minv[1][i] * n[1] + minv[2][i] * n[2];
}
double mt__area_scale(const mt_shape *s, const double n[3])
{
    const double(*m)[4] = s->o2w.m.m;
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    double w[3];
    xf_normal(s->o2w.minv.m, n, w);
    return fabs(det) * sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
}

static mt_vec3 to_vec(const double v[3]) { return mt_v3((mt_real)v[0], (mt_real)v[1], (mt_real)v[2]); }

/* Erratum normal-derivatives: the derivatives of the world normal dg.n
 * from the object-space derivatives dndu, dndv of the unit normal N. With
 * L the linear part of o2w, dg.n = sigma A N / |A N| for A = L^-T and sigma
 * = -1 under ReverseOrientation (the handedness flip cancels the sign of
 * det L in Cross(L dpdu, L dpdv) = det L A (dpdu x dpdv)), so
 * d(dg.n) = sigma (I - n n^T) A dN / |A N|. pbrt-v2 keeps A dN: half the
 * true value under Scale 2, and the wrong sign under ReverseOrientation. */
static void world_normal_derivatives(const mt_shape *s, const double dpdu[3],
                                     const double dpdv[3], const double dndu[3],
                                     const double dndv[3], const double nfallback[3],
                                     mt_diffgeom *dg)
{
    const double(*mi)[4] = s->o2w.minv.m;
    double N[3], a[3], la, b[3], c[3], k;
    int i;
    cross3(dpdu, dpdv, N);
    if (!(dot3(N, N) > 0) || !isfinite(dot3(N, N)))
        for (i = 0; i < 3; ++i) N[i] = nfallback[i];
    la = sqrt(dot3(N, N));
    for (i = 0; i < 3; ++i) N[i] /= la;
    xf_normal(mi, N, a);
    la = sqrt(dot3(a, a));
    for (i = 0; i < 3; ++i) a[i] /= la;
    k = (s->reverse_orientation ? -1 : 1) / la;
    xf_normal(mi, dndu, b);
    xf_normal(mi, dndv, c);
    {
        double ab = dot3(a, b), ac = dot3(a, c);
        for (i = 0; i < 3; ++i) {
            b[i] = (b[i] - a[i] * ab) * k;
            c[i] = (c[i] - a[i] * ac) * k;
        }
    }
    dg->dndu = to_vec(b);
    dg->dndv = to_vec(c);
}

void mt__surface_from_object(const mt_shape *s, const double p[3], const double perr[3],
                             const double dpdu[3], const double dpdv[3], const double dndu[3],
                             const double dndv[3], const double nfallback[3], mt_real u,
                             mt_real v, mt_surface *sf)
{
    const double(*m)[4] = s->o2w.m.m;
    const double(*mi)[4] = s->o2w.minv.m;
    double wp[3], w, wdu[3], wdv[3], wn[3], len, tmp[3];
    int i;
    mt_diffgeom *dg = &sf->dg;

    for (i = 0; i < 3; ++i) {
        double sum_abs = fabs(m[i][0] * p[0]) + fabs(m[i][1] * p[1]) + fabs(m[i][2] * p[2]) +
                         fabs(m[i][3]);
        wp[i] = m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3];
        /* pbrt-v3 Transform::operator()(Point3f, Vector3f) error propagation,
         * in double, plus the final rounding to mt_real (half an ulp). */
        tmp[i] = mt__gamma_d(3) * sum_abs +
                 (1 + mt__gamma_d(3)) * (fabs(m[i][0]) * perr[0] + fabs(m[i][1]) * perr[1] +
                                         fabs(m[i][2]) * perr[2]);
    }
    w = m[3][0] * p[0] + m[3][1] * p[1] + m[3][2] * p[2] + m[3][3];
    if (w != 1)
        for (i = 0; i < 3; ++i) {
            wp[i] /= w;
            tmp[i] = tmp[i] / fabs(w) * (1 + mt__gamma_d(2)) + mt__gamma_d(2) * fabs(wp[i]);
        }
    dg->p = to_vec(wp);
    sf->p_error = mt_v3((mt_real)(tmp[0] + MT_REAL_EPSILON * fabs(wp[0])),
                        (mt_real)(tmp[1] + MT_REAL_EPSILON * fabs(wp[1])),
                        (mt_real)(tmp[2] + MT_REAL_EPSILON * fabs(wp[2])));

    xf_vector(m, dpdu, wdu);
    xf_vector(m, dpdv, wdv);
    dg->dpdu = to_vec(wdu);
    dg->dpdv = to_vec(wdv);
    if (s->mode & MT_FIX_NORMAL_DERIVATIVES) {
        world_normal_derivatives(s, dpdu, dpdv, dndu, dndv, nfallback, dg);
    } else {
        /* pbrt-v2: o2w(dndu) with dndu a Normal (the inverse transpose) */
        xf_normal(mi, dndu, tmp);
        dg->dndu = to_vec(tmp);
        xf_normal(mi, dndv, tmp);
        dg->dndv = to_vec(tmp);
    }

    /* pbrt-v2 DifferentialGeometry: nn = Normalize(Cross(dpdu, dpdv)), negated
     * when ReverseOrientation ^ TransformSwapsHandedness. */
    cross3(wdu, wdv, wn);
    len = sqrt(dot3(wn, wn));
    if (!(len > 0) || !isfinite(len)) {
        /* degenerate parameterisation (a pole or centre): the surface normal,
         * which cross(dpdu, dpdv) would give in the limit */
        xf_normal(mi, nfallback, wn);
        if (s->swaps_handedness)
            for (i = 0; i < 3; ++i) wn[i] = -wn[i];
        len = sqrt(dot3(wn, wn));
    }
    for (i = 0; i < 3; ++i) wn[i] /= len;
    if (s->flip)
        for (i = 0; i < 3; ++i) wn[i] = -wn[i];
    dg->n = to_vec(wn);
    dg->u = u;
    dg->v = v;
    dg->flip = s->flip;
}
