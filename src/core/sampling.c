/*
 * Monte Carlo helpers, following pbrt-v2 montecarlo.cpp/.h and geometry.h
 * mapping for mapping: the region tests of the concentric disk and the order
 * of operations are kept so that the same uniform numbers give the same
 * directions.
 */
#include "materia/sampling.h"

void mt_concentric_sample_disk(mt_real u1, mt_real u2, mt_real *dx, mt_real *dy)
{
    mt_real r, theta;
    mt_real sx = 2 * u1 - 1, sy = 2 * u2 - 1;
    if (sx == 0 && sy == 0) {
        *dx = *dy = 0;
        return;
    }
    if (sx >= -sy) {
        if (sx > sy) {
            r = sx;
            theta = sy > 0 ? sy / r : 8 + sy / r;
        } else {
            r = sy;
            theta = 2 - sx / r;
        }
    } else {
        if (sx <= sy) {
            r = -sx;
            theta = 4 - sy / r;
        } else {
            r = -sy;
            theta = 6 + sx / r;
        }
    }
    theta *= MT_PI / 4;
    *dx = r * mt_cos(theta);
    *dy = r * mt_sin(theta);
}

void mt_uniform_sample_disk(mt_real u1, mt_real u2, mt_real *x, mt_real *y)
{
    mt_real r = mt_sqrt(u1);
    mt_real theta = 2 * MT_PI * u2;
    *x = r * mt_cos(theta);
    *y = r * mt_sin(theta);
}

mt_vec3 mt_cosine_sample_hemisphere(mt_real u1, mt_real u2)
{
    mt_vec3 w;
    mt_concentric_sample_disk(u1, u2, &w.x, &w.y);
    w.z = mt_sqrt(mt_max(0, 1 - w.x * w.x - w.y * w.y));
    return w;
}

mt_real mt_cosine_hemisphere_pdf(mt_real costheta) { return costheta * MT_INV_PI; }

mt_vec3 mt_uniform_sample_hemisphere(mt_real u1, mt_real u2)
{
    mt_real z = u1;
    mt_real r = mt_sqrt(mt_max(0, 1 - z * z));
    mt_real phi = 2 * MT_PI * u2;
    return mt_v3(r * mt_cos(phi), r * mt_sin(phi), z);
}

mt_real mt_uniform_hemisphere_pdf(void) { return MT_INV_2PI; }

mt_vec3 mt_uniform_sample_sphere(mt_real u1, mt_real u2)
{
    mt_real z = 1 - 2 * u1;
    mt_real r = mt_sqrt(mt_max(0, 1 - z * z));
    mt_real phi = 2 * MT_PI * u2;
    return mt_v3(r * mt_cos(phi), r * mt_sin(phi), z);
}

mt_real mt_uniform_sphere_pdf(void) { return 1 / (4 * MT_PI); }

mt_vec3 mt_uniform_sample_cone(mt_real u1, mt_real u2, mt_real costhetamax)
{
    mt_real costheta = (1 - u1) + u1 * costhetamax;
    /* pbrt-v2 takes sqrtf(1 - cos^2) unclamped; rounding can make the
     * argument -1 ulp, so it is clamped here (the only difference: no NaN). */
    mt_real sintheta = mt_sqrt(mt_max(0, 1 - costheta * costheta));
    mt_real phi = u2 * 2 * MT_PI;
    return mt_v3(mt_cos(phi) * sintheta, mt_sin(phi) * sintheta, costheta);
}

mt_vec3 mt_uniform_sample_cone_frame(mt_real u1, mt_real u2, mt_real costhetamax, mt_vec3 x,
                                     mt_vec3 y, mt_vec3 z)
{
    mt_real costheta = mt_lerp(u1, costhetamax, 1);
    mt_real sintheta = mt_sqrt(mt_max(0, 1 - costheta * costheta));
    mt_real phi = u2 * 2 * MT_PI;
    return mt_v3_add(mt_v3_add(mt_v3_scale(x, mt_cos(phi) * sintheta),
                               mt_v3_scale(y, mt_sin(phi) * sintheta)),
                     mt_v3_scale(z, costheta));
}

mt_real mt_uniform_cone_pdf(mt_real costhetamax)
{
    return 1 / (2 * MT_PI * (1 - costhetamax));
}

void mt_uniform_sample_triangle(mt_real u1, mt_real u2, mt_real *u, mt_real *v)
{
    mt_real su1 = mt_sqrt(u1);
    *u = 1 - su1;
    *v = u2 * su1;
}

mt_vec3 mt_spherical_direction(mt_real sintheta, mt_real costheta, mt_real phi)
{
    return mt_v3(sintheta * mt_cos(phi), sintheta * mt_sin(phi), costheta);
}

mt_vec3 mt_spherical_direction_frame(mt_real sintheta, mt_real costheta, mt_real phi,
                                     mt_vec3 x, mt_vec3 y, mt_vec3 z)
{
    return mt_v3_add(mt_v3_add(mt_v3_scale(x, sintheta * mt_cos(phi)),
                               mt_v3_scale(y, sintheta * mt_sin(phi))),
                     mt_v3_scale(z, costheta));
}

mt_real mt_spherical_theta(mt_vec3 v) { return mt_acos(mt_clamp(v.z, -1, 1)); }

mt_real mt_spherical_phi(mt_vec3 v)
{
    mt_real p = mt_atan2(v.y, v.x);
    return p < 0 ? p + 2 * MT_PI : p;
}

void mt_stratified_sample_1d(mt_real *samp, int n, mt_rng *rng, int jitter)
{
    mt_real inv = (mt_real)1 / n;
    int i;
    for (i = 0; i < n; ++i) {
        mt_real delta = jitter ? mt_rng_uniform(rng) : (mt_real)0.5;
        *samp++ = mt_min((i + delta) * inv, MT_ONE_MINUS_EPSILON);
    }
}

void mt_stratified_row_2d(mt_real *samp, int nx, int ny, int y, mt_rng *rng, int jitter)
{
    mt_real dx = (mt_real)1 / nx, dy = (mt_real)1 / ny;
    int x;
    for (x = 0; x < nx; ++x) {
        mt_real jx = jitter ? mt_rng_uniform(rng) : (mt_real)0.5;
        mt_real jy = jitter ? mt_rng_uniform(rng) : (mt_real)0.5;
        *samp++ = mt_min((x + jx) * dx, MT_ONE_MINUS_EPSILON);
        *samp++ = mt_min((y + jy) * dy, MT_ONE_MINUS_EPSILON);
    }
}

void mt_stratified_sample_2d(mt_real *samp, int nx, int ny, mt_rng *rng, int jitter)
{
    int y;
    for (y = 0; y < ny; ++y) mt_stratified_row_2d(samp + 2 * nx * y, nx, ny, y, rng, jitter);
}

mt_real mt_balance_heuristic(int nf, mt_real fpdf, int ng, mt_real gpdf)
{
    mt_real f = nf * fpdf, g = ng * gpdf;
    return f + g > 0 ? f / (f + g) : 0;
}

mt_real mt_power_heuristic(int nf, mt_real fpdf, int ng, mt_real gpdf)
{
    mt_real f = nf * fpdf, g = ng * gpdf;
    /* pbrt-v2 divides unguarded; both pdfs zero would be 0/0. */
    return f * f + g * g > 0 ? (f * f) / (f * f + g * g) : 0;
}
