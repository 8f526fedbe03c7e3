/*
 * pbrt-v2's Perlin noise, FBm and Turbulence (core/texture.cpp), computed in
 * mt_real with pbrt-v2's order of operations and float constants.
 */
#include "textures/noise.h"
#include "textures/tex.h"

/* Ken Perlin's permutation of 0..255, as pbrt-v2's NoisePerm lists it
 * (texture.cpp; pbrt-v2 stores it twice so that sums of two entries index
 * it directly: perm[i & 255] is the same lookup). */
static const unsigned char perm[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,
    103, 30,  69,  142, 8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,
    0,   26,  197, 62,  94,  252, 219, 203, 117, 35,  11,  32,  57,  177, 33,  88,  237, 149,
    56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165, 71,  134, 139, 48,  27,  166,
    77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,  55,  46,
    245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187,
    208, 89,  18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186,
    3,   64,  52,  217, 226, 250, 124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212,
    207, 206, 59,  227, 47,  16,  58,  17,  182, 189, 28,  42,  223, 183, 170, 213, 119, 248,
    152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,   129, 22,  39,  253,
    19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107,
    49,  192, 214, 31,  181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,
    150, 254, 138, 236, 205, 93,  222, 114, 67,  29,  24,  72,  243, 141, 128, 195, 78,  66,
    215, 61,  156, 180};

#define PERM(i) ((int)perm[(i) & 255])

/* The lattice cell of v modulo 256 (pbrt-v2: Floor2Int(v) & 255) and the
 * offset v - floor(v). Exact for every finite v: beyond 2^30 the residue
 * comes from fmod, which is exact, instead of an int conversion. */
static int lattice(mt_real v, mt_real *frac)
{
    mt_real f, r;
    if (v > -(mt_real)1073741824 && v < (mt_real)1073741824) {
        /* floor by truncation, corrected below zero (libm's floor is a call
         * without SSE4.1); exact in this range */
        int i = (int)v;
        if ((mt_real)i > v) i--;
        *frac = v - (mt_real)i;
        return (int)((unsigned)i & 255u);
    }
    f = mt_floor(v);
    *frac = v - f;
    r = mt_fmod(f, 256);
    if (r < 0) r += 256;
    return (int)r;
}

/* pbrt-v2 Grad: the gradient picked by the hash of the corner, dotted with
 * the offset from it. */
