/*
 * pbrt-v2's sphere (shapes/sphere.cpp): radius, zmin, zmax, phimax;
 * u = phi / phimax, v = (theta - thetamin) / (thetamax - thetamin) with
 * theta measured from +z, so v runs from zmin (v = 0) to zmax (v = 1).
 *
 * The intersection is solved in double precision in object space, with the
 * discriminant in the cancellation-free form r^2 |d|^2 - |o x d|^2 and the
 * hit point reprojected onto the sphere (pbrt-v3 3.9.4); its error bound is
 * gamma(5) |p| (in double).
 *
 * Sampling is pbrt-v2's in pbrt-v2 mode, its limits included; corrected
 * mode fixes two errata (neither is fixed in pbrt-v3):
 * - partial-sampling (MT_FIX_PARTIAL_SAMPLING): Sample(u1, u2) covers the
 *   whole sphere whatever zmin, zmax, phimax are, while Area() and Pdf()
 *   describe the clipped sphere; corrected: uniform in area on the clipped
 *   sphere, and a cone direction that misses it gives no sample (a zero
 *   normal, so no emission, and pdf 0) where pbrt-v2 takes the ray's point
 *   of closest approach to the centre.
 * - quadric-scale (MT_FIX_QUADRIC_SCALE): the cone sampled from outside has
 *   the object-space radius about the world-space centre (under Scale 2 the
 *   cone of a sphere half the size); corrected: the world radius, and area
 *   sampling where the transform is not a similarity (an ellipsoid has no
 *   cone to sample).
 */
#include "materia/frame.h"
#include "materia/sampling.h"
#include "tracer/shape_impl.h"

/* The ball mt__sphere_missed tests: under an affine o2w whose linear part L
 * is a similarity (within the 1e-5 that sim_scale allows), the world centre
 * and r^2 times a bound of the largest eigenvalue of L^T L (Gershgorin's:
 * its largest absolute row sum), padded and rounded up. */
static void ball_init(mt_shape *s)
{
    double(*m)[4] = s->o2w.m.m;
    double gmax = 0;
    int i, j, k;
    s->ball_ok = s->sim_scale > 0 && m[3][0] == 0 && m[3][1] == 0 && m[3][2] == 0 && m[3][3] == 1;
    if (!s->ball_ok) return;
    for (i = 0; i < 3; ++i) {
        double row = 0;
        for (j = 0; j < 3; ++j) {
            double g = 0;
            for (k = 0; k < 3; ++k) g += m[k][i] * m[k][j];
            row += fabs(g);
        }
        if (row > gmax) gmax = row;
    }
    s->ball_c = mt_v3((mt_real)m[0][3], (mt_real)m[1][3], (mt_real)m[2][3]);
    s->ball_c1 = mt_fabs(s->ball_c.x) + mt_fabs(s->ball_c.y) + mt_fabs(s->ball_c.z);
    s->ball_r2 = (mt_real)((double)s->radius * s->radius * gmax * (1 + 1e-6));
    s->ball_r = (mt_real)(sqrt((double)s->ball_r2) * (1 + 1e-6));
    s->ball_ok = mt_is_finite(s->ball_r2) && mt_is_finite(s->ball_c1);
}

