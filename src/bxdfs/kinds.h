/* Internal: helpers shared by the BxDF kinds. */
#ifndef MT_BXDFS_KINDS_H
#define MT_BXDFS_KINDS_H

#include "materia/bxdf.h"

/* Creators reject NaN and infinite parameters with a message naming them. */
static inline int mt__check_real(mt_real v, const char *param, const char *kind, mt_error *err)
{
    if (mt_is_finite(v)) return 1;
    mt_error_param(err, MT_ERR_INVALID, param, "%s: %s is not a finite number", kind, param);
    return 0;
}

static inline int mt__check_rgb(mt_rgb v, const char *param, const char *kind, mt_error *err)
{
    if (mt_rgb_is_finite(v)) return 1;
    mt_error_param(err, MT_ERR_INVALID, param, "%s: %s has a component that is not finite",
                   kind, param);
    return 0;
}

/* The cosines of a microfacet BxDF's half vector: *wh becomes normalize(wo +
 * wi) (which must not be zero); returns Dot(wi, wh) and puts AbsDot(wo, wh) in
 * *wo_dot_wh. For wo and wi of one length both are |wo + wi| / 2 in exact
 * arithmetic, and that value is returned: pbrt-v2's dot products of the
 * rounded wh differ between (wo, wi) and (wi, wo) by up to 1e-5 relative near
 * grazing, and the half length makes f reciprocal to the last bit. When the
 * lengths differ -- local directions in pbrt-v2's frame that is not
 * orthonormal (erratum bsdf-frame) -- the two cosines differ and pbrt-v2's
 * dot products are taken (Microfacet::f, Microfacet::G, FresnelBlend::f). */
static inline mt_real mt__half_cosines(mt_vec3 wo, mt_vec3 wi, mt_vec3 *wh, mt_real *wo_dot_wh)
{
    mt_real lo = mt_v3_len2(wo), li = mt_v3_len2(wi), c;
    mt_vec3 h = mt_v3_add(wi, wo);
    if (mt_fabs(lo - li) <= (mt_real)1e-5 * mt_max(lo, li)) {
        c = mt_v3_len(h) / 2;
        *wh = mt_v3_normalize(h);
        *wo_dot_wh = c;
        return c;
    }
    *wh = mt_v3_normalize(h);
    *wo_dot_wh = mt_fabs(mt_v3_dot(wo, *wh));
    return mt_v3_dot(wi, *wh);
}

int mt__check_fresnel(const mt_fresnel *f, const char *kind, mt_error *err);
int mt__check_distribution(const mt_distribution *d, const char *kind, mt_error *err);

#endif
