/* Reference MIP-map filters in double precision (see mipref.h). */
#include <math.h>
#include "support/mipref.h"

#define TWO_PI 6.283185307179586

t_pattern t_pattern_smooth(void)
{
    t_pattern p = {3, 0.5, {0.2, 0.15, 0.1}, {1.3, -0.9, 3.1}, {0.7, 2.1, -1.7}, {0.4, 1.1, 2.0}};
    return p;
}

t_pattern t_pattern_high(void)
{
    t_pattern p = {1, 0.5, {0.4}, {37}, {11}, {0.3}};
    return p;
}

double t_pattern_value(const t_pattern *p, double x, double y)
{
    double v = p->offset;
    int k;
    for (k = 0; k < p->nwaves; k++)
        v += p->a[k] * cos(TWO_PI * (p->fx[k] * x + p->fy[k] * y) + p->phase[k]);
    return v;
}

void t_pattern_gradient(const t_pattern *p, double x, double y, double g[2])
{
    int k;
    g[0] = g[1] = 0;
    for (k = 0; k < p->nwaves; k++) {
        double s = -p->a[k] * TWO_PI * sin(TWO_PI * (p->fx[k] * x + p->fy[k] * y) + p->phase[k]);
        g[0] += s * p->fx[k];
        g[1] += s * p->fy[k];
    }
}

double t_pattern_hessian_bound(const t_pattern *p)
{
    double b = 0;
    int k;
    for (k = 0; k < p->nwaves; k++)
        b += fabs(p->a[k]) * TWO_PI * TWO_PI * (p->fx[k] * p->fx[k] + p->fy[k] * p->fy[k]);
    return b;
}

void t_pattern_image(const t_pattern *p, int n, mt_image *img)
{
    int i, j;
    mt_image_create(img, n, n, 1, NULL);
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++)
            img->data[(size_t)j * (size_t)n + (size_t)i] =
                (float)t_pattern_value(p, (i + 0.5) / n, (j + 0.5) / n);
}

void t_moment_image(int n, int which, double cx, double cy, mt_image *img)
{
    int i, j;
    mt_image_create(img, n, n, 1, NULL);
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            double dx = (i + 0.5) / n - cx, dy = (j + 0.5) / n - cy;
            img->data[(size_t)j * (size_t)n + (size_t)i] =
                (float)(which == 1 ? dx : which == 2 ? dy : dx * dx + dy * dy);
        }
}

/* The bilinear interpolant's tent weights at p along one axis: texel i0 and
 * i0 + 1 with weights 1 - f and f (texel centers at (i + 0.5) / n). */
static void tent(double p, int n, int *i0, double *f)
{
    double u = p * n - 0.5;
    *i0 = (int)floor(u);
    *f = u - *i0;
}

static double texel(const mt_image *img, int i, int j)
{
    return img->data[(size_t)j * (size_t)img->width + (size_t)i];
}

/* The antiderivative of the unit tent max(0, 1 - |u|), from -1. */
static double tent_antiderivative(double u)
{
    u = u < -1 ? -1 : (u > 1 ? 1 : u);
    return u <= 0 ? 0.5 * (1 + u) * (1 + u) : 1 - 0.5 * (1 - u) * (1 - u);
}

/* The integral of the unit tent over [lo, hi]. */
static double tent_integral(double lo, double hi)
{
    return tent_antiderivative(hi) - tent_antiderivative(lo);
}

t_ref t_ref_box(const mt_image *img, double x, double y, double w)
{
    int n = img->width, i, j, i0, i1, j0, j1;
    double wx[64], wy[64], lo_x = (x - w / 2) * n, hi_x = (x + w / 2) * n,
           lo_y = (y - w / 2) * n, hi_y = (y + w / 2) * n;
    t_ref r = {0, 0, 0, 0};
    i0 = (int)floor(lo_x - 0.5) - 1;
    i1 = (int)ceil(hi_x - 0.5) + 1;
    j0 = (int)floor(lo_y - 0.5) - 1;
    j1 = (int)ceil(hi_y - 0.5) + 1;
    if (i1 - i0 >= 64 || j1 - j0 >= 64 || i0 < 0 || j0 < 0 || i1 >= n || j1 >= n) {
        r.value = NAN;
        return r;
    }
    /* texel i's tent is centered at i + 0.5 (texel units); its integral over
     * the box, divided by the box's side, is its weight */
    for (i = i0; i <= i1; i++) wx[i - i0] = tent_integral(lo_x - (i + 0.5), hi_x - (i + 0.5)) / (w * n);
    for (j = j0; j <= j1; j++) wy[j - j0] = tent_integral(lo_y - (j + 0.5), hi_y - (j + 0.5)) / (w * n);
    for (j = j0; j <= j1; j++)
        for (i = i0; i <= i1; i++) {
            double k = wx[i - i0] * wy[j - j0], dx = (i + 0.5) / n - x, dy = (j + 0.5) / n - y;
            r.value += k * texel(img, i, j);
            r.dx += k * dx;
            r.dy += k * dy;
            r.m2 += k * (dx * dx + dy * dy);
        }
    return r;
}

