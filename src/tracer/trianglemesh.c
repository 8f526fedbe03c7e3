/*
 * pbrt-v2's triangle mesh (shapes/trianglemesh.cpp): "indices", "P", and
 * optionally "N", "S", "uv" (or "st"), "discarddegenerateUVs".
 *
 * As in pbrt-v2 the vertices are transformed to world space once; N and S
 * stay in object space and are transformed when the shading geometry is
 * computed. dpdu and dpdv come from the uvs (default (0,0), (1,0), (1,1)).
 *
 * Erratum triangle-facing (MT_FIX_TRIANGLE_FACING): pbrt-v2 has no single
 * rule for the side a triangle faces. The normal of a hit follows dpdu x
 * dpdv, so it turns over with a mirrored uv map, and when the uv triangle
 * is degenerate pbrt-v2 takes a frame about Normalize(Cross(e2, e1)) -- the
 * opposite of the winding's normal; Sample() takes the winding's normal
 * negated under ReverseOrientation only, not under a mirroring transform
 * as a hit's is; and with "S" but no "N" the shading normal starts from the
 * hit's normal, already flipped, and is flipped again. pbrt-v2 mode keeps
 * all four; corrected mode has pbrt-v3's rule (Triangle::Intersect, and
 * pbrt-v4's Triangle::Sample): the winding's normal, negated under
 * ReverseOrientation xor a handedness change, for hits and samples alike,
 * and a shading normal from S alone that keeps the hit's side.
 *
 * Erratum normal-derivatives (MT_FIX_NORMAL_DERIVATIVES), shading part:
 * pbrt-v2's dndu, dndv are the derivatives of the interpolated vertex
 * normal before it is normalized, carried to world space as normals;
 * corrected mode gives the derivatives of the unit shading normal itself.
 */
#include <string.h>
#include "core/alloc.h"
#include "materia/frame.h"
#include "materia/sampling.h"
#include "params/report.h"
#include "tracer/shape_impl.h"

void mt__triangle_uvs(const mt_shape *s, uint32_t prim, mt_real uv[3][2])
{
    const int *v = s->indices + 3 * (size_t)prim;
    int i;
    if (s->uv) {
        for (i = 0; i < 3; ++i) {
            uv[i][0] = s->uv[2 * v[i]];
            uv[i][1] = s->uv[2 * v[i] + 1];
        }
    } else {
        uv[0][0] = 0;
        uv[0][1] = 0;
        uv[1][0] = 1;
        uv[1][1] = 0;
        uv[2][0] = 1;
        uv[2][1] = 1;
    }
}

mt_status mt__mesh_init(mt_shape *s, int ntris, const int *indices, int nverts, const mt_vec3 *P,
                        const mt_vec3 *N, const mt_vec3 *S, const mt_real *uv, mt_error *err)
{
    int i;
    s->kind = MT_SHAPE_TRIANGLES;
    if (ntris <= 0 || nverts <= 0)
        return mt_error_param(err, MT_ERR_INVALID, "indices", "triangle mesh has no triangles");
    for (i = 0; i < 3 * ntris; ++i)
        if (indices[i] < 0 || indices[i] >= nverts)
            return mt_error_param(err, MT_ERR_INVALID, "indices",
                                  "trianglemesh has out-of-bounds vertex index %d (%d \"P\" "
                                  "values were given)", indices[i], nverts);
    s->ntris = (uint32_t)ntris;
    s->nverts = (uint32_t)nverts;
    s->indices = mt__malloc(3 * (size_t)ntris * sizeof *s->indices);
    s->P = mt__malloc((size_t)nverts * sizeof *s->P);
    if (N) s->N = mt__malloc((size_t)nverts * sizeof *s->N);
    if (S) s->S = mt__malloc((size_t)nverts * sizeof *s->S);
    if (uv) s->uv = mt__malloc(2 * (size_t)nverts * sizeof *s->uv);
    if (!s->indices || !s->P || (N && !s->N) || (S && !s->S) || (uv && !s->uv))
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for a %d-triangle mesh", ntris);
    memcpy(s->indices, indices, 3 * (size_t)ntris * sizeof *s->indices);
    for (i = 0; i < nverts; ++i) s->P[i] = mt_transform_point(&s->o2w, P[i]);
    if (N) memcpy(s->N, N, (size_t)nverts * sizeof *s->N);
    if (S) memcpy(s->S, S, (size_t)nverts * sizeof *s->S);
    if (uv) memcpy(s->uv, uv, 2 * (size_t)nverts * sizeof *s->uv);
    return mt__triangle_frames_init(s, err);
}