mt_status mt__sphere_init(mt_shape *s, const mt_paramset *ps, mt_error *err)
{
    mt_real radius, z0, z1, pm;
    mt_status st;
    if ((st = mt_params_float(ps, "radius", 1, &radius, err)) != MT_OK ||
        (st = mt_params_float(ps, "zmin", -radius, &z0, err)) != MT_OK ||
        (st = mt_params_float(ps, "zmax", radius, &z1, err)) != MT_OK ||
        (st = mt_params_float(ps, "phimax", 360, &pm, err)) != MT_OK)
        return st;
    s->kind = MT_SHAPE_SPHERE;
    if (!(radius > 0)) {
        mt__locate_param(err, ps, "radius");
        return mt_error_param(err, MT_ERR_INVALID, "radius", "sphere radius %g is not positive",
                              (double)radius);
    }
    /* pbrt-v2 Sphere::Sphere */
    s->radius = radius;
    s->zmin = mt_clamp(mt_min(z0, z1), -radius, radius);
    s->zmax = mt_clamp(mt_max(z0, z1), -radius, radius);
    s->theta_min = mt_acos(mt_clamp(s->zmin / radius, -1, 1));
    s->theta_max = mt_acos(mt_clamp(s->zmax / radius, -1, 1));
    s->phi_max = mt_radians(mt_clamp(pm, 0, 360));
    s->center = mt_transform_point(&s->o2w, mt_v3(0, 0, 0));
    ball_init(s);
    if (!(s->zmin < s->zmax)) {
        mt__locate_param(err, ps, "zmin");
        return mt_error_param(err, MT_ERR_INVALID, "zmin",
                              "sphere zmin %g and zmax %g leave nothing of radius %g",
                              (double)z0, (double)z1, (double)radius);
    }
    if (!(s->phi_max > 0)) {
        mt__locate_param(err, ps, "phimax");
        return mt_error_param(err, MT_ERR_INVALID, "phimax", "sphere phimax %g is not positive",
                              (double)pm);
    }
    return MT_OK;
}

/* p pulled onto the sphere of radius rad (pbrt-v3 3.9.4's reprojection). */
static void reproject(double rad, double p[3])
{
    double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    int i;
    if (len > 0)
        for (i = 0; i < 3; ++i) p[i] *= rad / len;
}

static void ray_point(const mt__oray *r, double t, double p[3])
{
    int i;
    for (i = 0; i < 3; ++i) p[i] = r->o[i] + t * r->d[i];
}

/* Whether zmin, zmax or phimax cut anything away. */
static int clipped(const mt_shape *s)
{
    return s->zmin > -s->radius || s->zmax < s->radius || mt__phi_cut(s);
}

/* pbrt-v2's clipping test of the point at t, pulled onto the sphere. */
static int sphere_point(const mt_shape *s, const mt__oray *r, double t, double p[3])
{
    double rad = s->radius, phi;
    ray_point(r, t, p);
    reproject(rad, p);
    if ((s->zmin > -rad && p[2] < s->zmin) || (s->zmax < rad && p[2] > s->zmax)) return 0;
    if (!mt__phi_cut(s)) return 1;
    phi = p[0] == 0 && p[1] == 0 ? 0 : mt__phi(p[0], p[1]);
    return !(phi > s->phi_max);
}

/* The hit point p is returned as o + t d: mt__sphere_surface pulls it onto
 * the sphere, so that the candidates a BVH query rejects cost no square
 * root. A whole sphere needs no point to choose its root. */
int mt__sphere_hit(const mt_shape *s, const mt__oray *r, double *t, double p[3])
{
    const double *o = r->o, *d = r->d;
    double rad = s->radius, a, b, c, cx, cy, cz, t0, t1;
    a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
    c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - rad * rad;
    cx = o[1] * d[2] - o[2] * d[1];
    cy = o[2] * d[0] - o[0] * d[2];
    cz = o[0] * d[1] - o[1] * d[0];
    if (!mt__quadratic(a, b, c, a * rad * rad - (cx * cx + cy * cy + cz * cz), &t0, &t1))
        return 0;
    if (clipped(s)) {
        if (!mt__pick_root(s, r, t0, t1, sphere_point, t, p)) return 0;
    } else {
        /* mt__pick_root with every point on the shape */
        if (t0 > r->tmax || t1 < r->tmin) return 0;
        *t = t0 >= r->tmin ? t0 : t1;
        if (*t > r->tmax) return 0;
    }
    ray_point(r, *t, p);
    return 1;
}

