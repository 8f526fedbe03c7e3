/* The BVH benchmarks' ray sets (see traysets.h). */
#include <math.h>
#include <stdlib.h>
#include "materia/rng.h"
#include "materia/sampling.h"
#include "support/traysets.h"

const char *const t_ray_set_names[T_RAY_SETS] = {"primary", "incoherent", "occlusion"};

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l, v[1] /= l, v[2] /= l;
}
static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* pbrt-v2 LookAt and a perspective camera with fov on the shorter axis. */
static void primary_rays(mt_ray *rays, int w, int h, const double pos[3], const double look[3],
                         const double up[3], double fov_deg)
{
    double dir[3], left[3], nup[3], tanf2 = tan(fov_deg * 3.14159265358979323846 / 360), aspect = (double)w / h;
    int i, j;
    for (i = 0; i < 3; ++i) dir[i] = look[i] - pos[i];
    normalize3(dir);
    cross3(up, dir, left);
    normalize3(left);
    cross3(dir, left, nup);
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i) {
            double sx = (2 * (i + 0.5) / w - 1) * aspect * tanf2, sy = (1 - 2 * (j + 0.5) / h) * tanf2;
            double d[3];
            int k;
            for (k = 0; k < 3; ++k) d[k] = dir[k] - sx * left[k] + sy * nup[k];
            rays[(size_t)j * w + i] =
                mt_ray_make(mt_v3((mt_real)pos[0], (mt_real)pos[1], (mt_real)pos[2]),
                            mt_v3((mt_real)d[0], (mt_real)d[1], (mt_real)d[2]), 0, MT_RAY_TMAX);
        }
}

static mt_vec3 in_box(mt_rng *rng, mt_vec3 lo, mt_vec3 hi)
{
    mt_real x = lo.x + (hi.x - lo.x) * mt_rng_uniform(rng);
    mt_real y = lo.y + (hi.y - lo.y) * mt_rng_uniform(rng);
    mt_real z = lo.z + (hi.z - lo.z) * mt_rng_uniform(rng);
    return mt_v3(x, y, z);
}

void t_ray_sets_free(mt_ray *sets[T_RAY_SETS])
{
    int k;
    for (k = 0; k < T_RAY_SETS; ++k) free(sets[k]), sets[k] = NULL;
}

int t_ray_sets(const mt_geometry *g, int bunny_camera, mt_ray *sets[T_RAY_SETS],
               size_t counts[T_RAY_SETS])
{
    mt_vec3 lo, hi;
    mt_rng rng;
    size_t i;
    int k;
    counts[T_RAYS_PRIMARY] = 1024 * 768;
    counts[T_RAYS_INCOHERENT] = counts[T_RAYS_OCCLUSION] = 1000000;
    for (k = 0; k < T_RAY_SETS; ++k) sets[k] = malloc(counts[k] * sizeof *sets[k]);
    if (!sets[0] || !sets[1] || !sets[2]) {
        t_ray_sets_free(sets);
        return 0;
    }
    mt_geometry_bounds(g, &lo, &hi);
    if (bunny_camera) {
        static const double pos[3] = {0, .2, .2}, look[3] = {-.02, .1, 0}, up[3] = {0, 1, 0};
        primary_rays(sets[T_RAYS_PRIMARY], 1024, 768, pos, look, up, 60);
    } else {
        double c[3] = {(lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0, (lo.z + hi.z) / 2.0}, pos[3];
        double dx = hi.x - lo.x, dy = hi.y - lo.y, dz = hi.z - lo.z, off[3] = {1, .3, .4};
        double diag = sqrt(dx * dx + dy * dy + dz * dz);
        static const double up[3] = {0, 0, 1};
        normalize3(off);
        for (k = 0; k < 3; ++k) pos[k] = c[k] + 1.5 * diag * off[k];
        primary_rays(sets[T_RAYS_PRIMARY], 1024, 768, pos, c, up, 40);
    }
    mt_rng_seed(&rng, 2024, 1);
    for (i = 0; i < counts[T_RAYS_INCOHERENT]; ++i) {
        mt_vec3 o = in_box(&rng, lo, hi);
        mt_real u1 = mt_rng_uniform(&rng), u2 = mt_rng_uniform(&rng);
        sets[T_RAYS_INCOHERENT][i] = mt_ray_make(o, mt_uniform_sample_sphere(u1, u2), 0, MT_RAY_TMAX);
    }
    for (i = 0; i < counts[T_RAYS_OCCLUSION]; ++i) {
        mt_vec3 a = in_box(&rng, lo, hi), b = in_box(&rng, lo, hi);
        sets[T_RAYS_OCCLUSION][i] = mt_ray_make(a, mt_v3_sub(b, a), 0, 1);
    }
    return 1;
}