/* ---- creation from a parameter list (pbrt-v2 CreateTriangleMeshShape) ---------- */

typedef struct mesh_args {
    const int *vi;
    const double *P, *N, *S, *uv;
    int nvi, npi, nni, nsi, nuvi;
    const char *uvname;
} mesh_args;

static mt_status check_alpha(const mt_paramset *ps, mt_error *err)
{
    const mt_param *p = mt_paramset_find(ps, "alpha");
    mt_real a;
    mt_status st;
    if (!p) return MT_OK;
    if (p->type == MT_PARAM_FLOAT) {
        /* pbrt-v2 makes a cut-out only of a float alpha of exactly 0 */
        if ((st = mt_params_float(ps, "alpha", 1, &a, err)) != MT_OK) return st;
        if (a != 0) return MT_OK;
    } else {
        mt_paramset_mark_used(ps, "alpha");
    }
    mt__locate_param(err, ps, "alpha");
    return mt_error_param(err, MT_ERR_UNSUPPORTED, "alpha",
                          "alpha cut-outs of triangle meshes are not supported");
}

/* pbrt-v2 discards every uv when "discarddegenerateUVs" is set, N is given,
 * and a triangle of non-negligible area has two vertices with equal uvs. */
static int uvs_degenerate(const mesh_args *a)
{
    int i, k;
    for (i = 0; i + 2 < a->nvi; i += 3) {
        const int *vp = a->vi + i;
        mt_vec3 p[3], c;
        for (k = 0; k < 3; ++k)
            p[k] = mt_v3((mt_real)a->P[3 * vp[k]], (mt_real)a->P[3 * vp[k] + 1],
                         (mt_real)a->P[3 * vp[k] + 2]);
        c = mt_v3_cross(mt_v3_sub(p[0], p[1]), mt_v3_sub(p[2], p[1]));
        if ((mt_real)0.5 * mt_v3_len(c) < (mt_real)1e-7) continue;
        for (k = 0; k < 3; ++k) {
            int j = vp[k], l = vp[(k + 1) % 3];
            if (a->uv[2 * j] == a->uv[2 * l] && a->uv[2 * j + 1] == a->uv[2 * l + 1]) return 1;
        }
    }
    return 0;
}

static mt_status read_mesh_args(const mt_paramset *ps, const mt_shape_options *opt,
                                mesh_args *a, mt_error *err)
{
    mt_status st;
    int discard = 0;
    memset(a, 0, sizeof *a);
    if ((st = mt_params_ints(ps, "indices", &a->vi, &a->nvi, err)) != MT_OK ||
        (st = mt_params_points(ps, "P", &a->P, &a->npi, err)) != MT_OK)
        return st;
    a->uvname = "uv";
    if (mt_paramset_find(ps, "uv") || !mt_paramset_find(ps, "st")) {
        if ((st = mt_params_floats(ps, "uv", &a->uv, &a->nuvi, err)) != MT_OK) return st;
    } else {
        a->uvname = "st";
        if ((st = mt_params_floats(ps, "st", &a->uv, &a->nuvi, err)) != MT_OK) return st;
    }
    if ((st = mt_params_bool(ps, "discarddegenerateUVs", 0, &discard, err)) != MT_OK ||
        (st = mt_params_vectors(ps, "S", &a->S, &a->nsi, err)) != MT_OK ||
        (st = mt_params_normals(ps, "N", &a->N, &a->nni, err)) != MT_OK ||
        (st = check_alpha(ps, err)) != MT_OK)
        return st;
    if (!a->vi || !a->P) {
        const char *miss = !a->vi ? "indices" : "P";
        return mt_error_param(err, MT_ERR_INVALID, miss, "trianglemesh needs \"%s\"", miss);
    }
    if (a->nvi % 3 != 0) {
        mt__locate_param(err, ps, "indices");
        return mt_error_param(err, MT_ERR_INVALID, "indices",
                              "%d indices is not a whole number of triangles", a->nvi);
    }
    if (a->uv && a->nuvi < 2 * a->npi) {
        mt__locate_param(err, ps, a->uvname);
        return mt_error_param(err, MT_ERR_INVALID, a->uvname,
                              "not enough \"%s\"s for triangle mesh: expected %d, found %d",
                              a->uvname, 2 * a->npi, a->nuvi);
    }
    if (a->uv && a->nuvi > 2 * a->npi) {
        const mt_param *p = mt_paramset_find(ps, a->uvname);
        mt__warnf(opt->warn, opt->warn_ctx, p->file, p->line,
                  "more \"%s\"s provided than will be used for triangle mesh (%d expected, %d "
                  "found)", a->uvname, 2 * a->npi, a->nuvi);
    }
    if (a->S && a->nsi != a->npi) {
        mt__locate_param(err, ps, "S");
        return mt_error_param(err, MT_ERR_INVALID, "S",
                              "number of \"S\"s (%d) for triangle mesh must match \"P\"s (%d)",
                              a->nsi, a->npi);
    }
    if (a->N && a->nni != a->npi) {
        mt__locate_param(err, ps, "N");
        return mt_error_param(err, MT_ERR_INVALID, "N",
                              "number of \"N\"s (%d) for triangle mesh must match \"P\"s (%d)",
                              a->nni, a->npi);
    }
    {
        int i;
        for (i = 0; i < a->nvi; ++i)
            if (a->vi[i] < 0 || a->vi[i] >= a->npi) {
                mt__locate_param(err, ps, "indices");
                return mt_error_param(err, MT_ERR_INVALID, "indices",
                                      "trianglemesh has out-of-bounds vertex index %d (%d \"P\" "
                                      "values were given)", a->vi[i], a->npi);
            }
    }
    if (discard && a->uv && a->N && uvs_degenerate(a)) {
        const mt_param *p = mt_paramset_find(ps, a->uvname);
        mt__warnf(opt->warn, opt->warn_ctx, p->file, p->line,
                  "degenerate uv coordinates in triangle mesh: discarding all uvs");
        a->uv = NULL;
    }
    return MT_OK;
}