void mt__sphere_surface(const mt_shape *s, const double ray_p[3], int want_uv, mt_surface *sf)
{
    double rad = s->radius, pm = s->phi_max, dth = (double)s->theta_max - s->theta_min;
    double ph[3], p[3], perr[3], zr, cosphi, sinphi;
    mt_real u = 0, v = 0;
    double dpdu[3], dpdv[3], dndu[3], dndv[3];
    int i;
    for (i = 0; i < 3; ++i) ph[i] = ray_p[i];
    reproject(rad, ph);
    /* pbrt-v2 moves a hit exactly on the z axis off it by 1e-5 r so that phi
     * and the derivatives are defined; here only the derivatives use the
     * moved point, p stays on the sphere. */
    for (i = 0; i < 3; ++i) {
        p[i] = ph[i];
        perr[i] = mt__gamma_d(5) * fabs(ph[i]);
    }
    if (p[0] == 0 && p[1] == 0) p[0] = 1e-5 * rad;
    if (want_uv) {
        double phi = mt__phi(p[0], p[1]), theta = acos(fmax(-1.0, fmin(1.0, p[2] / rad)));
        u = (mt_real)(phi / pm);
        v = (mt_real)((theta - s->theta_min) / dth);
    }
    zr = sqrt(p[0] * p[0] + p[1] * p[1]);
    cosphi = p[0] / zr;
    sinphi = p[1] / zr;
    /* pbrt-v2's dpdu and dpdv, with r sin(theta) = zr on the sphere */
    dpdu[0] = -pm * p[1];
    dpdu[1] = pm * p[0];
    dpdu[2] = 0;
    dpdv[0] = dth * p[2] * cosphi;
    dpdv[1] = dth * p[2] * sinphi;
    dpdv[2] = dth * -zr;
    /* pbrt-v2 solves the Weingarten equations; on a sphere n = p / r, so
     * their solution is dndu = dpdu / r, dndv = dpdv / r */
    for (i = 0; i < 3; ++i) {
        dndu[i] = dpdu[i] / rad;
        dndv[i] = dpdv[i] / rad;
    }
    mt__surface_from_object(s, ph, perr, dpdu, dpdv, dndu, dndv, ph, u, v, sf);
}

mt_real mt__sphere_area(const mt_shape *s) { return s->phi_max * s->radius * (s->zmax - s->zmin); }

mt_vec3 mt__sphere_sample(const mt_shape *s, mt_real u1, mt_real u2, mt_vec3 *ns)
{
    mt_vec3 p;
    if ((s->mode & MT_FIX_PARTIAL_SAMPLING) && clipped(s)) {
        /* uniform in area on the clipped sphere: z uniform in [zmin, zmax]
         * (Archimedes' hat-box theorem), phi uniform in [0, phimax]; z runs
         * down from zmax as pbrt-v2's UniformSampleSphere runs from +z */
        mt_real z = mt_lerp(u1, s->zmax, s->zmin), phi = u2 * s->phi_max;
        mt_real rr = mt_sqrt(mt_max(0, s->radius * s->radius - z * z));
        p = mt_v3(rr * mt_cos(phi), rr * mt_sin(phi), z);
    } else {
        p = mt_v3_scale(mt_uniform_sample_sphere(u1, u2), s->radius);
    }
    *ns = mt_v3_normalize(mt_transform_normal(&s->o2w, p));
    if (s->reverse_orientation) *ns = mt_v3_neg(*ns);
    return mt_transform_point(&s->o2w, p);
}

/* the world-space centre, transformed once when the sphere is made */
static mt_vec3 sphere_center(const mt_shape *s) { return s->center; }

/* Whether the cone sampling applies: always in pbrt-v2 mode; with
 * quadric-scale fixed, only under a similarity (radius in world units). */
static int cone_radius(const mt_shape *s, mt_real *r)
{
    if (!(s->mode & MT_FIX_QUADRIC_SCALE)) {
        *r = s->radius;
        return 1;
    }
    *r = (mt_real)(s->radius * s->sim_scale);
    return s->sim_scale > 0;
}

