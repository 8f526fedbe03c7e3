/* IEEE 754 binary16 (OpenEXR's half) to and from binary32, by bits. */
#include <float.h>
#include <string.h>
#include "image/imageio.h"

float mt__half_to_float(uint16_t h)
{
    uint32_t sign = (uint32_t)(h & 0x8000u) << 16, e = (h >> 10) & 0x1fu, m = h & 0x3ffu, bits;
    float f;
    if (e == 0) {
        /* zero or subnormal: m * 2^-24, exact in float */
        f = (float)m * 0x1p-24f;
        return sign ? -f : f;
    }
    if (e == 31)
        bits = sign | 0x7f800000u | (m << 13); /* infinity or NaN (payload kept) */
    else
        bits = sign | ((e + 112u) << 23) | (m << 13); /* rebias 15 -> 127 */
    memcpy(&f, &bits, sizeof f);
    return f;
}

uint16_t mt__float_to_half(float f)
{
    uint32_t x, sign, e, m, r, rem, halfway;
    int shift;
    memcpy(&x, &f, sizeof x);
    sign = (x >> 16) & 0x8000u;
    x &= 0x7fffffffu;
    if (x >= 0x7f800000u) /* infinity, or NaN made quiet */
        return (uint16_t)(sign | 0x7c00u | (x > 0x7f800000u ? 0x200u | ((x >> 13) & 0x3ffu) : 0));
    if (x >= 0x477ff000u) return (uint16_t)(sign | 0x7c00u); /* >= 65520 rounds to infinity */
    if (x >= 0x38800000u) {
        /* normal half: rebias the exponent, round the 13 dropped bits to even */
        uint32_t u = x - 0x38000000u;
        return (uint16_t)(sign | ((u + 0x0fffu + ((u >> 13) & 1u)) >> 13));
    }
    if (x < 0x33000000u) return (uint16_t)sign; /* below half the smallest subnormal */
    /* subnormal half: the 24-bit significand shifted to units of 2^-24 */
    e = x >> 23;
    m = (x & 0x7fffffu) | 0x800000u;
    shift = 126 - (int)e;
    r = m >> shift;
    rem = m & ((1u << shift) - 1u);
    halfway = 1u << (shift - 1);
    if (rem > halfway || (rem == halfway && (r & 1u))) r++;
    return (uint16_t)(sign | r);
}

/* A float or uint channel read into a HALF slice of pbrt-v2's frame buffer
 * (imageio.cpp ReadImageEXR): OpenEXR converts with floatToHalf or
 * uintToHalf (ImfConvert.cpp), which round to nearest even but turn finite
 * values beyond HALF_MAX = 65504 into infinities. Here such values saturate
 * at +-65504 instead, so that the conversion never makes an infinity (a
 * stored infinity or NaN passes as it is, as in OpenEXR). A uint channel
 * comes here as float: its values up to 65504 are exact in float. */
float mt__float_through_half(float f)
{
    if (f > 65504.f && f <= FLT_MAX) return 65504.f;
    if (f < -65504.f && f >= -FLT_MAX) return -65504.f;
    return mt__half_to_float(mt__float_to_half(f));
}