static mt_vec3 *vec3s(const double *v, int n)
{
    mt_vec3 *out;
    int i;
    if (!v) return NULL;
    out = mt__malloc((size_t)n * sizeof *out);
    if (out)
        for (i = 0; i < n; ++i)
            out[i] = mt_v3((mt_real)v[3 * i], (mt_real)v[3 * i + 1], (mt_real)v[3 * i + 2]);
    return out;
}

mt_status mt__trianglemesh_init(mt_shape *s, const mt_paramset *ps, const mt_shape_options *opt,
                                mt_error *err)
{
    mesh_args a;
    mt_vec3 *P = NULL, *N = NULL, *S = NULL;
    mt_real *uv = NULL;
    mt_status st;
    int i;
    s->kind = MT_SHAPE_TRIANGLES;
    if ((st = read_mesh_args(ps, opt, &a, err)) != MT_OK) return st;
    P = vec3s(a.P, a.npi);
    N = vec3s(a.N, a.npi);
    S = vec3s(a.S, a.npi);
    if (a.uv) uv = mt__malloc(2 * (size_t)a.npi * sizeof *uv);
    if (!P || (a.N && !N) || (a.S && !S) || (a.uv && !uv)) {
        st = mt_error_set(err, MT_ERR_NOMEM, "out of memory reading a triangle mesh");
    } else {
        for (i = 0; uv && i < 2 * a.npi; ++i) uv[i] = (mt_real)a.uv[i];
        st = mt__mesh_init(s, a.nvi / 3, a.vi, a.npi, P, N, S, uv, err);
        if (st != MT_OK) mt__locate_param(err, ps, "indices");
    }
    mt__free(P);
    mt__free(N);
    mt__free(S);
    mt__free(uv);
    return st;
}

/* ---- differential geometry ------------------------------------------------------ */

/* Normalized in double (no underflow for tiny triangles); 0 when zero. */
static int unit_d(mt_vec3 v, double out[3])
{
    double x = v.x, y = v.y, z = v.z, m = fmax(fabs(x), fmax(fabs(y), fabs(z))), l;
    if (!(m > 0) || !isfinite(m)) return 0;
    x /= m;
    y /= m;
    z /= m;
    l = sqrt(x * x + y * y + z * z);
    out[0] = x / l;
    out[1] = y / l;
    out[2] = z / l;
    return 1;
}

/* What a hit's DifferentialGeometry takes from its triangle alone: dpdu,
 * dpdv and the normal n (flipped as the shape says). */