/* pbrt-v2: p counts as inside when DistanceSquared(p, centre) - r^2 < 1e-4. */
static int sees_outside(const mt_shape *s, mt_vec3 p, mt_real *costhetamax)
{
    mt_vec3 c = sphere_center(s);
    mt_real rad, d2, r2;
    if (!cone_radius(s, &rad)) return 0;
    d2 = mt_v3_len2(mt_v3_sub(p, c));
    r2 = rad * rad;
    if (d2 - r2 < (mt_real)1e-4) return 0;
    *costhetamax = mt_sqrt(mt_max(0, 1 - r2 / d2));
    return 1;
}

/* With e = c - o, the line misses the ball of radius R when |e x d| > R |d|.
 * Let M = (|e|_1 + |c|_1) |d|_1. Each component of e is off by at most
 * eps (|c|_1 + |e|_1) / 2 (the centre's rounding to mt_real and the
 * subtraction), so each of x = e x d by at most 3 eps M and |x| by at most
 * 6 eps M. Asking |x|^2 - R^2 |d|^2 to exceed 2 R |d|_1 dlt + dlt^2 with
 * dlt = 8 eps M, plus 4 eps of the two squares (their own rounding), gives
 * a true |e x d| - R |d| of at least 2 eps M: the line misses the world
 * ball by a relative 2 eps at least, and a partial sphere lies inside the
 * whole. The double-precision test (the ray taken to object space, the
 * quadratic's discriminant) errs by under 16 eps_double M^2 in these
 * units, which the last term covers: it finds no root either. M^2 >=
 * 1e-30 keeps underflow (absolute errors near 1e-45) out; NaN and overflow
 * fail the comparison. */
int mt__sphere_missed(const mt_shape *s, const mt_ray *r)
{
    mt_vec3 e, x;
    mt_real m, d1, rd2, x2, dlt;
    if (!s->ball_ok) return 0;
    e = mt_v3_sub(s->ball_c, r->o);
    x = mt_v3_cross(e, r->d);
    d1 = mt_fabs(r->d.x) + mt_fabs(r->d.y) + mt_fabs(r->d.z);
    m = (mt_fabs(e.x) + mt_fabs(e.y) + mt_fabs(e.z) + s->ball_c1) * d1;
    dlt = 8 * MT_REAL_EPSILON * m;
    rd2 = s->ball_r2 * mt_v3_len2(r->d);
    x2 = mt_v3_len2(x);
    return m * m >= (mt_real)1e-30 &&
           x2 - rd2 > 4 * MT_REAL_EPSILON * (x2 + rd2) + 2 * s->ball_r * d1 * dlt + dlt * dlt +
                          (mt_real)4e-15 * m * m;
}

int mt__sphere_area_sampled(const mt_shape *s)
{
    mt_real rad;
    return s->kind == MT_SHAPE_SPHERE && !cone_radius(s, &rad);
}

/* An area sample seen from p (an ellipsoid, where no cone applies: only with
 * quadric-scale fixed, pbrt-v2 never samples this way). It is moved to the
 * first point of the shape on the ray from p through it, and the pdf of a
 * direction sums over every point of the shape along it (mt_shape_pdf_from),
 * whatever shapeset-hit says: the two must go together, and corrected
 * mode's ShapeSet re-intersection under a mirroring transform moves the
 * sample anyway, so leaving a hidden sample where it is would be right only
 * without a mirror. */
static mt_vec3 area_sample_from(const mt_shape *s, mt_vec3 p, mt_real u1, mt_real u2,
                                mt_vec3 *ns)
{
    mt_vec3 ps = mt__sphere_sample(s, u1, u2, ns);
    mt_ray r = mt_ray_make(p, mt_v3_sub(ps, p), (mt_real)1e-3, MT_RAY_TMAX);
    mt_hit hit;
    mt_surface sf;
    if (!mt_shape_intersect(s, 0, &r, &hit)) return ps;
    mt_hit_surface_no_uv(&hit, &r, &sf);
    *ns = sf.dg.n;
    return mt_ray_at(&r, hit.t);
}