t_ref t_ref_ellipse(const mt_image *img, double x, double y, double d0s, double d0t, double d1s,
                    double d1t)
{
    enum { NR = 48, NT = 96 };
    int n = img->width, a, b;
    double sum = 0, e2 = exp(-2.0);
    t_ref r = {0, 0, 0, 0};
    for (a = 0; a < NR; a++) {
        double rr = (a + 0.5) / NR, wr = (exp(-2 * rr * rr) - e2) * rr;
        for (b = 0; b < NT; b++) {
            double th = TWO_PI * (b + 0.5) / NT, u = rr * cos(th), v = rr * sin(th);
            double px = x + u * d0s + v * d1s, py = y + u * d0t + v * d1t, fx, fy, dx, dy;
            int i, j;
            tent(px, n, &i, &fx);
            tent(py, n, &j, &fy);
            if (i < 0 || j < 0 || i + 1 >= n || j + 1 >= n) {
                r.value = NAN;
                return r;
            }
            r.value += wr * ((1 - fx) * (1 - fy) * texel(img, i, j) +
                             fx * (1 - fy) * texel(img, i + 1, j) +
                             (1 - fx) * fy * texel(img, i, j + 1) + fx * fy * texel(img, i + 1, j + 1));
            /* moments of the kernel on the samples: the interpolant of a
             * linear function is exact, and of |y - x|^2 adds the tent's own
             * variance at p */
            dx = px - x;
            dy = py - y;
            r.dx += wr * dx;
            r.dy += wr * dy;
            r.m2 += wr * (dx * dx + dy * dy + (fx * (1 - fx) + fy * (1 - fy)) / ((double)n * n));
            sum += wr;
        }
    }
    r.value /= sum;
    r.dx /= sum;
    r.dy /= sum;
    r.m2 /= sum;
    return r;
}

void t_footprints(t_footprint *f, int nclusters, int per_cluster, int n, double maxaniso,
                  uint64_t seed)
{
    mt_rng rng;
    int c, k;
    mt_rng_seed(&rng, seed, 5);
    for (c = 0; c < nclusters; c++) {
        double cx = 0.35 + 0.3 * mt_rng_uniform_d(&rng), cy = 0.35 + 0.3 * mt_rng_uniform_d(&rng);
        for (k = 0; k < per_cluster; k++) {
            t_footprint *p = &f[c * per_cluster + k];
            double a = pow(2, 4 * mt_rng_uniform_d(&rng)) / n,
                   ratio = pow(2, -4 * mt_rng_uniform_d(&rng)),
                   th = TWO_PI * mt_rng_uniform_d(&rng), b = a * ratio, cb;
            p->cx = cx;
            p->cy = cy;
            p->x = cx + (8 * mt_rng_uniform_d(&rng) - 4) / n;
            p->y = cy + (8 * mt_rng_uniform_d(&rng) - 4) / n;
            p->w = pow(2, 5 * mt_rng_uniform_d(&rng) - 1) / n;
            p->ds0 = a * cos(th);
            p->dt0 = a * sin(th);
            p->ds1 = -b * sin(th);
            p->dt1 = b * cos(th);
            /* pbrt-v2 lengthens the minor axis to major / maxanisotropy */
            cb = b * maxaniso < a ? a / maxaniso : b;
            p->cs1 = -cb * sin(th);
            p->ct1 = cb * cos(th);
        }
    }
}

const char *const t_filter_names[T_NFILTERS] = {"point (no filter)", "trilinear",
                                                "trilinear, pbrt-v2 width", "EWA"};

double t_filter_lookup(const mt_mipmap *m, int filter, const t_footprint *p)
{
    mt_real x = (mt_real)p->x, y = (mt_real)p->y;
    switch (filter) {
    case T_F_POINT: return mt_mipmap_lookup_width(m, x, y, 0).c[0];
    case T_F_TRI: return mt_mipmap_lookup_width(m, x, y, (mt_real)p->w).c[0];
    case T_F_TRI_PBRT: return mt_mipmap_lookup_width(m, x, y, (mt_real)(2 * p->w)).c[0];
    default:
        return mt_mipmap_lookup(m, x, y, (mt_real)p->ds0, (mt_real)p->dt0, (mt_real)p->ds1,
                                (mt_real)p->dt1)
            .c[0];
    }
}

t_ref t_filter_reference(const mt_image *img, int filter, const t_footprint *p)
{
    return filter == T_F_EWA ? t_ref_ellipse(img, p->x, p->y, p->ds0, p->dt0, p->cs1, p->ct1)
                             : t_ref_box(img, p->x, p->y, p->w);
}