static void triangle_frame(const mt_shape *s, uint32_t prim, mt_vec3 frame[3])
{
    const int *v = s->indices + 3 * (size_t)prim;
    mt_vec3 p0 = s->P[v[0]], p1 = s->P[v[1]], p2 = s->P[v[2]];
    mt_vec3 dp1 = mt_v3_sub(p0, p2), dp2 = mt_v3_sub(p1, p2), e1, e2;
    mt_real uv[3][2], du1, du2, dv1, dv2, det;
    double n[3];
    int i;

    mt__triangle_uvs(s, prim, uv);
    du1 = uv[0][0] - uv[2][0];
    du2 = uv[1][0] - uv[2][0];
    dv1 = uv[0][1] - uv[2][1];
    dv2 = uv[1][1] - uv[2][1];
    det = du1 * dv2 - dv1 * du2;
    e1 = mt_v3_sub(p1, p0);
    e2 = mt_v3_sub(p2, p0);
    if (det == 0) {
        /* pbrt-v2: CoordinateSystem(Normalize(Cross(e2, e1)), &dpdu, &dpdv);
         * corrected, about the winding's normal, so that dpdu x dpdv agrees
         * with the normal */
        double w[3];
        int facing = (s->mode & MT_FIX_TRIANGLE_FACING) != 0;
        if (!unit_d(facing ? mt_v3_cross(e1, e2) : mt_v3_cross(e2, e1), w)) w[0] = w[1] = 0, w[2] = 1;
        mt_coordinate_system(mt_v3((mt_real)w[0], (mt_real)w[1], (mt_real)w[2]), &frame[0],
                             &frame[1]);
    } else {
        mt_real inv = 1 / det;
        frame[0] = mt_v3_scale(mt_v3_sub(mt_v3_scale(dp1, dv2), mt_v3_scale(dp2, dv1)), inv);
        frame[1] = mt_v3_scale(mt_v3_add(mt_v3_scale(dp1, -du2), mt_v3_scale(dp2, du1)), inv);
    }
    /* pbrt-v2: nn = Normalize(Cross(dpdu, dpdv)), flipped; where that
     * underflows or overflows, the winding normal with the uv map's sign.
     * Corrected: the winding's normal whatever the uvs (pbrt-v3). */
    if (s->mode & MT_FIX_TRIANGLE_FACING) {
        if (!unit_d(mt_v3_cross(e1, e2), n)) n[0] = n[1] = 0, n[2] = 1;
    } else if (!unit_d(mt_v3_cross(frame[0], frame[1]), n)) {
        if (!unit_d(mt_v3_cross(e1, e2), n)) n[0] = n[1] = 0, n[2] = 1;
        if (det < 0)
            for (i = 0; i < 3; ++i) n[i] = -n[i];
    }
    if (s->flip)
        for (i = 0; i < 3; ++i) n[i] = -n[i];
    frame[2] = mt_v3((mt_real)n[0], (mt_real)n[1], (mt_real)n[2]);
}

/* The triangle's frame: kept for a small mesh, else computed into `computed`. */
static const mt_vec3 *frame_of(const mt_shape *s, uint32_t prim, mt_vec3 computed[3])
{
    if (s->tri_frames) return s->tri_frames + 3 * (size_t)prim;
    triangle_frame(s, prim, computed);
    return computed;
}

mt_vec3 mt__triangle_normal(const mt_shape *s, uint32_t prim)
{
    mt_vec3 computed[3];
    return frame_of(s, prim, computed)[2];
}

mt_status mt__triangle_frames_init(mt_shape *s, mt_error *err)
{
    uint32_t i;
    if (s->ntris > MT__TRI_FRAMES_MAX) return MT_OK;
    s->tri_frames = mt__malloc(3 * (size_t)s->ntris * sizeof *s->tri_frames);
    if (!s->tri_frames)
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for a %u-triangle mesh", (unsigned)s->ntris);
    for (i = 0; i < s->ntris; ++i) triangle_frame(s, i, s->tri_frames + 3 * (size_t)i);
    return MT_OK;
}

