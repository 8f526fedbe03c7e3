/*
 * Internal: pbrt-v2's Perlin noise, FBm and Turbulence (core/texture.cpp),
 * and the floor helpers the textures share.
 */
#ifndef MT_TEXTURES_NOISE_H
#define MT_TEXTURES_NOISE_H

#include "materia/vec.h"

/* pbrt-v2 Noise(x, y, z): Perlin's improved noise with his permutation
 * table and the 12 (+4 repeated) gradient directions; zero at every lattice
 * point, in about [-1, 1]. Exact for every finite input (pbrt-v2's
 * Floor2Int overflows beyond 2^31); 0 for non-finite input. */
mt_real mt__noise(mt_real x, mt_real y, mt_real z);

/* pbrt-v2 FBm(P, dpdx, dpdy, omega, maxOctaves): sum of omega^i Noise(1.99^i P)
 * over the octaves the footprint allows, -1 - log2(max |dpdx|^2, |dpdy|^2)/2
 * (clamped to maxOctaves; see noise.c on the -1), the last one faded in by
 * SmoothStep(.3, .7). */
mt_real mt__fbm(mt_vec3 p, mt_vec3 dpdx, mt_vec3 dpdy, mt_real omega, int max_octaves);
/* pbrt-v2 Turbulence: as FBm with |Noise|, plus 0.2 per octave not summed. */
mt_real mt__turbulence(mt_vec3 p, mt_vec3 dpdx, mt_vec3 dpdy, mt_real omega, int max_octaves);

/* The number of whole octaves and the fractional octave count pbrt-v2's FBm
 * and Turbulence sum for this footprint (exposed for tests). */
mt_real mt__noise_octaves(mt_vec3 dpdx, mt_vec3 dpdy, int max_octaves, int *whole);

/* 1 when floor(v) is odd, exactly for every finite v (pbrt-v2 computes
 * Floor2Int(v) % 2, which overflows beyond 2^31). */
static inline int mt__floor_odd(mt_real v)
{
    mt_real h;
    if (v > -(mt_real)1073741824 && v < (mt_real)1073741824) {
        int i = (int)v; /* floor by truncation: libm's floor is a call without SSE4.1 */
        if ((mt_real)i > v) i--;
        return (int)((unsigned)i & 1u);
    }
    h = mt_floor(v) * (mt_real)0.5;
    return h != mt_floor(h);
}

#endif