/* pbrt-v2's cone pdf, 0 where the cone is too narrow to be represented
 * (its Inf). */
static mt_real cone_pdf(mt_real costhetamax)
{
    mt_real pdf = mt_uniform_cone_pdf(costhetamax);
    return mt_is_finite(pdf) ? pdf : 0;
}

/* Whether Pdf(p, wi) of a sphere seen from outside is the cone's for every
 * direction: not when partial-sampling is fixed and the sphere clipped. */
static int cone_pdf_uniform(const mt_shape *s) { return !((s->mode & MT_FIX_PARTIAL_SAMPLING) && clipped(s)); }

mt_vec3 mt__sphere_sample_from_pdf(const mt_shape *s, mt_vec3 p, mt_real u1, mt_real u2, mt_vec3 *ns,
                                   int *uniform, mt_real *pdf)
{
    mt_vec3 c = sphere_center(s), wc, wcx, wcy, ps;
    mt_real costhetamax, rad;
    mt_ray r;
    mt_hit hit;
    *uniform = 0;
    if (!cone_radius(s, &rad)) return area_sample_from(s, p, u1, u2, ns);
    if (!sees_outside(s, p, &costhetamax)) return mt__sphere_sample(s, u1, u2, ns);
    if (cone_pdf_uniform(s)) {
        *uniform = 1;
        *pdf = cone_pdf(costhetamax);
    }
    wc = mt_v3_normalize(mt_v3_sub(c, p));
    mt_coordinate_system(wc, &wcx, &wcy);
    r = mt_ray_make(p, mt_uniform_sample_cone_frame(u1, u2, costhetamax, wcx, wcy, wc),
                    (mt_real)1e-3, MT_RAY_TMAX);
    if (!mt_shape_intersect(s, 0, &r, &hit)) {
        /* a direction at the cone's edge may graze past: pbrt-v2 then takes
         * the point of closest approach to the centre. A direction through
         * the clipped part of a partial sphere meets nothing either: pbrt-v2
         * does the same (a normal at right angles to the ray, which passes
         * the emission test one time in two); corrected, no sample. */
        hit.t = mt_v3_dot(mt_v3_sub(c, p), mt_v3_normalize(r.d));
        if ((s->mode & MT_FIX_PARTIAL_SAMPLING) && clipped(s)) {
            *ns = mt_v3(0, 0, 0);
            return mt_ray_at(&r, hit.t);
        }
    }
    ps = mt_ray_at(&r, hit.t);
    *ns = mt_v3_normalize(mt_v3_sub(ps, c));
    if (s->reverse_orientation) *ns = mt_v3_neg(*ns);
    return ps;
}

mt_vec3 mt__sphere_sample_from(const mt_shape *s, mt_vec3 p, mt_real u1, mt_real u2, mt_vec3 *ns)
{
    int uniform;
    mt_real pdf;
    return mt__sphere_sample_from_pdf(s, p, u1, u2, ns, &uniform, &pdf);
}

int mt__sphere_pdf_from(const mt_shape *s, mt_vec3 p, mt_vec3 wi, mt_real *pdf)
{
    mt_real costhetamax;
    if (!sees_outside(s, p, &costhetamax)) return 0;
    /* a sphere too small to subtend a representable cone: pbrt-v2's Inf */
    *pdf = cone_pdf(costhetamax);
    /* pbrt-v2 answers for any direction; a partial sphere is reached only by
     * the directions that meet it */
    if (!cone_pdf_uniform(s)) {
        mt_ray r = mt_ray_make(p, wi, (mt_real)1e-3, MT_RAY_TMAX);
        if (!mt_shape_occluded(s, 0, &r)) *pdf = 0;
    }
    return 1;
}