void mt__triangle_surface(const mt_shape *s, uint32_t prim, mt_real b1, mt_real b2, mt_real t,
                          const mt_ray *r, mt_surface *sf)
{
    const int *v = s->indices + 3 * (size_t)prim;
    mt_vec3 p0 = s->P[v[0]], p1 = s->P[v[1]], p2 = s->P[v[2]], computed[3];
    const mt_vec3 *frame = frame_of(s, prim, computed);
    mt_real uv[3][2], b0 = 1 - b1 - b2;
    mt_diffgeom *dg = &sf->dg;

    mt__triangle_uvs(s, prim, uv);
    dg->dpdu = frame[0];
    dg->dpdv = frame[1];
    dg->n = frame[2];
    dg->p = mt_v3(b0 * p0.x + b1 * p1.x + b2 * p2.x, b0 * p0.y + b1 * p1.y + b2 * p2.y,
                  b0 * p0.z + b1 * p1.z + b2 * p2.z);
    /* pbrt-v3 (3.9.4): gamma(7) (|b0 p0| + |b1 p1| + |b2 p2|) */
    sf->p_error = mt_v3_scale(
        mt_v3(mt_fabs(b0 * p0.x) + mt_fabs(b1 * p1.x) + mt_fabs(b2 * p2.x),
              mt_fabs(b0 * p0.y) + mt_fabs(b1 * p1.y) + mt_fabs(b2 * p2.y),
              mt_fabs(b0 * p0.z) + mt_fabs(b1 * p1.z) + mt_fabs(b2 * p2.z)),
        mt__gamma(7));
    if (r && !(s->mode & MT_FIX_TRIANGLE_HIT_POINT)) {
        /* pbrt-v2 (erratum triangle-hit-point): ray(t), off the plane by the
         * rounding of o + t d; its error bound grows by that distance from
         * the barycentric point, so spawned rays still clear the surface */
        mt_vec3 pr = mt_v3_add(r->o, mt_v3_scale(r->d, t)), off = mt_v3_sub(pr, dg->p);
        sf->p_error = mt_v3_add(sf->p_error, mt_v3(mt_fabs(off.x), mt_fabs(off.y), mt_fabs(off.z)));
        dg->p = pr;
    }
    dg->u = b0 * uv[0][0] + b1 * uv[1][0] + b2 * uv[2][0];
    dg->v = b0 * uv[0][1] + b1 * uv[1][1] + b2 * uv[2][1];
    dg->dndu = dg->dndv = mt_v3(0, 0, 0);
    dg->flip = s->flip;
    sf->ray_epsilon = (mt_real)1e-3 * t;
}

static mt_vec3 interp(const mt_vec3 *a, const int *v, const mt_real b[3])
{
    return mt_v3(b[0] * a[v[0]].x + b[1] * a[v[1]].x + b[2] * a[v[2]].x,
                 b[0] * a[v[0]].y + b[1] * a[v[1]].y + b[2] * a[v[2]].y,
                 b[0] * a[v[0]].z + b[1] * a[v[1]].z + b[2] * a[v[2]].z);
}

/* The derivative of the unit vector w / |w| along a direction in which w
 * changes by dw: (dw - m (m . dw)) / |w| with m = w / |w|. */
static mt_vec3 unit_derivative(mt_vec3 w, mt_vec3 dw)
{
    mt_real len = mt_v3_len(w);
    mt_vec3 m = mt_v3_scale(w, 1 / len);
    return mt_v3_scale(mt_v3_sub(dw, mt_v3_scale(m, mt_v3_dot(m, dw))), 1 / len);
}