static mt_real grad(int x, int y, int z, mt_real dx, mt_real dy, mt_real dz)
{
    int h = PERM(PERM(PERM(x) + y) + z) & 15;
    mt_real u = h < 8 || h == 12 || h == 13 ? dx : dy;
    mt_real v = h < 4 || h == 12 || h == 13 ? dy : dz;
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

/* pbrt-v2 NoiseWeight: the quintic 6t^5 - 15t^4 + 10t^3. */
static mt_real fade_weight(mt_real t)
{
    mt_real t3 = t * t * t;
    mt_real t4 = t3 * t;
    return 6 * t4 * t - 15 * t4 + 10 * t3;
}

mt_real mt__noise(mt_real x, mt_real y, mt_real z)
{
    mt_real dx, dy, dz, wx, wy, wz;
    mt_real w000, w100, w010, w110, w001, w101, w011, w111;
    mt_real x00, x10, x01, x11, y0, y1;
    int ix, iy, iz;
    if (!(mt_fabs(x) <= MT_REAL_MAX && mt_fabs(y) <= MT_REAL_MAX && mt_fabs(z) <= MT_REAL_MAX))
        return 0;
    ix = lattice(x, &dx);
    iy = lattice(y, &dy);
    iz = lattice(z, &dz);
    w000 = grad(ix, iy, iz, dx, dy, dz);
    w100 = grad(ix + 1, iy, iz, dx - 1, dy, dz);
    w010 = grad(ix, iy + 1, iz, dx, dy - 1, dz);
    w110 = grad(ix + 1, iy + 1, iz, dx - 1, dy - 1, dz);
    w001 = grad(ix, iy, iz + 1, dx, dy, dz - 1);
    w101 = grad(ix + 1, iy, iz + 1, dx - 1, dy, dz - 1);
    w011 = grad(ix, iy + 1, iz + 1, dx, dy - 1, dz - 1);
    w111 = grad(ix + 1, iy + 1, iz + 1, dx - 1, dy - 1, dz - 1);
    /* trilinear interpolation with the quintic weights (pbrt-v2 Lerp) */
    wx = fade_weight(dx);
    wy = fade_weight(dy);
    wz = fade_weight(dz);
    x00 = mt_lerp(wx, w000, w100);
    x10 = mt_lerp(wx, w010, w110);
    x01 = mt_lerp(wx, w001, w101);
    x11 = mt_lerp(wx, w011, w111);
    y0 = mt_lerp(wy, x00, x10);
    y1 = mt_lerp(wy, x01, x11);
    return mt_lerp(wz, y0, y1);
}

static mt_real noise_at(mt_vec3 p, mt_real lambda)
{
    return mt__noise(lambda * p.x, lambda * p.y, lambda * p.z);
}

/* pbrt-v2 texture.cpp SmoothStep(min, max, value). */
static mt_real smooth_step(mt_real lo, mt_real hi, mt_real value)
{
    mt_real v = mt_clamp((value - lo) / (hi - lo), 0, 1);
    return v * v * (-2 * v + 3);
}

/* pbrt-v2 pbrt.h Log2: logf(x) times the float 1 / logf(2). */
static mt_real noise_log2(mt_real x) { return mt_log(x) * ((mt_real)1 / mt_log((mt_real)2)); }

/* The octave count: -1 - log2(s2) / 2 clamped to [0, maxOctaves], s2 the
 * larger squared footprint vector. The pbrt-v2 sources in the project's
 * search index (commits before the reference's e6f6334f) read 1 - log2(s2)/2
 * without a lower bound, but every one of the 432 reference values of fbm,
 * wrinkled, windy and marble agrees with -1 (pbrt-v3's formula) and none with
 * +1, and the reference binary clamps at 0 as pbrt-v3 does: a footprint of
 * 0.7 gives FBm exactly 0 and Turbulence exactly 0.2 maxOctaves (renders of
 * an fbm and a wrinkled plane, docs/TEXTURES.md), where the unclamped count
 * (-0.49: a partial octave of 0.51) faded in a noise octave. */
mt_real mt__noise_octaves(mt_vec3 dpdx, mt_vec3 dpdy, int max_octaves, int *whole)
{
    mt_real a = mt_v3_len2(dpdx), b = mt_v3_len2(dpdy);
    mt_real s2 = a < b ? b : a; /* std::max */
    mt_real f = -1 - (mt_real)0.5 * noise_log2(s2), foct;
    /* An overflowing (or NaN) footprint is as wide as can be: no octave. */
    if (!(s2 <= MT_REAL_MAX)) f = 0;
    /* pbrt's Clamp(f, 0, maxOctaves): the lower bound tested first */
    foct = f < 0 ? 0 : (f > (mt_real)max_octaves ? (mt_real)max_octaves : f);
    *whole = (int)mt_floor(foct); /* foct is in [0, 128] (or a negative maxOctaves): exact */
    return foct;
}

/* The sum both FBm and Turbulence take: octaves of Noise (|Noise| when abs),
 * the partial octave faded in. */
static mt_real octave_sum(mt_vec3 p, mt_real omega, int octaves, mt_real foct, int abs)
{
    mt_real sum = 0, lambda = 1, o = 1, n, partial;
    int i;
    for (i = 0; i < octaves; ++i) {
        n = noise_at(p, lambda);
        sum += o * (abs ? mt_fabs(n) : n);
        lambda *= (mt_real)1.99;
        o *= omega;
    }
    partial = foct - (mt_real)octaves;
    n = noise_at(p, lambda);
    sum += o * smooth_step((mt_real)0.3, (mt_real)0.7, partial) * (abs ? mt_fabs(n) : n);
    return sum;
}

mt_real mt__fbm(mt_vec3 p, mt_vec3 dpdx, mt_vec3 dpdy, mt_real omega, int max_octaves)
{
    int octaves;
    mt_real foct = mt__noise_octaves(dpdx, dpdy, max_octaves, &octaves);
    return octave_sum(p, omega, octaves, foct, 0);
}

mt_real mt__turbulence(mt_vec3 p, mt_vec3 dpdx, mt_vec3 dpdy, mt_real omega, int max_octaves)
{
    int octaves;
    mt_real foct = mt__noise_octaves(dpdx, dpdy, max_octaves, &octaves);
    mt_real sum = octave_sum(p, omega, octaves, foct, 1);
    /* pbrt-v2: "add in value to account for average value of fabsf(Noise())
     * (~0.2) for the remaining octaves" */
    return sum + ((mt_real)max_octaves - foct) * (mt_real)0.2;
}

/* --- the layout of the textures made of noise (fbm, wrinkled, windy,
 * marble: textures/tex.h) --- */

void *mt__noise_alloc(size_t size, const mt_texture_ops *ops, int is_float, const mt_map3d *map,
                      int octaves, mt_real roughness, mt__octave_fn sum, mt_mode mode,
                      mt_error *err)
{
    mt__noise_tex *n;
    if (!mt__tex_check_octaves(octaves, roughness, ops->name, err)) return NULL;
    n = mt__texture_alloc(size, ops, is_float, mode, err);
    if (!n) return NULL;
    n->map = *map;
    n->octaves = octaves;
    n->omega = roughness;
    n->sum = sum;
    return n;
}

mt_real mt__noise_tex_float(const mt_texture *t, const mt_diffgeom *dg)
{
    const mt__noise_tex *n = (const mt__noise_tex *)t;
    mt_vec3 dpdx, dpdy, p = mt__map3d_apply(&n->map, dg, &dpdx, &dpdy);
    return n->sum(p, dpdx, dpdy, n->omega, n->octaves);
}