void mt__triangle_shading(const mt_surface *sf, mt_diffgeom *sh)
{
    const mt_shape *s = sf->shape;
    const mt_diffgeom *dg = &sf->dg;
    const int *v = s->indices + 3 * (size_t)sf->prim;
    mt_real uv[3][2], b[3];
    mt_vec3 ns, ss, ts, w = mt_v3(0, 0, 0);
    double n[3];
    int i, from_n = 0, fixed = (s->mode & MT_FIX_NORMAL_DERIVATIVES) != 0;
    if (!s->N && !s->S) {
        *sh = *dg;
        return;
    }
    /* barycentrics recovered from (u, v), as pbrt-v2 does (1/3 each when
     * the uv triangle is degenerate) */
    mt__triangle_uvs(s, sf->prim, uv);
    if (mt__solve2x2(uv[1][0] - uv[0][0], uv[2][0] - uv[0][0], uv[1][1] - uv[0][1],
                     uv[2][1] - uv[0][1], dg->u - uv[0][0], dg->v - uv[0][1], &b[1], &b[2]))
        b[0] = 1 - b[1] - b[2];
    else b[0] = b[1] = b[2] = (mt_real)1 / 3;

    ns = dg->n;
    if (s->N) {
        /* a zero interpolated normal (opposed vertex normals) would be NaN in
         * pbrt-v2: the geometric normal stands in */
        w = mt_transform_normal(&s->o2w, interp(s->N, v, b));
        if (mt_v3_len2(w) > 0 && mt_v3_is_finite(w)) {
            ns = mt_v3_normalize(w);
            from_n = 1;
        }
    }
    ss = dg->dpdu;
    if (s->S) ss = mt_transform_vector(&s->o2w, interp(s->S, v, b));
    ss = mt_v3_len2(ss) > 0 && mt_v3_is_finite(ss) ? mt_v3_normalize(ss) : mt_v3(0, 0, 0);
    ts = mt_v3_cross(ss, ns);
    if (mt_v3_len2(ts) > 0) {
        ts = mt_v3_normalize(ts);
        ss = mt_v3_cross(ts, ns);
    } else {
        mt_coordinate_system(ns, &ss, &ts);
    }
    *sh = *dg;
    sh->dpdu = ss;
    sh->dpdv = ts;
    sh->dndu = sh->dndv = mt_v3(0, 0, 0);
    if (s->N) {
        mt_real du1 = uv[0][0] - uv[2][0], du2 = uv[1][0] - uv[2][0];
        mt_real dv1 = uv[0][1] - uv[2][1], dv2 = uv[1][1] - uv[2][1];
        mt_real det = du1 * dv2 - dv1 * du2;
        mt_vec3 dn1 = mt_v3_sub(s->N[v[0]], s->N[v[2]]), dn2 = mt_v3_sub(s->N[v[1]], s->N[v[2]]);
        if (det != 0) {
            mt_real inv = 1 / det;
            mt_vec3 du = mt_transform_normal(
                &s->o2w, mt_v3_scale(mt_v3_sub(mt_v3_scale(dn1, dv2), mt_v3_scale(dn2, dv1)), inv));
            mt_vec3 dv = mt_transform_normal(
                &s->o2w, mt_v3_scale(mt_v3_add(mt_v3_scale(dn1, -du2), mt_v3_scale(dn2, du1)), inv));
            if (fixed && from_n) {
                /* the derivatives of the shading normal, +-w / |w| */
                mt_real sign = s->flip ? -1 : 1;
                du = mt_v3_scale(unit_derivative(w, du), sign);
                dv = mt_v3_scale(unit_derivative(w, dv), sign);
            }
            sh->dndu = du;
            sh->dndv = dv;
        }
    }
    /* DifferentialGeometry(p, ss, ts, ...): nn = Normalize(Cross(ss, ts)),
     * flipped -- a second time when ns was the hit's normal (corrected:
     * once) */
    if (!unit_d(mt_v3_cross(ss, ts), n)) n[0] = ns.x, n[1] = ns.y, n[2] = ns.z;
    if (s->flip && (from_n || !(s->mode & MT_FIX_TRIANGLE_FACING)))
        for (i = 0; i < 3; ++i) n[i] = -n[i];
    sh->n = mt_v3((mt_real)n[0], (mt_real)n[1], (mt_real)n[2]);
}

/* ---- area and sampling ------------------------------------------------------------ */

mt_real mt__triangle_area(const mt_shape *s, uint32_t prim)
{
    const int *v = s->indices + 3 * (size_t)prim;
    mt_vec3 p1 = s->P[v[0]], p2 = s->P[v[1]], p3 = s->P[v[2]];
    return (mt_real)0.5 * mt_v3_len(mt_v3_cross(mt_v3_sub(p2, p1), mt_v3_sub(p3, p1)));
}

mt_vec3 mt__triangle_sample(const mt_shape *s, uint32_t prim, mt_real u1, mt_real u2,
                            mt_vec3 *ns)
{
    const int *v = s->indices + 3 * (size_t)prim;
    mt_vec3 p1 = s->P[v[0]], p2 = s->P[v[1]], p3 = s->P[v[2]];
    mt_real b1, b2, b3;
    double n[3];
    mt_uniform_sample_triangle(u1, u2, &b1, &b2);
    b3 = 1 - b1 - b2;
    /* pbrt-v2 Triangle::Sample: the winding normal, negated under
     * ReverseOrientation only (not under a mirroring transform, unlike the
     * normal of an intersection); corrected (triangle-facing), negated as a
     * hit's is */
    if (!unit_d(mt_v3_cross(mt_v3_sub(p2, p1), mt_v3_sub(p3, p1)), n)) n[0] = n[1] = 0, n[2] = 1;
    *ns = mt_v3((mt_real)n[0], (mt_real)n[1], (mt_real)n[2]);
    if ((s->mode & MT_FIX_TRIANGLE_FACING) ? s->flip : s->reverse_orientation) *ns = mt_v3_neg(*ns);
    return mt_v3(b1 * p1.x + b2 * p2.x + b3 * p3.x, b1 * p1.y + b2 * p2.y + b3 * p3.y,
                 b1 * p1.z + b2 * p2.z + b3 * p3.z);
}
